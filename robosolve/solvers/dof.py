"""§1.1.3: degrees of freedom by Gruebler (planar) or Kutzbach (spatial).

Engine: robosolve.geometry.mobility. No robot needed.
"""

from __future__ import annotations

from robosolve.core.course_notes import note_link
from robosolve.geometry.mobility import mobility
from robosolve.load.problem import Question
from robosolve.solvers.base import Answer, SolveContext, Step


def solve(question: Question, ctx: SolveContext) -> Answer:
    ans = Answer(question.type, question.id)
    o = question.options
    space = o.get("space", "planar")
    try:
        r = mobility(o["bodies"], o.get("joints_1dof", 0), o.get("joints_2dof", 0),
                     o.get("joints_3dof", 0), space)
    except ValueError as exc:
        ans.error = str(exc)
        return ans
    ans.symbolic["dof"] = r.dof
    ans.numeric["dof"] = r.dof
    name = "Grübler (planar)" if space == "planar" else "Kutzbach (spatial)"
    free = 3 if space == "planar" else 6
    text = (f"Each of the $m - 1 = {r.bodies - 1}$ moving bodies has {free} DOF in "
            f"{'the plane' if space == 'planar' else 'space'}; a joint that leaves $k$ DOF removes "
            f"${free} - k$ of them. $m$ counts the base (" + note_link("mobility") + ").")
    formula = r.formula.replace("c1", "c_1").replace("c2", "c_2").replace("c3", "c_3")
    ans.steps.append(Step(
        f"Mobility by {name}", text,
        equations=[("", formula), ("", r.substituted.replace("·", " \\cdot ") + f" = {r.dof}")],
        table=(("contribution", "DOF"), [(label, f"{v:+d}") for label, v in r.terms]
               + [("total n", str(r.dof))]),
    ))
    if r.status == "overconstrained":
        ans.note(f"over-constrained: n = {r.dof} < 0 ({-r.dof} redundant constraints); the count "
                 "says it cannot move unless special geometry (e.g. parallel axes) gives it mobility")
    elif r.status == "structure":
        ans.note("n = 0: a structure (no motion) unless special geometry gives it mobility")
    return ans
