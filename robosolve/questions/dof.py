"""The `dof` question type (Degrees of freedom): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import SCALAR, QuestionType, _k


def _check(ql, path, item, q):
    if q.options.get("space", "planar") == "planar" and "joints_3dof" in item:
        ql.chk.error(path + ("joints_3dof",), "3-DOF joints exist only with space: spatial")


TYPE = QuestionType(
    "dof", "Degrees of freedom", "§1.1",
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
