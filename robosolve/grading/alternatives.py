"""The values a mistake gives, when it needs the robot (grading.md "Diagnosis"):

- `dh_convention`: the pose (and the point built from it) with every DH row read in the
  other convention (standard rows as modified, modified as standard);
- `end_effector_frame`: a vector or the geometric Jacobian expressed in the question's
  frame instead of frame 0: Rᵀ·v, blockdiag(Rᵀ, Rᵀ)·J with R = ⁰R of that frame.

`alternatives(report)` computes them once per problem, symbolically (no simplification),
beside the reference answers: question id -> key -> diagnosis -> value (the layout of the
symbolic answer). The grader reads and evaluates them like the expected value.
"""

from __future__ import annotations

import copy

import sympy as sp

from robosolve.questions.registry import question_type


def alternatives(report) -> dict:
    model = report.model
    if model is None:
        return {}
    problem = report.problem
    other = _other_convention(problem)
    out: dict = {}
    for q, a in zip(problem.questions, report.answers):
        if a.error is not None:
            continue
        qt = question_type(q.type)
        frame = q.frame or problem.last_frame
        for ak in qt.answers:
            value = a.symbolic.get(ak.name)
            if value is None:
                continue
            alt = {}
            if ak.dh_built and other is not None:
                alt["dh_convention"] = _dh_value(other, ak.dh_built, frame, q.point, value)
            if ak.in_frame0 and frame in model.frames:
                alt["end_effector_frame"] = _in_frame(model.M0(frame)[:3, :3].T, value)
            alt = {d: v for d, v in alt.items() if v is not None}
            if alt:
                out.setdefault(q.id, {})[ak.name] = alt
    return out


def _other_convention(problem):
    """The robot with every DH row read in the other convention (None: no DH row)."""
    from robosolve.model.chain import RobotModel

    frames = [f for f in problem.frames.values() if f.kind in ("dh", "mdh")] \
        if isinstance(problem.frames, dict) else []
    if not frames:
        return None
    other = copy.copy(problem)
    other.frames = dict(problem.frames)
    for f in frames:
        g = copy.copy(f)
        if f.kind == "dh":        # (theta, d, a, alpha) read as Rx(alpha) Tx(a) Rz(theta) Tz(d)
            th, d, a, al = f.factors
            g.kind, g.factors = "mdh", [al, a, th, d]
        else:                     # (alpha, a, theta, d) read as Rz(theta) Tz(d) Tx(a) Rx(alpha)
            al, a, th, d = f.factors
            g.kind, g.factors = "dh", [th, d, a, al]
        other.frames[f.name] = g
    try:
        return RobotModel(other)
    except Exception:  # noqa: BLE001 - a diagnosis must never stop grading
        return None


def _dh_value(model, built: str, frame: str, point: str, value):
    try:
        if built == "pose":
            return model.M0(frame) if frame != "0" else None
        p = model.point0(point)
        return list(p)[:len(value)] if isinstance(value, list) else p
    except Exception:  # noqa: BLE001
        return None


def _in_frame(Rt: sp.Matrix, value):
    """Rᵀ·v for a 3-vector, blockdiag(Rᵀ, Rᵀ)·J for a 6-row matrix; None otherwise."""
    m = sp.Matrix(value) if isinstance(value, (list, tuple, sp.MatrixBase)) else None
    if m is None:
        return None
    if m.shape == (3, 1) or m.shape == (1, 3):
        out = Rt * m.reshape(3, 1)
        return list(out) if isinstance(value, (list, tuple)) else out
    if m.shape[0] == 6:
        return sp.diag(Rt, Rt) * m
    return None
