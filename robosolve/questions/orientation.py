"""The `orientation` question type (Orientation representations): options, checks, answer schema."""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, RECORD, SCALAR, VECTOR, VECTOR_SET, QuestionType, _k
from robosolve.questions.notebook_code import at_literal, compare_line, lines, literal


def _needs_robot(item: dict) -> bool:
    return "matrix" not in item


def _check(ql, path, item, q):
    if "matrix" in item and "frame" in item:
        ql.chk.error(path, "give either matrix or frame (with at), not both")

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the matrix or the frame at `at`."""
    if "matrix" in q.options:
        what = f"the rotation matrix $R = $ {say.math(q.options['matrix'])}"
    else:
        at = say.at(q)
        what = f"the orientation of {say.frame(q)} in frame 0" + (f" {at}" if at else "")
    return (f"For {what}, give the ZYZ Euler angles, the roll-pitch-yaw angles (every solution, and "
            "whether it is singular), the axis and angle, and the unit quaternion.")


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    if q.options.get("matrix") is not None:
        source = f"robot.matrix({literal(sp.Matrix(q.options['matrix']))})"
    else:
        source = f"robot.pose({q.frame!r})"
    n = answer.numeric
    want = {"zyz": (n.get("zyz") or {}).get("solutions"), "rpy": (n.get("rpy") or {}).get("solutions"),
            "axis": (n.get("axis_angle") or {}).get("axis"), "angle": (n.get("axis_angle") or {}).get("angle"),
            "quaternion": n.get("quaternion")}
    want = {k: v for k, v in want.items() if v is not None}
    calls = {"zyz": "euler_zyz(R)", "rpy": "euler_rpy(R)", "axis": "axis_angle(R)[1]", "angle": "axis_angle(R)[0]",
             "quaternion": "quaternion(R)"}
    return lines(
        f"at = {at_literal(q)}",
        f"R = robot.number({source}, at)[:3, :3]",
        "# ZYZ: R = Rz(phi) Ry(theta) Rz(psi); RPY: R = Rz(yaw) Ry(pitch) Rx(roll)",
        "robosolve = " + literal(want),
        *[compare_line(k, calls[k]) for k in want],
    )


TYPE = QuestionType(
    "orientation", "Orientation representations", "§5.6",
    statement=_statement,
    options={"matrix": V.v_rotation_matrix},
    needs_robot=_needs_robot,
    answers=(
        _k("zyz", RECORD, "R = Rz(φ)·Ry(θ)·Rz(ψ)", principal=True, unit="rad", fields=(
            _k("solutions", VECTOR_SET, "[φ, θ, ψ] solution sets", shape=(3,), angle=True,
               unordered=True),
            _k("singular", BOOL, "at a singularity"))),
        _k("rpy", RECORD, "R = Rz(yaw)·Ry(pitch)·Rx(roll)", principal=True, unit="rad", fields=(
            _k("solutions", VECTOR_SET, "[roll, pitch, yaw] solution sets", shape=(3,), angle=True,
               unordered=True),
            _k("singular", BOOL, "at a singularity"))),
        _k("axis_angle", RECORD, "axis and angle in [0, π]", principal=True, fields=(
            _k("axis", VECTOR, "unit axis", shape=(3,)),
            _k("angle", SCALAR, "angle in [0, π]", angle=True))),
        _k("quaternion", VECTOR, "[η, εx, εy, εz], η ≥ 0", principal=True, shape=(4,)),
    ),
    cost=0.1,
    check=_check, needs_joints=False,
    notebook_cells=notebook_cell,
)
