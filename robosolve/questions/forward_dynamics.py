"""The `forward_dynamics` question type:
Forward dynamics (the motion under given actuators); its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import EQUATIONS, JOINT_MAP, RECORD, SCALAR, QuestionType, _k


def _check(ql, path, item, q):
    """`at` overrides parameters only: the motion starts from `start`."""
    at = item.get("at")
    if not isinstance(at, dict):
        return
    motion = {}
    for j in ql.b.joints:
        motion[j.name] = motion[j.dot.name] = motion[j.ddot.name] = j.name
    for key in at:
        if key in motion:
            ql.chk.error(path + ("at", key), f"a forward_dynamics question's `at` may override "
                         f"parameters only: give the starting value of '{key}' in `start` "
                         "(joint values and <joint>_dot rates)")


TYPE = QuestionType(
    "forward_dynamics", "Forward dynamics (the motion under given actuators)", "§6.5",
    options={"start": V.v_start_state, "actuators": V.v_actuator_laws, "duration": V.v_duration},
    required=("duration",),
    needs_dynamics=True,
    answers=(
        # the run is accurate to ~1e-9 of its scale (tests: 1e-8 against pinocchio): 10 digits
        _k("final", JOINT_MAP, "joint values at the end (unwrapped)", principal=True, symbolic=False,
           digits=10),
        _k("max", JOINT_MAP, "largest value of each joint over the run", principal=True,
           symbolic=False, digits=10),
        _k("min", JOINT_MAP, "smallest value of each joint over the run", principal=True,
           symbolic=False, digits=10),
        _k("final_velocity", JOINT_MAP, "joint rates at the end", symbolic=False, digits=10),
        _k("energy", RECORD, "total energy T + U", symbolic=False, fields=(
            _k("start", SCALAR, "at t = 0", digits=10),
            _k("end", SCALAR, "at the end of the run", digits=10))),
        _k("equations", EQUATIONS, "the equations of motion with the actuator laws substituted",
           numeric=False),
    ),
    figures=(("joint_<name>", "forward_dynamics"),),
    cost=0.2, cost_growth=2.5, unit="dynamics",
    check=_check, integrates=True, time_use=(1, "a forward_dynamics run"), time_laws="actuators",
)
