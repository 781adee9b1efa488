"""The `inverse_kinematics` question type (Inverse kinematics): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, JOINT_MAP, JOINT_MAP_LIST, JOINT_MAP_SET, TEXT, QuestionType, _k

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the target, the velocity and the selection."""
    o = q.options
    target = ", ".join(f"${say.tex(lhs)} = {say.tex(rhs)}$" for _, lhs, rhs in o["target"])
    text = (f"Find every configuration ({say.joints()}) within the joint limits that puts {target}"
            " (none, if the target cannot be reached)")
    if "velocity" in o:
        wanted = ", ".join(f"$\\dot{{{say.tex(lhs)}}} = {say.tex(rhs)}$" for _, lhs, rhs in o["velocity"])
        select = o.get("select")
        which = (f"the solution nearest to {say.joint_values(select)}" if isinstance(select, dict)
                 else "the selected solution")
        text += f"; at {which}, the joint rates giving {wanted}"
    return text + "."


TYPE = QuestionType(
    "inverse_kinematics", "Inverse kinematics", "§8 question 6",
    statement=_statement,
    options={"target": V.v_equations, "velocity": V.v_equations, "select": V.v_select},
    required=("target",),
    defaults={"select": "limits"},
    answers=(
        _k("solutions", JOINT_MAP_SET, "every solution within the limits, sorted",
           principal=True, unit="joint", angle=True, unordered=True, symbolic=False),
        _k("q_dot", JOINT_MAP, "joint rates at the selected solution", principal=True, unit="joint/s",
           symbolic=False),
        _k("selected", JOINT_MAP, "the selected solution", angle=True, symbolic=False),
        _k("closed_form", JOINT_MAP_LIST, "closed-form solution branches", numeric=False),
        _k("unreachable", BOOL, "true when there is no solution", top=True),
        _k("reason", TEXT, "why there is no solution", top=True),
    ),
    figures=(("solutions", "ik_solutions"),),
    paper_keys=lambda options, joints: ("solutions",) + (("q_dot",) if "velocity" in options else ()),
    cost=0.8,
    reaches=True,
)
