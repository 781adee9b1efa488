"""Equations of motion by the course's matrix method, engineered to stay small.

The course (seed §6; docs/course-notes.md, Dynamics):

* Tⱼ = ½ tr(⁰W₀ⱼ ⁰Jⱼ ⁰W₀ⱼᵀ), Uⱼ = −tr(⁰H_g ⁰Jⱼ), ℒ = Σ(Tⱼ − Uⱼ);
* fᵢ = (Σ_{j≥i} ⁰Φⱼ) ⊗ ⁰Lᵢ;
* d/dt ∂ℒ/∂q̇ᵢ − ∂ℒ/∂qᵢ = fᵢ.

How it is kept compact (same formulas, other frame and order of operations):

* With W₀ⱼ = Σᵢ ⁰Lᵢⱼ q̇ᵢ (⁰Lᵢⱼ = ∂M₀ⱼ/∂qᵢ·M₀ⱼ⁻¹), T = ½ Σᵢₖ q̇ᵢ q̇ₖ Σⱼ tr(⁰Lᵢⱼ ⁰Jⱼ ⁰Lₖⱼᵀ),
  so the mass matrix is M_ik = Σⱼ tr(⁰Lᵢⱼ ⁰Jⱼ ⁰Lₖⱼᵀ), built entry by entry.
* The trace is invariant when every factor is moved to the body frame j:
  tr(⁰L ⁰J ⁰Lᵀ) = tr(ᵇL ʲJ ᵇLᵀ) with ᵇLᵢⱼ = M₀ⱼ⁻¹ ∂M₀ⱼ/∂qᵢ = M_fj⁻¹ (A_f⁻¹ ∂A_f/∂qᵢ) M_fj,
  which depends only on the joints between joint i and body j (small entries), and ʲJ is
  the body's own pseudo-inertia (constant). The relative poses and ᵇL come from the one
  chain computation (core/chain/forward.py, its body-frame route), over the engine's algebra.
* Every entry is a polynomial in cos qᵢ, sin qᵢ (and prismatic qᵢ) with the parameters as
  coefficients, kept reduced modulo cos² + sin² = 1 in a sympy sparse polynomial ring
  (core/trigring.py): exact, canonical, fast; no `trigsimp` in the derivation. The final
  entries are shown in the shortest of three equivalent forms (`pretty`).
* The Lagrange derivatives are taken on M(q) and U(q) directly:
  d/dt ∂ℒ/∂q̇ − ∂ℒ/∂q = M q̈ + c + g with c from the Christoffel symbols of M and g = ∂U/∂q,
  which is the same expression as differentiating ℒ, term by term, but on small pieces.
* Generalized forces of external loads: Φ ⊗ L is frame invariant, so it is computed in the
  body frame, Φ_b ⊗ ᵇLᵢⱼ; the actuator of joint i contributes exactly its own value
  (own action on its link, reaction on the previous link: they cancel for every other joint).
"""

from __future__ import annotations

from typing import Mapping

import sympy as sp

from robosolve.core.chain.algebras import ListChainAlgebra
from robosolve.core.chain.forward import forward
from robosolve.core.matrices import action_matrix
from robosolve.core.simplify import coefficient, congruence_entries
from robosolve.core.transforms import skew, vex
from robosolve.core.trigring import TrigAlgebra, fourier_terms, product_terms
from robosolve.dynamics.sympy_algebra import SympyAlgebra
from robosolve.dynamics.types import BodySpec, Dynamics, FrameSpec, JointSpec, LoadSpec
from robosolve.core.opcount import count_ops

__all__ = ["DynamicsEngine"]

BASE = "0"
COMPACT_MAX_JOINTS = 4  # robots up to this size get the sum-of-angles compaction
# A mass matrix with more terms than this (all entries, in the trig ring) is a big robot's: its
# answers are written straight from the ring (dynamics/ring_text.py), its report shows the
# entries that are short enough, and its sympy expressions are built only when asked for.
# (PUMA 560, UR5, KUKA KR: 200-300 terms; the Franka Panda: 5 549.)
LARGE_TERMS = 2000
# Largest entry (terms of the expanded polynomial) the report of a big robot writes out.
SHOW_TERMS = 40


def _rounding_only(rest, scale) -> bool:
    """Every term of `rest` has a decimal coefficient that is floating-point noise next to
    the largest coefficient of `scale` (terms of the expanded expressions)."""
    def coeffs(e):
        return [t.as_coeff_Mul()[0] for t in sp.Add.make_args(sp.expand(e))]
    mine = coeffs(rest)
    if not all(isinstance(c, sp.Float) for c in mine):
        return False
    big = max([abs(float(c)) for c in coeffs(scale)] + [1.0])
    return max(abs(float(c)) for c in mine) <= 1e-9 * big


class DynamicsEngine:
    """Holds the chain and caches every intermediate matrix (also used by the report).

    The core quantities (relative poses, body-frame L matrices, M, U, c, g, external
    forces) are computed in a :class:`TrigAlgebra` (polynomials in cos qᵢ, sin qᵢ reduced by
    cos² + sin² = 1) when the inputs allow it, else on sympy expressions with small-piece
    `trigsimp`. Public methods return sympy objects.
    """

    def __init__(self, frames, joints, bodies, gravity, loads=(), *, simplify=True,
                 subs: Mapping | None = None, algebra: str = "auto"):
        rep = {sp.sympify(k): sp.sympify(v) for k, v in (subs or {}).items()}
        self._rep = rep
        self.simplify = simplify
        self.joints: list[JointSpec] = list(joints)
        self.n = len(self.joints)
        self.q = [j.q for j in self.joints]
        self.qd = [j.qd for j in self.joints]
        self.qdd = [j.qdd for j in self.joints]
        self.frames: dict[str, FrameSpec] = {}
        self.order: list[str] = []
        for f in frames:
            if f.parent != BASE and f.parent not in self.frames:
                raise ValueError(f"frame {f.name!r}: parent {f.parent!r} must be listed before it")
            if f.name == BASE or f.name in self.frames:
                raise ValueError(f"frame {f.name!r} is defined twice")
            self.frames[f.name] = FrameSpec(f.name, f.parent, self._sub(sp.Matrix(f.local)))
            self.order.append(f.name)
        self.bodies: list[BodySpec] = [
            BodySpec(b.name, b.frame, self._sub(sp.Matrix(b.J))) for b in bodies]
        self.gravity = self._sub(sp.Matrix(list(gravity)))
        self.loads: list[LoadSpec] = []
        for ld in loads:
            def vec(v):
                return None if v is None else list(self._sub(sp.Matrix(list(v))))
            self.loads.append(LoadSpec(ld.name, ld.frame, vec(ld.force), vec(ld.point),
                                       vec(ld.torque), ld.in_frame))
        for name in [b.frame for b in self.bodies] + [ld.frame for ld in self.loads] + \
                [ld.in_frame for ld in self.loads if ld.in_frame]:
            if name != BASE and name not in self.frames:
                raise ValueError(f"unknown frame {name!r}")
        self._cache: dict = {}
        self._setup_algebra(algebra)

    # ------------------------------------------------------------------ algebra
    def _setup_algebra(self, algebra):
        exprs, self._slot = [], {}

        def put(key, values):
            self._slot[key] = len(exprs)
            exprs.extend(values)

        for name in self.order:
            put(("A", name), list(self.local(name)))
        for b in self.bodies:
            put(("J", b.name), list(b.J))
        put(("grav",), list(self.gravity))
        put(("act",), [j.actuator for j in self.joints])  # actuator symbols in the domain
        for k, ld in enumerate(self.loads):
            put(("F", k), ld.force or [0, 0, 0])
            put(("P", k), ld.point or [0, 0, 0])
            put(("C", k), ld.torque or [0, 0, 0])
        alg = None
        if algebra in ("auto", "trig"):
            alg = TrigAlgebra.from_inputs(self.q, exprs)
        if alg is None:
            alg = SympyAlgebra(self.q, exprs, simplify=self.simplify)
        self.alg = alg
        # the one chain computation (core/chain/forward.py: relative poses, body twists, ᵇL),
        # over this algebra, the engine its own description
        local = {name: self._mat4(("A", name)) for name in self.order}
        self.chain_data = forward(self, ListChainAlgebra(alg, local))

    def _elems(self, key, n):
        k = self._slot[key]
        return [self.alg.element(k + t) for t in range(n)]

    def _mat4(self, key):
        e = self._elems(key, 16)
        return [e[4 * r:4 * r + 4] for r in range(4)]

    # ------------------------------------------------------------------ helpers
    def _sub(self, obj):
        return obj.xreplace(self._rep) if self._rep else obj

    def _cached(self, key, fn):
        if key not in self._cache:
            self._cache[key] = fn()
        return self._cache[key]

    def path(self, name: str) -> list[str]:
        """Frames from the base's first child down to `name` (inclusive)."""
        out = []
        while name != BASE:
            out.append(name)
            name = self.frames[name].parent
        return out[::-1]

    def local(self, name: str) -> sp.Matrix:
        return self.frames[name].local

    def moving(self, name: str) -> list[int]:
        """Indices of the joints that move frame `name` (all on its path to the base)."""
        if name == BASE:
            return []
        return self._cached(("moving", name), lambda: [
            i for i in range(self.n)
            if any(self.local(f).has(self.q[i]) for f in self.path(name))])

    def joint_frame(self, i: int) -> str | None:
        """The first frame whose local pose contains joint i (the joint's link)."""
        q = self.q[i]
        for name in self.order:
            if self.local(name).has(q):
                return name
        return None

    # -- the engine as the description of its chain (what core/chain/forward.py asks) ------
    def parent(self, name: str) -> str | None:
        return None if name == BASE else self.frames[name].parent

    def chain(self, name: str) -> list[str]:
        return self.path(name)

    def moved_by(self, name: str) -> list[int]:
        """Indices of the joints in frame `name`'s local pose."""
        return self._cached(("moved_by", name), lambda: [
            i for i in range(self.n) if self.local(name).has(self.q[i])])

    # ------------------------------------------------------------------ core (algebra)
    def _rbody_M(self, b: BodySpec):
        """Mass matrix of one body: tr(ᵇLᵢ ʲJ ᵇLₖᵀ)."""
        def build():
            alg = self.alg
            jm = self._mat4(("J", b.name))
            out = alg.zeros(self.n)
            idx = self.moving(b.frame)
            lbs = {i: self.chain_data.body_L(i, b.frame) for i in idx}
            # ᵇLᵢ J once per i, then the trace with ᵇLₖ
            lj = {i: alg.matmul(lbs[i], jm) for i in idx}
            for a_, i in enumerate(idx):
                for k in idx[a_:]:
                    acc = alg.zero
                    for r in range(4):
                        for t in range(4):
                            x, y = lj[i][r][t], lbs[k][r][t]
                            if x != 0 and y != 0:
                                acc += x * y
                    out[i][k] = out[k][i] = alg.reduce(acc)
            return out
        return self._cached(("rMb", b.name), build)

    def _rM(self):
        def build():
            alg = self.alg
            out = alg.zeros(self.n)
            for b in self.bodies:
                mb = self._rbody_M(b)
                out = alg.madd(out, mb)
            return [[alg.reduce(x) for x in row] for row in out]
        return self._cached("rM", build)

    def _rU(self):
        """U_b = −tr(⁰H_g ⁰J_b) = −(g, 0)·(M₀ⱼ · ʲJ[:, 4]) (the only column the trace uses)."""
        def build():
            alg = self.alg
            grav = self._elems(("grav",), 3)
            out = {}
            for b in self.bodies:
                m0 = self.chain_data.relative(BASE, b.frame)
                jm = self._mat4(("J", b.name))
                acc = alg.zero
                for r in range(3):
                    if grav[r] == 0:
                        continue
                    for k in range(4):
                        if m0[r][k] != 0 and jm[k][3] != 0:
                            acc -= grav[r] * m0[r][k] * jm[k][3]
                out[b.name] = alg.reduce(acc)
            return out
        return self._cached("rU", build)

    def _rg(self):
        def build():
            alg = self.alg
            u = sum(self._rU().values(), alg.zero)
            return [alg.diff(u, i) for i in range(self.n)]
        return self._cached("rg", build)

    def _rc(self):
        """Christoffel coefficients: cᵢ = Σ_{j≤k} coef[i][(j,k)] q̇ⱼ q̇ₖ."""
        def build():
            alg = self.alg
            m = self._rM()
            n = self.n
            dm = {}

            def d(i, j, k):
                key = (min(i, j), max(i, j), k)
                if key not in dm:
                    dm[key] = alg.diff(m[i][j], k)
                return dm[key]

            out = []
            for i in range(n):
                coefs = {}
                for j in range(n):
                    for k in range(j, n):
                        if j == k:
                            coef = d(i, j, j) - alg.half * d(j, j, i)
                        else:
                            coef = d(i, j, k) + d(i, k, j) - d(j, k, i)
                        coef = alg.reduce(coef)
                        if coef != 0:
                            coefs[(j, k)] = coef
                out.append(coefs)
            return out
        return self._cached("rc", build)

    def _rload_phi(self, k: int):
        """Φ of load k in the body frame of its frame (components rotated from `in`)."""
        def build():
            alg = self.alg
            ld = self.loads[k]
            f, p, c = (self._elems((key, k), 3) for key in ("F", "P", "C"))
            src = ld.in_frame or ld.frame
            if src != ld.frame:
                m_f = self.chain_data.relative(BASE, ld.frame)
                m_s = self.chain_data.relative(BASE, src) if src != BASE else alg.eye(4)
                rot = [[alg.reduce(sum((m_f[t][r] * m_s[t][col] for t in range(3)), alg.zero))
                        for col in range(3)] for r in range(3)]
                f = [alg.reduce(sum((rot[r][t] * f[t] for t in range(3)), alg.zero))
                     for r in range(3)]
                c = [alg.reduce(sum((rot[r][t] * c[t] for t in range(3)), alg.zero))
                     for r in range(3)]
            phi = alg.zeros(4)
            p4 = [*p, alg.one]
            f4 = [*f, alg.zero]
            for r in range(4):
                for col in range(4):
                    phi[r][col] = f4[r] * p4[col] - p4[r] * f4[col]
            # + [C]
            phi[0][1] -= c[2]
            phi[0][2] += c[1]
            phi[1][0] += c[2]
            phi[1][2] -= c[0]
            phi[2][0] -= c[1]
            phi[2][1] += c[0]
            return [[alg.reduce(x) for x in row] for row in phi]
        return self._cached(("rPhi", k), build)

    def _rext(self):
        """Generalized forces of the loads: Σ Φ_b ⊗ ᵇLᵢⱼ (frame invariant, course-notes#note-pseudo-scalar-product)."""
        def terms(i):
            return ((self._rload_phi(k), self.chain_data.body_L(i, ld.frame))
                    for k, ld in enumerate(self.loads) if i in self.moving(ld.frame))
        return self._cached("rext", lambda: self._pseudo_scalar_sums(terms))

    def external_polynomials(self) -> list:
        """The generalized forces of the loads as plain sympy expressions (the canonical
        polynomials, no readable form: numeric code lambdifies them)."""
        return [self.alg.to_expr(x) for x in self._rext()]

    def _pseudo_scalar_sums(self, terms) -> list:
        """For each joint i, Σ Φ ⊗ L over the pairs (Φ, L) of `terms(i)`, in the algebra."""
        from robosolve.core.matrices import _PSP_ENTRIES

        alg = self.alg
        out = []
        for i in range(self.n):
            acc = alg.zero
            for phi, l_matrix in terms(i):
                for r, c in _PSP_ENTRIES:
                    acc += phi[r][c] * l_matrix[r][c]
            out.append(alg.reduce(acc))
        return out

    # ------------------------------------------------------------------ sympy views
    def pretty(self, p, light: bool = False, force: bool = False):
        """Readable form of a final algebra element (M entries, c coefficients, g, U).

        Two candidate forms, the smaller (`count_ops`) wins:
        the canonical polynomial in cos qᵢ, sin qᵢ (sin² eliminated), and its Fourier form
        (products turned into cosines / sines of sums of angles, e.g. cos(2θ₂ + θ₃)); in
        both the terms are grouped by their trig factor with the parameter coefficient
        factored. No `trigsimp`: both forms come from the polynomial in microseconds.
        """
        alg = self.alg
        if not isinstance(alg, TrigAlgebra):
            expr = sp.sympify(p)
            return self._group([(c, t) for c, t in (
                term.as_independent(sp.sin, sp.cos) for term in sp.Add.make_args(sp.expand(expr)))]) \
                if self.simplify else expr
        if not self.simplify or (self.n > COMPACT_MAX_JOINTS and not force):
            return alg.to_expr(p)  # big robots: the canonical polynomial as it is
        key = ("pretty", light, p)
        if key in self._cache:
            return self._cache[key]
        if light:  # report matrices: the product form, coefficients with common factors out
            best = self._group(product_terms(alg, p) if alg.trig else alg.expanded_pairs(p), factor=False)
            self._cache[key] = best
            return best
        cands = [self._group(alg.expanded_pairs(p))]
        if alg.trig and any(alg.depends(p, i) for i in alg.trig):
            if self.n <= COMPACT_MAX_JOINTS:
                cands.append(self._group(fourier_terms(alg, p)))
            cands.append(self._group(product_terms(alg, p)))
        best = min(cands, key=count_ops)
        self._cache[key] = best
        return best

    def _group(self, pairs, factor: bool = True):
        """Σ coef·trig with equal trig factors merged, coefficients factored (small ones)."""
        groups: dict = {}
        for coef, trig in pairs:
            groups[trig] = groups.get(trig, 0) + coef
        out = []
        small = self.n <= COMPACT_MAX_JOINTS
        for trig in sorted(groups, key=sp.default_sort_key):
            coef = sp.expand(groups[trig])
            if coef == 0:
                continue
            coef = coefficient(coef, small=factor and small)
            out.append(coef * trig)
        return sp.Add(*out)

    def _view(self, key, m):
        return self._cached(("view",) + key, lambda: sp.Matrix(
            [[self.pretty(x, light=True) for x in row] for row in m]))

    def rel(self, a: str, b: str) -> sp.Matrix:
        """ᵃM_b for `a` an ancestor of `b` (or a == b)."""
        return self._view(("rel", a, b), self.chain_data.relative(a, b))

    def M0(self, name: str) -> sp.Matrix:
        return self.rel(BASE, name) if name != BASE else sp.eye(4)

    def twist_local(self, name: str, i: int) -> sp.Matrix:
        return self._view(("S", name, i), self.chain_data.body_twist(name, i))

    def Lb(self, i: int, name: str) -> sp.Matrix:
        """ᵇLᵢⱼ = M₀ⱼ⁻¹ ∂M₀ⱼ/∂qᵢ, the L matrix of joint i seen in body frame `name`."""
        return self._view(("Lb", i, name), self.chain_data.body_L(i, name))

    def L0(self, i: int, name: str | None = None) -> sp.Matrix:
        """⁰Lᵢ = ∂M₀ⱼ/∂qᵢ·M₀ⱼ⁻¹ (frame j = the joint's own frame by default)."""
        name = name or self.joint_frame(i)
        if name is None:
            return sp.zeros(4, 4)

        return self._view(("L0", i, name), self._rL0(i, name))

    def body_mass_matrix(self, b: BodySpec) -> sp.Matrix:
        return self._view(("Mb", b.name), self._rbody_M(b))

    def mass_matrix(self) -> sp.Matrix:
        return self._cached(("view", "M"), lambda: sp.Matrix(
            [[self.pretty(x, force=True) for x in row] for row in self._rM()]))

    def kinetic_energy(self) -> dict:
        """T_b = ½ Σᵢₖ q̇ᵢ q̇ₖ tr(ᵇLᵢ J ᵇLₖᵀ) = ½ tr(W J Wᵀ)."""
        def build():
            out = {}
            for b in self.bodies:
                mb = self._rbody_M(b)
                terms = []
                for i in range(self.n):
                    for k in range(i, self.n):
                        if mb[i][k] != 0:
                            w = 1 if i != k else sp.Rational(1, 2)
                            terms.append(w * self.qd[i] * self.qd[k] *
                                         self.pretty(mb[i][k]))
                out[b.name] = sp.Add(*terms)
            return out
        return self._cached("T", build)

    def potential_energy(self) -> dict:
        return self._cached("U", lambda: {k: self.pretty(v)
                                          for k, v in self._rU().items()})

    def gravity_terms(self) -> sp.Matrix:
        return self._cached("g", lambda: sp.Matrix(
            [self.pretty(x, force=True) for x in self._rg()]))

    def velocity_terms(self) -> sp.Matrix:
        def build():
            out = []
            for coefs in self._rc():
                out.append(sp.Add(*[self.pretty(v) * self.qd[j] * self.qd[k]
                                    for (j, k), v in coefs.items()]))
            return sp.Matrix(out)
        return self._cached("c", build)

    def external_forces(self) -> sp.Matrix:
        return self._cached("ext", lambda: sp.Matrix(
            [self.pretty(x) for x in self._rext()]))

    def hg(self) -> sp.Matrix:
        """⁰H_g: the gravity vector in the last column (course-notes#note-gravity)."""
        out = sp.zeros(4, 4)
        out[:3, 3] = self.gravity
        return out

    def J0(self, b: BodySpec, limit: int | None = None) -> sp.Matrix:
        """⁰J = M₀ⱼ ʲJ M₀ⱼᵀ (for the report; energies use the body frame). `limit`: the count of
        operations the report shows the matrix within; past it the entries not yet compacted keep
        their canonical forms (simplify.congruence_entries)."""
        def build():
            alg = self.alg
            m = self.chain_data.relative(BASE, b.frame)
            mt = [list(r) for r in zip(*m)]
            return alg.matmul(alg.matmul(m, self._mat4(("J", b.name))), mt)
        ring = self._view(("J0", b.name), self._cached(("rJ0", b.name), build))
        if not self.simplify or self.n > COMPACT_MAX_JOINTS:
            return ring

        def compact():
            m = self.M0(b.frame)
            product = m * sp.Matrix(b.J) * m.T
            return sp.Matrix(4, 4, congruence_entries(ring, product, limit))
        return self._cached(("J0 compact", b.name, limit), compact)

    def W0(self, name: str) -> sp.Matrix:
        """⁰W₀ⱼ = Σᵢ ⁰Lᵢⱼ q̇ᵢ (for the report)."""
        return self._cached(("W0", name), lambda: sp.Matrix(sp.Add(*[
            self.L0(i, name) * self.qd[i] for i in self.moving(name)] or [sp.zeros(4, 4)]))
            if self.moving(name) else sp.zeros(4, 4))

    def load_in_body(self, load: LoadSpec) -> sp.Matrix:
        k = self.loads.index(load)
        return self._view(("Phi_load", k), self._rload_phi(k))

    # ------------------------------------------------------------------ actions
    def actuator_action(self, i: int) -> sp.Matrix:
        """Φ of actuator i on its link, in the joint's frame: a pure torque along the
        joint axis (revolute) or a force along it through the frame origin (prismatic),
        scaled so that Φ ⊗ L = actuator."""
        def build():
            name = self.joint_frame(i)
            s = self.alg.to_matrix(self.chain_data.body_twist(name, i))
            w = vex(s[:3, :3]).applyfunc(self._fixed_trig)
            a = self.joints[i].actuator
            if any(x != 0 for x in w):
                out = sp.zeros(4, 4)
                out[:3, :3] = skew(a * w / self._axis_norm2(w))
                return out.applyfunc(sp.expand)
            v = s[:3, 3].applyfunc(self._fixed_trig)
            return action_matrix(list(a * v / self._axis_norm2(v)), [0, 0, 0]).applyfunc(sp.expand)
        return self._cached(("Phi_act", i), build)

    def _axis_norm2(self, v) -> sp.Expr:
        """|v|² of a joint's axis in the frame it moves: a constant. Poses written with floats
        (alpha: 0.7) leave rounding noise in it (5.6e-17·c₂s₂ from cos²0.7 + sin²0.7 ≠ 1 in
        floating point), which is dropped so that Φ stays a polynomial in the joints."""
        norm2 = sp.expand((v.T * v)[0, 0])
        norm2 = sp.Add(*[t for t in sp.Add.make_args(norm2)
                         if not (t.has(*self.q) and abs(t.as_coeff_Mul()[0]) < 1e-12)])
        return self._fixed_trig(norm2)

    def _fixed_trig(self, x):
        """An entry free of the joints simplified when it holds sines and cosines: a fixed rotation
        by an exact angle sympy keeps as it is (Rz(2), Rx(1/3)) leaves cos²2 + sin²2 in the joint's
        axis, which must be 1 for Φ to stay a polynomial (it divides by the axis' |w|²)."""
        from robosolve.core.simplify import fixed_angles

        return x if x.has(*self.q) else fixed_angles(x)

    def link_of(self, name: str) -> str | None:
        """The frame of the link that frame `name` belongs to: the nearest frame (itself
        or an ancestor) whose local pose contains a joint; None for frames fixed to the base."""
        for f in reversed(self.path(name)):
            if any(self.local(f).has(q) for q in self.q):
                return f
        return None

    def _rlink_actions0(self) -> dict:
        """⁰Φ of each link (keyed by its joint frame), as algebra matrices."""
        def build():
            alg = self.alg
            out: dict = {}

            def add(link, m, phi_local, sign):
                mt = [list(r) for r in zip(*m)]
                phi0 = alg.matmul(alg.matmul(m, phi_local), mt)
                cur = out.get(link, alg.zeros(4))
                out[link] = [[x + sign * y for x, y in zip(rc, rp)]
                             for rc, rp in zip(cur, phi0)]

            for i in range(self.n):
                f = self.joint_frame(i)
                if f is None:
                    continue
                phi = [[alg.from_expr(x) for x in row] for row in
                       self.actuator_action(i).tolist()]
                m = self.chain_data.relative(BASE, f)
                add(f, m, phi, 1)
                parent = self.frames[f].parent
                parent_link = self.link_of(parent) if parent != BASE else None
                if parent_link is not None:
                    add(parent_link, m, phi, -1)
            for k, load in enumerate(self.loads):
                link = self.link_of(load.frame)
                if link is not None:
                    add(link, self.chain_data.relative(BASE, load.frame), self._rload_phi(k), 1)
            order = {f: t for t, f in enumerate(self.order)}
            return {k: [[alg.reduce(x) for x in row] for row in out[k]]
                    for k in sorted(out, key=order.get)}
        return self._cached("rPhi0", build)

    def link_actions0(self) -> dict[str, sp.Matrix]:
        """⁰Φ of each link: +own actuator, −next actuators' reactions, external loads on
        any frame of the link (course-notes#note-matrix-of-actions)."""
        return {k: self._view(("Phi0", k), v) for k, v in self._rlink_actions0().items()}

    def _rL0(self, i: int, name: str):
        def build():
            alg = self.alg
            m = self.chain_data.M(name)
            return alg.matmul(alg.matmul(m, self.chain_data.body_L(i, name)), alg.rigid_inverse(m))
        return self._cached(("rL0", i, name), build)

    def _rcourse_f(self):
        def terms(i):
            return ((phi, self._rL0(i, link))
                    for link, phi in self._rlink_actions0().items() if i in self.moving(link))
        return self._cached("rcourse_f", lambda: self._pseudo_scalar_sums(terms))

    def course_generalized_forces(self) -> sp.Matrix:
        """fᵢ = (Σ_{links j moved by joint i} ⁰Φⱼ) ⊗ ⁰Lᵢⱼ, literally (for the report)."""
        return sp.Matrix([self.pretty(x) for x in self._rcourse_f()])

    def course_forces_agree(self) -> bool:
        """The literal course formula equals actuator + external forces: exactly, or up to
        floating-point rounding when the inputs are decimals (alpha: -1.129, an offset
        q2 + 0.577 leave ~1e-17 remainders, which are no disagreement)."""
        alg = self.alg
        lit = self._rcourse_f()
        ext = self._rext()
        for i in range(self.n):
            act = alg.from_expr(self.joints[i].actuator)
            rest = alg.reduce(lit[i] - act - ext[i])
            if rest != 0 and not _rounding_only(alg.to_expr(rest), alg.to_expr(lit[i])):
                return False
        return True

    # ------------------------------------------------------------------ big robots
    @property
    def large(self) -> bool:
        """A big robot's equations (see LARGE_TERMS): answers written from the ring."""
        def build():
            if not isinstance(self.alg, TrigAlgebra) or not self.simplify:
                return False
            big = sum(len(x) for row in self._rM() for x in row) > LARGE_TERMS
            if big:     # what follows (c, texts) is new to this route: the faster reduction
                self.alg.term_by_term = True
            return big
        return self._cached("large", build)

    def _ring_text(self):
        from robosolve.dynamics.ring_text import RingText
        return self._cached("ring text", lambda: RingText(self.alg))

    def term_count(self, p) -> int:
        """Terms of an algebra element written out (expanded)."""
        if isinstance(self.alg, TrigAlgebra):
            return self._ring_text().term_count(p)
        return len(sp.Add.make_args(sp.expand(p)))

    def shown(self, p):
        """(the readable sympy form, or None when longer than SHOW_TERMS terms; the count)."""
        count = self.term_count(p)
        if count > SHOW_TERMS:
            return None, count
        return self.pretty(p, light=True), count

    def polynomials(self) -> dict:
        """The final algebra elements: M (rows), c (per joint: {(j, k): Γ}), g, U and M per body."""
        return {"mass_matrix": self._rM(), "velocity_terms": self._rc(), "gravity_terms": self._rg(),
                "potential_energy": self._rU(),
                "body_mass_matrices": {b.name: self._rbody_M(b) for b in self.bodies}}

    def _rates_text(self, j: int, k: int, half: bool = False) -> str:
        if j == k:
            return f"{self.qd[j]}**2" + ("/2" if half else "")
        return f"{self.qd[j]}*{self.qd[k]}"

    def _kinetic_text(self, m) -> str:
        """T = ½ q̇ᵀ M q̇ written from M's upper triangle."""
        rt = self._ring_text()
        return rt.weighted_sum([(self._rates_text(i, k, half=True), m[i][k])
                                for i in range(self.n) for k in range(i, self.n)])

    def answer_texts(self) -> dict:
        """The symbolic answers as text (sympy's syntax), straight from the ring: mass_matrix,
        velocity_terms, gravity_terms, kinetic / potential energy (per body and total), and
        the left sides of the equations Σₖ M_ik q̈ₖ + cᵢ + gᵢ."""
        def build():
            rt = self._ring_text()
            m, c, g = self._rM(), self._rc(), self._rg()
            velocity = [rt.weighted_sum([(self._rates_text(j, k), v) for (j, k), v in ci.items()])
                        for ci in c]
            kinetic = {b.name: self._kinetic_text(self._rbody_M(b)) for b in self.bodies}
            kinetic["total"] = self._kinetic_text(m)
            u = self._rU()
            potential = {name: rt.text(v) for name, v in u.items()}
            potential["total"] = rt.text(sum(u.values(), self.alg.zero))
            lhs = []
            for i in range(self.n):
                pieces = [(str(self.qdd[k]), m[i][k]) for k in range(self.n)]
                pieces += [(self._rates_text(j, k), v) for (j, k), v in c[i].items()]
                pieces.append(("", g[i]))
                lhs.append(rt.weighted_sum(pieces))
            return {"mass_matrix": [[rt.text(x) for x in row] for row in m],
                    "velocity_terms": velocity,
                    "gravity_terms": [rt.text(x) for x in g],
                    "kinetic_energy": kinetic, "potential_energy": potential, "lhs": lhs}
        return self._cached("answer texts", build)

    def _lazy_dynamics(self) -> Dynamics:
        """A big robot's Dynamics: the sympy expressions (canonical polynomials) built on use."""
        alg = self.alg

        def kinetic():
            out = {}
            for b in self.bodies:
                mb = self._rbody_M(b)
                out[b.name] = sp.Add(*[(sp.S.Half if i == k else 1) * self.qd[i] * self.qd[k] *
                                       alg.to_expr(mb[i][k])
                                       for i in range(self.n) for k in range(i, self.n) if mb[i][k]])
            return out

        return Dynamics(joints=self.joints, engine=self, builders={
            "mass_matrix": lambda: alg.to_matrix(self._rM()),
            "velocity_terms": lambda: sp.Matrix([
                sp.Add(*[alg.to_expr(v) * self.qd[j] * self.qd[k] for (j, k), v in ci.items()])
                for ci in self._rc()]),
            "gravity_terms": lambda: sp.Matrix([alg.to_expr(x) for x in self._rg()]),
            "external_forces": lambda: sp.Matrix(self.external_polynomials()),
            "kinetic_energy": kinetic,
            "potential_energy": lambda: {k: alg.to_expr(v) for k, v in self._rU().items()},
        })

    # ------------------------------------------------------------------ result
    def dynamics(self) -> Dynamics:
        if self.large:
            return self._lazy_dynamics()
        return Dynamics(
            joints=self.joints,
            mass_matrix=self.mass_matrix(),
            velocity_terms=self.velocity_terms(),
            gravity_terms=self.gravity_terms(),
            external_forces=self.external_forces(),
            kinetic_energy=self.kinetic_energy(),
            potential_energy=dict(self.potential_energy()),
            engine=self,
        )
