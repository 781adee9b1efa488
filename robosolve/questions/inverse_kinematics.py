"""The `inverse_kinematics` question type (Inverse kinematics): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, JOINT_MAP, JOINT_MAP_LIST, JOINT_MAP_SET, TEXT, QuestionType, _k


def _check(ql, path, item, q):
    """`at` overrides parameters only: the joints are the unknowns (they were ignored silently)."""
    at = item.get("at")
    if not isinstance(at, dict):
        return
    motion = {}
    for j in ql.b.joints:
        motion[j.name] = motion[j.dot.name] = motion[j.ddot.name] = j.name
    for key in at:
        if key in motion:
            hint = (" (to choose the solution nearest a configuration, give it in `select`)"
                    if key == motion[key] else " (joint rates come from `velocity`)")
            ql.chk.error(path + ("at", key), "an inverse_kinematics question solves for the joints: "
                         f"its `at` may override parameters only, not '{key}'{hint}")


TYPE = QuestionType(
    "inverse_kinematics", "Inverse kinematics", "§8 question 6",
    options={"target": V.v_equations, "velocity": V.v_equations, "select": V.v_select},
    required=("target",),
    defaults={"select": "limits"},
    answers=(
        _k("solutions", JOINT_MAP_SET, "every solution within the limits, sorted",
           principal=True, angle=True, unordered=True, symbolic=False),
        _k("q_dot", JOINT_MAP, "joint rates at the selected solution", principal=True,
           symbolic=False),
        _k("selected", JOINT_MAP, "the selected solution", angle=True, symbolic=False),
        _k("closed_form", JOINT_MAP_LIST, "closed-form solution branches", numeric=False),
        _k("unreachable", BOOL, "true when there is no solution", top=True),
        _k("reason", TEXT, "why there is no solution", top=True),
    ),
    figures=(("solutions", "ik_solutions"),),
    cost=0.8,
    reaches=True,
    check=_check,
)
