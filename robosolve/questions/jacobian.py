"""The `jacobian` question type:
Jacobian and singular configurations; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP_SET, MATRIX, MATRIX_MAP, N, R, SCALAR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import (at_literal, compare_line, guarded, jacobian_lines, lines, literal,
                                               robosolve_numbers)


def _check(ql, path, item, q):
    if q.options.get("geometric") and "coordinates" in item:
        ql.chk.error(path + ("geometric",), "geometric: true cannot be combined with coordinates")


def _rows(q) -> int:
    return 6 if q.options.get("geometric") else len(q.options.get("coordinates") or ()) or 3


def _needs_bodies(q, joints) -> str:
    return "" if q.options.get("bodies") else "the centre-of-mass Jacobians are computed only with bodies: true"


def _needs_square(q, joints) -> str:
    rows, n = _rows(q), len(joints)
    return "" if rows == n else f"J is {rows}x{n}: it has no determinant (grade its manipulability)"


def _needs_wide(q, joints) -> str:
    rows, n = _rows(q), len(joints)
    return "" if rows != n else f"J is {rows}x{n}, square: grade its determinant (det)"


def _cost_factor(question, joints: int) -> float:
    """A wide J of 5+ joints (a 6R flange's 3×6, a 7-joint arm's 6×7) costs about four times a
    square one: its rank conditions come from the search over its many minors (measured: the
    UR5 flange's 3.6 s CPU against its 6×6 geometric Jacobian's 1.0 s, the Panda's 6×7 6.7 s)."""
    options = getattr(question, "options", None) or {}
    rows = 6 if options.get("geometric") else len(options.get("coordinates") or ()) or 3
    return 4.0 if rows < joints and joints >= 5 else 1.0


def _paper_keys(options: dict, joints: int) -> tuple:
    """J and its singularities, with det J when J is square, else the manipulability."""
    rows = 6 if options.get("geometric") else len(options.get("coordinates") or ()) or 3
    return ("J", "det" if rows == joints else "manipulability", "singularities")


WORDS = {
    "det": "its determinant",
    "manipulability": "its manipulability (the product of its singular values)",
    "singularities": "the singular configurations (the joint values that make $J$ lose rank)",
    "com_jacobians": "the Jacobian of the centre of mass of each body (its position in frame 0)",
}


def _statement(q, say) -> str:
    """The paper's statement (papers.md): J of the coordinates (or geometric), then what of it the
    question grades (det J or the manipulability, the singular configurations, the bodies'
    centre-of-mass Jacobians), at its `at`."""
    o, at = q.options, say.at(q)
    if o.get("geometric"):
        what = (f"the geometric Jacobian $J$ of {say.point(q)} and {say.frame(q)} (linear velocity of the "
                "point above the angular velocity of the frame, both in frame 0)")
    elif o.get("coordinates"):
        what = f"the Jacobian $J$ of the coordinates {say.coordinates(o['coordinates'])}"
    else:
        what = f"the Jacobian $J$ of the coordinates of {say.point(q)} in frame 0 (x, y, z)"
    what += f" with respect to the joint variables ({say.joints()})"
    rest = listing(asked(q, say, WORDS))
    numbers = f"; give the numbers {at}" if at else ""
    if "J" in say.asked(q):
        return f"Compute {what}" + (f"; give {rest}" if rest else "") + numbers + "."
    return f"For {what}, give {rest}" + numbers + "."


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    if q.options.get("geometric"):
        head = [f"at = {at_literal(q)}",
                "# geometric: the point's linear velocity over the angular velocity, column by joint",
                f"J = robot.geometric_jacobian({q.point!r})",
                "Jn = robot.number(J, at)"]
    else:
        head = jacobian_lines(q)
    if "J" not in answer.numeric:     # a value is not given (a null parameter, a joint): the formula
        given = all(v is not None or s in q.at for s, v in problem.parameters.items())
        return lines(*head[:-1], "show(J)", *(_singular_lines(answer) if given else []))
    return lines(
        *head,
        "show(J)",
        robosolve_numbers(answer, ["J", "det", "manipulability"]),
        *guarded(answer, ("J", compare_line("J", "Jn")),
                  ("det", compare_line("det", "np.linalg.det(Jn)")),
                  ("manipulability", compare_line("manipulability", "np.prod(np.linalg.svd(Jn, compute_uv=False))"))),
        *_com_lines(answer),
        *_singular_lines(answer),
    )


def _singular_lines(answer) -> list[str]:
    """Each singular condition {joint: value} makes J lose rank: its smallest singular value over
    its largest is 0 there (the other joints as in `at`, else generic values; an equation between
    joints is not evaluated)."""
    conditions = [c for c in answer.symbolic.get("singularities") or [] if isinstance(c, dict)]
    if not conditions:
        return []
    return [
        "# each singular condition {joint: value} of robosolve, the other joints as in `at` (else",
        "# 0.3, 0.5, 0.7, ...): J loses rank there, its smallest singular value over its largest is 0",
        f"conditions = {literal(conditions)}",
        "generic = {str(q): repr(0.3 + 0.2 * i) for i, q in enumerate(robot.joints)}",
        "sigma = [np.linalg.svd(robot.number(J, {**generic, **at, **c}), compute_uv=False) for c in conditions]",
        "compare('singularities', [s[-1] / s[0] for s in sigma], [0.0] * len(conditions))",
    ]


def _com_lines(answer) -> list[str]:
    """The centre-of-mass Jacobians d G / dq, G = (0M J e4) / m (bodies: true)."""
    bodies = answer.numeric.get("com_jacobians")
    if not bodies:
        return []
    return ["robosolve['com_jacobians'] = " + literal(bodies),
            "compare('com_jacobians', {body: robot.number(robot.com_jacobian(body), at) for body in "
            + literal(list(bodies)) + "}, robosolve['com_jacobians'])"]


TYPE = QuestionType(
    "jacobian", "Jacobian and singular configurations", "§8 question 3",
    statement=_statement,
    options={"coordinates": V.v_coordinates, "geometric": V.v_bool, "bodies": V.v_bool},
    defaults={"geometric": False, "bodies": False},
    answers=(
        _k("J", MATRIX, "the Jacobian of the coordinates", principal=True, shape=(R, N), in_frame0=True,
           hints=(("transposed", "J has one row per coordinate and one column per joint: "
                                 "column i is ∂(coordinates)/∂qᵢ"),)),
        _k("det", SCALAR, "det J", principal=True, needs=_needs_square),
        _k("manipulability", SCALAR, "product of the singular values (J not square)", principal=True,
           needs=_needs_wide),
        _k("singularities", JOINT_MAP_SET, "conditions joint -> value making J lose rank",
           principal=True, unit="joint", angle=True, unordered=True, by_value=True),
        _k("com_jacobians", MATRIX_MAP, "body -> 3xn Jacobian of its centre of mass", shape=(3, N),
           needs=_needs_bodies),
    ),
    paper_keys=_paper_keys,
    cost=0.5, cost_growth=2, cost_factor=_cost_factor,
    check=_check, has_jacobian=True,
    notebook_cells=notebook_cell,
)
