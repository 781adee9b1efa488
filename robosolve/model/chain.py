"""The symbolic robot: frames, points, L/W/H matrices, bodies' pseudo-inertia.

`RobotModel` is built once per problem and memoises everything it derives, so
solvers share one chain product, one set of L matrices, and so on. It holds the problem's
`ChainDescription` (model/description.py) and its chain data over sympy (core/chain/forward.py
with core/chain/algebras.SympyChainAlgebra); the LaTeX names are render/chain_names.py's.

Conventions (spec §3; docs/course-notes.md: frame-notation, w-matrix, h-matrix, l-matrix): M_0j = M_01 M_12 ... ; W_0j = Mdot_0j M_0j^-1
and H_0j = Mddot_0j M_0j^-1, both expressed in frame 0; the L matrix of joint i
is dM/dq_i M^-1 moved to frame 0. Time derivatives use the chain rule with the
symbols q, q_dot, q_ddot (no sympy Functions of t: faster and printable).
"""

from __future__ import annotations

import sympy as sp

from robosolve.core import matrices as mx
from robosolve.core.simplify import tidy, tidy_matrix
from robosolve.core.transforms import ELEMENTARY, rigid_inverse
from robosolve.load.problem import Body, Problem
from robosolve.core.chain.algebras import RingChainAlgebra, SympyChainAlgebra
from robosolve.model.description import ChainDescription, elementary_factors
from robosolve.core.chain.forward import forward


class RobotModel:
    """Symbolic kinematics and mass model of a problem's robot: the sympy user of the one
    chain computation (core/chain/forward.py over core/chain/algebras.SympyChainAlgebra)."""

    def __init__(self, problem: Problem):
        self.problem = problem
        self.description = ChainDescription.from_problem(problem)
        self.joints = problem.joints
        self.q = [j.symbol for j in self.joints]
        self.qd = [j.dot for j in self.joints]
        self.qdd = [j.ddot for j in self.joints]
        self.frames = problem.frames
        self.parameters = problem.parameters
        self.gravity = problem.gravity
        self.bodies = problem.bodies
        self.forces = problem.forces
        self.points = problem.points
        self.algebra = SympyChainAlgebra(self.description)
        self.data = forward(self.description, self.algebra)
        self._cache: dict = {}

    def ring_chain(self, frames, points=()):
        """The chain data of `frames` (a chain from the base) in the trig ring, with extra point
        coordinates `points` as ring elements (`.algebra.points`); None when a pose is not a
        polynomial in cos qᵢ, sin qᵢ (kinematics/structured_det.py's RingChain)."""
        algebra = RingChainAlgebra(self.description, frames, points)
        return None if algebra.ring is None else forward(self.description, algebra)

    # -- frames -------------------------------------------------------
    def frame_names(self) -> list[str]:
        return list(self.frames)

    def parent(self, frame: str) -> str | None:
        return self.description.parent(frame)

    def chain(self, frame: str) -> list[str]:
        """Frames from the base (excluded) down to `frame` (included)."""
        return self.description.chain(frame)

    def elementary_factors(self, frame: str) -> list | None:
        """The frame's pose as elementary motions [(op, arg)] (DH rows expanded), or
        None for a pose given as a matrix."""
        return elementary_factors(self.description.frame[frame])

    def M_local(self, frame: str) -> sp.Matrix:
        """Pose of `frame` in its parent (the product of its elementary factors)."""
        return self.description.local_pose(frame)

    def M0(self, frame: str) -> sp.Matrix:
        """Pose of `frame` in frame 0: M_0p * M_p,frame (memoised, trig-tidied)."""
        return self.data.M(frame)

    def M0_inverse(self, frame: str) -> sp.Matrix:
        return rigid_inverse(self.M0(frame))

    def intermediate_origins(self, frame: str) -> list[sp.Matrix]:
        """Origins after each translation factor of a pose (for drawing links)."""
        f = self.frames[frame]
        base = self.M0(f.parent)
        out = []
        if f.kind == "pose":
            m = base
            for op, arg in f.factors:
                m = m * ELEMENTARY[op](arg)
                if op[0] == "T":
                    out.append(m[:3, 3])
        return out[:-1] if out and out[-1] == self.M0(frame)[:3, 3] else out

    # -- points and coordinates ---------------------------------------
    def point_local(self, name: str):
        p = self.points[name]
        return p.frame, p.at

    def point0(self, name: str) -> sp.Matrix:
        """Coordinates of point `name` in frame 0 (3x1)."""
        return self.data.point(name)

    def coordinate(self, expr):
        """Replace the placeholders P.x, P.y, P.z by the point's coordinates in frame 0."""
        expr = sp.sympify(expr)
        subs = {}
        for s in expr.free_symbols:
            if "." in s.name:
                pname, axis = s.name.split(".")
                subs[s] = self.point0(pname)["xyz".index(axis)]
        return expr.xreplace(subs) if subs else expr

    # -- time derivatives ---------------------------------------------
    def time_derivative(self, expr):
        """d/dt of an expression of q and q_dot (chain rule)."""
        return self.description.time_derivative(expr)

    def local_derivative(self, frame: str, order: int) -> sp.Matrix:
        """Mdot (order 1) or Mddot (2) of the frame's local pose, raw (chain rule, no
        simplification); once per description."""
        return self.description.local_rate(frame, order)

    # -- L, W, H ------------------------------------------------------
    def joints_in(self, frame: str) -> list[int]:
        """Indices of the joints whose variable appears in the frame's local pose."""
        return self.description.moved_by(frame)

    def joint_frame(self, index: int) -> str | None:
        """The first frame (file order) whose local pose contains joint `index`."""
        return self.description.joint_frame(index)

    def L_local(self, index: int, frame: str | None = None) -> sp.Matrix:
        """L of joint `index` in the parent of the frame it moves: dM/dq M^-1."""
        return self.description.local_twist(frame or self.joint_frame(index), index)

    def L0(self, index: int, frame: str | None = None) -> sp.Matrix:
        """L of joint `index` in frame 0, for the motion of `frame` (default: the
        frame the joint moves). Sums the contributions of every frame of the chain
        whose pose contains the joint (one, for an ordinary serial robot)."""
        return self.data.L(index, frame)

    def W_local(self, frame: str) -> sp.Matrix:
        """Velocity of `frame` relative to its parent, expressed in the parent."""
        key = ("W_local", frame)
        if key not in self._cache:
            w = sp.zeros(4, 4)
            for i in self.joints_in(frame):
                w += self.L_local(i, frame) * self.joints[i].dot
            self._cache[key] = w
        return self._cache[key]

    def H_local(self, frame: str) -> sp.Matrix:
        """Acceleration of `frame` relative to its parent, in the parent: Mddot M^-1."""
        return self.algebra.acceleration(frame)

    def W_relative0(self, frame: str) -> sp.Matrix:
        """0W_{p,frame} = sum of 0L_i q_dot_i: the relative velocity matrix in frame 0."""
        return self.data.W_relative(frame)

    def H_relative0(self, frame: str) -> sp.Matrix:
        """0H_{p,frame}: Mddot M^-1 of the relative motion, moved to frame 0."""
        return self.data.H_relative(frame)

    def W0(self, frame: str) -> sp.Matrix:
        """Rivals: W_0j = W_0p + 0W_pj (every term in frame 0)."""
        return self.data.W(frame)

    def H0(self, frame: str) -> sp.Matrix:
        """Coriolis: H_0j = H_0p + 2 W_0p 0W_pj + 0H_pj (every term in frame 0)."""
        return self.data.H(frame)

    def auxiliary(self, point: str) -> sp.Matrix:
        """0_aM: the auxiliary frame with origin at the point and the axes of frame 0."""
        m = sp.eye(4)
        m[:3, 3] = self.point0(point)
        return m

    def W_aux(self, frame: str, point: str) -> sp.Matrix:
        """aW = a_0M W_0 0_aM; its last column is the velocity of the point."""
        a = self.auxiliary(point)
        return tidy_matrix(rigid_inverse(a) * self.W0(frame) * a)

    def H_aux(self, frame: str, point: str) -> sp.Matrix:
        a = self.auxiliary(point)
        return tidy_matrix(rigid_inverse(a) * self.H0(frame) * a)

    # -- bodies ---------------------------------------------------------
    def body(self, name: str) -> Body:
        for b in self.bodies:
            if b.name == name:
                return b
        raise KeyError(name)

    def J_local(self, body: Body) -> sp.Matrix:
        """Pseudo-inertia of a body in its own frame."""
        d = body.data
        if body.kind == "point":
            return mx.pseudo_inertia_point(body.mass, d["at"])
        if body.kind == "rod":
            return mx.pseudo_inertia_rod(body.mass, d["from"], d["to"])
        if body.kind == "com":
            return mx.pseudo_inertia_from_com(body.mass, d["com"], d["inertia"])
        return d["J"]

    def J0(self, body: Body) -> sp.Matrix:
        """Pseudo-inertia in frame 0: M J M^T."""
        key = ("J0", body.name)
        if key not in self._cache:
            m = self.M0(body.frame)
            self._cache[key] = tidy_matrix(m * self.J_local(body) * m.T)
        return self._cache[key]

    def com_local(self, body: Body) -> sp.Matrix:
        j = self.J_local(body)
        return sp.Matrix([sp.cancel(j[i, 3] / j[3, 3]) for i in range(3)])

    def com0(self, body: Body) -> sp.Matrix:
        """Centre of mass of a body in frame 0."""
        hp = self.M0(body.frame) * sp.Matrix([*self.com_local(body), 1])
        return sp.Matrix([tidy(e) for e in hp[:3, 0]])
