"""The `p_control` question type (Closed-loop control): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, QuestionType, _k
from robosolve.questions.notebook_code import at_literal, compare_line, lines, literal, profile_lines, question_by_id, robosolve_numbers, text


def _check(ql, path, item, q):
    law = q.options.get("law", "p")
    if law != "p" and "gains_d" not in item:
        ql.chk.error(path, f"law {law} needs gains_d")
    if law == "p" and "gains_d" in item:
        ql.chk.error(path + ("gains_d",), "gains_d goes with law pd, pd_gravity or computed_torque")

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the profile, law, gains, start and duration."""
    o = q.options
    laws = {"p": "a proportional", "pd": "a PD", "pd_gravity": "a PD with gravity compensation",
            "computed_torque": "a computed-torque"}
    text = (f"The robot follows the motion of {say.question_number(o['profile'])} under "
            f"{laws.get(o.get('law', 'p'), o.get('law', 'p'))} controller with the gains "
            f"$K_p$ {say.per_joint(o['gains'])}")
    if "gains_d" in o:
        text += f" and $K_d$ {say.per_joint(o['gains_d'])}"
    if "start" in o:
        text += f", starting from {say.joint_values(o['start'])}"
    if "duration" in o:
        text += f", for {say.value(o['duration'])} s"
    return (text + ". Simulate the closed loop; give, for each joint, the largest tracking error "
            "$|e|$ over the run and the signed error at the end.")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    o = q.options
    if "profile" not in o and o.get("trajectory") is not None:
        return None                                  # a work-space reference: not rebuilt here
    pq = question_by_id(problem, o["profile"])
    if "max_error" not in answer.numeric:
        return None
    names = [j.name for j in problem.joints]

    def gains(key):
        return f"numbers({literal([text(o[key][n]) for n in names])})" if key in o else "None"

    duration = f"robot.number(robot.parse({text(o['duration'])!r}), at)" if "duration" in o else "None"
    return lines(
        "# the reference followed (its profile question)",
        *profile_lines(pq, problem),
        f"at = {at_literal(q)}",
        f"law = {o.get('law', 'p')!r}",
        f"kp, kd, start = {gains('gains')}, {gains('gains_d')}, {gains('start')}",
        f"max_error, t_max_error, final_error, times, errors = simulate_control(robot, profile, law, kp, kd, "
        f"start, {duration}, at)",
        robosolve_numbers(answer, ["max_error", "t_max_error", "final_error"]),
        compare_line("max_error", f"dict(zip({names!r}, max_error))", rtol=1e-4),
        f"compare('final_error', dict(zip({names!r}, final_error)), robosolve['final_error'], rtol=1e-3, atol=1e-7)",
        "plot_errors(times, errors, " + literal(names) + ", law)",
    )


TYPE = QuestionType(
    "p_control", "Closed-loop control", "§8 question 10",
    statement=_statement,
    options={"profile": V.v_profile_ref, "gains": V.v_joint_values, "law": V.v_law,
             "gains_d": V.v_joint_values, "start": V.v_joint_values, "duration": V.v_expr},
    required=("gains",),
    defaults={"law": "p"},
    needs_dynamics=True,
    answers=(
        # the simulation is accurate to ~1e-6 relative: 6 digits, the same on every machine
        _k("max_error", JOINT_MAP, "max |e| over the run", principal=True, unit="joint", symbolic=False,
           digits=6),
        _k("final_error", JOINT_MAP, "signed e at the end", principal=True, unit="joint", symbolic=False,
           digits=6),
        _k("t_max_error", JOINT_MAP, "time of the largest |e|", symbolic=False, digits=6),
    ),
    figures=(("tracking", "control_tracking"), ("effort", "control_effort")),
    cost=1.3, unit="dynamics",
    check=_check, integrates=True, uses_profile=True, time_use=(2, "a p_control simulation"),
    notebook_cells=notebook_cell,
)
