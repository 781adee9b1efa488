"""The `p_control` question type (Closed-loop control): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, QuestionType, _k


def _check(ql, path, item, q):
    law = q.options.get("law", "p")
    if law != "p" and "gains_d" not in item:
        ql.chk.error(path, f"law {law} needs gains_d")
    if law == "p" and "gains_d" in item:
        ql.chk.error(path + ("gains_d",), "gains_d goes with law pd, pd_gravity or computed_torque")


TYPE = QuestionType(
    "p_control", "Closed-loop control", "§8 question 10",
    options={"profile": V.v_profile_ref, "gains": V.v_joint_values, "law": V.v_law,
             "gains_d": V.v_joint_values, "start": V.v_joint_values, "duration": V.v_expr},
    required=("gains",),
    defaults={"law": "p"},
    needs_dynamics=True,
    answers=(
        # the simulation is accurate to ~1e-6 relative: 6 digits, the same on every machine
        _k("max_error", JOINT_MAP, "max |e| over the run", principal=True, symbolic=False,
           digits=6),
        _k("final_error", JOINT_MAP, "signed e at the end", principal=True, symbolic=False,
           digits=6),
        _k("t_max_error", JOINT_MAP, "time of the largest |e|", symbolic=False, digits=6),
    ),
    figures=(("tracking", "control_tracking"), ("effort", "control_effort")),
    cost=1.3, unit="dynamics",
    check=_check, integrates=True, uses_profile=True, time_use=(2, "a p_control simulation"),
)
