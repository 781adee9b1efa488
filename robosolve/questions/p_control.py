"""The `p_control` question type (Closed-loop control): options, checks, answer schema.

With a `trajectory` (the id of a work-space trajectory question), the joint laws follow the
trajectory converted by inverse kinematics (the ideal work-space scheme) and the task laws
use the error in the task coordinates (the actual scheme); their gains are keyed by coordinate.
"""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.load.expressions import ExpressionError
from robosolve.questions.schema import CONTROL_MAP, COORDINATE_MAP, QuestionType, _k
from robosolve.questions.work_space import coordinate_list, coordinate_unit, gain_unit, joint_unit, path_phrase
from robosolve.questions.notebook_code import (at_literal, compare_line, coordinate_values, followed_question, lines,
                                               literal, profile_lines, question_by_id, robosolve_numbers, text,
                                               trajectory_lines)

TASK_LAWS = ("task_pd_gravity", "task_computed_torque")


def v_control_law(ql, path, value, q):
    return V._choice(ql, path, value, V.LAWS + TASK_LAWS)


def v_gains(ql, path, value, q):
    """A mapping joint -> gain, or (task laws) coordinate -> gain: {"coordinates": [(text, expr, gain)]}."""
    if isinstance(value, dict) and value and not any(k in ql.joint_names for k in value):
        out = []
        for key, v in value.items():
            try:
                lhs = ql.b.ns_points.parse_text(str(key))
            except ExpressionError as exc:
                ql.chk.error(path + (key,), str(exc))
                continue
            e = ql.chk.expr(path + (key,), v, ql.params_ns)
            if e is not None:
                out.append((str(key), lhs, e))
        return {"coordinates": out} if len(out) == len(value) else None
    return V.v_joint_values(ql, path, value, q)


def v_trajectory_ref(ql, path, value, q):
    if not isinstance(value, str):
        ql.chk.error(path, f"expected the id of a {ql.type_name('makes_trajectory')} question")
        return None
    return value


def _check(ql, path, item, q):
    law = q.options.get("law", "p")
    by_coordinate = [k for k in ("gains", "gains_d")
                     if isinstance(q.options.get(k), dict) and "coordinates" in q.options[k]]
    if "law" not in item and by_coordinate:
        # gains per coordinate and no law: the law is what is missing (one message, not the default
        # law p's complaints about each gain)
        ql.chk.error(path, f"{' and '.join(by_coordinate)} per coordinate need a task law: give "
                     f"law: {' or '.join(TASK_LAWS)} (the default law p takes gains per joint)")
        return
    if law != "p" and "gains_d" not in item:
        ql.chk.error(path, f"law {law} needs gains_d")
    if law == "p" and "gains_d" in item:
        ql.chk.error(path + ("gains_d",), "gains_d goes with law pd, pd_gravity or computed_torque")
    if "trajectory" in item and "profile" in item:
        ql.chk.error(path + ("profile",), "give either a profile (joint space) or a trajectory (work space)")
    if law in TASK_LAWS and "trajectory" not in item:
        ql.chk.error(path + ("law",), f"law {law} works on a work-space `trajectory` (give its id)")
    for key in ("gains", "gains_d"):
        by_coord = isinstance(q.options.get(key), dict) and "coordinates" in q.options[key]
        if key in q.options and by_coord != (law in TASK_LAWS):
            ql.chk.error(path + (key,), "the task laws take gains per coordinate (e.g. {E.y: 2000}), the joint "
                         "laws per joint" if law in TASK_LAWS else
                         f"law {law} takes gains per joint (joints: {', '.join(ql.joint_names)})")


def _resolve(ql, q, questions):
    """The trajectory reference, and the task gains against its coordinates."""
    ref = q.options.get("trajectory")
    if ref is None:
        return
    base = ("questions", q.index)
    trajs = [t for t in questions if getattr(_qt(t), "makes_trajectory", False)]
    target = next((t for t in trajs if t.id == ref), None)
    if target is None:
        if not ql.refused(ref):
            ql.chk.error(base + ("trajectory",), f"no {ql.type_name('makes_trajectory')} question with id '{ref}'"
                         + V.did_you_mean(ref, [t.id for t in trajs]))
        return
    if target.index > q.index:      # solved in file order: the follower would find no answer yet
        ql.chk.error(base + ("trajectory",), f"the {ql.type_name('makes_trajectory')} question '{ref}' is "
                     f"questions[{target.index}], after this one: put it before (questions are answered "
                     "in file order)")
        return
    if "coordinates" in target.rejected:
        return          # the trajectory's coordinates were refused (said): its gains are not judged
    law = q.options.get("law", "p")
    if law not in TASK_LAWS:
        return
    coords = coordinate_list(target)
    texts = [str(c) for c in coords]
    if law == "task_computed_torque" and len(coords) != len(ql.joint_names):
        ql.chk.error(base + ("law",), f"task_computed_torque needs a square J: the trajectory '{ref}' has "
                     f"{len(coords)} coordinates for {len(ql.joint_names)} joints (use task_pd_gravity)")
    for key in ("gains", "gains_d"):
        gains = q.options.get(key)
        if not isinstance(gains, dict) or "coordinates" not in gains:
            continue
        unknown = [t for t, lhs, _v in gains["coordinates"] if not any(sp.expand(lhs - c) == 0 for c in coords)]
        for text in unknown:
            ql.chk.error(base + (key, text), f"the trajectory '{ref}' has no coordinate '{text}' "
                         f"(its coordinates: {', '.join(texts)})" + V.did_you_mean(text, texts))
        for c, t in zip(coords, texts):
            if not unknown and not any(sp.expand(lhs - c) == 0 for _t, lhs, _v in gains["coordinates"]):
                ql.chk.error(base + (key,), f"missing the gain of the coordinate {t}")


def _qt(q):
    from robosolve.questions.registry import QUESTION_TYPES

    return QUESTION_TYPES.get(q.type)


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the profile, law, gains, start and duration."""
    o = q.options
    laws = {"p": "a proportional", "pd": "a PD", "pd_gravity": "a PD with gravity compensation",
            "computed_torque": "a computed-torque"}
    if "trajectory" in o:
        return _task_statement(q, say)
    text = (f"The robot follows the motion of {say.question_number(o['profile'])} under "
            f"{laws.get(o.get('law', 'p'), o.get('law', 'p'))} controller, "
            f"${JOINT_LAW_TEX.get(o.get('law', 'p'), '')}$ with $e = q_d - q$, with the gains {_gains_text(q, say, [])}")
    text += (f", starting from rest at {say.joint_values(o['start'])}" if "start" in o
             else ", starting from rest at the start of that motion")
    text += (f", for {say.value(o['duration'])} s" if "duration" in o
             else ", from $t = 0$ to the end $T$ of that motion")
    give = _task_asked(q, say, [])
    return text + ". Simulate the closed loop on the robot's equations of motion; " + give[:1].lower() + give[1:]


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    o = q.options
    if "profile" not in o and o.get("trajectory") is not None:
        return _trajectory_cell(q, answer, problem)
    pq = followed_question(problem, o["profile"], q)
    if "max_error" not in answer.numeric:
        return None
    names = [j.name for j in problem.joints]

    def gains(key):
        return f"numbers({literal([text(o[key][n]) for n in names])})" if key in o else "None"

    duration = f"robot.number(robot.parse({text(o['duration'])!r}), at)" if "duration" in o else "None"
    return lines(
        "# the reference followed (its profile question)",
        *profile_lines(pq, problem),
        f"at = {at_literal(q, problem)}",
        f"law = {o.get('law', 'p')!r}",
        f"kp, kd, start = {gains('gains')}, {gains('gains_d')}, {gains('start')}",
        f"max_error, t_max_error, final_error, times, errors = simulate_control(robot, profile, law, kp, kd, "
        f"start, {duration}, at)",
        robosolve_numbers(answer, ["max_error", "t_max_error", "final_error"]),
        compare_line("max_error", f"dict(zip({names!r}, max_error))", rtol=1e-4),
        f"compare('final_error', dict(zip({names!r}, final_error)), robosolve['final_error'], rtol=1e-3, atol=1e-7)",
        "plot_errors(times, errors, " + literal(names) + ", law)",
    )


def _trajectory_cell(q, answer, problem):
    """The cell of a run along a work-space trajectory: the trajectory rebuilt, then the loop."""
    o = q.options
    if "max_error" not in answer.numeric:
        return None
    tq = followed_question(problem, o["trajectory"], q)
    law = o.get("law", "p")
    names = [j.name for j in problem.joints]
    coords = coordinate_list(tq)
    labels = [str(c) for c in coords]

    def gains(key):
        if key not in o:
            return "None"
        given = o[key]
        texts = coordinate_values(given["coordinates"], coords) if law in TASK_LAWS else [text(given[n]) for n in names]
        return f"numbers({literal(texts)})"

    start = f"numbers({literal([text(o['start'][n]) for n in names])})" if "start" in o else "None"
    duration = f"robot.number(robot.parse({text(o['duration'])!r}), at)" if "duration" in o else "None"
    keys = labels if law in TASK_LAWS else names
    return lines(
        "# the reference followed (its work-space trajectory question)",
        *trajectory_lines(tq, problem),
        f"at = {at_literal(q, problem)}",
        f"law = {law!r}",
        f"kp, kd, start = {gains('gains')}, {gains('gains_d')}, {start}",
        "max_error, t_max_error, final_error, times, errors, task_errors = simulate_task_control(",
        f"    robot, trajectory, law, kp, kd, start, {duration}, at)",
        robosolve_numbers(answer, ["max_error", "t_max_error", "final_error", "max_task_error"]),
        compare_line("max_error", f"dict(zip({keys!r}, max_error))", rtol=1e-4),
        f"compare('final_error', dict(zip({keys!r}, final_error)), robosolve['final_error'], rtol=1e-3, atol=1e-7)",
        compare_line("max_task_error", f"dict(zip({labels!r}, np.abs(task_errors).max(axis=0)))", rtol=1e-3),
        f"plot_errors(times, errors, {literal(keys)}, law)",
    )


JOINT_LAW_WORDS = {"p": "a proportional joint law", "pd": "a PD joint law",
                   "pd_gravity": "a PD joint law with gravity compensation",
                   "computed_torque": "a computed-torque joint law"}
JOINT_LAW_TEX = {"p": "\\tau = K_p e", "pd": "\\tau = K_p e + K_d \\dot e",
                 "pd_gravity": "\\tau = K_p e + K_d \\dot e + g(q)",
                 "computed_torque": "\\tau = M(q)(\\ddot q_d + K_d \\dot e + K_p e) + c(q, \\dot q) + g(q)"}


def _trajectory_of(q, problem):
    return question_by_id(problem, q.options["trajectory"])


def _gains_text(q, say, coords) -> str:
    """'$K_p$: $E_y$: $2000$ N/m, … and $K_d$: …', per coordinate (task laws) or per joint."""
    o, law = q.options, q.options.get("law", "p")
    ct = law in ("computed_torque", "task_computed_torque")

    def listing(key, derivative):
        if law in TASK_LAWS:
            pairs = [(c, next(v for _t, lhs, v in o[key]["coordinates"] if sp.expand(lhs - c) == 0),
                      coordinate_unit(c, say.problem)) for c in coords]
        else:
            pairs = [(j.symbol, o[key][j.name], "rad" if j.is_revolute else "m") for j in say.problem.joints]
        return ", ".join(f"${say.tex(c)}$: {say.value(v)}" + (f" {u}" if (u := gain_unit(unit, derivative, ct)) else "")
                         for c, v, unit in pairs)

    out = f"$K_p$ ({listing('gains', False)})"
    return out + (f" and $K_d$ ({listing('gains_d', True)})" if "gains_d" in o else "")


def _scheme_text(q, say) -> str:
    law = q.options.get("law", "p")
    if law == "task_pd_gravity":
        return ("the actual work-space scheme: the error in the task coordinates, $e = x_d - x(q)$ and "
                "$\\dot e = \\dot x_d - J(q)\\,\\dot q$, acts through the transposed Jacobian, with gravity "
                "compensation: $\\tau = J^T(q)\\,(K_p e + K_d \\dot e) + g(q)$")
    if law == "task_computed_torque":
        return ("the actual work-space scheme with a resolved-acceleration computed torque: with the error in the "
                "task coordinates $e = x_d - x(q)$, $\\dot e = \\dot x_d - J(q)\\,\\dot q$, "
                "$\\tau = M(q)\\,J^{-1}(q)\\,(\\ddot x_d + K_d \\dot e + K_p e - \\dot J\\,\\dot q) + c(q, \\dot q) + g(q)$")
    return ("the ideal work-space scheme: the trajectory is converted by inverse kinematics into joint "
            "references $q_d(t)$, $\\dot q_d(t)$, $\\ddot q_d(t)$, which " + JOINT_LAW_WORDS.get(law, law)
            + f" follows, ${JOINT_LAW_TEX.get(law, '')}$ with $e = q_d - q$")


def _task_asked(q, say, coords) -> str:
    """What to compute, with the units: the errors per coordinate (task laws) or per joint."""
    law = q.options.get("law", "p")
    keys = q.grade or TYPE.template_keys(q.options, len(say.problem.joints))
    units = {coordinate_unit(c, say.problem) for c in coords}
    x_unit = units.pop() if len(units) == 1 and None not in units else "m for a position, rad for an angle"
    if law in TASK_LAWS:
        who, err, unit = "each task coordinate (" + ", ".join(say.math(c) for c in coords) + ")", "|x_d - x|", x_unit
    else:
        who, err, unit = f"each joint ({say.joints()})", "|q_d - q|", joint_unit(say.problem)
    words = {"max_error": f"the largest error ${err}$ over the run ({unit})",
             "final_error": f"the signed error at the end of the run ({unit})",
             "t_max_error": "the time of the largest error (s)",
             "max_task_error": f"the largest work-space error $|x_d - x|$ of each task coordinate ({x_unit})"}
    asked = [words[k] for k in keys if k in words]
    return f"Give, for {who}: " + "; ".join(asked) + "." if asked else ""


def _task_statement(q, say) -> str:
    """The statement of a run along a work-space trajectory: the path restated, the scheme with
    its gains and units, the start, the duration, what to give with its units."""
    o = q.options
    tq = _trajectory_of(q, say.problem)
    coords = coordinate_list(tq)
    start = (f"from rest at {say.joint_values(o['start'])}" if "start" in o else
             f"from rest at the configuration of {say.question_number(o['trajectory'])} at the start of the path")
    duration = (f"for {say.value(o['duration'])} s (after the end $T$ of the path the reference stays at its end)"
                if "duration" in o else "from $t = 0$ to the end $T$ of the path")
    point = say.point(tq)
    return (f"Along the work-space trajectory of {say.question_number(o['trajectory'])}: {point} "
            f"{path_phrase(tq, say)}, in the task coordinates " + ", ".join(say.math(c) for c in coords)
            + f". The actuators follow it under {_scheme_text(q, say)}. Gains: {_gains_text(q, say, coords)}. "
            f"The arm starts {start}; simulate the closed loop on the robot's equations of motion (its bodies, "
            f"gravity and loads) {duration}. " + _task_asked(q, say, coords))


def paper_layout(q, problem) -> dict:
    """{key: (entries, unit)}: the errors per joint (joint laws) or per task coordinate (task laws)."""
    names = [j.name for j in problem.joints]
    law = q.options.get("law", "p")
    out = {"max_error": (names, None), "final_error": (names, None), "t_max_error": (names, "s")}
    if q.options.get("trajectory") is None:
        return out
    try:
        coords = coordinate_list(_trajectory_of(q, problem))
    except StopIteration:
        return out
    units = {coordinate_unit(c, problem) for c in coords}
    x_unit = units.pop() if len(units) == 1 and None not in units else "m (positions) or rad (angles)"
    labels = [str(c) for c in coords]
    if law in TASK_LAWS:
        out = {"max_error": (labels, x_unit), "final_error": (labels, x_unit), "t_max_error": (labels, "s")}
    out["max_task_error"] = (labels, x_unit)
    return out


TYPE = QuestionType(
    "p_control", "Closed-loop control", "§8 question 10",
    statement=_statement,
    options={"profile": V.v_profile_ref, "trajectory": v_trajectory_ref, "gains": v_gains,
             "law": v_control_law, "gains_d": v_gains, "start": V.v_joint_values, "duration": V.v_expr},
    required=("gains",),
    defaults={"law": "p"},
    needs_dynamics=True,
    answers=(
        # the simulation is accurate to ~1e-6 relative: 6 digits, the same on every machine
        _k("max_error", CONTROL_MAP, "max |e| over the run (per coordinate for a task law)", principal=True,
           unit="joint", symbolic=False, digits=6),
        _k("final_error", CONTROL_MAP, "signed e at the end (per coordinate for a task law)", principal=True,
           unit="joint", symbolic=False, digits=6),
        _k("max_task_error", COORDINATE_MAP, "coordinate -> max |x_d - x| along a trajectory",
           symbolic=False, digits=6,
           needs=lambda q, joints: "" if "trajectory" in q.options else
           "the work-space error is computed only when the question follows a trajectory"),
        _k("t_max_error", CONTROL_MAP, "time of the largest |e|", symbolic=False, digits=6),
    ),
    figures=(("tracking", "control_tracking"), ("effort", "control_effort"), ("task", "control_tracking")),
    cost=1.3, unit="dynamics",
    check=_check, resolve=_resolve, integrates=True, uses_profile=True, time_use=(2, "a p_control simulation"),
    notebook_cells=notebook_cell, paper_layout=paper_layout,
)
