"""Fast numeric M(q), c(q, qd), g(q), external(q) from the symbolic equations of motion.

The equations of motion are M(q) qdd + c(q, qd) + g(q) = tau + f_ext(q), tau the
actuators.  :class:`FastDynamics` lambdifies all four terms into ONE function
(common subexpressions shared, ``math`` module for scalar speed), which is what
the closed-loop ODE calls thousands of times.  A vectorized numpy twin serves
the sampling of torques along a trajectory.
"""

from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
import sympy as sp

__all__ = ["FastDynamics"]


class FastDynamics:
    """Numeric dynamics of an n-joint arm.

    ``terms(q, qd) -> (M, c, g, f_ext)`` (numpy; M is n x n); ``inverse(q, qd, qdd)``
    gives the actuators tau = M qdd + c + g - f_ext; both accept 1-D states.
    ``inverse_many(Q, QD, QDD)`` takes arrays of shape (n, N).
    """

    def __init__(self, n: int, terms: Callable, terms_many: Callable | None = None, symbolic=None,
                 time=None):
        self.n = n
        self._terms = terms
        self._terms_many = terms_many
        self._symbolic = symbolic        # (M, c, g, f, q, qd) with numbers only, when known
        # the time symbol when the external forces vary with time (then every evaluation takes t)
        self.time = time

    @property
    def timed(self) -> bool:
        return self.time is not None

    # ---------------------------------------------------------- construction
    @classmethod
    def from_symbolic(cls, mass, velocity_terms, gravity_terms, q: Sequence[sp.Symbol],
                      qd: Sequence[sp.Symbol], external=None, subs: dict | None = None,
                      time: sp.Symbol | None = None) -> "FastDynamics":
        """Lambdify M, c, g (and f_ext, default 0) after substituting ``subs``.

        ``time``: the symbol t that forces given as functions of time use; when f_ext has it,
        every evaluation takes t as its last argument.
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

        vec = sp.lambdify(args, flat, modules="numpy", cse=True)

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
    def from_callables(cls, n: int, mass, velocity_terms, gravity, external=None) -> "FastDynamics":
        """Wrap separate numeric callables (e.g. the dynamics helper's NumericDynamics)."""
        zero = np.zeros(n)

        def terms(qv, qdv):
            return (np.asarray(mass(qv), dtype=float).reshape(n, n),
                    np.asarray(velocity_terms(qv, qdv), dtype=float).reshape(n),
                    np.asarray(gravity(qv), dtype=float).reshape(n),
                    zero if external is None else np.asarray(external(qv), dtype=float).reshape(n))

        return cls(n, terms)

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

    def inverse(self, q, qd, qdd, t=None):
        m, c, g, f = self.terms(q, qd, t)
        return m @ np.asarray(qdd, dtype=float) + c + g - f

    def forward(self, q, qd, tau, t=None):
        """qdd = M^-1 (tau + f_ext - c - g)."""
        m, c, g, f = self.terms(q, qd, t)
        return np.linalg.solve(m, tau + f - c - g)

    def terms_many(self, Q, QD, T=None):
        return self._terms_many(Q, QD, T) if self.timed else self._terms_many(Q, QD)

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


def _sympified(subs: dict) -> dict:
    return {sp.sympify(k): sp.sympify(v) for k, v in subs.items()}
