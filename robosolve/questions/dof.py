"""The `dof` question type (Degrees of freedom): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import SCALAR, QuestionType, _k


def _check(ql, path, item, q):
    if q.options.get("space", "planar") == "planar" and "joints_3dof" in item:
        ql.chk.error(path + ("joints_3dof",), "3-DOF joints exist only with space: spatial")

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the bodies and joints counted."""
    o = q.options
    joints = [f"{o[k]} joints of {k[7]} degree{'s' if k[7] != '1' else ''} of freedom"
              for k in ("joints_1dof", "joints_2dof", "joints_3dof") if k in o]
    space = o.get("space", "planar")
    return (f"A {space} mechanism has {say.value(o['bodies'])} bodies (the ground included) and "
            + ", ".join(joints) + ". Give its number of degrees of freedom.")


TYPE = QuestionType(
    "dof", "Degrees of freedom", "§1.1",
    statement=_statement,
    options={"bodies": V.v_count, "joints_1dof": V.v_count, "joints_2dof": V.v_count,
             "joints_3dof": V.v_count, "space": V.v_space},
    required=("bodies",),
    defaults={"space": "planar"},
    needs_robot=lambda item: False,
    answers=(
        _k("dof", SCALAR, "Grübler (planar) / Kutzbach (spatial)", principal=True),
    ),
    cost=0.01,
    check=_check,
)
