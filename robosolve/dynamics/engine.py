"""Equations of motion by the course's matrix method, engineered to stay small.

The course (seed §6, ERRATA §D.5-9):

* Tⱼ = ½ tr(⁰W₀ⱼ ⁰Jⱼ ⁰W₀ⱼᵀ), Uⱼ = −tr(⁰H_g ⁰Jⱼ), ℒ = Σ(Tⱼ − Uⱼ);
* fᵢ = (Σ_{j≥i} ⁰Φⱼ) ⊗ ⁰Lᵢ;
* d/dt ∂ℒ/∂q̇ᵢ − ∂ℒ/∂qᵢ = fᵢ.

How it is kept compact (same formulas, other frame and order of operations):

* With W₀ⱼ = Σᵢ ⁰Lᵢⱼ q̇ᵢ (⁰Lᵢⱼ = ∂M₀ⱼ/∂qᵢ·M₀ⱼ⁻¹), T = ½ Σᵢₖ q̇ᵢ q̇ₖ Σⱼ tr(⁰Lᵢⱼ ⁰Jⱼ ⁰Lₖⱼᵀ),
  so the mass matrix is M_ik = Σⱼ tr(⁰Lᵢⱼ ⁰Jⱼ ⁰Lₖⱼᵀ), built entry by entry.
* The trace is invariant when every factor is moved to the body frame j:
  tr(⁰L ⁰J ⁰Lᵀ) = tr(ᵇL ʲJ ᵇLᵀ) with ᵇLᵢⱼ = M₀ⱼ⁻¹ ∂M₀ⱼ/∂qᵢ = M_fj⁻¹ (A_f⁻¹ ∂A_f/∂qᵢ) M_fj,
  which depends only on the joints between joint i and body j (small entries), and ʲJ is
  the body's own pseudo-inertia (constant).
* Every small matrix is trig-simplified as soon as it is formed (relative poses, body-frame
  L matrices); never one big `simplify` at the end.
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

from robosolve.core.matrices import action_matrix, pseudo_scalar_product
from robosolve.core.transforms import rigid_inverse, skew, vex
from robosolve.dynamics.api import BodySpec, Dynamics, FrameSpec, JointSpec, LoadSpec

__all__ = ["DynamicsEngine", "tsimp"]

BASE = "0"


def tsimp(expr):
    """Trig-simplify a *small* expression (cheap canonical form otherwise)."""
    expr = sp.sympify(expr)
    if expr.is_number or not expr.has(sp.sin, sp.cos):
        return sp.expand(expr)
    out = sp.trigsimp(sp.expand(expr))
    return out


def _msimp(m: sp.Matrix) -> sp.Matrix:
    return m.applyfunc(tsimp)


def _trace_product(a: sp.Matrix, j: sp.Matrix, b: sp.Matrix):
    """tr(A J Bᵀ) = Σ A[r,s] J[s,t] B[r,t], skipping zeros."""
    terms = []
    for r in range(4):
        for s in range(4):
            ars = a[r, s]
            if ars == 0:
                continue
            for t in range(4):
                jst = j[s, t]
                if jst == 0:
                    continue
                brt = b[r, t]
                if brt == 0:
                    continue
                terms.append(ars * jst * brt)
    return sp.Add(*terms)


class DynamicsEngine:
    """Holds the chain and caches every intermediate matrix (also used by the report)."""

    def __init__(self, frames, joints, bodies, gravity, loads=(), *, simplify=True,
                 subs: Mapping | None = None):
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
            self.frames[f.name] = FrameSpec(f.name, f.parent, self._sub(sp.Matrix(f.local)))
            self.order.append(f.name)
        self.bodies: list[BodySpec] = [
            BodySpec(b.name, b.frame, self._sub(sp.Matrix(b.J))) for b in bodies]
        self.gravity = self._sub(sp.Matrix(list(gravity)))
        self.loads: list[LoadSpec] = list(loads)
        self._cache: dict = {}

    # ------------------------------------------------------------------ helpers
    def _sub(self, obj):
        return obj.xreplace(self._rep) if self._rep else obj

    def _s(self, expr):
        return tsimp(expr) if self.simplify else expr

    def _ms(self, m):
        return m.applyfunc(self._s)

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

    def rel(self, a: str, b: str) -> sp.Matrix:
        """ᵃM_b for `a` an ancestor of `b` (or a == b), trig-simplified entry by entry."""
        if a == b:
            return sp.eye(4)

        def build():
            parent = self.frames[b].parent
            return self._ms(self.rel(a, parent) * self.local(b))
        return self._cached(("rel", a, b), build)

    def M0(self, name: str) -> sp.Matrix:
        return self.rel(BASE, name)

    def joint_frame(self, i: int) -> str | None:
        """The first frame whose local pose contains joint i (the joint's link)."""
        q = self.q[i]
        for name in self.order:
            if self.local(name).has(q):
                return name
        return None

    def twist_local(self, name: str, i: int) -> sp.Matrix:
        """A_f⁻¹ ∂A_f/∂qᵢ: the L of joint i in the frame it moves (body frame f)."""
        def build():
            a = self.local(name)
            return self._ms(rigid_inverse(a) * a.diff(self.q[i]))
        return self._cached(("S", name, i), build)

    def Lb(self, i: int, name: str) -> sp.Matrix:
        """ᵇLᵢⱼ = M₀ⱼ⁻¹ ∂M₀ⱼ/∂qᵢ, the L matrix of joint i seen in body frame `name`."""
        def build():
            q = self.q[i]
            total = sp.zeros(4, 4)
            for f in self.path(name):
                if not self.local(f).has(q):
                    continue
                s = self.twist_local(f, i)
                r = self.rel(f, name)
                total += rigid_inverse(r) * s * r
            return self._ms(total)
        return self._cached(("Lb", i, name), build)

    def L0(self, i: int, name: str | None = None) -> sp.Matrix:
        """⁰Lᵢ = ∂M₀ⱼ/∂qᵢ·M₀ⱼ⁻¹ (frame j = the joint's own frame by default)."""
        name = name or self.joint_frame(i)
        if name is None:
            return sp.zeros(4, 4)
        m = self.M0(name)
        return self._cached(("L0", i, name),
                            lambda: self._ms(m * self.Lb(i, name) * rigid_inverse(m)))

    def moving(self, name: str) -> list[int]:
        """Indices of the joints that move frame `name`."""
        return [i for i in range(self.n) if any(self.local(f).has(self.q[i])
                                                for f in self.path(name))]

    # ------------------------------------------------------------------ energies
    def body_mass_matrix(self, b: BodySpec) -> sp.Matrix:
        """M of one body: tr(ᵇLᵢ ʲJ ᵇLₖᵀ), so T_b = ½ q̇ᵀ M_b q̇."""
        def build():
            out = sp.zeros(self.n, self.n)
            idx = self.moving(b.frame)
            for a_, i in enumerate(idx):
                for k in idx[a_:]:
                    v = self._s(_trace_product(self.Lb(i, b.frame), b.J, self.Lb(k, b.frame)))
                    out[i, k] = out[k, i] = v
            return out
        return self._cached(("Mb", b.name), build)

    def mass_matrix(self) -> sp.Matrix:
        def build():
            out = sp.zeros(self.n, self.n)
            for i in range(self.n):
                for k in range(i, self.n):
                    v = self._s(sp.Add(*[self.body_mass_matrix(b)[i, k] for b in self.bodies]))
                    out[i, k] = out[k, i] = v
            return out
        return self._cached("M", build)

    def kinetic_energy(self) -> dict:
        qd = sp.Matrix(self.qd)
        out = {}
        for b in self.bodies:
            mb = self.body_mass_matrix(b)
            out[b.name] = sp.factor_terms(sp.expand((qd.T * mb * qd)[0, 0] / 2))
        return out

    def hg(self) -> sp.Matrix:
        """⁰H_g: the gravity vector in the last column (ERRATA §D.9)."""
        out = sp.zeros(4, 4)
        out[:3, 3] = self.gravity
        return out

    def J0(self, b: BodySpec) -> sp.Matrix:
        """⁰J = M₀ⱼ ʲJ M₀ⱼᵀ (for the report; energies use the body frame)."""
        m = self.M0(b.frame)
        return self._cached(("J0", b.name), lambda: self._ms(m * b.J * m.T))

    def potential_energy(self) -> dict:
        """U_b = −tr(⁰H_g ⁰J_b) = −(g, 0)·(M₀ⱼ · ʲJ[:, 4]) (the only column tr uses)."""
        def build():
            g4 = sp.Matrix([*self.gravity, 0])
            out = {}
            for b in self.bodies:
                col = self.M0(b.frame) * b.J[:, 3]
                out[b.name] = self._s(-(g4.T * col)[0, 0])
            return out
        return self._cached("U", build)

    def gravity_terms(self) -> sp.Matrix:
        def build():
            u = sp.Add(*self.potential_energy().values())
            return sp.Matrix([self._s(u.diff(q)) for q in self.q])
        return self._cached("g", build)

    def velocity_terms(self) -> sp.Matrix:
        """cᵢ = Σⱼₖ Γᵢⱼₖ q̇ⱼ q̇ₖ, Γᵢⱼₖ = ½(∂Mᵢⱼ/∂qₖ + ∂Mᵢₖ/∂qⱼ − ∂Mⱼₖ/∂qᵢ)."""
        def build():
            m = self.mass_matrix()
            n = self.n
            dm = {}

            def d(i, j, k):
                key = (min(i, j), max(i, j), k)
                if key not in dm:
                    dm[key] = m[i, j].diff(self.q[k])
                return dm[key]

            out = []
            for i in range(n):
                terms = []
                for j in range(n):
                    for k in range(j, n):
                        if j == k:
                            coef = d(i, j, j) - d(j, j, i) / 2
                        else:
                            coef = d(i, j, k) + d(i, k, j) - d(j, k, i)
                        coef = self._s(coef)
                        if coef != 0:
                            terms.append(coef * self.qd[j] * self.qd[k])
                out.append(sp.Add(*terms))
            return sp.Matrix(out)
        return self._cached("c", build)

    # ------------------------------------------------------------------ actions
    def load_in_body(self, load: LoadSpec) -> sp.Matrix:
        """Φ of an external load in its body frame; components rotated from `in`."""
        def build():
            src = load.in_frame or load.frame
            rot = None
            if src != load.frame:
                r_src = sp.eye(3) if src == BASE else self.M0(src)[:3, :3]
                rot = self._ms(self.M0(load.frame)[:3, :3].T * r_src)

            def vec(v):
                if v is None:
                    return None
                v = self._sub(sp.Matrix(list(v)))
                return list(self._ms(rot * v)) if rot is not None else list(v)

            point = self._sub(sp.Matrix(list(load.point))) if load.point is not None else None
            return self._ms(action_matrix(vec(load.force),
                                          list(point) if point is not None else None,
                                          vec(load.torque)))
        return self._cached(("Phi_load", load.name), build)

    def external_forces(self) -> sp.Matrix:
        """Generalized forces of the external loads: Σ Φ_b ⊗ ᵇLᵢⱼ (frame invariant)."""
        def build():
            out = []
            for i in range(self.n):
                terms = []
                for load in self.loads:
                    if i in self.moving(load.frame):
                        terms.append(pseudo_scalar_product(self.load_in_body(load),
                                                           self.Lb(i, load.frame)))
                out.append(self._s(sp.Add(*terms)))
            return sp.Matrix(out)
        return self._cached("ext", build)

    def actuator_action(self, i: int) -> sp.Matrix:
        """Φ of actuator i on its link, in the joint's frame: a pure torque along the
        joint axis (revolute) or a force along it through the frame origin (prismatic),
        scaled so that Φ ⊗ L = actuator."""
        name = self.joint_frame(i)
        s = self.twist_local(name, i)
        w = vex(s[:3, :3])
        a = self.joints[i].actuator
        if any(x != 0 for x in w):
            return self._ms(skew(a * w / (w.T * w)[0, 0]).row_join(sp.zeros(3, 1))
                            .col_join(sp.zeros(1, 4)))
        v = s[:3, 3]
        return self._ms(action_matrix(list(a * v / (v.T * v)[0, 0]), [0, 0, 0]))

    def link_of(self, name: str) -> str | None:
        """The frame of the link that frame `name` belongs to: the nearest frame (itself
        or an ancestor) whose local pose contains a joint; None for frames fixed to the base."""
        for f in reversed(self.path(name)):
            if any(self.local(f).has(q) for q in self.q):
                return f
        return None

    def link_actions0(self) -> dict[str, sp.Matrix]:
        """⁰Φ of each link (keyed by its joint frame): +own actuator, −next actuators'
        reactions, external loads on any frame of the link (ERRATA §D.5)."""
        def build():
            out: dict[str, sp.Matrix] = {}
            for i in range(self.n):
                f = self.joint_frame(i)
                if f is None:
                    continue
                m = self.M0(f)
                phi0 = m * self.actuator_action(i) * m.T
                out[f] = out.get(f, sp.zeros(4, 4)) + phi0
                parent_link = self.link_of(self.frames[f].parent) if \
                    self.frames[f].parent != BASE else None
                if parent_link is not None:
                    out[parent_link] = out.get(parent_link, sp.zeros(4, 4)) - phi0
            for load in self.loads:
                link = self.link_of(load.frame)
                if link is None:
                    continue
                m = self.M0(load.frame)
                out[link] = out.get(link, sp.zeros(4, 4)) + m * self.load_in_body(load) * m.T
            return {k: self._ms(v) for k, v in out.items()}
        return self._cached("Phi0", build)

    def course_generalized_forces(self) -> sp.Matrix:
        """fᵢ = (Σ_{links j moved by joint i} ⁰Φⱼ) ⊗ ⁰Lᵢⱼ, literally (for the report)."""
        phis = self.link_actions0()
        out = []
        for i in range(self.n):
            terms = []
            for link, phi in phis.items():
                if i in self.moving(link):
                    terms.append(pseudo_scalar_product(phi, self.L0(i, link)))
            out.append(self._s(sp.Add(*terms)))
        return sp.Matrix(out)

    # ------------------------------------------------------------------ result
    def dynamics(self) -> Dynamics:
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
