"""The robot's description (pinocchio's Model): what the chain is, not what it computes.

`ChainDescription` is built once from a Problem and never changes: the frames in file order
and their parents, each frame's pose in its parent as elementary factors (DH rows expanded) or
a matrix, the joints (kind, symbols of q, q̇, q̈), which joints each frame's pose contains and
the frame each joint moves, and the points. The symbolic inputs every algebra starts from are
derived from it once and memoised (it is the only state it keeps): the local pose A_f (the
product of its factors, tidied), the local twist of each joint ᵖL = ∂A/∂qᵢ A⁻¹ (from the
factors' structure when it applies), and the raw chain-rule derivatives Ȧ, Ä.
`robosolve.core.chain.forward` computes the chain data (M, L, W, H) from it over an algebra.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Mapping

import sympy as sp

from robosolve.core import matrices as mx
from robosolve.core.simplify import tidy_matrix
from robosolve.core.transforms import ELEMENTARY, dh_modified, dh_standard

__all__ = ["ChainDescription", "FrameDescription", "JointDescription", "PointDescription",
           "elementary_factors", "factor_matrices"]

BASE = "0"


@dataclass(frozen=True)
class FrameDescription:
    name: str
    parent: str
    kind: str                  # "pose", "matrix", "dh", "mdh" (as written in the file)
    factors: tuple             # pose: ((op, arg), ...); dh: (θ, d, a, α); mdh: (α, a, θ, d)
    matrix: sp.ImmutableMatrix | None = None      # kind == "matrix"


@dataclass(frozen=True)
class JointDescription:
    index: int
    name: str
    kind: str                  # REVOLUTE or PRISMATIC
    q: sp.Symbol
    qd: sp.Symbol
    qdd: sp.Symbol


@dataclass(frozen=True)
class PointDescription:
    name: str
    frame: str
    at: tuple                  # coordinates in `frame`


def elementary_factors(frame: FrameDescription) -> list | None:
    """The frame's pose as elementary motions [(op, arg)] (DH rows expanded), or None for a
    pose given as a matrix."""
    if frame.kind == "pose":
        return list(frame.factors)
    if frame.kind == "dh":
        th, d, a, al = frame.factors
        return [("Rz", th), ("Tz", d), ("Tx", a), ("Rx", al)]
    if frame.kind == "mdh":
        al, a, th, d = frame.factors
        return [("Rx", al), ("Tx", a), ("Rz", th), ("Tz", d)]
    return None


def factor_matrices(frame: FrameDescription) -> list[sp.Matrix]:
    """The matrices whose product is the frame's pose, as written (one per pose factor, one
    DH / MDH matrix, or the given matrix)."""
    if frame.kind == "pose":
        return [ELEMENTARY[op](arg) for op, arg in frame.factors]
    if frame.kind == "matrix":
        return [sp.Matrix(frame.matrix)]
    if frame.kind == "dh":
        return [dh_standard(*frame.factors)]
    return [dh_modified(*frame.factors)]


@dataclass(frozen=True, eq=False)
class ChainDescription:
    """The immutable description of a robot's chain (frames, joints, points)."""

    frames: tuple                               # frame names in file order (parents first)
    frame: Mapping[str, FrameDescription]
    joints: tuple                               # JointDescription in joint order
    points: Mapping[str, PointDescription]
    _memo: dict = field(default_factory=dict, repr=False, compare=False)

    @classmethod
    def from_problem(cls, problem) -> "ChainDescription":
        frames = {name: FrameDescription(name, f.parent, f.kind, tuple(f.factors),
                                         None if f.matrix is None else sp.ImmutableMatrix(f.matrix))
                  for name, f in problem.frames.items()}
        joints = tuple(JointDescription(j.index, j.name, j.kind, j.symbol, j.dot, j.ddot)
                       for j in problem.joints)
        points = {name: PointDescription(name, p.frame, tuple(p.at)) for name, p in problem.points.items()}
        return cls(tuple(frames), MappingProxyType(frames), joints, MappingProxyType(points))

    def _memoised(self, key, build):
        if key not in self._memo:
            self._memo[key] = build()
        return self._memo[key]

    # -- structure ------------------------------------------------------
    @property
    def q(self) -> list:
        return [j.q for j in self.joints]

    def parent(self, frame: str) -> str | None:
        return None if frame == BASE else self.frame[frame].parent

    def chain(self, frame: str) -> list[str]:
        """Frames from the base (excluded) down to `frame` (included)."""
        out = []
        while frame != BASE:
            out.append(frame)
            frame = self.frame[frame].parent
        return out[::-1]

    def moved_by(self, frame: str) -> list[int]:
        """Indices of the joints whose variable appears in the frame's local pose."""
        def build():
            free = self.local_pose(frame).free_symbols
            return [j.index for j in self.joints if j.q in free]
        return list(self._memoised(("moved_by", frame), build))

    def point_frame(self, name: str) -> str:
        return self.points[name].frame

    def joint_frame(self, index: int) -> str | None:
        """The first frame (file order) whose local pose contains joint `index`."""
        for f in self.frames:
            if index in self.moved_by(f):
                return f
        return None

    # -- the symbolic inputs of every algebra (memoised) ----------------
    def local_pose(self, frame: str) -> sp.Matrix:
        """A_f: the pose of `frame` in its parent, the product of its factors, tidied."""
        def build():
            m = sp.eye(4)
            for factor in factor_matrices(self.frame[frame]):
                m = m * factor
            return tidy_matrix(m)
        return self._memoised(("pose", frame), build)

    def local_twist(self, frame: str, index: int) -> sp.Matrix:
        """ᵖL of joint `index` in the parent of `frame`: ∂A/∂qᵢ A⁻¹ (by the factors'
        structure when qᵢ sits in one factor, linearly; else by differentiating A)."""
        def build():
            q = self.joints[index].q
            factors = elementary_factors(self.frame[frame])
            l_mat = mx.l_matrix_of_factors(factors, q) if factors is not None else None
            return tidy_matrix(l_mat) if l_mat is not None else mx.l_matrix(self.local_pose(frame), q)
        return self._memoised(("twist", frame, index), build)

    def constant_twist(self, frame: str) -> int | None:
        """The joint moving `frame` when it is the only one and its twist is constant
        (then ᵖH = ᵖL q̈ + ᵖL² q̇²); None otherwise."""
        joints = self.moved_by(frame)
        if len(joints) == 1 and not self.local_twist(frame, joints[0]).free_symbols & set(self.q):
            return joints[0]
        return None

    def time_derivative(self, expr):
        """d/dt of an expression of q and q̇ (chain rule on the symbols, no Functions of t)."""
        expr = sp.sympify(expr)
        if isinstance(expr, sp.MatrixBase):
            return expr.applyfunc(self.time_derivative)
        out = 0
        for j in self.joints:
            if expr.has(j.q):
                out += sp.diff(expr, j.q) * j.qd
            if expr.has(j.qd):
                out += sp.diff(expr, j.qd) * j.qdd
        return out

    def local_rate(self, frame: str, order: int) -> sp.Matrix:
        """A (order 0), Ȧ (1) or Ä (2) of the frame's local pose, raw (chain rule)."""
        if order == 0:
            return self.local_pose(frame)
        return self._memoised(("rate", frame, order),
                              lambda: self.time_derivative(self.local_rate(frame, order - 1)))

    def local_partial(self, frame: str, index: int) -> sp.Matrix:
        """∂A_f/∂qᵢ, raw."""
        return self._memoised(("partial", frame, index),
                              lambda: self.local_pose(frame).diff(self.joints[index].q))
