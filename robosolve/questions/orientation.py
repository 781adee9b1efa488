"""The `orientation` question type (Orientation representations): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import BOOL, RECORD, SCALAR, VECTOR, VECTOR_SET, QuestionType, _k


def _needs_robot(item: dict) -> bool:
    return "matrix" not in item


def _check(ql, path, item, q):
    if "matrix" in item and "frame" in item:
        ql.chk.error(path, "give either matrix or frame (with at), not both")


TYPE = QuestionType(
    "orientation", "Orientation representations", "§5.6",
    options={"matrix": V.v_rotation_matrix},
    needs_robot=_needs_robot,
    answers=(
        _k("zyz", RECORD, "R = Rz(φ)·Ry(θ)·Rz(ψ)", principal=True, fields=(
            _k("solutions", VECTOR_SET, "[φ, θ, ψ] solution sets", shape=(3,), angle=True,
               unordered=True),
            _k("singular", BOOL, "at a singularity"))),
        _k("rpy", RECORD, "R = Rz(yaw)·Ry(pitch)·Rx(roll)", principal=True, fields=(
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
)
