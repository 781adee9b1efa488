"""The `orientation` question type (Orientation representations): options, checks, answer schema."""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, RECORD, SCALAR, VECTOR, VECTOR_SET, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, lines, literal


def _needs_robot(item: dict) -> bool:
    return "matrix" not in item


def _check(ql, path, item, q):
    if "matrix" in item and "frame" in item:
        ql.chk.error(path, "give either matrix or frame (with at), not both")

ZYZ = "the ZYZ Euler angles, $R = R_z(\\varphi)\\,R_y(\\theta)\\,R_z(\\psi)$"
RPY = "the roll-pitch-yaw angles, $R = R_z(\\mathrm{yaw})\\,R_y(\\mathrm{pitch})\\,R_x(\\mathrm{roll})$"
WORDS = {
    "zyz": ZYZ + " (every solution, and whether R is a singularity of them)",
    "zyz.solutions": ZYZ + " (every solution)",
    "zyz.singular": "whether R is a singularity of the ZYZ Euler angles",
    "rpy": RPY + " (every solution, and whether R is a singularity of them)",
    "rpy.solutions": RPY + " (every solution)",
    "rpy.singular": "whether R is a singularity of the roll-pitch-yaw angles",
    "axis_angle": "the axis and the angle of the rotation (angle in $[0, \\pi]$)",
    "axis_angle.axis": "the unit axis of the rotation (its angle taken in $[0, \\pi]$)",
    "axis_angle.angle": "the angle of the rotation, in $[0, \\pi]$",
    "quaternion": "the unit quaternion $[\\eta, \\varepsilon_x, \\varepsilon_y, \\varepsilon_z]$ with $\\eta \\ge 0$",
}


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the matrix or the frame at `at`, then what the
    question grades (the Euler and roll-pitch-yaw angles, the axis and angle, the quaternion)."""
    if "matrix" in q.options:
        what = f"the rotation matrix $R = $ {say.math(q.options['matrix'])}"
    else:
        at = say.at(q)
        what = f"the orientation $R$ of {say.frame(q)} in frame 0" + (f" {at}" if at else "")
    return f"For {what}, give {listing(asked(q, say, WORDS))}."


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
    if not want:                                  # a joint or a value is not given: the matrix
        return lines(f"at = {at_literal(q)}", f"R = {source}[:3, :3].subs(robot.values(at))", "show(R)")
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
        _k("quaternion", VECTOR, "[η, εx, εy, εz], η ≥ 0", principal=True, shape=(4,), quaternion=True),
    ),
    cost=0.1,
    check=_check, needs_joints=False,
    notebook_cells=notebook_cell,
)
