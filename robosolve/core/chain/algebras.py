"""The algebras `robosolve.core.chain.forward` computes the chain in (its strategy objects).

* `SympyChainAlgebra`: sympy matrices, every product tidied by core/simplify.py's chain
  variants (the report's M, L, W, H: RobotModel);
* `RingChainAlgebra`: 4×4 lists of trig-ring polynomials (core/trigring.py), every product
  reduced modulo sᵢ² + cᵢ² = 1, canonical (the structured determinant); `ListChainAlgebra`,
  which it extends, takes any list algebra with that interface and its poses (the dynamics
  engine's own ring, or its SympyAlgebra fallback);
* `NumpyChainAlgebra`: floats at one configuration (the operations of core/chain/numpy_algebra.py);
  only the small local inputs are symbolic and evaluated once (NumericChain).

Each one turns the description's symbolic inputs (local pose, twist, Ä A⁻¹, joint rates,
point coordinates) into its own entries and provides the operations listed in forward.py.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.core import matrices as mx
from robosolve.core.simplify import tidy, tidy_matrix, tidy_products_matrix
from robosolve.core.transforms import homogeneous, rigid_inverse
from robosolve.core.trigring import TrigAlgebra
from robosolve.errors import MissingValues
from robosolve.core.chain.numpy_algebra import NumpyOperations
from robosolve.core.chain.numpy_algebra import rigid_inverse as rigid_inverse_np

__all__ = ["ListChainAlgebra", "NumpyChainAlgebra", "RingChainAlgebra", "SympyChainAlgebra", "evaluate"]


class SympyChainAlgebra:
    """sympy matrices with the chain's simplification policy."""

    def __init__(self, description):
        self.description = description
        # arms of 5+ joints: addition formulas only (trigsimp finds nothing more in their
        # products and costs seconds per entry), see core.simplify
        self._tidy_pose = tidy_matrix if len(description.joints) <= 4 else tidy_products_matrix
        self._memo: dict = {}

    # -- inputs -----------------------------------------------------------
    def pose(self, frame):
        return self.description.local_pose(frame)

    def twist(self, frame, index):
        return self.description.local_twist(frame, index)

    def acceleration(self, frame):
        """ᵖH_f = Ä A⁻¹ of the frame's local pose, tidied."""
        key = ("acceleration", frame)
        if key not in self._memo:
            d = self.description
            self._memo[key] = tidy_matrix(d.local_rate(frame, 2) * rigid_inverse(d.local_pose(frame)))
        return self._memo[key]

    def rate(self, index, order):
        j = self.description.joints[index]
        return j.qd if order == 1 else j.qdd

    def body_twist(self, frame, index):
        d = self.description
        return tidy_matrix(rigid_inverse(d.local_pose(frame)) * d.local_partial(frame, index))

    def coordinates(self, name):
        return self.description.points[name].at

    # -- operations -------------------------------------------------------
    @staticmethod
    def identity():
        return sp.eye(4)

    @staticmethod
    def zero():
        return sp.zeros(4, 4)

    def compose(self, mp, ml):
        # Only the new products are tidied: the parent's translation is already tidy, so
        # re-simplifying the whole growing sum (exponential in the chain length) is avoided.
        r = self._tidy_pose(mp[:3, :3] * ml[:3, :3])
        t = mp[:3, 3] + self._tidy_pose(mp[:3, :3] * ml[:3, 3])
        return homogeneous(r, t)

    @staticmethod
    def inverse(m):
        return rigid_inverse(m)

    @staticmethod
    def act(m, a):
        """M A M⁻¹ for A = [[skew(w), v], [0, 0]], computed as vectors:
        [[skew(R w), R v − (R w) × t], [0, 0]] (cheaper and smaller than two 4×4 products)."""
        r, t = m[:3, :3], m[:3, 3]
        w = r * sp.Matrix([a[2, 1], a[0, 2], a[1, 0]])
        w = w.applyfunc(tidy)
        v = (r * a[:3, 3] - w.cross(t)).applyfunc(tidy)
        return mx.velocity_matrix(w, v)

    @staticmethod
    def conjugate(m, a):
        return mx.change_frame(m, a)

    @staticmethod
    def add(a, b):
        return a + b

    @staticmethod
    def scale(a, s):
        return a * s

    @staticmethod
    def mul(a, b):
        return a * b

    @staticmethod
    def tidy(a):
        return tidy_matrix(a)

    @staticmethod
    def expand(a):
        return a.applyfunc(sp.expand)

    @staticmethod
    def point(m, p):
        hp = m * sp.Matrix([*p, 1])
        return sp.Matrix([tidy(e) for e in hp[:3, 0]])


class ListChainAlgebra:
    """4×4 lists over a list algebra: `alg` has matmul, rigid_inverse, mdiff, madd, zeros, eye
    and reduce (core/trigring.TrigAlgebra, or the dynamics engine's SympyAlgebra fallback);
    `local` maps each frame to its pose in its parent as such a 4×4 list. `tidy` reduces each
    entry (the ring's products are already reduced; SympyAlgebra tidies small pieces)."""

    def __init__(self, alg, local: dict):
        self.ring = alg
        self.local = local

    def pose(self, frame):
        return self.local[frame]

    def twist(self, frame, index):
        loc, ring = self.local[frame], self.ring
        return ring.matmul(ring.mdiff(loc, index), ring.rigid_inverse(loc))

    def body_twist(self, frame, index):
        loc, ring = self.local[frame], self.ring
        return ring.matmul(ring.rigid_inverse(loc), ring.mdiff(loc, index))

    def identity(self):
        return self.ring.eye(4)

    def zero(self):
        return self.ring.zeros(4)

    def compose(self, a, b):
        return self.ring.matmul(a, b)

    def inverse(self, m):
        return self.ring.rigid_inverse(m)

    def act(self, m, a):
        ring = self.ring
        return ring.matmul(ring.matmul(m, a), ring.rigid_inverse(m))

    conjugate = act

    def add(self, a, b):
        return self.ring.madd(a, b)

    def mul(self, a, b):
        return self.ring.matmul(a, b)

    def tidy(self, a):
        return [[self.ring.reduce(x) for x in row] for row in a]

    @staticmethod
    def expand(a):
        return a

    def point(self, m, p):
        return [self.ring.reduce(sum((m[r][k] * p[k] for k in range(3)), m[r][3])) for r in range(3)]


class RingChainAlgebra(ListChainAlgebra):
    """The trig ring over the poses of `frames` (and extra point coordinates `points`, lists of
    three expressions); `ring` is None when an input is not a polynomial in cos qᵢ, sin qᵢ (and
    prismatic qᵢ)."""

    def __init__(self, description, frames, points=()):
        frames = list(frames)
        extra = [c for p in points for c in p]
        entries = [e for f in frames for e in description.local_pose(f)]
        ring = TrigAlgebra.from_inputs(description.q, entries + extra)
        local = {} if ring is None else {
            f: [[ring.element(16 * k + 4 * r + c) for c in range(4)] for r in range(4)]
            for k, f in enumerate(frames)}
        super().__init__(ring, local)
        k0 = 16 * len(frames)
        self.points = [] if ring is None else [[ring.element(k0 + 3 * j + r) for r in range(3)]
                                               for j in range(len(points))]


def evaluate(obj, subs) -> np.ndarray:
    """A small sympy matrix (a local pose, a factor) as floats at `subs`; MissingValues names
    the symbols without a value."""
    m = sp.Matrix(obj).xreplace(subs).evalf(17)
    missing = sorted(s.name for s in m.free_symbols)
    if missing:
        raise MissingValues(missing)
    return np.array(m.tolist(), dtype=float)


class NumpyChainAlgebra(NumpyOperations):
    """Floats at the substitutions `subs`: the local inputs evaluated once each, the operations
    of core/chain/numpy_algebra.py."""

    def __init__(self, description, subs: dict):
        self.description = description
        self.subs = subs
        self._memo: dict = {}

    def _evaluated(self, key, expr):
        if key not in self._memo:
            self._memo[key] = evaluate(expr, self.subs)
        return self._memo[key]

    # -- inputs -----------------------------------------------------------
    def pose(self, frame):
        return self._evaluated(("pose", frame), self.description.local_pose(frame))

    def twist(self, frame, index):
        d = self.description
        return self._evaluated(("partial", frame, index), d.local_partial(frame, index)) @ \
            rigid_inverse_np(self.pose(frame))

    def acceleration(self, frame):
        return self._evaluated(("rate", frame), self.description.local_rate(frame, 2)) @ \
            rigid_inverse_np(self.pose(frame))

    def body_twist(self, frame, index):
        return rigid_inverse_np(self.pose(frame)) @ \
            self._evaluated(("partial", frame, index), self.description.local_partial(frame, index))

    def rate(self, index, order):
        j = self.description.joints[index]
        return float(self._evaluated(("q", index, order), sp.Matrix([j.qd if order == 1 else j.qdd]))[0, 0])

    def coordinates(self, name):
        return self._evaluated(("point", name), sp.Matrix([*self.description.points[name].at, 1]))[:, 0]
