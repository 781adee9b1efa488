"""The `dof` question type (Degrees of freedom): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import SCALAR, QuestionType, _k
from robosolve.questions.wording import listing
from robosolve.questions.notebook_code import compare_line, lines, robosolve_numbers


def _check(ql, path, item, q):
    if q.options.get("space", "planar") == "planar" and "joints_3dof" in item:
        ql.chk.error(path + ("joints_3dof",), "3-DOF joints exist only with space: spatial")

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the bodies and joints counted."""
    o = q.options
    joints = [f"{o[k]} joint{'' if o[k] == 1 else 's'} of {k[7]} degree{'s' if k[7] != '1' else ''} of freedom"
              for k in ("joints_1dof", "joints_2dof", "joints_3dof") if k in o]
    space = o.get("space", "planar")
    return (f"A {space} mechanism has {say.value(o['bodies'])} bodies (the ground included) and "
            + listing(joints) + ". Give its number of degrees of freedom.")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    o = q.options
    counts = [int(o.get(k, 0)) for k in ("bodies", "joints_1dof", "joints_2dof", "joints_3dof")]
    planar = o.get("space", "planar") == "planar"
    return lines(
        f"dof = mobility({', '.join(map(str, counts))}, planar={planar!r})"
        f"   # {'Grübler (planar)' if planar else 'Kutzbach (spatial)'}",
        robosolve_numbers(answer, ["dof"]),
        compare_line("dof", "dof") if "dof" in answer.numeric else None,
    )


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
    notebook_cells=notebook_cell,
)
