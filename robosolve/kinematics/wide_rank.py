"""The maximal minors of a wide Jacobian (3×n position, 6×n geometric, n > rows) by structure,
within a counted budget of polynomial terms.

J loses rank where all its maximal minors vanish together (robosolve.kinematics.singularities).
Expanded in frame 0 the minors of a 6-joint arm's position Jacobian take sympy minutes; here:

* the Jacobian is built in the trig ring (robosolve.core.trigring, `RingChain`): entries are
  reduced polynomials in cᵢ, sᵢ;
* its rows are written in the axes of the frame k of the chain that makes them smallest (the
  fewest ring terms, a count), and the geometric Jacobian's velocity is taken at k's origin:
  J_k = [[Rᵀ, 0], [0, Rᵀ]]·[[I, −[o_k − P]], [0, I]]·J, a product of matrices of determinant 1,
  so every maximal minor of J_k equals the same minor of J (the minors shown are J's);
* columns that are identically zero (a joint that does not move the point) give zero minors;
* each minor is a determinant in the ring (Laplace expansion with its sub-minors memoised),
  factored as a polynomial (robosolve.kinematics.structured_det's factors).

The budget is a count, the same on every machine (spec §2): the ring terms of every sub-minor
and minor computed so far; past `max_terms` the work stops (`OverBudget`) and the caller answers
with the numeric distance from singularity. Pure math, no solver, no I/O, no clock.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import sympy as sp

from robosolve.kinematics.structured_det import RingChain, _factored

__all__ = ["OverBudget", "WideMinors", "wide_minors"]


class OverBudget(Exception):
    """The minors need more ring terms than the budget allows (`terms` counted when it stopped)."""

    def __init__(self, terms: int, budget: int):
        super().__init__(f"{terms:,} polynomial terms, above the budget of {budget:,}")
        self.terms, self.budget = terms, budget


@dataclass
class WideMinors:
    frame: str                     # the frame whose axes (and origin, geometric) the rows use
    columns: list                  # maximal column sets (joint indices), in lexicographic order
    minors: list                   # their determinants, factored (0 where identically zero)
    terms: int                     # ring terms counted (the budget's measure)
    zero_columns: list = field(default_factory=list)   # joints that do not move the point


def _terms(p) -> int:
    return len(p.terms()) if p != 0 else 0


def _rows_in(ring, rows, k, geometric, point):
    """The Jacobian's rows in the axes of frame k (velocity at k's origin when geometric)."""
    m0 = ring.M0(k)
    rot = [[m0[r][c] for c in range(3)] for r in range(3)]
    return _moved(ring.alg, rows, rot, [m0[r][3] - point[r] for r in range(3)], geometric)


def _moved(alg, rows, rot, d, geometric):
    """Rows (3 linear, then 3 angular when geometric) written in axes rotated by `rot`, the
    linear ones first moved by ω × d (the velocity at a point d further, when geometric)."""
    n = len(rows[0])
    lin = [list(r) for r in rows[:3]]
    if geometric:
        # v_k = v_P + ω × (o_k − P)
        w = rows[3:]
        for c in range(n):
            cross = (w[1][c] * d[2] - w[2][c] * d[1], w[2][c] * d[0] - w[0][c] * d[2],
                     w[0][c] * d[1] - w[1][c] * d[0])
            for r in range(3):
                lin[r][c] = lin[r][c] + cross[r]
    blocks = [lin] + ([rows[3:]] if geometric else [])
    out = []
    for block in blocks:
        for r in range(3):
            out.append([alg.reduce(sum((rot[i][r] * block[i][c] for i in range(3)), alg.zero))
                        for c in range(n)])
    return out


def _rows_in_every_frame(ring, rows, geometric, point):
    """`_rows_in` for frame 0 and every frame of the chain, each from the one before by its local
    pose: rows_{k+1} = ᵏR_{k+1}ᵀ (rows_k, the linear ones moved by ω × ᵏt_{k+1} when geometric).
    The local rotation has the entries of one joint, so each step is cheap where ⁰R_k·rows costs a
    product of long polynomials; in the ring's normal form (reduced modulo sᵢ² + cᵢ² = 1, unique
    for exact coefficients) the rows are the same elements. Decimal coefficients, whose sums would
    round in another order, take `_rows_in` frame by frame."""
    alg = ring.alg
    frames = ["0"] + list(ring.chain)
    if not (alg.ring.domain.is_Exact and all(f in ring.data.algebra.local for f in frames[1:])):
        return [_rows_in(ring, rows, k, geometric, point) for k in frames]
    out = [_rows_in(ring, rows, "0", geometric, point)]
    for frame in frames[1:]:
        local = ring.data.algebra.local[frame]
        rot = [[local[r][c] for c in range(3)] for r in range(3)]
        out.append(_moved(alg, out[-1], rot, [local[r][3] for r in range(3)], geometric))
    return out


class _Counter:
    def __init__(self, budget):
        self.budget, self.total = budget, 0

    def add(self, p):
        self.total += _terms(p)
        if self.budget is not None and self.total > self.budget:
            raise OverBudget(self.total, self.budget)


def _minor(alg, rows, rs, cs, memo, counter):
    """det of rows rs × columns cs (tuples), Laplace along the first row, sub-minors memoised."""
    key = (rs, cs)
    if key in memo:
        return memo[key]
    if len(rs) == 1:
        out = rows[rs[0]][cs[0]]
    else:
        out = alg.zero
        for j, c in enumerate(cs):
            a = rows[rs[0]][c]
            if a == 0:
                continue
            sub = _minor(alg, rows, rs[1:], cs[:j] + cs[j + 1:], memo, counter)
            if sub == 0:
                continue
            term = a * sub
            out = out + term if j % 2 == 0 else out - term
        out = alg.reduce(out)
        counter.add(out)
    memo[key] = out
    return out


def wide_minors(model, point_frame: str, point_local, frame: str, geometric: bool,
                max_terms: int | None) -> WideMinors | None:
    """The maximal minors of the (3×n position or 6×n geometric) Jacobian of the point, or None when
    the poses are not trig polynomials or J is not wide. Raises OverBudget past `max_terms`."""
    top = frame if geometric and point_frame in model.chain(frame) + ["0"] else point_frame
    ring = RingChain(model, top, points=[list(point_local)])
    alg = ring.alg
    if alg is None or (geometric and frame != top and frame not in ring.chain + ["0"]):
        return None
    n = len(model.q)
    m = 6 if geometric else 3
    if n <= m:
        return None
    w = ring.point0(point_frame, ring.points[0])
    l_point = [ring.l0(i, point_frame) for i in range(n)]
    l_frame = [ring.l0(i, frame) for i in range(n)] if geometric else l_point
    rows = ring.columns(l_point, l_frame, w)[:m]
    candidates = _rows_in_every_frame(ring, rows, geometric, w)
    sizes = [sum(_terms(x) for row in cand for x in row) for cand in candidates]
    best = min(range(len(candidates)), key=lambda i: (sizes[i], i))
    chosen, name = candidates[best], (["0"] + list(ring.chain))[best]
    counter = _Counter(max_terms)
    counter.total = sizes[best]
    if max_terms is not None and counter.total > max_terms:
        raise OverBudget(counter.total, max_terms)
    zero_cols = [c for c in range(n) if all(chosen[r][c] == 0 for r in range(m))]
    memo: dict = {}
    columns, minors = [], []
    for cs in itertools.combinations(range(n), m):
        columns.append(list(cs))
        if any(c in zero_cols for c in cs):
            minors.append(sp.Integer(0))
            continue
        d = _minor(alg, chosen, tuple(range(m)), cs, memo, counter)
        minors.append(sp.Integer(0) if d == 0 else _factored(alg, d, model.q))
    return WideMinors(name, columns, minors, counter.total, zero_cols)
