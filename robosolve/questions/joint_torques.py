"""The `joint_torques` question type:
Actuator torques along the profile; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import ACTUATOR_MAP, ACTUATOR_RECORDS, SCALAR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, followed_question, lines, literal, profile_lines


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    pq = followed_question(problem, q.options["profile"], q)
    if "actuators" not in answer.numeric:
        return None
    want = answer.numeric["actuators"]
    return lines(
        "# the profile followed (its profile question)",
        *profile_lines(pq, problem),
        f"at = {at_literal(q, problem)}",
        "# tau(t) = M(q) q'' + c(q, q') + g(q) - Q along the profile; the signed peak of each actuator",
        "peaks, t_peaks = torque_peaks(robot, profile, at)",
        "robosolve = " + literal({"peak": [v["peak"] for v in want.values()],
                                  "t_peak": [v["t_peak"] for v in want.values()]}),
        compare_line("peak", "peaks"),
        compare_line("t_peak", "t_peaks", rtol=1e-5),
    )

WORDS = {
    "actuators": "each actuator's signed peak (the value of largest magnitude) and the time of that peak",
    "profiles": "each actuator's action as a piecewise expression of the time $t$",
}


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the profile it follows, then what the question
    grades (the peaks and their times, the actions as expressions of t)."""
    return (f"Along the motion of {say.question_number(q.options['profile'])}, with the bodies, "
            f"forces and gravity of the data, compute the actuator actions; give {listing(asked(q, say, WORDS))}.")


TYPE = QuestionType(
    "joint_torques", "Actuator torques along the profile", "§8 question 9",
    statement=_statement,
    options={"profile": V.v_profile_ref},
    needs_dynamics=True,
    answers=(
        _k("actuators", ACTUATOR_RECORDS, "actuator -> signed peak and its time", principal=True,
           symbolic=False, fields=(_k("peak", SCALAR, "signed value of largest magnitude", unit="effort"),
                                   # an interior peak is flat: its time is known to ~1e-8
                                   _k("t_peak", SCALAR, "time of the peak", unit="s", digits=8))),
        _k("profiles", ACTUATOR_MAP, "actuator -> piecewise expression in t, written piecewise(t <= t1, e1, e2) "
           "with t1 a number and e1, e2 expressions in t",
           unit="effort", numeric=False),
    ),
    figures=(("torques", "joint_torques"),),
    cost=0.4, cost_growth=2.5, unit="dynamics",
    uses_profile=True, time_use=(3, "a joint_torques profile"),
    notebook_cells=notebook_cell,
)
