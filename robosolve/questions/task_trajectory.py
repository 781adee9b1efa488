"""The `task_trajectory` question type (Work-space trajectory): options, checks, answer schema.

The checks that need the robot (a circle's centre equidistant from both ends, a `start` that
reaches `from`) run before solving: solvers/task_trajectory.py `check_input`, called by the
pipeline's `check_inputs` (they are input errors, FILE:LINE, exit 2). Ends out of reach or at a
singular configuration are answers (`unreachable` / `singular`), as the spec has a path that
leaves the workspace.
"""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.questions.notebook_code import compare_line, lines, literal, robosolve_numbers, trajectory_lines
from robosolve.questions.schema import BOOL, JOINT_MAP, SCALAR, TEXT, QuestionType, _k
from robosolve.questions.work_space import common_unit, coordinate_list, coordinate_unit, joint_unit, path_phrase


def v_path(ql, path, value, q):
    """`line`, or {circle: {center: [...], normal: [...]}}."""
    chk = ql.chk
    if value == "line":
        return {"kind": "line"}
    if not isinstance(value, dict) or list(value) != ["circle"] or not isinstance(value["circle"], dict):
        chk.error(path, "expected `line` or {circle: {center: [...], normal: [...]}}")
        return None
    spec = value["circle"]
    if not chk.mapping(path + ("circle",), spec, ("center", "normal"), required=("center",)):
        return None
    out = {"kind": "circle"}
    for key in ("center", "normal"):
        if key in spec:
            v = chk.vector(path + ("circle", key), spec[key], ql.params_ns, length=None)
            if v is None:
                return None
            out[key] = list(v)
    return out


def v_quintic(ql, path, value, q):
    if value != "quintic":
        ql.chk.error(path, f"unknown value {value!r} (a trajectory timed by `duration` has shape: quintic; "
                           "max_velocity and max_acceleration give the trapezoidal law)")
        return None
    return value


def v_positive(ql, path, value, q):
    e = ql.chk.expr(path, value, ql.params_ns)
    v = ql.chk.number_value(e) if e is not None else None
    if v is not None and not v > 0:
        ql.chk.error(path, f"must be positive, got {value!r}")
        return None
    return e


def _check_ends(ql, path, item, q, coords):
    texts = [str(c) for c in coords]
    for key in ("from", "to"):
        given = q.options.get(key)
        if given is None:
            continue
        for text, lhs, _rhs in given:
            if not any(sp.expand(lhs - c) == 0 for c in coords):
                ql.chk.error(path + (key, text), f"'{text}' is not one of the coordinates ({', '.join(texts)})"
                             + V.did_you_mean(text, texts))
        for c, t in zip(coords, texts):
            if not any(sp.expand(lhs - c) == 0 for _t, lhs, _r in given):
                ql.chk.error(path + (key,), f"missing the coordinate {t}" + (
                    "" if "coordinates" in item else
                    f" (the coordinates are {', '.join(texts)} by default; give `coordinates` for fewer)"))


def _check(ql, path, item, q):
    chk = ql.chk
    coords = coordinate_list(q)
    if ql.joint_names and len(coords) > len(ql.joint_names):
        chk.error(path + (("coordinates",) if "coordinates" in item else ("type",)),
                  f"{len(coords)} coordinates for {len(ql.joint_names)} joints: J would be tall "
                  "(give at most as many coordinates as joints, e.g. `coordinates: [E.y, E.z]`)")
        return
    _check_ends(ql, path, item, q, coords)
    timed = "duration" in item
    speed = [k for k in ("max_velocity", "max_acceleration") if k in item]
    if timed and speed:
        chk.error(path + (speed[0],), "give either `duration` (quintic) or max_velocity and max_acceleration")
    elif not timed and len(speed) < 2:
        missing = [k for k in ("max_velocity", "max_acceleration") if k not in item]
        chk.error(path, "the timing needs " + " and ".join(missing) + " (or a `duration`, quintic)")
    if "shape" in item and not timed:
        chk.error(path + ("shape",), "shape: quintic goes with `duration`")


def _branch(q, say) -> str:
    """Which inverse-kinematics solution the motion starts from, in words."""
    start = q.options.get("start")
    if len(coordinate_list(q)) < len(say.problem.joints):      # a family at `from`: the answer's rule
        nearest = say.joint_values(start) if isinstance(start, dict) else "$q = 0$"
        return ("With fewer coordinates than joints, a family of configurations puts the point at the start "
                f"of the path: the arm starts from the one nearest {nearest} (the least distance in the "
                "joint values), and the joint rates are the minimum-norm ones, $\\dot q = J^+ \\dot x$")
    if isinstance(start, dict):
        return (f"The arm starts on the inverse-kinematics branch of {say.joint_values(start)} (Newton's "
                "method from this configuration onto the start of the path)")
    return ("The arm starts from the inverse-kinematics solution of the start of the path that lies within "
            "the joint limits and comes first in the order of the joints' values (" + say.joints()
            + "; smallest first)")


def _asked(q, say) -> list[str]:
    """The quantities the paper asks for (the graded keys), with their units."""
    unit = common_unit(coordinate_unit(c, say.problem) for c in coordinate_list(q))
    words = {
        "T": "the duration $T$ of the motion (s)",
        "length": "the length of the path" + (f" ({unit})" if unit else ""),
        "start": f"the joint configuration at the start ({joint_unit(say.problem)})",
        "end": f"the joint configuration at the end ({joint_unit(say.problem)})",
        "max_joint_velocity": "the largest rate $|\\dot q|$ of each joint over $[0, T]$ ("
                              + joint_unit(say.problem, "/s") + ")",
        "max_joint_acceleration": "the largest acceleration $|\\ddot q|$ of each joint over $[0, T]$ ("
                                  + joint_unit(say.problem, "/s²") + ")",
        "min_singular_value": "the smallest singular value of the Jacobian along the path",
    }
    return [words[k] for k in _graded(q, say.problem) if k in words]


def _graded(q, problem) -> list:
    return list(q.grade or TYPE.template_keys(q.options, len(problem.joints)))


def paper_layout(q, problem) -> dict:
    """{key: (entries, unit)} of the keys whose unit the coordinates decide (papers)."""
    unit = common_unit(coordinate_unit(c, problem) for c in coordinate_list(q))
    return {"length": (None, unit)} if unit else {}


def _statement(q, say) -> str:
    """The paper's statement (papers.md): the path, its ends and timing, the branch, the asked
    quantities with their units."""
    coords = ", ".join(say.math(c) for c in coordinate_list(q))
    point = say.point(q)
    text = (f"{point[0].upper() + point[1:]} {path_phrase(q, say)}; the task coordinates are {coords} "
            f"(in frame 0). {_branch(q, say)}, and follows the path on the same branch, converting each "
            "sample by inverse kinematics ($\\dot q$ and $\\ddot q$ from the Jacobian $J$ and its "
            "derivative).")
    asked = _asked(q, say)
    if asked:
        text += " Compute " + "; ".join(asked) + "."
    return text


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py): the path, its
    timing and the joint motion from the same branch, then the extremes."""
    names = [j.name for j in problem.joints]
    per_joint = f"dict(zip({names!r}, {{}}))"
    followed = "end" in answer.numeric
    if "start" not in answer.numeric:       # `from` out of reach: no configuration to start from
        return lines(
            *trajectory_lines(q, problem)[:-1],
            robosolve_numbers(answer, ["T", "length"]),
            compare_line("T", "timing.T"),
            compare_line("length", "path.length"),
            "if start is None:",
            "    print('the path cannot be followed: no configuration of the arm reaches its start', path.a)",
            "else:",
            "    print('recomputed: a configuration reaches the start', start, '(robosolve found none)')",
        )
    return lines(
        *trajectory_lines(q, problem),
        robosolve_numbers(answer, ["T", "length", "start", "end", "max_joint_velocity", "max_joint_acceleration",
                                   "min_singular_value"]),
        compare_line("T", "timing.T"),
        compare_line("length", "path.length"),
        # Newton's start at a singular `from` (a double root) is only as close as √(round-off)
        compare_line("start", per_joint.format("start"), atol="arm.root_tolerance(start, path.a)"),
        "if trajectory.failure is not None:",
        "    print('the path cannot be followed:', trajectory.failure)",
        *(["velocities, accelerations, (sigma_min, t_sigma_min) = trajectory.extremes()",
           compare_line("end", per_joint.format("trajectory.q[:, -1]")),
           compare_line("max_joint_velocity", per_joint.format("velocities")),
           compare_line("max_joint_acceleration", per_joint.format("accelerations")),
           compare_line("min_singular_value", "sigma_min"),
           f"plot_joints(trajectory.t, trajectory.q.T, {literal(names)})"] if followed else []),
    )


TYPE = QuestionType(
    "task_trajectory", "Work-space trajectory", "§1.2.2",
    statement=_statement,
    options={"coordinates": V.v_coordinates, "from": V.v_equations, "to": V.v_equations, "path": v_path,
             "max_velocity": v_positive, "max_acceleration": v_positive, "duration": V.v_duration,
             "shape": v_quintic, "start": V.v_joint_values},
    required=("from", "to"),
    defaults={"path": "line"},
    answers=(
        _k("T", SCALAR, "duration of the motion", principal=True, unit="s", symbolic=False),
        _k("length", SCALAR, "length of the path", principal=True, symbolic=False),
        _k("start", JOINT_MAP, "the joint configuration at the start of the path", angle=True, unit="joint", symbolic=False),
        _k("end", JOINT_MAP, "the joint configuration at the end of the path", angle=True, unit="joint", symbolic=False),
        _k("max_joint_velocity", JOINT_MAP, "max |q_dot| over [0, T]", principal=True, unit="joint/s", symbolic=False),
        _k("max_joint_acceleration", JOINT_MAP, "max |q_ddot| over [0, T]", principal=True, unit="joint/s²", symbolic=False),
        _k("min_singular_value", SCALAR, "smallest singular value of J along the path", symbolic=False),
        _k("unreachable", BOOL, "the path leaves the workspace", top=True),
        _k("singular", BOOL, "the path crosses a singular configuration", top=True),
        _k("reason", TEXT, "where and when the path cannot be followed", top=True),
    ),
    figures=(("path", "task_path"), ("joints", "joint_motion")),
    cost=0.4, unit="dynamics",
    check=_check, model_checked=True, makes_trajectory=True,
    notebook_cells=notebook_cell, paper_layout=paper_layout,
)
