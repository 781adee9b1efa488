"""Names for singular conditions, found geometrically (numerically) at the condition.

Rules, checked at a representative configuration of the condition (the condition's
joint values, the other joints at fixed generic values, the parameters at their
values or at generic positive samples):

* the point lies on the axis of a revolute joint → "the point lies on the axis of
  joint i" (a shoulder singularity for an arm; for a polar robot d = 0 puts it on
  the axes of joints 1 and 2);
* two revolute axes coincide (not everywhere) → "the axes of joints i and j are
  aligned" (the wrist singularity of a spherical wrist);
* revolute axes that become parallel without meeting (not parallel in general) → "the axes
  of joints i and j are parallel" (an offset wrist, the UR family: s5 = 0 makes the axes of
  joints 4 and 6 parallel, not aligned);
* a revolute joint k of the condition sets the distance from the point to the axis
  of the previous revolute joint to its maximum → "arm stretched at joint k", to its
  minimum → "arm folded at joint k".
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from robosolve.core.numpy_code import numpy_modules
from robosolve.kinematics.singularities import Condition, _sample_params

__all__ = ["name_conditions"]

_GENERIC = (0.31, 0.57, 0.83, -0.44, 1.07, -0.71, 0.19, 0.93, -0.27, 0.66)


class _Geometry:
    """Numeric joint axes and point. The L matrices are either given (symbolic ⁰Lᵢ) or
    obtained by central differences of the frames' poses, L = ∂M/∂qᵢ·M⁻¹ (no symbolic
    simplification needed: naming is numeric)."""

    def __init__(self, joints, kinds, l_matrices, point, params, m0_frames=None):
        self.joints = list(joints)
        self.kinds = kinds
        mats_in = list(l_matrices) if l_matrices is not None else list(m0_frames)
        syms = set()
        for m in mats_in:
            syms |= sp.Matrix(m).free_symbols
        syms |= sp.Matrix(list(point)).free_symbols
        syms -= set(self.joints)
        self.params = _sample_params(syms, params)
        sub = {k: v for k, v in self.params.items()}
        # numbers for symbols: xreplace builds the same expressions as subs, without its search
        mats = [sp.Matrix(m).xreplace(sub) for m in mats_in]
        pt = sp.Matrix(list(point)).xreplace(sub)

        # the matrices and the point are evaluated by one function of a stack of configurations,
        # generated on first use (`_many`): generating code costs more than evaluating it
        self._mats, self._pt = mats, pt
        self._flat = None
        self._given_l = l_matrices is not None

    def _l(self, q):
        """Every joint's ⁰Lᵢ at q."""
        n = len(q)
        return list(self._l_at(np.tile(np.asarray(q, dtype=float), (n, 1)), range(n)))

    def _l_one(self, q, i):
        return self._l_at(np.asarray(q, dtype=float)[None, :], [i])[0]

    def _l_at(self, Q, joints, eps=1e-6):
        """⁰Lᵢ at each row of Q for that row's joint i (`joints`: one index per row): given, or
        Lᵢ = ∂Mᵢ/∂qᵢ·Mᵢ⁻¹ by a central difference in qᵢ alone — the poses at the rows and at the
        rows ± eps in their joint evaluated in one pass over the stack."""
        Q = np.asarray(Q, dtype=float)
        i = np.asarray(list(joints), dtype=int)
        r = np.arange(len(i))
        if self._given_l:
            return self._many(Q)[0][r, i]
        steps = np.zeros_like(Q)
        steps[r, i] = eps
        poses = self._many(np.vstack([Q, Q + steps, Q - steps]))[0]
        k = len(i)
        return (poses[k + r, i] - poses[2 * k + r, i]) / (2 * eps) @ np.linalg.inv(poses[r, i])

    def _axis_of(self, i, m):
        if self.kinds[self.joints[i]] != "revolute":
            return None
        u, a, n = _axis_from_l(np.asarray(m, dtype=float))
        return None if n < 1e-12 else (u, a)

    def axes(self, q):
        """(joint index, unit direction, a point on the axis) of each revolute joint."""
        out = []
        for i, m in enumerate(self._l(q)):
            axis = self._axis_of(i, m)
            if axis is not None:
                out.append((i, *axis))
        return out

    def axis(self, q, i):
        """(unit direction, a point on the axis) of joint i, or None (prismatic, or no axis)."""
        if self.kinds[self.joints[i]] != "revolute":
            return None
        return self._axis_of(i, self._l_one(q, i))

    def point(self, q):
        return self._many(np.asarray(q, dtype=float)[None, :])[1][0]

    # -- many configurations at once (rows of Q) ---------------------------------------------
    def _many(self, Q):
        """(the matrices, N x k x 4 x 4; the point, N x 3) at the rows of Q."""
        if self._flat is None:
            entries = [e for m in self._mats for e in m] + list(self._pt)
            self._flat = sp.lambdify([self.joints], entries, numpy_modules())
        N = Q.shape[0]
        vals = self._flat([Q[:, j] for j in range(Q.shape[1])])
        cols = np.stack([np.broadcast_to(np.asarray(v, dtype=float), (N,)) for v in vals], axis=1)
        k = len(self._mats)
        return cols[:, :16 * k].reshape(N, k, 4, 4), cols[:, 16 * k:]

    def axis_many(self, Q, i):
        """(directions, points), N x 3 each, of revolute joint i's axis at the rows of Q (None:
        prismatic), as `axis` computes it row by row."""
        if self.kinds[self.joints[i]] != "revolute":
            return None
        u, a, _n = _axis_from_l(self._l_at(Q, [i] * len(Q)))
        return u, a

    def point_many(self, Q):
        return self._many(Q)[1]


def _axis_from_l(m):
    """(unit direction, a point on the axis, the direction's norm) of a joint's ⁰L (..., 4, 4:
    one matrix or a stack): the direction is the vector of its skew part, the point u × t/|ω|."""
    u = np.stack([m[..., 2, 1], m[..., 0, 2], m[..., 1, 0]], axis=-1)
    n = np.linalg.norm(u, axis=-1)
    u = u / n[..., None]
    return u, np.cross(u, m[..., :3, 3] / n[..., None]), n


def _dist_point_line(p, u, a):
    d = p - a
    return float(np.linalg.norm(d - np.dot(d, u) * u))


def _lines_coincide(u1, a1, u2, a2, tol):
    return abs(abs(np.dot(u1, u2)) - 1) < 1e-9 and _dist_point_line(a2, u1, a1) < tol


def _config(cond: Condition, geo: _Geometry):
    """Numeric joint vector for the condition, or None."""
    q = {s: _GENERIC[i % len(_GENERIC)] for i, s in enumerate(geo.joints)}
    fixed = dict(cond.values)
    for _ in range(len(fixed) + 1):       # values may depend on other joints
        for s, v in fixed.items():
            try:
                val = complex(sp.sympify(v).evalf(subs={**geo.params, **q}))
            except (TypeError, ValueError):
                return None
            if abs(val.imag) > 1e-9:
                return None
            q[s] = val.real
    if cond.equations:
        if len(cond.equations) != 1:
            return None
        f = cond.equations[0]
        present = [s for s in geo.joints if f.has(s) and s not in fixed]
        if not present:
            return None
        grid = np.linspace(-math.pi, math.pi, 721)
        for var in reversed(present):
            values = {**geo.params, **{s: q[s] for s in geo.joints if s != var}}
            sub = f.xreplace({k: sp.sympify(v) for k, v in values.items()})     # = f.subs(values)
            g = sp.lambdify(var, sub, numpy_modules())
            vals = np.array([float(g(x)) for x in grid])
            idx = np.where(np.sign(vals[:-1]) * np.sign(vals[1:]) <= 0)[0]
            if len(idx):
                i = int(idx[0])
                q[var] = grid[i] if vals[i] == 0 else _bisect(g, grid[i], grid[i + 1])
                break
        else:
            return None
    return [q[s] for s in geo.joints]


def _bisect(f, lo: float, hi: float) -> float:
    """A root of f in [lo, hi] (f(lo), f(hi) of opposite signs) by bisection, to the last
    bit. Plain Python on purpose: importing scipy.optimize for brentq costs ~0.8 s, more
    than naming every condition of a 3R arm; the grid step is 0.5°, so 60 halvings reach
    machine precision."""
    flo = float(f(lo))
    for _ in range(60):
        mid = (lo + hi) / 2
        if mid in (lo, hi):
            break
        fmid = float(f(mid))
        if fmid == 0:
            return mid
        if (fmid < 0) == (flo < 0):
            lo, flo = mid, fmid
        else:
            hi = mid
    return (lo + hi) / 2


def _far_point(geo, q, k, prev, prev_axis=None):
    """The point whose distance to the axis of joint `prev` measures the reach at joint k:
    the next revolute axis when it is parallel to that axis (planar chains), else the point.
    `prev_axis`: that axis, when known (it does not depend on joint k > prev)."""
    u_prev, a_prev = prev_axis if prev_axis is not None else geo.axis(q, prev)
    # the first revolute axis after joint k (only that one: each axis costs a difference)
    later = next((ax for ax in (geo.axis(q, i) for i in range(k + 1, len(geo.joints))) if ax is not None), None)
    if later is not None and abs(abs(np.dot(later[0], u_prev)) - 1) < 1e-9:
        return later[1], u_prev, a_prev
    return geo.point(q), u_prev, a_prev


def _far_distances(geo, Q, k, prev_axis):
    """`_far_point`'s distance at every row of Q (joint k moving), in one pass."""
    u_prev, a_prev = prev_axis
    later = next((i for i in range(k + 1, len(geo.joints)) if geo.kinds[geo.joints[i]] == "revolute"), None)
    far = geo.point_many(Q)
    if later is not None:
        u_l, a_l = geo.axis_many(Q, later)
        parallel = np.abs(np.abs(u_l @ u_prev) - 1) < 1e-9
        far = np.where(parallel[:, None], a_l, far)
    d = far - a_prev
    return np.linalg.norm(d - (d @ u_prev)[:, None] * u_prev[None, :], axis=1)


def _stretch(geo, qv, k, prev, scale):
    grid = np.linspace(-math.pi, math.pi, 121)
    prev_axis = geo.axis(qv, prev)       # the same at every value of joint k > prev
    Q = np.tile(np.asarray(qv, dtype=float), (len(grid), 1))
    Q[:, k] = grid
    dists = _far_distances(geo, Q, k, prev_axis)
    d0 = _dist_point_line(*_far_point(geo, qv, k, prev, prev_axis))
    lo, hi = min(dists), max(dists)
    if hi - lo < 1e-7 * scale:
        return []
    if d0 >= hi - 1e-6 * scale:
        return [f"arm stretched at joint {k + 1}"]
    if d0 <= lo + 1e-6 * scale:
        return [f"arm folded at joint {k + 1}"]
    return []


def _parallel(u1, u2) -> bool:
    return abs(abs(float(np.dot(u1, u2))) - 1) < 1e-9


def _parallel_names(axes, generic, tol, n) -> list[str]:
    """Axes that become parallel here without meeting (not parallel in general): an offset wrist
    (the UR family: s5 = 0 makes the axes of joints 4 and 6 parallel, with those of joints 2 and 3)."""
    fresh = [(i, j) for x, (i, ui, ai) in enumerate(axes) for (j, uj, aj) in axes[x + 1:]
             if _parallel(ui, uj) and not _lines_coincide(ui, ai, uj, aj, tol)
             and not (i in generic and j in generic and _parallel(generic[i][0], generic[j][0]))]
    out = []
    for i, j in fresh:
        group = sorted({k for k, u, _a in axes if _parallel(u, dict((a, b) for a, b, _c in axes)[i])})
        if tuple(group) in out:
            continue
        out.append(tuple(group))
    names = []
    for group in out:
        joints = [g + 1 for g in group]
        if n == 6 and 3 in group and 5 in group:
            names.append("wrist singularity: the axes of joints 4 and 6 are parallel, not aligned "
                         "(the wrist is not spherical)")
        else:
            names.append(f"the axes of joints {_and(joints)} are parallel")
    return names


def _and(items) -> str:
    items = [str(x) for x in items]
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


def _names(cond: Condition, geo: _Geometry) -> tuple[str, ...]:
    qv = _config(cond, geo)
    if qv is None:
        return ()
    p = geo.point(qv)
    axes = geo.axes(qv)
    scale = max(1.0, float(np.linalg.norm(p)), *(float(np.linalg.norm(a)) for _, _, a in axes))
    tol = 1e-7 * scale
    names: list[str] = []
    # the point on an axis (only where it is not on it in general: a wrist centre lies on
    # the wrist's axes everywhere, which names nothing)
    q_generic = [_GENERIC[i % len(_GENERIC)] for i in range(len(geo.joints))]
    p_generic = geo.point(q_generic)
    always = {i for i, u, a in geo.axes(q_generic) if _dist_point_line(p_generic, u, a) < tol}
    on = [i + 1 for i, u, a in axes if _dist_point_line(p, u, a) < tol and i not in always]
    if on:
        which = (f"axis of joint {on[0]}" if len(on) == 1
                 else "axes of joints " + ", ".join(map(str, on[:-1])) + f" and {on[-1]}")
        names.append(f"the point lies on the {which}")
    # aligned axes (only where they are not aligned in general)
    generic = {i: (u, a) for i, u, a in geo.axes(q_generic)}
    for x in range(len(axes)):
        for y in range(x + 1, len(axes)):
            i, ui, ai = axes[x]
            j, uj, aj = axes[y]
            if _lines_coincide(ui, ai, uj, aj, tol) and not (
                    i in generic and j in generic
                    and _lines_coincide(*generic[i], *generic[j], tol)):
                names.append(f"the axes of joints {i + 1} and {j + 1} are aligned")
    names += _parallel_names(axes, generic, tol, len(geo.joints))
    # stretched / folded: an elbow whose axis is parallel to the previous revolute axis
    if not cond.equations:
        index = {s: k for k, s in enumerate(geo.joints)}
        by_joint = {i: u for i, u, _a in axes}
        stretch = []
        for s, _v in cond.values:
            k = index[s]
            if geo.kinds[s] != "revolute" or k not in by_joint:
                continue
            prev = [i for i, _u, _a in axes if i < k]
            if not prev or abs(abs(float(np.dot(by_joint[k], by_joint[prev[-1]]))) - 1) > 1e-9:
                continue
            stretch.extend(_stretch(geo, qv, k, prev[-1], scale))
        names[:0] = stretch
    return tuple(names)


def name_conditions(conditions: Sequence[Condition], joints: Sequence[sp.Symbol], kinds: Mapping,
                    l_matrices: Sequence[sp.Matrix] | None, point, params: Mapping | None = None,
                    m0_frames: Sequence[sp.Matrix] | None = None) -> list[Condition]:
    """The same conditions, each with its geometric names (possibly none).

    Give either ``l_matrices`` (⁰Lᵢ of each joint) or ``m0_frames`` (⁰Mᵢ of the frame each
    joint moves, 4x4; its L is then obtained numerically)."""
    try:
        geo = _Geometry(joints, kinds, l_matrices, point, dict(params or {}), m0_frames)
    except Exception:  # noqa: BLE001 - naming is a courtesy; never fail the answer for it
        return list(conditions)
    out = []
    for c in conditions:
        try:
            names = _names(c, geo)
        except Exception:  # noqa: BLE001
            names = ()
        out.append(Condition(values=c.values, equations=c.equations, factor=c.factor, names=names))
    return out
