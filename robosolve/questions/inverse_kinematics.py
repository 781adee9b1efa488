"""The `inverse_kinematics` question type (Inverse kinematics): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, JOINT_MAP, JOINT_MAP_LIST, JOINT_MAP_SET, TEXT, QuestionType, _k


TYPE = QuestionType(
    "inverse_kinematics", "Inverse kinematics", "§8 question 6",
    options={"target": V.v_ik_target, "velocity": V.v_equations, "select": V.v_select},
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
)
