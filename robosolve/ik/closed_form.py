"""Closed-form inverse kinematics by the eliminations of an exam solution.

The unknowns are solved one at a time; each solved joint is a *stage* with
one or two alternatives (expressions in the known symbols: parameters, target
symbols and the joints solved before it).  Branches are the products of the
alternatives, so the symbolic work is done once whatever the number of
solutions.  Rules, tried in this order on the remaining equations (each
``e = 0``):

1. an equation with one unknown: when a second equation has that joint as its only unknown and
   the two, linear in (cos q, sin q), fix both (Cramer), ``q = atan2(sin q, cos q)``, one value
   (a wrist's ZYZ-like angles from ³R₆'s entries); else from the one equation,
   revolute ``a cos q + b sin q + c = 0`` gives ``cos q = K`` (q = +-acos K),
   ``sin q = K`` (q = asin K, pi - asin K), ``tan q = -a/b`` (two atan2) or
   ``q = atan2(b, a) +- acos(-c / sqrt(a^2 + b^2))``; prismatic: linear or
   quadratic in q;
2. an unknown that appears linearly with a known coefficient (``theta1 +
   theta2 + theta3 = phi``, ``z = h - l``) is isolated and substituted;
3. a pair of equations that is a rotation by q of a vector (u, w),
   ``(e_i, e_j) = Rot(q)(u, w) - (X, Y)``: the combination ``-X sin q + Y cos q
   = w`` has q as its only unknown (shoulder angle of an anthropomorphic arm,
   polar robots);
4. a pair linear in (cos q, sin q): Cramer gives cos q = C/D, sin q = S/D,
   ``C^2 + S^2 = D^2`` eliminates q (the cos theta2 formula of a 2R arm), and q
   is recovered later as atan2(S, C).

Rule 4 is attempted on a pair only when its Cramer numerators and determinant together have at
most `ELIMINATION_OPS` operations (a count, the same on every machine): past it no closed form
is derived, with the reason, and the solutions are numeric. Everything is plain sympy; `derive`
should still run under a time limit (a safety net).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import sympy as sp

from robosolve.core.simplify import common_factors, ik_fraction, memoised
from robosolve.core.opcount import count_ops
from robosolve.core.printing import latex


class NoClosedForm(Exception):
    """No rule applies: the caller answers numerically."""


# The most operations (count_ops of the Cramer numerators and determinant of a pair) a joint is
# eliminated from: an exam arm's pairs have at most 30 (a UR5's or a KUKA's position equations:
# 25), and their eliminated equations take milliseconds; a 3R arm with a decimal twist (alpha:
# 1.5708, whose cosine -3.7e-6 keeps every term) gives pairs of 400-800, each eliminated in
# seconds into an equation of 3,000 operations, and ended in no closed form only when the 20 s
# safety net struck — at a time that followed the machine's load, and so did the answer's note.
ELIMINATION_OPS = 300


class _TooLong(Exception):
    """A pair too long to eliminate a joint from (its operations)."""

    def __init__(self, ops: int):
        self.ops = ops


def whole_floats(e):
    """Whole-number floats as integers (1.0*px -> px): sympy's polynomial algebra over floats
    (`Poly`, `rem` of a chain with numbers) gives every coefficient as a float, 1 included;
    the report and results.json print whole numbers as integers (render/numbers.py's policy)."""
    e = sp.sympify(e)
    whole = {f: sp.Integer(int(f)) for f in e.atoms(sp.Float) if float(f).is_integer()}
    return e.xreplace(whole) if whole else e


@dataclass
class Stage:
    """One solved joint: its alternatives and how they were obtained."""

    joint: sp.Symbol
    alternatives: list[sp.Expr]
    rule: str                         # cos, sin, tan, phase, linear, quadratic, atan2, isolate
    equation: sp.Expr | None = None   # the equation (= 0) it came from
    lhs: str | None = None            # e.g. r"\cos\theta_2" for the step display
    rhs: sp.Expr | None = None        # the value of lhs (K of cos q = K)
    extra: dict = field(default_factory=dict)


@dataclass
class Step:
    """A derivation step as data (the solver renders it)."""

    title: str
    text: str
    equations: list[tuple[str, object]] = field(default_factory=list)


@dataclass
class ClosedForm:
    unknowns: list[sp.Symbol]
    stages: list[Stage]
    steps: list[Step]
    conditions: list[sp.Expr]         # target compatibility: each must be 0

    def branches(self) -> list[dict]:
        """Every combination of alternatives: mapping joint -> expression.

        An expression may contain the joints found before it (see `order`);
        auxiliary quantities are substituted."""
        out = [dict()]
        for st in self.stages:
            new = []
            for b in out:
                for alt in st.alternatives:
                    nb = dict(b)
                    nb[st.joint] = alt
                    new.append(nb)
            out = new
        aux = [st.joint for st in self.stages if st.rule == "aux"]
        result = []
        for b in out:
            e = {}
            for st in self.stages:
                val = b[st.joint]
                if aux:
                    val = val.subs({a: e[a] for a in aux if a in e})
                e[st.joint] = val
            result.append({q: e[q] for q in self.unknowns})
        return result

    def order(self) -> list[sp.Symbol]:
        """The joints in the order they are found (an expression may use earlier ones)."""
        return [st.joint for st in self.stages if st.rule != "aux"]

    def branch_labels(self) -> list[list[int]]:
        labels = [[]]
        for st in self.stages:
            labels = [b + [k] for b in labels for k in range(len(st.alternatives))]
        return labels


# ---------------------------------------------------------------------------
# helpers

# The derivation asks the same questions of the same expressions again (a pair's rotation
# test in `_trig_pairs`, in `_best_pair_candidate`, in `_eliminated_equation`; the linear
# form of an equation left unchanged by an elimination): the answers are pure functions of
# the expression, kept in the project's one memo (core/simplify.memoised).
@memoised
def _is_zero(e) -> bool:
    """Exact zero test: trig of every symbol to (c, s) with c^2 + s^2 = 1, then expand."""
    e = sp.expand(e)
    if e == 0:
        return True
    syms = sorted(e.free_symbols, key=sp.default_sort_key)
    # quick numeric rejection at two fixed points
    for k in (1, 2):
        vals = {s: sp.Float(0.3 + 0.17 * k * (i + 1) + 0.011 * i * i) for i, s in enumerate(syms)}
        try:
            v = complex(e.evalf(subs=vals))
            if abs(v) > 1e-8:
                return False
        except (TypeError, ValueError):
            break
    g = _expanded_trig(e)
    args = sorted({a.args[0] for a in g.atoms(sp.sin, sp.cos) if a.args[0].is_Symbol}, key=sp.default_sort_key)
    g, _, rel = _to_poly_symbols(g, args)
    return _reduce_pythagoras(g, rel) == 0


def _cs(q):
    # plain symbols with reserved names: equal across calls (Dummies are not)
    return sp.Symbol("_c__" + q.name), sp.Symbol("_s__" + q.name)


@memoised
def _expanded_trig(expr):
    """expand(expand_trig(expr)), once per expression (asked for each joint in turn)."""
    return sp.expand(sp.expand_trig(expr))


@memoised
def trig_linear(expr, q):
    """(a, b, c) with expr = a cos q + b sin q + c, free of q; None otherwise."""
    e = _expanded_trig(expr)
    C, S = _cs(q)
    e = e.subs({sp.cos(q): C, sp.sin(q): S})
    if e.has(q):
        return None
    try:
        p = sp.Poly(e, C, S)
    except sp.PolynomialError:
        return None
    if p.total_degree() > 1:
        return None
    return tuple(whole_floats(p.coeff_monomial(m)) for m in (C, S, 1))


def _unknowns_in(e, unknowns):
    fs = e.free_symbols
    return [q for q in unknowns if q in fs]


def _to_poly_symbols(e, qs):
    """Replace cos/sin of each joint by dummy symbols (after expanding)."""
    e = _expanded_trig(sp.sympify(e))
    rep, back, rel = {}, {}, []
    for q in qs:
        C, S = _cs(q)
        rep[sp.cos(q)] = C
        rep[sp.sin(q)] = S
        back[C] = sp.cos(q)
        back[S] = sp.sin(q)
        rel.append((C, S))
    return sp.expand(e.subs(rep)), back, rel


def _reduce_pythagoras(e, rel):
    for C, S in rel:
        if e.has(S):
            e = whole_floats(sp.expand(sp.rem(e, S**2 + C**2 - 1, S)))
    return e


# ---------------------------------------------------------------------------
# rules

def _solve_single(e, q, revolute, latex_q):
    """Stage for equation e(q) = 0 with q the only unknown, or None."""
    if revolute:
        abc = trig_linear(e, q)
        if abc is None:
            return None
        a, b, c = abc
        za, zb, zc = _is_zero(a), _is_zero(b), _is_zero(c)
        if za and zb:
            return None
        if zb:
            K = ik_fraction(-c / a)
            return Stage(q, [sp.acos(K), -sp.acos(K)], "cos", e, rf"\cos {latex_q}", K)
        if za:
            K = ik_fraction(-c / b)
            return Stage(q, [sp.asin(K), sp.pi - sp.asin(K)], "sin", e, rf"\sin {latex_q}", K)
        if zc:
            a, b = ik_fraction(a), ik_fraction(b)
            return Stage(q, [sp.atan2(-a, b), sp.atan2(a, -b)], "tan", e, rf"\tan {latex_q}", ik_fraction(-a / b))
        a, b, c = ik_fraction(a), ik_fraction(b), ik_fraction(c)
        r = sp.sqrt(a**2 + b**2)
        phi = sp.atan2(b, a)
        K = ik_fraction(-c / r)
        return Stage(q, [phi + sp.acos(K), phi - sp.acos(K)], "phase", e,
                     rf"\cos({latex_q} - \varphi)", K, {"phi": phi, "a": a, "b": b, "c": c})
    ee = sp.expand(e)
    try:
        p = sp.Poly(ee, q)
    except sp.PolynomialError:
        return None
    coeffs = [whole_floats(cf) for cf in p.all_coeffs()]
    if any(cf.has(q) for cf in coeffs):
        return None
    d = p.degree()
    if d == 1:
        c1, c0 = coeffs
        return Stage(q, [ik_fraction(-c0 / c1)], "linear", e, latex_q, ik_fraction(-c0 / c1))
    if d == 2:
        a, b, c = [ik_fraction(x) for x in coeffs]
        disc = ik_fraction(b**2 - 4 * a * c)
        if _is_zero(b):
            root = ik_fraction(sp.sqrt(-c / a))
            return Stage(q, [root, -root], "quadratic", e, latex_q + "^2", ik_fraction(-c / a), {"disc": -c / a})
        return Stage(q, [ik_fraction((-b + sp.sqrt(disc)) / (2 * a)), ik_fraction((-b - sp.sqrt(disc)) / (2 * a))],
                     "quadratic", e, latex_q, None, {"disc": disc})
    return None


def _isolate_linear(e, unknowns, revolute_of):
    """(q, expr) if e is linear in some unknown q with a known coefficient (q not in trig)."""
    for q in reversed(unknowns):
        if q not in e.free_symbols:
            continue
        ee = sp.expand(e)
        coeff = ee.coeff(q, 1)
        if coeff == 0 or _unknowns_in(coeff, unknowns):
            continue
        rest = sp.expand(ee - coeff * q)
        if rest.has(q):
            continue
        return q, ik_fraction(-rest / coeff)
    return None


_TEX = [latex]


def _tex(e):
    return _TEX[0](e)


def derive(equations, unknowns, revolute, latex_names=None, angular=None, tex=None) -> ClosedForm:
    """Closed-form solution of equations (each an expression = 0) for `unknowns`.

    `tex` renders sympy objects in the step texts (default sympy.latex).
    Raises NoClosedForm when no rule applies.  Run it under a time limit.
    """
    _TEX[0] = tex or latex
    try:
        return _derive(equations, unknowns, revolute, latex_names)
    finally:
        _TEX[0] = latex


def _derive(equations, unknowns, revolute, latex_names=None) -> ClosedForm:
    return _Elimination(equations, unknowns, revolute, latex_names).run()


def _without_common_scale(S, C):
    """(S, C) with a positive number both carry divided out: atan2(2 y, 2 x) is atan2(y, x)."""
    ks, kc = S.as_coeff_Mul()[0], C.as_coeff_Mul()[0]
    k = abs(ks)
    if k.is_Number and k != 0 and k != 1 and abs(float(k) - abs(float(kc))) <= 1e-15 * float(k):
        return whole_floats(ik_fraction(S / k)), whole_floats(ik_fraction(C / k))
    return S, C


def _is_rotation(Ai, Bi, Aj, Bj) -> bool:
    """(A_i, B_i, A_j, B_j) = (u, -w, w, u): the pair rotates the vector (u, w) by q."""
    return _is_zero(Ai - Bj) and _is_zero(Aj + Bi)


def _trig_pairs(eqs, q):
    """Every pair (i, j, (A_i, B_i, E_i), (A_j, B_j, E_j)) of equations linear in (cos q, sin q).

    A reflection has its first equation's signs changed: it is then a rotation."""
    lin = []
    for i, e in enumerate(eqs):
        if q in e.free_symbols:
            abc = trig_linear(e, q)
            if abc is not None and not (_is_zero(abc[0]) and _is_zero(abc[1])):
                lin.append((i, abc))
    out = []
    for (i, (Ai, Bi, Ei)), (j, (Aj, Bj, Ej)) in [(x, y) for k, x in enumerate(lin) for y in lin[k + 1:]]:
        if not _is_rotation(Ai, Bi, Aj, Bj) and _is_zero(Ai + Bj) and _is_zero(Aj - Bi):
            Ai, Bi, Ei = -Ai, -Bi, -Ei
        out.append((i, j, (Ai, Bi, Ei), (Aj, Bj, Ej)))
    return out


def _rotation_split(q, ci, cj):
    """A rotation pair (e_i, e_j) = Rot(q)(u, w) - (X, Y) = 0 rotated back by -q:
    F1 = X cos q + Y sin q - u and F2 = -X sin q + Y cos q - w, both = 0."""
    (Ai, _, Ei), (Aj, _, Ej) = ci, cj
    u_, w_ = Ai, Aj
    F1 = sp.expand(-sp.cos(q) * Ei - sp.sin(q) * Ej - u_)
    F2 = sp.expand(sp.sin(q) * Ei - sp.cos(q) * Ej - w_)
    return F1, F2


def _eliminated_equation(ci, cj):
    """The pair linear in (cos q, sin q) solved by Cramer, cos q = Nc/D, sin q = Ns/D, and
    q removed with cos^2 + sin^2 = 1: (new equation, Nc, Ns, D, rotation data or None);
    None when D or the new equation is identically zero."""
    (Ai, Bi, Ei), (Aj, Bj, Ej) = ci, cj
    D = sp.expand(Ai * Bj - Aj * Bi)
    Nc = sp.expand(Bi * Ej - Bj * Ei)
    Ns = sp.expand(Aj * Ei - Ai * Ej)
    ops = count_ops(D) + count_ops(Nc) + count_ops(Ns)
    if ops > ELIMINATION_OPS:
        raise _TooLong(ops)
    if _is_zero(D):
        return None
    rotation = _is_rotation(Ai, Bi, Aj, Bj)
    if rotation:
        # (X, Y) = Rot(q)(u, w): Nc^2 + Ns^2 = D (X^2 + Y^2) and D = u^2 + w^2
        raw = sp.expand(sp.expand_trig(Ei**2 + Ej**2 - D))
    else:
        raw = sp.expand(sp.expand_trig(Nc**2 + Ns**2 - D**2))
    trig_args = sorted({a.args[0] for a in (raw.atoms(sp.sin, sp.cos) | D.atoms(sp.sin, sp.cos))
                        if a.args[0].is_Symbol}, key=sp.default_sort_key)
    g, back, rel = _to_poly_symbols(raw, trig_args)
    g = _reduce_pythagoras(g, rel)
    if rotation:
        new = g
    else:
        Dp, _, _ = _to_poly_symbols(D, trig_args)
        Dp = _reduce_pythagoras(Dp, rel)
        h = sp.cancel(g / Dp)
        num, den = sp.fraction(h)
        dummies = {s for pair in rel for s in pair}
        new = num if not (den.free_symbols & dummies) else g
    new = sp.expand(common_factors(new).subs(back))
    if _is_zero(new):
        return None
    rot = (Ai, Aj, -Ei, -Ej) if rotation else None
    return new, Nc, Ns, D, rot


class _Candidate(NamedTuple):
    """A way to remove a joint from a pair of equations; the smallest (rank, unknowns_left,
    joint_index) is taken: rotations before eliminations, then the fewest unknowns left."""

    rank: int
    unknowns_left: int
    joint_index: int
    kind: str                 # rotation | eliminate
    joint: sp.Symbol
    i: int
    j: int
    data: tuple


class _Elimination:
    """One derivation: the rules of the module docstring applied in order until every joint
    is solved.  State: the equations left, the joints still unknown (`remaining`), the joints
    eliminated but not yet recovered (`pending`), and what was found so far."""

    MAX_ROUNDS = 50

    def __init__(self, equations, unknowns, revolute, latex_names=None):
        self.unknowns = list(unknowns)
        self.revolute = dict(zip(self.unknowns, revolute))
        self.names = latex_names or {q: latex(q) for q in self.unknowns}
        self.eqs = [sp.expand(sp.sympify(e)) for e in equations]
        self.remaining = list(self.unknowns)   # still unknown and present in the equations
        self.pending = []                      # (q, kind, data): recovered once its dependencies are known
        self.stages: list[Stage] = []
        self.steps: list[Step] = []
        self.conditions: list[sp.Expr] = []
        self.aux_count = 0
        # auxiliary names must not clash with a symbol of the equations
        self.taken = set().union(*[e.free_symbols for e in self.eqs]) if self.eqs else set()

    def run(self) -> ClosedForm:
        rounds = 0
        while self.remaining:
            rounds += 1
            if rounds > self.MAX_ROUNDS:
                raise NoClosedForm("too many elimination steps")
            self._set_aside_conditions()
            if not self.eqs:
                raise NoClosedForm("fewer independent equations than unknowns")
            if self._solve_single_unknown():
                self._flush_pending()
                self._introduce_aux()
            elif self._isolate_linear_unknown():
                self._flush_pending()
            else:
                self._eliminate_from_pair()
                self._flush_pending()
                self._introduce_aux()
        self._flush_pending()
        if self.pending:
            raise NoClosedForm("an eliminated joint could not be recovered")
        # equations left over with every unknown solved are further conditions
        self._set_aside_conditions()
        return ClosedForm(self.unknowns, self.stages, self.steps, self.conditions)

    def _unknown_now(self):
        return self.remaining + [p[0] for p in self.pending]

    def _by_fewest_unknowns(self):
        return sorted(enumerate(self.eqs), key=lambda t: (len(_unknowns_in(t[1], self.remaining)), t[0]))

    def _set_aside_conditions(self):
        """Equations with no unknown left are compatibility conditions on the target."""
        keep = []
        for e in self.eqs:
            if not _unknowns_in(e, self.remaining):
                if not _is_zero(e):
                    self.conditions.append(e)
            else:
                keep.append(e)
        self.eqs = keep

    def _solve_single_unknown(self) -> bool:
        """Rule 1: an equation with a single unknown."""
        for idx, e in self._by_fewest_unknowns():
            us = _unknowns_in(e, self.remaining)
            if len(us) != 1:
                continue
            q = us[0]
            pair = self._solve_pair(q) if self.revolute[q] else None
            if pair:
                idx, st, step = pair
            else:
                st = _solve_single(e, q, self.revolute[q], self.names[q])
                step = _single_step(st, self.names[q]) if st is not None else None
            if st is None:
                continue
            self.stages.append(st)
            self.steps.append(step)
            self.remaining.remove(q)
            self.eqs.pop(idx)
            return True
        return False

    def _solve_pair(self, q):
        """Rule 1 on two equations: when two equations have q as their only unknown and the pair,
        linear in (cos q, sin q), fixes both (Cramer, determinant not identically 0), q is the one
        angle atan2(sin q, cos q): one value, where either equation alone gives two (±acos, asin
        and pi - asin, phase) and only one of them satisfies the other (a wrist's ZYZ-like angles:
        q4 from a13 and a23 once q5 is known). The shortest such pair; (index of its first
        equation, stage, step) or None. The partner stays among the equations (a condition once
        q is known)."""
        lin = [(k, e, trig_linear(e, q)) for k, e in enumerate(self.eqs) if _unknowns_in(e, self.remaining) == [q]]
        lin = [t for t in lin if t[2] is not None]
        best = None
        for n, (i, ei, (Ai, Bi, Ei)) in enumerate(lin):
            for j, ej, (Aj, Bj, Ej) in lin[n + 1:]:
                D = sp.expand(Ai * Bj - Aj * Bi)
                if _is_zero(D):
                    continue
                C = ik_fraction(sp.expand(Bi * Ej - Bj * Ei) / D)
                S = ik_fraction(sp.expand(Aj * Ei - Ai * Ej) / D)
                ops = count_ops(C) + count_ops(S)
                if best is None or ops < best[0]:
                    best = (ops, i, ei, ej, C, S)
        if best is None:
            return None
        _, i, ei, ej, C, S = best
        alt = sp.atan2(*_without_common_scale(S, C))
        return (i, Stage(q, [alt], "atan2", ei, self.names[q], alt, {"S": S, "C": C}),
                _pair_step(self.names[q], ei, ej, C, S, alt))

    def _isolate_linear_unknown(self) -> bool:
        """Rule 2: an unknown that appears linearly is isolated and substituted."""
        for idx, e in self._by_fewest_unknowns():
            iso = _isolate_linear(e, self.remaining, self.revolute)
            if iso is None:
                continue
            q, expr = iso
            self.steps.append(_isolation_step(self.names[q], e, expr))
            self.eqs.pop(idx)
            self.eqs = [sp.expand(x.subs(q, expr)) for x in self.eqs]
            self.remaining.remove(q)
            self.pending.append((q, "isolate", expr))
            return True
        return False

    def _eliminate_from_pair(self):
        """Rules 3 and 4: the best way to remove a joint from a pair of equations."""
        cand = self._best_pair_candidate()
        q, name = cand.joint, self.names[cand.joint]
        ei, ej = self.eqs[cand.i], self.eqs[cand.j]
        rest = [e for k, e in enumerate(self.eqs) if k not in (cand.i, cand.j)]
        if cand.kind == "rotation":
            Fa, Fb = cand.data
            self.steps.append(_rotation_step(name, ei, ej, Fa, Fb))
            self.eqs = [Fa, Fb] + rest
        else:
            new, Nc, Ns, D, rot = cand.data
            self.steps.append(_elimination_step(name, ei, ej, new))
            self.remaining.remove(q)
            self.pending.append((q, "atan2", (Ns, Nc, D, rot)))
            self.eqs = [new] + rest

    def _best_pair_candidate(self) -> _Candidate:
        """Rotations first (cheap); eliminations only when no rotation applies."""
        rotations, pairs = [], []
        for q in [u for u in self.remaining if self.revolute[u]]:
            for i, j, ci, cj in _trig_pairs(self.eqs, q):
                if _is_rotation(ci[0], ci[1], cj[0], cj[1]):
                    cand = self._rotation_candidate(q, i, j, ci, cj)
                    if cand is not None:
                        rotations.append(cand)
                pairs.append((q, i, j, ci, cj))
        cands = rotations or self._elimination_candidates(pairs)
        if not cands:
            raise NoClosedForm("no elimination pattern applies")
        return min(cands, key=lambda c: c[:3])

    def _rotation_candidate(self, q, i, j, ci, cj) -> _Candidate | None:
        """Rule 3: the combination of a rotation pair that has q as its only unknown."""
        F1, F2 = _rotation_split(q, ci, cj)
        for Fa, Fb in ((F2, F1), (F1, F2)):
            if _unknowns_in(Fa, self.remaining) == [q] and _solve_single(Fa, q, True, self.names[q]) is not None:
                return _Candidate(0, len(_unknowns_in(Fb, self.remaining)), self.unknowns.index(q), "rotation",
                                  q, i, j, (Fa, Fb))
        return None

    def _elimination_candidates(self, pairs) -> list[_Candidate]:
        """Rule 4 for each pair, until one leaves an equation in one unknown (the best possible);
        pairs above ELIMINATION_OPS are not eliminated (none left: NoClosedForm says so)."""
        cands, too_long = [], []
        for q, i, j, ci, cj in pairs:
            try:
                found = _eliminated_equation(ci, cj)
            except _TooLong as exc:
                too_long.append(exc.ops)
                continue
            if found is None:
                continue
            cands.append(_Candidate(1, len(_unknowns_in(found[0], self.remaining)), self.unknowns.index(q),
                                    "eliminate", q, i, j, found))
            if cands[-1].unknowns_left <= 1:
                break
        if not cands and too_long:
            raise NoClosedForm(f"the equations are too long to eliminate a joint by hand "
                               f"({min(too_long)} operations, at most {ELIMINATION_OPS})")
        return cands

    def _flush_pending(self):
        """Recover every eliminated joint whose expression no longer involves an unknown."""
        changed = True
        while changed:
            changed = False
            for item in list(self.pending):
                if self._recover(*item):
                    self.pending.remove(item)
                    changed = True

    def _recover(self, q, kind, data) -> bool:
        others = [u for u in self._unknown_now() if u != q]
        name = self.names[q]
        if kind == "isolate":
            if _unknowns_in(data, others):
                return False
            self.stages.append(Stage(q, [data], "isolate", None, name, data))
            return True
        S, C, D, rot = data
        if _unknowns_in(S, others) or _unknowns_in(C, others) or _unknowns_in(D, others):
            return False
        if rot is not None:
            u_, w_, X, Y = [ik_fraction(v) for v in rot]
            alt = sp.atan2(Y, X) - sp.atan2(w_, u_)
            self.stages.append(Stage(q, [alt], "atan2", None, name, alt,
                                     {"S": S, "C": C, "D": D, "rot": (u_, w_, X, Y)}))
            self.steps.append(_recovery_by_rotation_step(name, u_, w_, X, Y, alt))
        else:
            alt = sp.atan2(ik_fraction(S / D), ik_fraction(C / D))
            self.stages.append(Stage(q, [alt], "atan2", None, name, alt, {"S": S, "C": C, "D": D}))
            self.steps.append(_recovery_by_cramer_step(name, ik_fraction(C / D), ik_fraction(S / D), alt))
        return True

    def _introduce_aux(self):
        """Name the known part of an equation when it involves solved joints (r = x c1 + y s1)."""
        solved = {st.joint for st in self.stages if st.rule != "aux"}
        self.eqs = [self._with_aux(e, solved) for e in self.eqs]

    def _with_aux(self, e, solved):
        e = sp.expand(e)
        unk = set(self._unknown_now())
        known = sp.Add(*[t for t in sp.Add.make_args(e) if not (t.free_symbols & unk)])
        if not ((known.free_symbols & solved) and count_ops(known) > 2 and known != e
                and len(_unknowns_in(e, list(unk))) > 1):
            return e
        sign = -1 if known.could_extract_minus_sign() else 1
        self.aux_count += 1
        while sp.Symbol(f"rho_{self.aux_count}") in self.taken:
            self.aux_count += 1
        r = sp.Symbol(f"rho_{self.aux_count}")
        definition = ik_fraction(sign * known)
        self.stages.append(Stage(r, [definition], "aux", None, _tex(r), definition))
        self.steps.append(Step(f"Auxiliary quantity ${_tex(r)}$",
                               "A known combination, named to keep the next steps short.",
                               [(_tex(r), definition)]))
        return sp.expand(e - known + sign * r)


# ---------------------------------------------------------------------------
# steps (derivation text as data)

def _isolation_step(name, e, expr) -> Step:
    return Step(
        f"${name}$ appears linearly",
        f"The equation ${_tex(e)} = 0$ gives ${name}$ directly; it is substituted "
        f"into the other equations.",
        [(name, expr)])


def _rotation_step(name, ei, ej, Fa, Fb) -> Step:
    return Step(
        f"${name}$ by a rotation of two equations",
        f"The two equations ${_tex(ei)} = 0$ and ${_tex(ej)} = 0$ rotate a vector by "
        f"${name}$; combining them with $\\cos {name}$ and $\\sin {name}$ leaves an "
        f"equation in ${name}$ alone and one without it.",
        [("0", ik_fraction(Fa)), ("0", ik_fraction(Fb))])


def _elimination_step(name, ei, ej, new) -> Step:
    return Step(
        f"Eliminate ${name}$ with $\\cos^2 + \\sin^2 = 1$",
        f"The equations ${_tex(ei)} = 0$ and ${_tex(ej)} = 0$ are linear in "
        f"$\\cos {name}$ and $\\sin {name}$. Solving for them (Cramer) and imposing "
        f"$\\cos^2 {name} + \\sin^2 {name} = 1$ removes ${name}$:",
        [("0", ik_fraction(new))])


def _recovery_by_rotation_step(name, u_, w_, X, Y, alt) -> Step:
    return Step(
        f"${name}$ from the two equations it was eliminated from",
        f"These two equations say that the vector $({_tex(X)},\\ {_tex(Y)})$ is the "
        f"vector $({_tex(u_)},\\ {_tex(w_)})$ rotated by ${name}$: "
        f"${name}$ is the difference of their directions (one value per branch).",
        [(name, alt)])


def _recovery_by_cramer_step(name, cos_q, sin_q, alt) -> Step:
    return Step(
        f"${name}$ from the two equations it was eliminated from",
        f"With the joints found so far, $\\cos {name}$ and $\\sin {name}$ follow "
        f"from the linear system (Cramer), and the angle from atan2 (one value per branch).",
        [(rf"\cos {name}", cos_q), (rf"\sin {name}", sin_q), (name, alt)])


def _pair_step(name, ei, ej, cos_q, sin_q, alt) -> Step:
    return Step(
        f"${name}$ from two equations",
        f"The equations ${_tex(ik_fraction(ei))} = 0$ and ${_tex(ik_fraction(ej))} = 0$ contain ${name}$ "
        f"only, through $\\cos {name}$ and $\\sin {name}$: together (Cramer) they give both, and the "
        f"angle from atan2 (one value, where either equation alone would give two).",
        [(rf"\cos {name}", cos_q), (rf"\sin {name}", sin_q), (name, alt)])


def _frac_tex(e):
    """LaTeX of a fraction with its numerator expanded (no double minus signs)."""
    num, den = sp.fraction(sp.together(e))
    if den == 1:
        return _tex(e)
    return rf"\frac{{{_tex(sp.expand(num))}}}{{{_tex(den)}}}"


def _single_step(st: Stage, name: str) -> Step:
    eq = [(st.lhs, _frac_tex(st.rhs) if st.rule in ("cos", "sin", "phase") else st.rhs)] \
        if st.rhs is not None else []
    if st.rule == "cos":
        text = f"This equation contains ${name}$ only, through its cosine: two solutions $\\pm$."
        eq.append((name, r"\pm \arccos\left(" + _frac_tex(st.rhs) + r"\right)"))
    elif st.rule == "sin":
        text = f"This equation contains ${name}$ only, through its sine: ${name} = \\arcsin K$ or $\\pi - \\arcsin K$."
        eq += [(name, st.alternatives[0]), (name, st.alternatives[1])]
    elif st.rule == "tan":
        text = f"This equation is $a\\cos {name} + b\\sin {name} = 0$: two solutions, $\\pi$ apart."
        eq += [(name, st.alternatives[0]), (name, st.alternatives[1])]
    elif st.rule == "phase":
        text = (f"This equation is $a\\cos {name} + b\\sin {name} + c = 0$; with "
                f"$\\varphi = \\operatorname{{atan2}}(b, a)$ it becomes "
                f"$\\sqrt{{a^2+b^2}}\\cos({name} - \\varphi) = -c$: two solutions.")
        eq += [(name, st.alternatives[0]), (name, st.alternatives[1])]
    elif st.rule == "quadratic":
        text = f"This equation is quadratic in ${name}$: two roots."
        eq += [(name, a) for a in st.alternatives]
    else:
        text = f"This equation is linear in ${name}$."
    return Step(f"${name}$", f"From ${_tex(ik_fraction(st.equation))} = 0$. " + text, eq)


# ---------------------------------------------------------------------------
# numeric evaluation of the branches

class DomainFailure(Exception):
    def __init__(self, what, value):
        super().__init__(what)
        self.what, self.value = what, value


CLAMP = 1e-9


def _acos(x):
    if abs(x) > 1 + CLAMP:
        raise DomainFailure("acos", x)
    return math.acos(max(-1.0, min(1.0, x)))


def _asin(x):
    if abs(x) > 1 + CLAMP:
        raise DomainFailure("asin", x)
    return math.asin(max(-1.0, min(1.0, x)))


def _sqrt(x):
    if x < -CLAMP:
        raise DomainFailure("sqrt", x)
    return math.sqrt(max(0.0, x))


def _atan2(y, x):
    if abs(x) < 1e-12 and abs(y) < 1e-12:
        raise DomainFailure("atan2", (y, x))
    return math.atan2(y, x)


_MODULE = {"acos": _acos, "asin": _asin, "sqrt": _sqrt, "atan2": _atan2}


@dataclass
class BranchValue:
    label: list[int]
    q: dict | None
    failure: tuple | None = None      # (stage index, joint, DomainFailure)
    partial: dict | None = None       # values found before the failure


def evaluate(cf: ClosedForm, values: dict) -> list[BranchValue]:
    """Evaluate every branch numerically. `values` maps every other symbol to a float."""
    known = dict(values)
    out = []
    funcs = []
    for k, st in enumerate(cf.stages):
        prev = [s.joint for s in cf.stages[:k]]
        fl = []
        for alt in st.alternatives:
            syms = sorted((alt.free_symbols - set(prev)), key=sp.default_sort_key)
            args = prev + syms
            fl.append((sp.lambdify(args, alt, modules=[_MODULE, "math"]), syms))
        funcs.append(fl)
    for label in cf.branch_labels():
        q = {}
        fail = None
        for k, (st, alt_k) in enumerate(zip(cf.stages, label)):
            f, syms = funcs[k][alt_k]
            try:
                args = [q[s.joint] for s in cf.stages[:k]] + [float(known[s]) for s in syms]
                v = float(f(*args))
                if not math.isfinite(v):
                    raise DomainFailure("nan", v)
            except DomainFailure as ex:
                fail = (k, st.joint, ex)
                break
            except (ZeroDivisionError, ValueError, OverflowError) as ex:
                fail = (k, st.joint, DomainFailure("zero", str(ex)))
                break
            q[st.joint] = v
        out.append(BranchValue(label, None if fail else q, fail, dict(q)))
    return out
