"""The `ellipsoids` question type:
Force, velocity and compliance ellipsoids; its options, checks and answer schema.
"""

from __future__ import annotations

import math

from robosolve.load import validators as V
from robosolve.questions.schema import AXES, JOINT_MAP, M, MATRIX, RECORD, SCALAR, VECTOR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import compare_line, jacobian_lines, lines, literal, text


def _ellipse(name: str, what: str, principal: bool) -> AnswerKey:
    return _k(name, RECORD, f"the {what} ellipsoid", fields=(
        _k("semi_axes", AXES, "semi-axes scaled to their lengths, by decreasing length",
           shape=(M, M), sign_free=True, symbolic=False),
        _k("lengths", VECTOR, "semi-axis lengths, decreasing", principal=principal, shape=(M,)),
        _k("directions", AXES, "unit directions of the semi-axes", shape=(M, M), sign_free=True,
           symbolic=False),
    ))


def _check(ql, path, item, q):
    chk, opts, joints = ql.chk, q.options, ql.b.joints
    ncoord = len(opts["coordinates"]) if "coordinates" in opts else 3
    if isinstance(opts.get("velocity"), V.CoordinateMapping):
        point = q.point
        coordinates = opts.get("coordinates") or [ql.b.ns_points.parse_text(f"{point}.{a}") for a in "xyz"]
        if "coordinates" in item and opts.get("coordinates") is None:
            return                      # the coordinates have their own error
        opts["velocity"] = V.in_coordinate_order(ql, path + ("velocity",), opts["velocity"], coordinates)
        if opts["velocity"] is None:
            del opts["velocity"]
    elif "velocity" in opts and len(opts["velocity"]) != ncoord:
        chk.error(path + ("velocity",), f"expected {ncoord} components (one per coordinate), "
                  f"got {len(opts['velocity'])}")
    if "joint_compliance" in opts and len(opts["joint_compliance"]) != len(joints):
        chk.error(path + ("joint_compliance",),
                  f"expected {len(joints)} values (one per joint), got {len(opts['joint_compliance'])}")

def _words(q, say) -> dict:
    out = {"condition_number": "the condition number of $A = J J^T$ (its largest eigenvalue over its smallest)",
           "A": "the matrix $A = J J^T$",
           "eigenvalues": "the eigenvalues of $A = J J^T$ (largest first)"}
    for kind in ("force", "velocity", "compliance"):
        out[kind] = (f"the {kind} ellipsoid (its semi-axes scaled to their lengths, the lengths and the "
                     "unit directions, longest first)")
        out[f"{kind}.semi_axes"] = f"the semi-axes of the {kind} ellipsoid (each scaled to its length, longest first)"
        out[f"{kind}.lengths"] = f"the semi-axis lengths of the {kind} ellipsoid (longest first)"
        out[f"{kind}.directions"] = f"the unit directions of the semi-axes of the {kind} ellipsoid (longest first)"
    if "velocity" in q.options:
        out["q_dot"] = (f"the joint rates giving the velocity {say.math(list(q.options['velocity']))} of the "
                        "coordinates")
    return out


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the coordinates, budgets, compliance, `at`, then
    what the question grades (the ellipsoids' lengths, axes, A, the joint rates of a velocity)."""
    o, at = q.options, say.at(q)
    coords = (f"the coordinates {say.coordinates(o['coordinates'])}" if o.get("coordinates")
              else f"the coordinates of {say.point(q)} in frame 0")
    text = f"For {coords}" + (f", {at}" if at else "") + f", compute {listing(asked(q, say, _words(q, say)))}"
    budgets = o.get("budgets")
    if budgets:
        text += "; the budgets are " + ", ".join(f"{k} {say.value(v)}" for k, v in budgets.items())
    if "joint_compliance" in o and any(k.startswith("compliance") for k in say.asked(q)):
        text += f"; the joint compliances are {say.math(list(o['joint_compliance']))}"
    return text + "."


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    budgets = q.options.get("budgets") or {}
    kf, kv, ka = (text(budgets.get(k, 1)) for k in ("force", "velocity", "compliance"))
    kq = q.options.get("joint_compliance")
    want = {"eigenvalues": sorted(answer.numeric.get("eigenvalues") or [])}
    for kind in ("force", "velocity", "compliance"):
        lengths = (answer.numeric.get(kind) or {}).get("lengths")
        if lengths is not None:                     # None: infinite (a singular direction)
            want[kind] = sorted((math.inf if x is None else x for x in lengths), reverse=True)
    if "condition_number" in answer.numeric:            # None: infinite (singular)
        cond = answer.numeric["condition_number"]
        want["condition_number"] = math.inf if cond is None else cond
    # the joint compliances Kq (default ones: Ks = J J^T); k null: no compliance numbers
    kq_arg = ("" if "compliance" not in answer.numeric else
              f", Kq=robot.number(robot.vector({literal([text(x) for x in kq])}), at).ravel()" if kq else
              ", Kq=np.ones(Jn.shape[1])")
    compared = [compare_line(k, f"axes[{k if k != 'eigenvalues' else 'nu'!r}]") for k in want]
    if "A" not in answer.numeric:                 # a value is not given (a null parameter): the formula
        return lines(*jacobian_lines(q)[:-1], "show(J * J.T)")
    want["A"] = answer.numeric["A"]
    compared.insert(0, compare_line("A", "Jn @ Jn.T"))
    return lines(
        *jacobian_lines(q),
        "# A = J J^T: force semi-axes K_f / sqrt(nu), velocity K_v sqrt(nu), compliance K_a kappa",
        f"Kf, Kv, Ka = (robot.number(robot.parse(k), at) for k in {literal([kf, kv, ka])})",
        f"axes = ellipsoid_axes(Jn, Kf, Kv, Ka{kq_arg})",
        *_rates_lines(q, answer, problem, want),
        "robosolve = " + literal(want) + "   # lengths largest first",
        *compared,
        *(["compare('q_dot', dict(zip(" + literal([j.name for j in problem.joints]) + ", q_dot)), "
           "robosolve['q_dot'])"] if "q_dot" in want else []),
    )


def _rates_lines(q, answer, problem, want) -> list[str]:
    """The joint rates giving the desired velocity: J^-1 v, or the minimum-norm J^+ v."""
    velocity = q.options.get("velocity")
    if velocity is None or "q_dot" not in answer.numeric:
        return []
    want["q_dot"] = answer.numeric["q_dot"]
    return [f"v = robot.number(robot.vector({literal([text(x) for x in velocity])}), at).ravel()",
            "# the joint rates giving the desired velocity: J^-1 v, or the minimum-norm J^+ v",
            "q_dot = np.linalg.pinv(Jn) @ v"]


TYPE = QuestionType(
    "ellipsoids", "Force, velocity and compliance ellipsoids", "§8 question 5",
    statement=_statement,
    options={"coordinates": V.v_coordinates, "budgets": V.v_budgets,
             "joint_compliance": V.v_exprs, "velocity": V.v_exprs_or_coordinate_map},
    required=("at",),
    defaults={"budgets": {"force": 1, "velocity": 1, "compliance": 1}},
    answers=(
        _ellipse("force", "force", True),
        _ellipse("velocity", "velocity", True),
        _k("condition_number", SCALAR, "max/min eigenvalue of A", principal=True),
        _ellipse("compliance", "compliance", False),
        _k("A", MATRIX, "A = J Jᵀ", shape=(M, M)),
        _k("eigenvalues", VECTOR, "eigenvalues of A, decreasing", shape=(M,)),
        _k("q_dot", JOINT_MAP, "joint rates giving the desired velocity", symbolic=False,
           needs=lambda q, joints: "" if "velocity" in q.options else "q_dot is computed only for a given velocity"),
    ),
    figures=(("ellipsoids", "ellipsoids"),),
    cost=0.3,
    check=_check, has_jacobian=True,
    notebook_cells=notebook_cell,
)
