"""Rigid displacements and their helical (screw) axis (seed §3.1.3-3.1.6 as
corrected as in docs/course-notes.md#note-helical-axis).

A body moves from pose M01 to pose M02 (both in frame 0).  The displacement
matrix Q0 = M02 * M01^-1 maps the initial position of any body point to its
final one, both in frame 0: P2 = Q0 * P1 (item 22).  In another frame k,
Qk = M0k^-1 * Q0 * M0k (item 24).

Mozzi-Chasles: Q = [R, dT; 0, 1] is a rotation by alpha about an axis of
direction u through a point P*, plus a translation h along it:

    R  = I + sin(alpha) [u] + (1 - cos alpha) [u]^2      (Rodrigues)
    dT = (I - R) P* + h u

with alpha in [0, pi] (sin alpha >= 0 fixes the sign of u), h = u . dT,
P* the point of the axis nearest the origin (P* . u = 0)

    P* = (I - R^T) dT / (2 (1 - cos alpha))              (item 31, alpha != 0)
       = (dT_perp + cot(alpha/2) u x dT) / 2             (same, no cancellation)

and pitch = h / alpha.  A pure translation has alpha = 0, u = dT/|dT|,
h = |dT| and no P* or pitch; the identity has no axis at all.

`helical_numeric` works in floats and is robust at alpha = 0, alpha = pi and for
tiny angles (1e-9 rad keeps full relative precision); `helical_symbolic` keeps
sympy expressions and decides the special cases exactly when the rotation has
no free symbols.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import sympy as sp

from robosolve.core.simplify import exact_geometry, full, is_zero
from robosolve.core.transforms import rigid_inverse, skew
from robosolve.geometry.rotations import ZERO_TOL, axis_angle_numeric, axis_angle_symbolic, axis_angle_matrix

__all__ = [
    "HelicalAxis", "displacement_matrix", "express_in_frame",
    "helical_numeric", "helical_symbolic", "helical_matrix", "axis_l_matrix",
]


@dataclass(frozen=True)
class HelicalAxis:
    """The helical axis of a displacement Q.

    ``case``:
      * ``"identity"``  - Q = I: no motion, no axis (u, P, pitch are None);
      * ``"translation"`` - alpha = 0: u = dT/|dT|, h = |dT|, P and pitch None;
      * ``"general"``   - 0 < alpha < pi: u = vex(R - R^T)/(2 sin alpha);
      * ``"half_turn"`` - alpha = pi: u from the symmetric part of R (its
        first non-zero component positive, since u and -u are the same
        displacement);
      * ``"generic"``   - symbolic rotation: the general formulas, valid where
        sin(alpha) != 0 (see ``notes``).
    """

    case: str
    R: Any                # 3x3 (sympy Matrix or nested float lists)
    dT: Any               # 3-vector
    cos_alpha: Any
    sin_alpha: Any
    axis: Any             # u or None
    angle: Any            # alpha
    h: Any
    point: Any            # P* or None
    pitch: Any            # h / alpha or None
    notes: list = field(default_factory=list)


# --------------------------------------------------------------------------
# Q from poses


def _is_numeric_array(m) -> bool:
    return isinstance(m, np.ndarray) or (
        not isinstance(m, sp.MatrixBase)
        and all(isinstance(x, (int, float, np.floating, np.integer))
                for x in np.asarray(m, dtype=object).ravel())
    )


def displacement_matrix(m01, m02):
    """Q0 = M02 * M01^-1: the displacement from pose M01 to pose M02, in frame 0.

    numpy in, numpy out; anything else is treated as sympy.
    """
    if _is_numeric_array(m01) and _is_numeric_array(m02):
        a = np.asarray(m01, dtype=float)
        b = np.asarray(m02, dtype=float)
        inv = np.eye(4)
        inv[:3, :3] = a[:3, :3].T
        inv[:3, 3] = -a[:3, :3].T @ a[:3, 3]
        return b @ inv
    return sp.Matrix(m02) * rigid_inverse(sp.Matrix(m01))


def express_in_frame(q0, m0k):
    """Qk = M0k^-1 * Q0 * M0k: the same displacement written in frame k (item 24)."""
    if _is_numeric_array(q0) and _is_numeric_array(m0k):
        m = np.asarray(m0k, dtype=float)
        inv = np.eye(4)
        inv[:3, :3] = m[:3, :3].T
        inv[:3, 3] = -m[:3, :3].T @ m[:3, 3]
        return inv @ np.asarray(q0, dtype=float) @ m
    m = sp.Matrix(m0k)
    return rigid_inverse(m) * sp.Matrix(q0) * m


# --------------------------------------------------------------------------
# Q -> helical axis


def helical_numeric(q, tol: float = ZERO_TOL) -> HelicalAxis:
    """Helical axis of a numeric 4x4 displacement (floats out; robust)."""
    a = np.asarray(q, dtype=float)
    if a.shape != (4, 4):
        raise ValueError(f"expected a 4x4 matrix, got shape {a.shape}")
    r, dt = a[:3, :3], a[:3, 3]
    aa = axis_angle_numeric(r, tol)
    base = dict(R=r.tolist(), dT=(dt + 0.0).tolist(), cos_alpha=aa.cos_angle, sin_alpha=aa.sin_angle)
    if aa.case == "zero":
        n = float(np.linalg.norm(dt))
        if n <= tol:
            return HelicalAxis("identity", **base, axis=None, angle=0.0, h=0.0, point=None,
                               pitch=None, notes=["Q = I: no displacement, the axis is undefined"])
        return HelicalAxis("translation", **base, axis=(dt / n + 0.0).tolist(), angle=0.0, h=n,
                           point=None, pitch=None,
                           notes=["pure translation: alpha = 0, u = dT/|dT|, no axis point, infinite pitch"])
    u = np.asarray(aa.axis)
    alpha = aa.angle
    h = float(u @ dt)
    perp = dt - h * u
    if aa.case == "half_turn":
        p = 0.5 * perp
    else:
        # cot(alpha/2) u x dT: no 1 - cos(alpha) cancellation for small alpha.
        p = 0.5 * (perp + np.cross(u, dt) / math.tan(alpha / 2.0))
    return HelicalAxis(aa.case, **base, axis=(u + 0.0).tolist(), angle=alpha, h=h,
                       point=(p + 0.0).tolist(), pitch=h / alpha)


#: The few small exact expressions of one helical axis: the policy's blanket variant.
_default_simplify = full


def _sympy_floats(v):
    if isinstance(v, float):
        return sp.Float(v)
    if isinstance(v, list):
        return [_sympy_floats(x) for x in v]
    return v


def helical_symbolic(q, simplify: Callable | None = None) -> HelicalAxis:
    """Helical axis of a sympy 4x4 displacement, with the course's formulas.

    cos(alpha) = (tr R - 1)/2, sin(alpha) = |vex(R - R^T)|/2,
    u = vex(R - R^T)/(2 sin alpha) (or the symmetric part at alpha = pi),
    h = u . dT, P* = (I - R^T) dT/(2 (1 - cos alpha)), pitch = h/alpha.
    """
    m = sp.Matrix(q)
    if m.shape != (4, 4):
        raise ValueError(f"expected a 4x4 matrix, got shape {m.shape}")
    if not m.free_symbols and m.atoms(sp.Float):
        # numbers, some of them decimals: the numeric axis (its tolerances hold at round-off)
        hx = helical_numeric(np.array(m, dtype=float))
        return HelicalAxis(hx.case, m[:3, :3], m[:3, 3], *(_sympy_floats(getattr(hx, k)) for k in (
            "cos_alpha", "sin_alpha", "axis", "angle", "h", "point", "pitch")), list(hx.notes))
    if simplify is None:
        # decimals beside symbols (a configuration in decimals, the lengths kept): the bounded
        # geometric simplification — a blanket simplify of such entries takes minutes
        simplify = exact_geometry if m.atoms(sp.Float) else _default_simplify
    r, dt = m[:3, :3], m[:3, 3]
    aa = axis_angle_symbolic(r, simplify)
    base = dict(R=r, dT=dt, cos_alpha=aa.cos_angle, sin_alpha=aa.sin_angle)
    if aa.case == "zero":
        n = simplify(sp.sqrt(dt.dot(dt)))
        if is_zero(n):
            return HelicalAxis("identity", **base, axis=None, angle=sp.Integer(0), h=sp.Integer(0),
                               point=None, pitch=None,
                               notes=["Q = I: no displacement, the axis is undefined"])
        notes = ["pure translation: alpha = 0, u = dT/|dT|, no axis point, infinite pitch"]
        if dt.free_symbols:
            notes.append("assumes dT != 0")
        return HelicalAxis("translation", **base, axis=[simplify(x / n) for x in dt],
                           angle=sp.Integer(0), h=n, point=None, pitch=None, notes=notes)
    u = sp.Matrix(aa.axis)
    h = simplify(u.dot(dt))
    p = ((sp.eye(3) - r.T) * dt / (2 * (1 - aa.cos_angle))).applyfunc(simplify)
    pitch = simplify(h / aa.angle)
    notes = ["valid where sin(alpha) != 0"] if aa.case == "generic" else []
    return HelicalAxis(aa.case, **base, axis=list(u), angle=aa.angle, h=h, point=list(p),
                       pitch=pitch, notes=notes)


# --------------------------------------------------------------------------
# helical axis -> Q, and the infinitesimal L matrix


def helical_matrix(u, alpha, h, point=None) -> sp.Matrix:
    """Q from the helical parameters: R by Rodrigues, dT = (I - R) P* + h u (seed §3.1.5)."""
    u = sp.Matrix(list(u))
    r = axis_angle_matrix(u, alpha)
    p = sp.zeros(3, 1) if point is None else sp.Matrix(list(point))
    out = sp.eye(4)
    out[:3, :3] = r
    out[:3, 3] = (sp.eye(3) - r) * p + h * u
    return out


def axis_l_matrix(u, point=None, pitch=0) -> sp.Matrix:
    """L = [[u], t; 0 0 0 0] of a screw axis, t = P* x u + pitch * u (item 35).

    ``pitch=None`` means a pure translation along u: L = [0, u; 0, 0].
    Q(d alpha) = I + d alpha * L for an infinitesimal motion.
    """
    u = sp.Matrix(list(u))
    out = sp.zeros(4, 4)
    if pitch is None:
        out[:3, 3] = u
        return out
    p = sp.zeros(3, 1) if point is None else sp.Matrix(list(point))
    out[:3, :3] = skew(list(u))
    out[:3, 3] = p.cross(u) + pitch * u
    return out


# --------------------------------------------------------------------------
# a screw (axis, angle, point, translation) -> its normalised helical parameters


@dataclass(frozen=True)
class Screw:
    """A screw normalised as the from/to form gives it from Q (so the two forms round-trip).

    ``case``: "general" (0 < alpha < pi), "half_turn" (alpha = pi), "translation"
    (alpha = 0, h > 0) or "identity" (alpha = 0, h = 0).  u, P, pitch are None where the
    spec makes them null.  ``flipped``: the given angle was brought into [0, pi] by
    turning u around (a negative angle, or one beyond pi).
    """

    case: str
    axis: Any
    angle: Any
    h: Any
    point: Any
    pitch: Any
    flipped: bool = False
    turns: Any = 0            # whole turns removed from the given angle


def _first_nonzero_positive(u, values) -> bool:
    for x in u:
        v = float(sp.sympify(x).xreplace(values))
        if abs(v) > ZERO_TOL:
            return v > 0
    return True


def normalise_screw(axis, angle, through=None, translation=0, values=None,
                    simplify: Callable = _default_simplify) -> Screw:
    """The screw of ``axis`` (any non-zero length), ``angle`` (any real value), a point
    ``through`` of the axis (default the origin) and ``translation`` h along the given axis.

    The branch (how many turns, whether u flips) is decided from the numbers: ``values``
    gives the parameters' values (symbols without one are an error: ValueError).
    Exact data give exact results.
    """
    values = values or {}
    a = sp.Matrix([sp.sympify(x) for x in axis])
    norm = simplify(sp.sqrt(a.dot(a)))
    if abs(float(norm.xreplace(values))) <= ZERO_TOL:
        raise ValueError("the axis is the zero vector")
    u0 = [simplify(x / norm) for x in a]
    p0 = sp.Matrix([sp.sympify(x) for x in (through or (0, 0, 0))])
    h0 = sp.sympify(translation)
    theta = sp.sympify(angle)
    two_pi = 2 * sp.pi
    turns = sp.floor(theta.xreplace(values) / two_pi)
    if not turns.is_number:
        raise ValueError("the angle needs a value")
    turns = sp.Integer(int(turns))
    wrapped = simplify(theta - two_pi * turns)             # in [0, 2 pi)
    w = float(wrapped.xreplace(values))
    flipped = w > math.pi + 1e-15
    if flipped:
        alpha, u, h = simplify(two_pi - wrapped), [-x for x in u0], -h0
    else:
        alpha, u, h = wrapped, u0, h0
    if abs(float(sp.sympify(alpha).xreplace(values))) <= ZERO_TOL and sp.sympify(alpha).is_zero is not False:
        hv = float(h.xreplace(values))
        if abs(hv) <= ZERO_TOL:
            return Screw("identity", None, sp.S.Zero, sp.S.Zero, None, None, flipped, turns)
        if hv < 0:
            u, h = [-x for x in u], -h
        return Screw("translation", [simplify(x) for x in u], sp.S.Zero, simplify(h), None, None,
                     flipped, turns)
    case = "general"
    if abs(float(sp.sympify(alpha).xreplace(values)) - math.pi) <= ZERO_TOL:
        case = "half_turn"
        if not _first_nonzero_positive(u, values):
            u, h = [-x for x in u], -h
    uu = sp.Matrix(u)
    point = [simplify(x) for x in (p0 - p0.dot(uu) * uu)]  # the axis point nearest the origin
    h = simplify(h)
    return Screw(case, [simplify(x) for x in u], simplify(alpha), h, point, simplify(h / alpha),
                 flipped, turns)


def screw_matrices(screw: Screw, simplify: Callable = _default_simplify):
    """(Q, L) of a normalised screw: Q by Rodrigues with dT = (I - R) P* + h u, and
    L = [[u], P* x u + pitch u; 0, 0] (so Q = expm(alpha L); a pure translation:
    L = [0, u; 0, 0] and Q = expm(h L); the identity: L = 0)."""
    if screw.case == "identity":
        return sp.eye(4), sp.zeros(4, 4)
    if screw.case == "translation":
        q = sp.eye(4)
        q[:3, 3] = sp.Matrix(screw.axis) * screw.h
        return q.applyfunc(simplify), axis_l_matrix(screw.axis, None, None)
    q = helical_matrix(screw.axis, screw.angle, screw.h, screw.point)
    return q.applyfunc(simplify), axis_l_matrix(screw.axis, screw.point, screw.pitch).applyfunc(simplify)
