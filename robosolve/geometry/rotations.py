"""Rotation representations: ZYZ Euler angles, roll-pitch-yaw, axis-angle and
unit quaternion (seed §5.6, docs/course-notes.md#note-orientation).

Conventions (the spec's "Orientation" layout):

* ZYZ: R = Rz(phi) Ry(theta) Rz(psi), returned as [phi, theta, psi].
  First solution theta in [0, pi], second theta' = -theta (phi and psi move by
  pi).  Singular when sin(theta) = 0: theta = 0 fixes only phi + psi, theta = pi
  only phi - psi; one representative is returned with psi = 0.
* RPY: R = Rz(yaw) Ry(pitch) Rx(roll), returned as [roll, pitch, yaw].
  First solution pitch in [-pi/2, pi/2], second pitch' = pi - pitch (roll and
  yaw move by pi).  Singular when cos(pitch) = 0: pitch = +pi/2 fixes only
  roll - yaw, pitch = -pi/2 only roll + yaw; the representative has yaw = 0.
* Every angle is wrapped into (-pi, pi].
* Axis-angle: angle alpha in [0, pi] with sin(alpha) >= 0, which fixes the sign
  of the axis u.  alpha = 0: the axis is undefined (None).  alpha = pi: u and -u
  are the same rotation; the one whose first non-zero component is positive is
  returned.
* Unit quaternion [eta, eps_x, eps_y, eps_z] = [cos(alpha/2), sin(alpha/2) u]
  with eta >= 0 (q and -q are the same rotation).

Two families of functions: ``*_numeric`` take anything numpy can turn into a
float array and return floats, robust at every special case (alpha = 1e-9,
alpha = pi, gimbal lock); ``*_symbolic`` take a sympy Matrix (exact numbers or
symbols) and return sympy expressions, deciding the special cases exactly when
the matrix has no free symbols.  Both accept a 3x3 rotation or a 4x4 pose.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import sympy as sp

from robosolve.core.angles import wrap_angle
from robosolve.core.simplify import exact_geometry, is_zero
from robosolve.core.opcount import count_ops

__all__ = [
    "SINGULAR_TOL", "ZERO_TOL",
    "AxisAngle", "EulerAngles",
    "axis_angle_numeric", "axis_angle_symbolic",
    "zyz_numeric", "zyz_symbolic", "rpy_numeric", "rpy_symbolic",
    "quaternion_numeric", "quaternion_symbolic",
    "zyz_matrix", "rpy_matrix", "axis_angle_matrix", "quaternion_matrix",
    "wrap_angle", "canonical_sign",
]

#: |sin(theta)| (ZYZ) or |cos(pitch)| (RPY) below which a matrix is singular.
SINGULAR_TOL = 1e-9
#: |sin(alpha)| below which a rotation counts as alpha = 0 or alpha = pi.
#: Far below 1e-9 so that a genuine rotation of 1e-9 rad is still a rotation.
ZERO_TOL = 1e-12


# --------------------------------------------------------------------------
# results


@dataclass(frozen=True)
class AxisAngle:
    """Axis-angle of a rotation.

    ``case`` is ``"zero"`` (alpha = 0, axis None), ``"general"``
    (0 < alpha < pi, u = vex(R - R^T) / (2 sin alpha)), ``"half_turn"``
    (alpha = pi, u from the symmetric part (R + R^T)/2) or, for a matrix with
    free symbols, ``"generic"`` (the general formulas, valid where
    sin(alpha) != 0).  ``cos_angle``/``sin_angle`` are the quantities the
    formulas start from: cos(alpha) = (tr R - 1)/2 and
    sin(alpha) = |vex(R - R^T)|/2 (course-notes#note-helical-axis).
    """

    axis: Any            # [ux, uy, uz] or None
    angle: Any
    case: str
    cos_angle: Any
    sin_angle: Any


@dataclass(frozen=True)
class EulerAngles:
    """A three-angle representation (ZYZ or RPY).

    ``solutions``: two lists of three angles, or one representative at a
    singularity.  ``singular``: True/False, or None for a symbolic matrix whose
    singularity depends on the symbols (then ``condition`` must be non-zero for
    the two solutions to hold).  ``family`` at a singularity: (combination,
    value), e.g. ("phi + psi", pi/3): every triple with that combination
    equal to that value gives the same matrix.
    """

    solutions: list
    singular: bool | None
    family: tuple | None = None
    condition: Any = None
    notes: list = field(default_factory=list)


# --------------------------------------------------------------------------
# helpers


def _atan2(y: float, x: float) -> float:
    # +0.0 turns -0.0 into +0.0, so atan2(-0.0, -1) gives pi, not -pi.
    a = math.atan2(float(y) + 0.0, float(x) + 0.0)
    return math.pi if a <= -math.pi else a + 0.0


def canonical_sign(v, tol: float = 1e-9):
    """Return v or -v so that its first non-zero component (|x| > tol*max) is positive.

    Works on float sequences and on sympy matrices with exact entries.
    """
    if isinstance(v, sp.MatrixBase):
        vals = [float(sp.N(x)) for x in v]
        big = max(abs(x) for x in vals) if vals else 0.0
        for x in vals:
            if abs(x) > tol * big:
                return v if x > 0 else -v
        return v
    arr = np.asarray(v, dtype=float)
    big = float(np.max(np.abs(arr))) if arr.size else 0.0
    for x in arr:
        if abs(x) > tol * big:
            return arr if x > 0 else -arr
    return arr


def _rot3_numeric(m) -> np.ndarray:
    a = np.asarray(m, dtype=float)
    if a.shape == (4, 4):
        a = a[:3, :3]
    if a.shape != (3, 3):
        raise ValueError(f"expected a 3x3 or 4x4 matrix, got shape {a.shape}")
    return a


def _rot3_symbolic(m) -> sp.Matrix:
    a = sp.Matrix(m)
    if a.shape == (4, 4):
        a = a[:3, :3]
    if a.shape != (3, 3):
        raise ValueError(f"expected a 3x3 or 4x4 matrix, got shape {a.shape}")
    return a


def _inexact(r: sp.Matrix) -> bool:
    """A matrix of numbers some of them floats: its angles come from the numeric functions (as
    sympy Floats), whose tolerances hold at round-off; the exact route would square entries
    and drop what the simplification takes for round-off (a rotation of 1e-7 rad read as none)."""
    return not r.free_symbols and bool(r.atoms(sp.Float))


def _as_sympy(value):
    """A numeric result with its floats as sympy Floats (lists and tuples kept as such)."""
    if isinstance(value, float):
        return sp.Float(value)
    if isinstance(value, (list, tuple)):
        return type(value)(_as_sympy(v) for v in value)
    return value


def _euler_as_sympy(e: "EulerAngles") -> "EulerAngles":
    return EulerAngles(_as_sympy(e.solutions), e.singular, _as_sympy(e.family), e.condition, list(e.notes))


#: The simplification of every symbolic quantity here: the policy's `exact_geometry`
#: variant (exact numbers fully, small expressions with trigsimp, large ones untouched).
_default_simplify = exact_geometry


def _num(e) -> float:
    return float(sp.N(e, 30))


def _positive_unit(e) -> bool:
    """For an entry known to be +1 or -1 (a singular rotation): True when it is +1."""
    if not sp.sympify(e).free_symbols:
        return _num(e) > 0
    if is_zero(e - 1):
        return True
    if is_zero(e + 1):
        return False
    raise ValueError(f"cannot decide the sign of {e} (expected +1 or -1)")


def _sym_angle(y, x, simplify):
    """atan2(y, x) for sympy expressions (exact when sympy can evaluate it)."""
    y, x = sp.sympify(y), sp.sympify(x)
    if y.free_symbols or x.free_symbols:
        return sp.atan2(simplify(y), simplify(x))
    return simplify(sp.atan2(y, x))


# --------------------------------------------------------------------------
# axis-angle


def axis_angle_numeric(m, tol: float = ZERO_TOL) -> AxisAngle:
    """Axis u and angle alpha in [0, pi] of a numeric rotation (robust).

    alpha = atan2(|v|, (tr R - 1)/2) with v = vex(R - R^T)/2 = sin(alpha) u keeps
    full relative precision for tiny angles (cos alpha alone would round to 1).
    For alpha >= pi/2 the axis comes from the symmetric part
    (R + R^T)/2 - cos(alpha) I = (1 - cos alpha) u u^T (well conditioned near pi)
    and its sign from v.
    """
    r = _rot3_numeric(m)
    v = 0.5 * np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    s = float(np.linalg.norm(v))
    c = float(min(1.0, max(-1.0, (np.trace(r) - 1.0) / 2.0)))
    alpha = math.atan2(s, c)
    if s <= tol and c > 0:
        return AxisAngle(None, 0.0, "zero", c, s)
    if c > 0:
        return AxisAngle((v / s).tolist(), alpha, "general", c, s)
    b = 0.5 * (r + r.T) - c * np.eye(3)
    k = int(np.argmax(np.diag(b)))
    u = b[:, k] / math.sqrt(max(b[k, k], 0.0) * (1.0 - c))
    u = u / np.linalg.norm(u)
    d = float(u @ v)
    if s <= tol:
        u = canonical_sign(u)
        return AxisAngle((u + 0.0).tolist(), math.pi, "half_turn", -1.0, 0.0)
    if d < 0:
        u = -u
    return AxisAngle((u + 0.0).tolist(), alpha, "general", c, s)


def axis_angle_symbolic(m, simplify: Callable = _default_simplify) -> AxisAngle:
    """Axis-angle of a sympy rotation matrix (course-notes#note-helical-axis).

    cos(alpha) = (tr R - 1)/2, sin(alpha) = |vex(R - R^T)|/2 >= 0 and
    u = vex(R - R^T)/(2 sin alpha); at alpha = pi (exact matrices only)
    u_i^2 = (R_ii + 1)/2 and u_i u_j = (R_ij + R_ji)/4.
    """
    r = _rot3_symbolic(m)
    if _inexact(r):
        aa = axis_angle_numeric(np.array(r, dtype=float))
        return AxisAngle(_as_sympy(aa.axis), _as_sympy(aa.angle), aa.case, _as_sympy(aa.cos_angle),
                         _as_sympy(aa.sin_angle))
    c = simplify((r.trace() - 1) / 2)
    v = (r - r.T) / 2
    v = sp.Matrix([v[2, 1], v[0, 2], v[1, 0]])
    s2 = simplify(1 - c**2)  # = |v|^2 for a rotation; far cheaper to simplify
    if is_zero(s2):
        if is_zero(c - 1):
            return AxisAngle(None, sp.Integer(0), "zero", sp.Integer(1), sp.Integer(0))
        if is_zero(c + 1) and r.free_symbols:
            raise ValueError("a half-turn about a symbolic axis: give numeric values")
        if is_zero(c + 1):
            d = [simplify((r[i, i] + 1) / 2) for i in range(3)]
            k = max(range(3), key=lambda i: (_num(d[i]), -i))
            uk = simplify(sp.sqrt(d[k]))
            u = sp.Matrix([uk if i == k else simplify((r[i, k] + r[k, i]) / (4 * uk))
                           for i in range(3)])
            u = canonical_sign(u)
            return AxisAngle(list(u), sp.pi, "half_turn", sp.Integer(-1), sp.Integer(0))
        raise ValueError("not a rotation matrix: R - R^T = 0 but trace(R) is neither 3 nor -1")
    s = simplify(sp.sqrt(s2))
    alpha = _sym_angle(s, c, simplify)
    if not r.free_symbols:  # alpha in [0, pi]: acos(cos alpha) is as valid; keep the shorter
        alpha = min((alpha, sp.acos(c)), key=lambda e: (count_ops(e), sp.default_sort_key(e)))
    u = [simplify(x / s) for x in v]
    case = "generic" if r.free_symbols else "general"
    return AxisAngle(u, alpha, case, c, s)


def axis_angle_matrix(u, alpha) -> sp.Matrix:
    """Rodrigues: R = I + sin(alpha) [u] + (1 - cos alpha) [u]^2 (seed §3.1.5)."""
    from robosolve.core.transforms import skew

    uu = skew(list(u))
    return sp.eye(3) + sp.sin(alpha) * uu + (1 - sp.cos(alpha)) * uu * uu


# --------------------------------------------------------------------------
# quaternion


def quaternion_numeric(m) -> list[float]:
    """[eta, eps_x, eps_y, eps_z], eta >= 0, from the robust axis-angle."""
    aa = axis_angle_numeric(m)
    if aa.case == "zero":
        return [1.0, 0.0, 0.0, 0.0]
    half = aa.angle / 2.0
    return [math.cos(half)] + [math.sin(half) * x + 0.0 for x in aa.axis]


def quaternion_symbolic(m, simplify: Callable = _default_simplify) -> list:
    """eta = sqrt(1 + tr R)/2 = cos(alpha/2) and eps = vex(R - R^T)/(4 eta) = sin(alpha/2) u.

    At alpha = pi (eta = 0) eps = u from `axis_angle_symbolic`.
    """
    r = _rot3_symbolic(m)
    if _inexact(r):
        return _as_sympy(quaternion_numeric(np.array(r, dtype=float)))
    eta = sp.sqrt(simplify(1 + r.trace())) / 2
    if is_zero(eta) and not r.free_symbols:
        aa = axis_angle_symbolic(r, simplify)
        return [sp.Integer(0)] + list(aa.axis)
    eps = [simplify((r[2, 1] - r[1, 2]) / (4 * eta)),
           simplify((r[0, 2] - r[2, 0]) / (4 * eta)),
           simplify((r[1, 0] - r[0, 1]) / (4 * eta))]
    return [eta] + eps


def quaternion_matrix(q) -> sp.Matrix:
    """Rotation of a unit quaternion [eta, ex, ey, ez]."""
    eta, ex, ey, ez = [sp.sympify(x) for x in q]
    eps = sp.Matrix([ex, ey, ez])
    from robosolve.core.transforms import skew

    e = skew([ex, ey, ez])
    return (eta**2 - eps.dot(eps)) * sp.eye(3) + 2 * eps * eps.T + 2 * eta * e


# --------------------------------------------------------------------------
# ZYZ Euler angles


def _locked(gamma, middle, combination: str, zero=0.0) -> EulerAngles:
    """The singular case of a convention: one set in which only `combination` of the two outer
    angles is fixed (= gamma, put in the first angle, the last one 0)."""
    return EulerAngles([[gamma, middle, zero]], True, (combination, gamma))


def _gimbal_lock_numeric(pivot: float, plus, minus) -> EulerAngles:
    """The singular case of a numeric rotation: `pivot` is the entry that is +1 or -1 there;
    `plus` / `minus` = (y, x, middle angle, combination) for each sign, gamma = atan2(y, x)."""
    y, x, middle, combination = plus if pivot > 0 else minus
    return _locked(_atan2(y, x), middle, combination)


def _gimbal_lock_symbolic(pivot, plus, minus, simplify) -> EulerAngles:
    """`_gimbal_lock_numeric` for a sympy rotation: gamma exact and wrapped to (-pi, pi]."""
    y, x, middle, combination = plus if _positive_unit(pivot) else minus
    return _locked(wrap_angle(_sym_angle(y, x, simplify)), middle, combination, sp.Integer(0))


def _two_sets_symbolic(s1, s2, exact: bool, factor, validity: str) -> EulerAngles:
    """The two regular solution sets of a sympy rotation: wrapped to (-pi, pi] when exact,
    else kept with the `factor` that must not vanish and where they are valid."""
    if exact:
        return EulerAngles([[wrap_angle(x) for x in s1], [wrap_angle(x) for x in s2]], False)
    return EulerAngles([s1, s2], None, None, factor, [validity])


def zyz_matrix(phi, theta, psi) -> sp.Matrix:
    """R = Rz(phi) Ry(theta) Rz(psi)."""
    from robosolve.core.transforms import rot_y, rot_z

    return (rot_z(phi) * rot_y(theta) * rot_z(psi))[:3, :3]


def zyz_numeric(m, tol: float = SINGULAR_TOL) -> EulerAngles:
    """ZYZ angles [phi, theta, psi] of a numeric rotation, both solution sets.

    theta = atan2(sqrt(r13^2 + r23^2), r33), phi = atan2(r23, r13),
    psi = atan2(r32, -r31); the second set uses -sqrt(...), i.e.
    phi' = atan2(-r23, -r13), psi' = atan2(-r32, r31).
    """
    r = _rot3_numeric(m)
    st = math.hypot(r[0, 2], r[1, 2])
    if st <= tol:   # theta = 0: R = Rz(phi + psi); theta = pi: R = Rz(phi - psi) Ry(pi)
        return _gimbal_lock_numeric(r[2, 2], (r[1, 0], r[0, 0], 0.0, "phi + psi"),
                                    (-r[0, 1], -r[0, 0], math.pi, "phi - psi"))
    theta = _atan2(st, r[2, 2])
    s1 = [_atan2(r[1, 2], r[0, 2]), theta, _atan2(r[2, 1], -r[2, 0])]
    s2 = [_atan2(-r[1, 2], -r[0, 2]), -theta + 0.0, _atan2(-r[2, 1], r[2, 0])]
    return EulerAngles([s1, s2], False)


def zyz_symbolic(m, simplify: Callable = _default_simplify) -> EulerAngles:
    """ZYZ angles of a sympy rotation; exact singular cases when there are no symbols."""
    def regular_sets(r, st, angle):
        theta = angle(st, r[2, 2])
        return ([angle(r[1, 2], r[0, 2]), theta, angle(r[2, 1], -r[2, 0])],
                [angle(-r[1, 2], -r[0, 2]), simplify(-theta), angle(-r[2, 1], r[2, 0])])

    def lock_cases(r):      # theta = 0 / theta = pi
        return (r[1, 0], r[0, 0], sp.Integer(0), "phi + psi"), (-r[0, 1], -r[0, 0], sp.pi, "phi - psi")

    # st = sin(theta) = sqrt(r13^2 + r23^2) = sqrt(1 - r33^2) (unit column)
    if _inexact(_rot3_symbolic(m)):
        return _euler_as_sympy(zyz_numeric(np.array(_rot3_symbolic(m), dtype=float)))
    return _euler_symbolic(m, (2, 2), 1, lock_cases, regular_sets, "valid where sin(theta) != 0", simplify)


def _euler_symbolic(m, pivot_at, pivot_sign, lock_cases, regular_sets, validity, simplify) -> EulerAngles:
    """The angles of a sympy rotation in one convention. The pivot, `pivot_sign` times the
    entry at `pivot_at`, is the middle angle's cosine or sine; the other one, `magnitude` =
    sqrt(1 - pivot^2), vanishes at the gimbal lock (`lock_cases(r)`: plus and minus cases of
    `_gimbal_lock_symbolic`); elsewhere `regular_sets(r, magnitude, angle)` gives the two sets."""
    r = _rot3_symbolic(m)
    entry = r[pivot_at]
    magnitude = sp.sqrt(simplify(1 - entry ** 2))
    if is_zero(magnitude):
        return _gimbal_lock_symbolic(pivot_sign * entry, *lock_cases(r), simplify)
    s1, s2 = regular_sets(r, magnitude, lambda y, x: _sym_angle(y, x, simplify))
    return _two_sets_symbolic(s1, s2, not r.free_symbols, magnitude, validity)


# --------------------------------------------------------------------------
# roll-pitch-yaw


def rpy_matrix(roll, pitch, yaw) -> sp.Matrix:
    """R = Rz(yaw) Ry(pitch) Rx(roll) (course-notes#note-orientation)."""
    from robosolve.core.transforms import rot_x, rot_y, rot_z

    return (rot_z(yaw) * rot_y(pitch) * rot_x(roll))[:3, :3]


def rpy_numeric(m, tol: float = SINGULAR_TOL) -> EulerAngles:
    """Roll-pitch-yaw [roll, pitch, yaw] of a numeric rotation, both solution sets.

    pitch = atan2(-r31, sqrt(r11^2 + r21^2)), yaw = atan2(r21, r11),
    roll = atan2(r32, r33); the second set uses -sqrt(...).
    """
    r = _rot3_numeric(m)
    cp = math.hypot(r[0, 0], r[1, 0])
    if cp <= tol:   # pitch = +pi/2: only roll - yaw is fixed; pitch = -pi/2: only roll + yaw
        return _gimbal_lock_numeric(-r[2, 0], (r[0, 1], r[1, 1], math.pi / 2, "roll - yaw"),
                                    (-r[0, 1], r[1, 1], -math.pi / 2, "roll + yaw"))
    pitch = _atan2(-r[2, 0], cp)
    s1 = [_atan2(r[2, 1], r[2, 2]), pitch, _atan2(r[1, 0], r[0, 0])]
    s2 = [_atan2(-r[2, 1], -r[2, 2]), _atan2(-r[2, 0], -cp), _atan2(-r[1, 0], -r[0, 0])]
    return EulerAngles([s1, s2], False)


def rpy_symbolic(m, simplify: Callable = _default_simplify) -> EulerAngles:
    """Roll-pitch-yaw of a sympy rotation; exact singular cases when there are no symbols."""
    def regular_sets(r, cp, angle):
        return ([angle(r[2, 1], r[2, 2]), angle(-r[2, 0], cp), angle(r[1, 0], r[0, 0])],
                [angle(-r[2, 1], -r[2, 2]), angle(-r[2, 0], -cp), angle(-r[1, 0], -r[0, 0])])

    def lock_cases(r):      # pitch = +pi/2 / pitch = -pi/2
        return ((r[0, 1], r[1, 1], sp.pi / 2, "roll - yaw"),
                (-r[0, 1], r[1, 1], -sp.pi / 2, "roll + yaw"))

    # cp = cos(pitch) = sqrt(r11^2 + r21^2) = sqrt(1 - r31^2) (unit column); -r31 = sin(pitch)
    if _inexact(_rot3_symbolic(m)):
        return _euler_as_sympy(rpy_numeric(np.array(_rot3_symbolic(m), dtype=float)))
    return _euler_symbolic(m, (2, 0), -1, lock_cases, regular_sets, "valid where cos(pitch) != 0", simplify)
