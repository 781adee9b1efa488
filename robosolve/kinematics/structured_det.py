"""det J by its structure, factored before anything is expanded (6-joint arms in seconds).

* **Decoupling at the wrist.** When the last three joint axes of a 6-joint arm meet at a
  point W (a spherical wrist: PUMA 560, Stanford arm), the geometric Jacobian taken at W,
  J_W = [[I, -[W - P]], [0, I]] · J_P (the velocity of W = v_P + ω × (W − P)), has the same
  determinant as J_P (the shear has determinant 1), and the wrist joints move W not at all,
  so J_W = [[J11, 0], [J21, J22]] is block triangular: det J = det J11 · det J22, the arm's
  (shoulder, elbow) times the wrist's.
* **Zero blocks in general.** Any square J whose zero pattern splits it into a block
  triangular form is cut the same way (rows/columns permuted, the sign kept).
* **Small determinants in the trig-polynomial ring.** Each block's entries become
  polynomials in cᵢ = cos qᵢ, sᵢ = sin qᵢ (robosolve.core.trigring); zero tests there are
  exact (reduced modulo sᵢ² + cᵢ² = 1); the block's determinant is a ring polynomial,
  factored as a polynomial (factors such as sᵢ² + cᵢ² are 1 and dropped), and each factor
  is turned back into sines and cosines of sums (cos(q2 + q3)) by core.simplify.tidy_products.

Pure math on sympy: no solver, no I/O. Callers run it under their time limit.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import sympy as sp

from robosolve.core.ring_factor import factor_list_by_contents
from robosolve.core.simplify import tidy_products
from robosolve.core.trigring import TrigAlgebra

__all__ = ["RingChain", "StructuredDet", "WristJacobian", "geometric_jacobian_ring", "structured_det",
           "wrist_decoupled_det"]


@dataclass
class StructuredDet:
    det: sp.Expr                                   # coefficient × product of tidied factors
    blocks: list = field(default_factory=list)     # [(rows, cols, block matrix, its det)]
    sign: int = 1


def _ring(entries, joints):
    alg = TrigAlgebra.from_inputs(list(joints), list(entries))
    return alg


def _ring_det(alg, m):
    """Laplace expansion along the first row (blocks are small: 1-3 rows). The minors of the
    lower rows are kept by their columns: a 6x6 block needs 63 of them, not 1,956 expansions
    (each is computed by the same steps whichever path reaches it, so the sum is the same)."""
    n = len(m)
    memo: dict = {}

    def det(row, cols):
        if len(cols) == 1:
            return m[row][cols[0]]
        if len(cols) == 2:
            a, b = cols
            return m[row][a] * m[row + 1][b] - m[row][b] * m[row + 1][a]
        hit = memo.get(cols)
        if hit is not None:
            return hit
        total = alg.zero
        for k, c in enumerate(cols):
            if m[row][c] == 0:
                continue
            term = m[row][c] * det(row + 1, cols[:k] + cols[k + 1:])
            total = total + term if k % 2 == 0 else total - term
        memo[cols] = total
        return total

    return det(0, tuple(range(n)))


def _blocks(zero, rows, cols):
    """Split the index sets into diagonal blocks of a block triangular form: the smallest
    column set C (|C| = |R|) whose rows R have zeros outside C, recursively."""
    n = len(rows)
    for k in range(1, n):
        for cs in itertools.combinations(cols, k):
            rs = [r for r in rows if all(zero[r][c] for c in cols if c not in cs)]
            if len(rs) == k:
                rest_r = [r for r in rows if r not in rs]
                rest_c = [c for c in cols if c not in cs]
                return [(rs, list(cs))] + _blocks(zero, rest_r, rest_c)
    return [(list(rows), list(cols))]


def _permutation_sign(order) -> int:
    sign, seen = 1, list(order)
    for i in range(len(seen)):
        while seen[i] != i:
            j = seen[i]
            seen[i], seen[j] = seen[j], seen[i]
            sign = -sign
    return sign


def _factored(alg, p, joints):
    """coefficient × Π tidy(factor)^k of a ring polynomial; factors free of the joints
    after tidying (sᵢ² + cᵢ² = 1, parameters) go into the coefficient."""
    coeff, factors = factor_list_by_contents(p)
    out = alg.ring.domain.to_sympy(coeff)
    for f, k in factors:
        reduced = alg.reduce(f)               # sᵢ² + cᵢ² is 1: such factors become constants
        out *= tidy_products(alg.to_expr(reduced)) ** k
    return out


def structured_det(j: sp.Matrix, joints) -> StructuredDet | None:
    """det J factored by structure, or None when the entries are not trig polynomials."""
    j = sp.Matrix(j)
    n = j.shape[0]
    if j.shape != (n, n):
        return None
    alg = _ring(list(j), joints)
    if alg is None:
        return None
    ring = [[alg.element(r * n + c) for c in range(n)] for r in range(n)]
    out = _structured_ring_det(alg, ring, joints)
    out.blocks = [(rs, cs, j.extract(rs, cs), d) for rs, cs, _, d in out.blocks]
    return out


def _structured_ring_det(alg, ring, joints) -> StructuredDet:
    n = len(ring)
    zero = [[alg.reduce(ring[r][c]) == 0 for c in range(n)] for r in range(n)]
    blocks = _blocks(zero, list(range(n)), list(range(n)))
    # det of a block triangular matrix after permuting rows and columns into that order
    row_order = [r for rs, _ in blocks for r in rs]
    col_order = [c for _, cs in blocks for c in cs]
    sign = _permutation_sign(row_order) * _permutation_sign(col_order)
    total = sp.Integer(sign)
    parts = []
    for rs, cs in blocks:
        d = _ring_det(alg, [[ring[r][c] for c in cs] for r in rs])
        if alg.reduce(d) == 0:
            return StructuredDet(sp.Integer(0), parts, sign)
        fd = _factored(alg, d, joints)
        parts.append((rs, cs, None, fd))
        total *= fd
    return StructuredDet(_collect(total, joints), parts, sign)


def _collect(expr, joints):
    """Constant factors together in front, the joint factors after (stable display)."""
    coeff, rest = sp.Integer(1), sp.Integer(1)
    for f in sp.Mul.make_args(expr):
        if any(f.has(q) for q in joints):
            rest *= f
        else:
            coeff *= f
    return coeff * rest


# ---------------------------------------------------------------------------
# the chain in the trig ring (poses, L matrices, the Jacobian at the wrist centre)

@dataclass
class WristJacobian:
    frame: str                 # the frame whose origin is the wrist centre W
    centre: sp.Matrix          # W in frame 0
    jacobian: sp.Matrix        # J_W (6×6), entries reduced and tidied (for the report)
    det: StructuredDet


class RingChain:
    """Poses ⁰Mf and ⁰Lᵢ of a serial chain in the trig ring, every product reduced
    (canonical: the entries of a serial arm's Jacobian come out multilinear, as compact
    as trigsimp would make them, in milliseconds): the one chain computation
    (core/chain/forward.py) over the ring, `model.ring_chain` (the model's
    core/chain/algebras.RingChainAlgebra over these frames)."""

    def __init__(self, model, frame: str, points=()):
        self.model = model
        self.chain = model.chain(frame)
        self.data = model.ring_chain(self.chain, points)
        self.alg = None if self.data is None else self.data.algebra.ring
        if self.alg is None:
            return
        self.points = self.data.algebra.points

    def M0(self, frame: str):
        return self.data.M(frame)

    def l0(self, i: int, frame: str):
        """⁰Lᵢ for the motion of `frame` (zero when joint i does not move it)."""
        return self.data.L(i, frame)

    def point0(self, frame: str, local):
        return self.data.algebra.point(self.M0(frame), local)

    def columns(self, l_point, l_frame, w):
        """Geometric Jacobian entries (rows × joints): ([uᵢ] w + tᵢ, uᵢ)."""
        alg = self.alg
        n = len(l_point)
        rows = [[None] * n for _ in range(6)]
        for c in range(n):
            lp, lf = l_point[c], l_frame[c]
            for r in range(3):
                rows[r][c] = alg.reduce(sum((lp[r][k] * w[k] for k in range(3)), lp[r][3]))
            for r, (a, b) in enumerate(((2, 1), (0, 2), (1, 0))):
                rows[3 + r][c] = lf[a][b]
        return rows

    def to_matrix(self, rows):
        return sp.Matrix([[tidy_products(self.alg.to_expr(x)) for x in row] for row in rows])


def geometric_jacobian_ring(model, point_frame: str, point_local, frame: str) -> sp.Matrix | None:
    """The 6×n geometric Jacobian (velocity of the point, angular velocity of `frame`)
    computed in the trig ring; None when the poses are not trig polynomials."""
    top = frame if point_frame in model.chain(frame) + ["0"] else point_frame
    ring = RingChain(model, top, points=[list(point_local)])
    if ring.alg is None or (frame != top and frame not in ring.chain + ["0"]):
        return None
    n = len(model.q)
    w = ring.point0(point_frame, ring.points[0])
    rows = ring.columns([ring.l0(i, point_frame) for i in range(n)], [ring.l0(i, frame) for i in range(n)], w)
    return ring.to_matrix(rows)


def wrist_decoupled_det(model, point_frame: str, frame: str) -> WristJacobian | None:
    """det of the 6×6 geometric Jacobian of a 6-joint arm with a spherical wrist, by
    decoupling at the wrist centre; None when no frame origin of the chain lies on the
    last three joint axes (or the poses are not trig polynomials)."""
    q = model.q
    if len(q) != 6 or point_frame != frame:
        return None          # the shear argument needs one body for v and ω
    ring = RingChain(model, frame)
    alg = ring.alg
    if alg is None:
        return None
    l0 = [ring.l0(i, frame) for i in range(6)]
    for f in ring.chain:
        w = [ring.M0(f)[r][3] for r in range(3)]
        # reduced entries (canonical and small); the blocks' determinants are taken
        # unreduced, so products of rotation entries factor literally (sᵢ² + cᵢ² factors)
        ring_j = ring.columns(l0, l0, w)
        if all(ring_j[r][c] == 0 for r in range(3) for c in range(3, 6)):
            det = _structured_ring_det(alg, ring_j, q)
            shown = ring.to_matrix(ring_j)
            det.blocks = [(rs, cs, shown.extract(rs, cs), d) for rs, cs, _, d in det.blocks]
            centre = sp.Matrix([tidy_products(alg.to_expr(x)) for x in w])
            return WristJacobian(f, centre, shown, det)
    return None
