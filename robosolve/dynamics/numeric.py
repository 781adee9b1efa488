"""Numeric evaluation of the equations of motion: the one numeric type `NumericDynamics`
(lambdified with cse from the symbolic equations, or assembled numerically)."""

from __future__ import annotations

from typing import Callable, Mapping, Sequence

import numpy as np
import sympy as sp

from robosolve.core.numpy_code import numpy_modules
from robosolve.core.symbols import TIME
from robosolve.dynamics.types import Dynamics

__all__ = ["ChainDynamics", "NumericDynamics", "lambdify_dynamics", "numeric_from_engine",
           "free_symbols_left"]


class NumericDynamics:
    """The one numeric form of the equations of motion M(q) qdd + c(q, qd) + g(q) = tau + f_ext(q).

    Evaluation (1-D states in joint order, numpy results):
    ``mass(q)``, ``velocity_terms(q, qd)``, ``gravity(q)``, ``external(q)``;
    ``terms(q, qd) -> (M, c, g, f_ext)`` in one call; ``actuators(q, qd, qdd)`` (alias
    ``inverse``) gives tau = M qdd + c + g - f_ext; ``forward(q, qd, tau)`` the
    accelerations; ``inverse_many(Q, QD, QDD)`` takes arrays of shape (n, N);
    ``closed_loop(...)`` compiles a control law (symbolic construction only).

    Built three ways: :meth:`from_symbolic` (one lambdified function for M, c, g, f_ext:
    what the closed-loop ODE calls thousands of times), :func:`lambdify_dynamics` (one
    function per term, from a `Dynamics`), :func:`numeric_from_engine` (numeric-only path
    for big robots). ``note`` says which path answered when that matters to a reader.
    """

    def __init__(self, n: int, terms: Callable | None = None, terms_many: Callable | None = None,
                 symbolic=None, *, mass: Callable | None = None,
                 velocity_terms: Callable | None = None, gravity: Callable | None = None,
                 external: Callable | None = None, actuators: Callable | None = None,
                 note: str = "", time: sp.Symbol | None = None):
        self.n = n
        self.note = note
        # the time symbol when the external forces vary with time: every evaluation that
        # involves them takes t (``terms(q, qd, t)``); None otherwise
        self.time = time
        self._symbolic = symbolic        # (M, c, g, f, q, qd) with numbers only, when known
        self._terms_many = terms_many
        self._actuators = actuators
        if terms is None:
            zero = np.zeros(n)

            def terms(qv, qdv):
                return (np.asarray(mass(qv), dtype=float).reshape(n, n),
                        np.asarray(velocity_terms(qv, qdv), dtype=float).reshape(n),
                        np.asarray(gravity(qv), dtype=float).reshape(n),
                        zero if external is None else np.asarray(external(qv), dtype=float).reshape(n))
        self._terms = terms
        zeros = np.zeros(n)
        # M, c and g never depend on time: any t serves to evaluate them
        steady = (lambda qv, qdv: terms(qv, qdv, 0.0)) if time is not None else terms
        self._mass = mass or (lambda qv: steady(qv, zeros)[0])
        self._velocity = velocity_terms or (lambda qv, qdv: steady(qv, qdv)[1])
        self._gravity = gravity or (lambda qv: steady(qv, zeros)[2])
        self._external = external or (lambda qv, t=None: terms(qv, zeros, *_time_arg(time is not None, t))[3])

    @property
    def timed(self) -> bool:
        return self.time is not None

    # ---------------------------------------------------------- construction
    @classmethod
    def from_symbolic(cls, mass, velocity_terms, gravity_terms, q: Sequence[sp.Symbol],
                      qd: Sequence[sp.Symbol], external=None, subs: dict | None = None,
                      time: sp.Symbol | None = None) -> "NumericDynamics":
        """Lambdify M, c, g (and f_ext, default 0) after substituting ``subs``.

        ``time``: the symbol t of forces given as functions of time; when f_ext has it,
        every evaluation of the terms takes t as its last argument.
        Raises ValueError naming the symbols left over (a parameter without a value).
        """
        n = len(q)
        mass = sp.Matrix(mass)
        c = sp.Matrix(velocity_terms)
        g = sp.Matrix(gravity_terms)
        f = sp.zeros(n, 1) if external is None else sp.Matrix(external)
        flat = list(mass) + list(c) + list(g) + list(f)
        if subs:
            flat = [sp.sympify(e).xreplace(_sympified(subs)) for e in flat]
        args = list(q) + list(qd)
        free = set().union(*(sp.sympify(e).free_symbols for e in flat))
        timed = time is not None and time in free
        if timed:
            args.append(time)
        extra = free - set(args)
        if extra:
            names = ", ".join(sorted(str(s) for s in extra))
            raise ValueError(f"no value for {names}")
        scalar = sp.lambdify(args, flat, modules="math", cse=True)
        nn = n * n

        def terms(qv, qdv, t=None):
            out = scalar(*qv, *qdv, *_time_arg(timed, t))
            return (np.array(out[:nn], dtype=float).reshape(n, n), np.array(out[nn:nn + n], dtype=float),
                    np.array(out[nn + n:nn + 2 * n], dtype=float), np.array(out[nn + 2 * n:], dtype=float))

        vec = sp.lambdify(args, flat, modules=numpy_modules(), cse=True)

        def terms_many(Q, QD, T=None):
            size = Q.shape[1]
            out = [np.broadcast_to(np.asarray(v, dtype=float), (size,))
                   for v in vec(*Q, *QD, *_time_arg(timed, T))]
            arr = np.vstack(out)
            return arr[:nn].reshape(n, n, size), arr[nn:nn + n], arr[nn + n:nn + 2 * n], arr[nn + 2 * n:]

        sym = (sp.Matrix(n, n, flat[:nn]), sp.Matrix(flat[nn:nn + n]), sp.Matrix(flat[nn + n:nn + 2 * n]),
               sp.Matrix(flat[nn + 2 * n:]), list(q), list(qd))
        return cls(n, terms, terms_many, sym, time=time if timed else None)

    @classmethod
    def from_dynamics(cls, dyn: Dynamics, subs: Mapping | None = None) -> "NumericDynamics":
        """:meth:`from_symbolic` on a `Dynamics` (external forces included; forces given as
        functions of time use the loader's t, a real symbol)."""
        return cls.from_symbolic(dyn.mass_matrix, dyn.velocity_terms, dyn.gravity_terms,
                                 dyn.q, dyn.qd, external=dyn.external_forces,
                                 subs=None if subs is None else _sympified(subs),
                                 time=TIME)

    def closed_loop(self, law: str, kp, kd):
        """A fast scalar function qdd(q, qd, e, ed, qdd_d) -> list of floats, or None.

        The plant's acceleration under the control law, compiled in one piece: M is
        solved symbolically (LU) for up to 3 joints, so each call of the ODE's
        right-hand side is a single lambdified function of floats (no small numpy
        arrays, whose overhead would dominate).  None when only callables are known
        or the arm has more than 3 joints (the caller then uses :meth:`forward`).
        """
        if self._symbolic is None or self.n > 3:
            return None
        m, c, g, f, q, qd = self._symbolic
        n = self.n
        e = sp.symbols(f"e0:{n}", real=True)
        ed = sp.symbols(f"ed0:{n}", real=True)
        ad = sp.symbols(f"ad0:{n}", real=True)
        ev, edv, adv = sp.Matrix(e), sp.Matrix(ed), sp.Matrix(ad)
        kpm = sp.diag(*[sp.Float(float(k)) for k in kp])
        kdm = sp.diag(*[sp.Float(float(k)) for k in kd])
        if law == "p":
            tau = kpm * ev
        elif law == "pd":
            tau = kpm * ev + kdm * edv
        elif law == "pd_gravity":
            tau = kpm * ev + kdm * edv + g
        elif law == "computed_torque":
            tau = m * (adv + kdm * edv + kpm * ev) + c + g
        else:
            raise ValueError(f"unknown control law {law!r}")
        if law == "computed_torque":
            qdd = adv + kdm * edv + kpm * ev + m.LUsolve(f)      # M^-1 (tau + f - c - g)
        else:
            qdd = m.LUsolve(tau + f - c - g)
        return sp.lambdify(list(q) + list(qd) + list(e) + list(ed) + list(ad)
                           + ([self.time] if self.timed else []), list(qdd), modules="math", cse=True)

    # ------------------------------------------------------------- evaluation
    # ``t`` (``T`` for arrays): the time, needed when the external forces vary with it.
    def terms(self, q, qd, t=None):
        return self._terms(q, qd, t) if self.timed else self._terms(q, qd)

    def terms_many(self, Q, QD, T=None):
        return self._terms_many(Q, QD, T) if self.timed else self._terms_many(Q, QD)

    def mass(self, q):
        return self._mass(q)

    def velocity_terms(self, q, qd):
        return self._velocity(q, qd)

    def gravity(self, q):
        return self._gravity(q)

    def external(self, q, t=None):
        return self._external(q, t) if self.timed else self._external(q)

    def actuators(self, q, qd, qdd, t=None):
        """Actuator values needed: M qdd + c + g - f_ext."""
        if self._actuators is not None and not self.timed:
            return self._actuators(q, qd, qdd)
        m, c, g, f = self.terms(q, qd, t)
        return m @ np.asarray(qdd, dtype=float) + c + g - f

    inverse = actuators

    def forward(self, q, qd, tau, t=None):
        """qdd = M^-1 (tau + f_ext - c - g)."""
        m, c, g, f = self.terms(q, qd, t)
        return np.linalg.solve(m, np.asarray(tau, dtype=float) + f - c - g)

    def inverse_many(self, Q, QD, QDD, T=None):
        Q, QD, QDD = (np.asarray(a, dtype=float) for a in (Q, QD, QDD))
        if self._terms_many is not None:
            m, c, g, f = self.terms_many(Q, QD, T)
            return np.einsum("ijk,jk->ik", m, QDD) + c + g - f
        return np.column_stack([self.inverse(Q[:, k], QD[:, k], QDD[:, k], None if T is None else T[k])
                                for k in range(Q.shape[1])])


def _time_arg(timed: bool, t) -> tuple:
    if not timed:
        return ()
    if t is None:
        raise ValueError("the external forces vary with time: give t")
    return (t,)


def _sympified(subs: Mapping) -> dict:
    return {sp.sympify(k): sp.sympify(v) for k, v in subs.items()}


def _subs(expr, rep):
    return expr.xreplace(rep) if rep else expr


def free_symbols_left(exprs, allowed) -> list[sp.Symbol]:
    """Symbols other than `allowed` still present (null parameters), sorted by name."""
    allowed = set(allowed)
    left = set()
    for e in exprs:
        left |= {s for s in e.free_symbols if s not in allowed}
    return sorted(left, key=lambda s: s.name)


def _lambdify(args, expr):
    # 'math' on scalars is the fastest for small matrices; the result is a nested list.
    return sp.lambdify(args, expr, modules=["math"], cse=True)


def lambdify_dynamics(dyn: Dynamics, subs: Mapping) -> NumericDynamics:
    """numpy callables for M, c, g, external and the actuators, parameters substituted."""
    rep = {sp.sympify(k): sp.sympify(v) for k, v in subs.items()}
    n = len(dyn.joints)
    q, qd, qdd = dyn.q, dyn.qd, dyn.qdd
    m = _subs(dyn.mass_matrix, rep)
    c = _subs(dyn.velocity_terms, rep)
    g = _subs(dyn.gravity_terms, rep)
    ext = _subs(dyn.external_forces, rep)
    left = free_symbols_left([*m, *c, *g, *ext], [*q, *qd])
    if left:
        raise ValueError("parameters without a value: " + ", ".join(s.name for s in left))
    tau = _subs(dyn.actuator_expressions(), rep)
    fm = _lambdify([q], m.tolist())
    fc = _lambdify([q, qd], list(c))
    fg = _lambdify([q], list(g))
    fe = _lambdify([q], list(ext))
    ft = _lambdify([q, qd, qdd], list(tau))
    def floats(v):
        # plain Python floats: the math module is much faster on them than on numpy scalars
        return v.tolist() if isinstance(v, np.ndarray) else [float(x) for x in v]

    return NumericDynamics(
        n,
        mass=lambda qv: np.array(fm(floats(qv)), dtype=float),
        velocity_terms=lambda qv, qdv: np.array(fc(floats(qv), floats(qdv)), dtype=float),
        gravity=lambda qv: np.array(fg(floats(qv)), dtype=float),
        external=lambda qv: np.array(fe(floats(qv)), dtype=float),
        actuators=lambda qv, qdv, qddv: np.array(
            ft(floats(qv), floats(qdv), floats(qddv)), dtype=float),
    )


class ChainDynamics:
    """The course's equations of motion evaluated with numbers (no symbolic M, c, g).

    Only the local poses are symbolic: Aᶠ(q), ∂Aᶠ/∂qᵢ and ∂²Aᶠ/∂qᵢ∂qₖ of each frame, lambdified
    once (small 4×4 matrices). At a state (q, q̇), parents before children,

        ⁰Tᶠ = ⁰Tᵖ Aᶠ,   Uᶠᵢ = ∂⁰Tᶠ/∂qᵢ = Uᵖᵢ Aᶠ + ⁰Tᵖ ∂Aᶠ/∂qᵢ,
        Vᶠ = d²⁰Tᶠ/dt² at q̈ = 0 = Vᵖ Aᶠ + 2 Ṫᵖ Ȧᶠ + ⁰Tᵖ Äᶠ   (Ṫ = Σ Uᵢ q̇ᵢ),

    then M_ik = Σ_b tr(Uᵇᵢ J_b Uᵇₖᵀ) (= Σ tr(L J Lᵀ) of the course, the trace being the same in
    frame 0 and in the body frame), cᵢ = Σ_b tr(Vᵇ J_b Uᵇᵢᵀ), gᵢ = ∂U/∂qᵢ = −Σ_b (g, 0)·Uᵇᵢ J_b[:, 4]:
    d/dt ∂T/∂q̇ᵢ − ∂T/∂qᵢ = Σ_b tr(T̈ᵇ J_b Uᵇᵢᵀ) written out. Energies per body: T_b = ½ q̇ᵀ M_b q̇,
    U_b = −(g, 0)·⁰Tᵇ J_b[:, 4]. External loads: their generalized forces Φ ⊗ L lambdified from
    the engine's (small) polynomials.
    """

    def __init__(self, eng, subs: Mapping | None = None):
        rep = _sympified(subs or {})
        self.n = n = eng.n
        q = list(eng.q)
        self.order = list(eng.order)
        self.parent = {f: eng.frames[f].parent for f in self.order}
        self.moving = {f: [i for i in range(n) if eng.local(f).has(q[i])] for f in self.order}
        self._local = {}
        for f in self.order:
            a = _subs(eng.local(f), rep)
            idx = self.moving[f]
            d1 = [a.diff(q[i]) for i in idx]
            d2 = [[m.diff(q[k]) for k in idx] for m in d1]
            _no_symbols_left([a, *d1, *[m for row in d2 for m in row]], q, f"the pose of frame {f}")
            self._local[f] = _lambdify([q], [a.tolist(), [m.tolist() for m in d1],
                                              [[m.tolist() for m in row] for row in d2]])
        self.bodies = []
        for b in eng.bodies:
            j = _subs(b.J, rep)
            _no_symbols_left([j], [], f"the inertia of {b.name}")
            self.bodies.append((b.name, b.frame, np.array(j.tolist(), dtype=float)))
        grav = _subs(sp.Matrix(eng.gravity), rep)
        _no_symbols_left([grav], [], "gravity")
        self.gravity = np.array([float(x) for x in grav] + [0.0])
        ext = [_subs(e, rep) for e in eng.external_polynomials()]
        _no_symbols_left(ext, q, "the external forces")
        self._ext = _lambdify([q], ext) if any(e != 0 for e in ext) else None

    def _frames(self, qv, qdv):
        """{frame: (⁰T, U (n, 4, 4), V)} at (q, q̇)."""
        n = self.n
        qv = [float(x) for x in qv]
        qdv = np.asarray(qdv, dtype=float)
        base = (np.eye(4), np.zeros((n, 4, 4)), np.zeros((4, 4)))
        out = {"0": base}
        for f in self.order:
            t_p, u_p, v_p = out[self.parent[f]]
            a, d1, d2 = self._local[f](qv)
            a = np.array(a, dtype=float)
            idx = self.moving[f]
            u = u_p @ a
            tdot_p = np.tensordot(qdv, u_p, axes=1)
            if idx:
                d1 = np.array(d1, dtype=float)
                d2 = np.array(d2, dtype=float)
                rates = qdv[idx]
                u[idx] += t_p @ d1
                adot = np.tensordot(rates, d1, axes=1)
                addot = np.einsum("i,k,ikrs->rs", rates, rates, d2)
                v = v_p @ a + 2.0 * tdot_p @ adot + t_p @ addot
            else:
                v = v_p @ a
            out[f] = (t_p @ a, u, v)
        return out

    def evaluate(self, qv, qdv) -> dict:
        """M, c, g and the energies per body at (q, q̇), as numpy arrays / floats."""
        n = self.n
        frames = self._frames(qv, qdv)
        qdv = np.asarray(qdv, dtype=float)
        m = np.zeros((n, n))
        c = np.zeros(n)
        g = np.zeros(n)
        kinetic, potential = {}, {}
        for name, frame, j in self.bodies:
            t, u, v = frames[frame]
            uj = u @ j
            mb = np.einsum("irs,krs->ik", uj, u)
            m += mb
            c += np.einsum("rs,irs->i", v @ j, u)
            g -= u[:, :, :] @ j[:, 3] @ self.gravity
            kinetic[name] = 0.5 * float(qdv @ mb @ qdv)
            potential[name] = -float(self.gravity @ (t @ j[:, 3]))
        return {"mass_matrix": m, "velocity_terms": c, "gravity_terms": g,
                "kinetic_energy": kinetic, "potential_energy": potential}

    def external(self, qv):
        if self._ext is None:
            return np.zeros(self.n)
        return np.array(self._ext([float(x) for x in qv]), dtype=float)

    def numeric(self, note: str = "") -> NumericDynamics:
        zeros = np.zeros(self.n)

        def terms(qv, qdv):
            out = self.evaluate(qv, qdv)
            return out["mass_matrix"], out["velocity_terms"], out["gravity_terms"], self.external(qv)

        return NumericDynamics(
            self.n, terms,
            mass=lambda qv: self.evaluate(qv, zeros)["mass_matrix"],
            velocity_terms=lambda qv, qdv: self.evaluate(qv, qdv)["velocity_terms"],
            gravity=lambda qv: self.evaluate(qv, zeros)["gravity_terms"],
            external=self.external, note=note)


def _no_symbols_left(exprs, allowed, what: str) -> None:
    left = free_symbols_left([e for m in exprs for e in (m if isinstance(m, sp.MatrixBase) else [m])],
                             allowed)
    if left:
        raise ValueError(f"parameters without a value in {what}: " + ", ".join(s.name for s in left))


def numeric_from_engine(eng, subs: Mapping | None = None) -> NumericDynamics:
    """Numeric-only dynamics (`ChainDynamics`): M, c, g assembled with numpy at each call from
    the lambdified local poses and their derivatives; nothing symbolic beyond 4×4 matrices."""
    return ChainDynamics(eng, subs).numeric(
        note="numeric-only dynamics (mass matrix assembled numerically at each call)")
