"""The `joint_torques` question type:
Actuator torques along the profile; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import ACTUATOR_MAP, ACTUATOR_RECORDS, SCALAR, QuestionType, _k


TYPE = QuestionType(
    "joint_torques", "Actuator torques along the profile", "§8 question 9",
    options={"profile": V.v_profile_ref},
    needs_dynamics=True,
    answers=(
        _k("actuators", ACTUATOR_RECORDS, "actuator -> signed peak and its time", principal=True,
           symbolic=False, fields=(_k("peak", SCALAR, "signed value of largest magnitude"),
                                   # an interior peak is flat: its time is known to ~1e-8
                                   _k("t_peak", SCALAR, "time of the peak", digits=8))),
        _k("profiles", ACTUATOR_MAP, "actuator -> piecewise expression in t", numeric=False),
    ),
    figures=(("torques", "joint_torques"),),
    cost=0.4, cost_growth=2.5, unit="dynamics",
    uses_profile=True, time_use=(3, "a joint_torques profile"),
)
