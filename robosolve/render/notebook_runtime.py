"""The runtime of report.ipynb: the course's computations in sympy, numpy and matplotlib alone.

robosolve copies this module's source into the first code cell of every notebook it writes
(robosolve/render/notebook.py, with `inspect.getsource`), so a notebook runs anywhere with only
sympy, numpy and matplotlib installed: this module imports nothing else but robosolve's own
numeric chain computation (robosolve/core/chain/forward.py and core/chain/numpy_algebra.py, which import
nothing but numpy), whose sources the cell copies in before it, without the two import lines. The tests import it in-process and compare it with robosolve's engines
(tests/render/test_notebook_runtime.py).

* `Robot`: the problem's data (parameters, joints, frames, points, bodies, forces, gravity) given
  as text expressions, so that a reader changes a number and re-runs; the chain products
  (0M of a frame, points in frame 0), W and H (symbolic, and `chain_at`: robosolve's chain
  computation at numbers, Rivals and Coriolis), Jacobians, Lagrange's equations of motion from
  the bodies' pseudo-inertia matrices, the weight's generalized forces, numeric dynamics.
* `Profile`: the synchronized bang-bang, trapezoidal and quintic profiles, numerically.
* `torque_peaks`, `simulate_control`, `forward_run`: the actuators along a profile, the closed
  loop, and the motion under given actuator laws, integrated by an adaptive Dormand-Prince 5(4).
* `TaskPath`, `Timing`, `TaskArm`, `TaskTrajectory`: a line or an arc of task coordinates timed
  along its length (trapezoidal or quintic), the task map x(q), J, J' q', and the joint motion
  by Newton's method sample to sample from one IK branch (q' = J+ x', q'' from J'), with its
  extremes; `simulate_task_control`: the work-space closed loops along it (the task laws, or a
  joint law on the converted trajectory, `JointPlan`).
* geometry (axis-angle, helical axis, Euler angles, screws), `newton_solutions` (IK), ellipsoid
  semi-axes, and `compare`, which prints a recomputed value beside robosolve's.
"""

import numpy as np
import sympy as sp

from robosolve.core.chain.forward import ChainData  # the notebook: forward.py is copied in above
from robosolve.core.chain.numpy_algebra import NumpyOperations, rigid_inverse  # copied in above

np.set_printoptions(precision=6, suppress=True)


# -- elementary motions -------------------------------------------------------------------

def Rx(a):
    return sp.Matrix([[1, 0, 0, 0], [0, sp.cos(a), -sp.sin(a), 0], [0, sp.sin(a), sp.cos(a), 0], [0, 0, 0, 1]])


def Ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a), 0], [0, 1, 0, 0], [-sp.sin(a), 0, sp.cos(a), 0], [0, 0, 0, 1]])


def Rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0, 0], [sp.sin(a), sp.cos(a), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def Tx(d):
    return sp.Matrix([[1, 0, 0, d], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def Ty(d):
    return sp.Matrix([[1, 0, 0, 0], [0, 1, 0, d], [0, 0, 1, 0], [0, 0, 0, 1]])


def Tz(d):
    return sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, d], [0, 0, 0, 1]])


MOTIONS = {"Rx": Rx, "Ry": Ry, "Rz": Rz, "Tx": Tx, "Ty": Ty, "Tz": Tz}


def dh(theta, d, a, alpha):
    """Standard Denavit-Hartenberg: Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    return Rz(theta) * Tz(d) * Tx(a) * Rx(alpha)


def mdh(alpha, a, theta, d):
    """Modified Denavit-Hartenberg: Rx(alpha) Tx(a) Rz(theta) Tz(d)."""
    return Rx(alpha) * Tx(a) * Rz(theta) * Tz(d)


def inverse_pose(M):
    """[R, t; 0, 1]^-1 = [R^T, -R^T t; 0, 1]."""
    R, p = M[:3, :3], M[:3, 3]
    out = sp.eye(4)
    out[:3, :3], out[:3, 3] = R.T, -R.T * p
    return out


def nearest_rotation_pose(M):
    """A pose written in numbers rounded by hand (0.707): its rotation block replaced by the
    nearest rotation U·Vᵀ (polar decomposition), as robosolve reads it when it is orthonormal to
    1e-3 but not to 1e-9; any other pose as it is (exact entries, symbols)."""
    if M.free_symbols:
        return M
    R = np.array(sp.N(M[:3, :3]).tolist(), dtype=float)
    off = np.max(np.abs(R.T @ R - np.eye(3)))
    if off <= 1e-9 or off > 1e-3 or np.linalg.det(R) <= 0:
        return M
    U, _, Vt = np.linalg.svd(R)
    out = sp.Matrix(M)
    out[:3, :3] = sp.Matrix((U @ Vt).tolist())
    return out


def vex(S):
    """The vector w of a skew-symmetric [w]."""
    return sp.Matrix([S[2, 1], S[0, 2], S[1, 0]])


# -- the robot ------------------------------------------------------------------------------

class Robot:
    """The problem's data, every value a text expression over the problem's names.

    parameters: {name: value text, or None when not given};  joints: [(name, kind, actuator)];
    frames: {name: (parent, pose)}, pose = [(motion, text), ...] (elementary motions in
    order), ("dh", [theta, d, a, alpha]), ("mdh", [alpha, a, theta, d]) or ("matrix", rows);
    points: {name: (frame, [x, y, z])};  gravity: [gx, gy, gz] in frame 0;
    bodies: {name: (frame, pseudo-inertia J as 4 rows, in that frame)};
    forces: {name: (frame, point [x, y, z] in it, force or None, torque or None, components' frame)}.
    """

    def __init__(self, parameters, joints, frames, points=None, gravity=("0", "0", "-g"),
                 bodies=None, forces=None):
        self.t = sp.Symbol("t", real=True)
        self.names = {"t": self.t}
        for name in parameters:
            self.names[name] = sp.Symbol(name, real=True)
        self.joints, self.rates, self.accelerations, self.actuators, self.kinds = [], [], [], [], []
        self.names_of_joints = [name for name, _, _ in joints]
        for name, kind, actuator in joints:
            for suffix, into in (("", self.joints), ("_dot", self.rates), ("_ddot", self.accelerations)):
                symbol = sp.Symbol(name + suffix, real=True)
                self.names[name + suffix] = symbol
                into.append(symbol)
            self.actuators.append(actuator)
            self.kinds.append(kind)
            self.names[actuator] = sp.Symbol(actuator, real=True)
        self.parameters = {self.names[k]: (None if v is None else self.parse(v)) for k, v in parameters.items()}
        self.frames = {name: (parent, self._local_pose(pose)) for name, (parent, pose) in frames.items()}
        self._poses = {"0": sp.eye(4)}
        self.points = {name: (frame, self.vector(at)) for name, (frame, at) in (points or {}).items()}
        for name in self.points:                  # P.x, P.y, P.z of a point: P_x, P_y, P_z
            x, y, z = self.point0(name)
            self.names.update({name + "_x": x, name + "_y": y, name + "_z": z})
        self.gravity = sp.zeros(3, 1) if gravity is None else self.vector(gravity)
        self.bodies = {name: (frame, self.matrix(J)) for name, (frame, J) in (bodies or {}).items()}
        self.forces = {name: (frame, self.vector(at), None if f is None else self.vector(f),
                              None if tau is None else self.vector(tau), in_frame)
                       for name, (frame, at, f, tau, in_frame) in (forces or {}).items()}

    # -- values
    def parse(self, text):
        """A text expression over the problem's names (sympy's own syntax)."""
        return sp.sympify(text, locals=self.names)

    def vector(self, texts):
        return sp.Matrix([self.parse(x) for x in texts])

    def matrix(self, rows):
        return sp.Matrix([[self.parse(x) for x in row] for row in rows])

    def configuration(self, at):
        """{symbol: value} of a question's `at` ({name: text})."""
        return {self.names[k]: self.parse(v) for k, v in (at or {}).items()}

    def values(self, at=None):
        """Parameters (with the question's overrides) and the `at` values, resolved to numbers
        where they can be."""
        given = {s: v for s, v in self.parameters.items() if v is not None}
        given.update(self.configuration(at))
        out = dict(given)
        for _ in range(len(given) + 1):
            out = {s: sp.sympify(v).subs(out) for s, v in given.items()}
        return out

    def fixed(self, at=None):
        """The values of everything but the joints, their rates and accelerations."""
        moving = set(self.joints) | set(self.rates) | set(self.accelerations)
        return {s: v for s, v in self.values(at).items() if s not in moving}

    def number(self, expr, at=None):
        """A sympy object evaluated to floats at the data and `at`."""
        v = sp.N(sp.sympify(expr).subs(self.values(at)))
        return np.array(v.tolist(), dtype=float) if hasattr(v, "tolist") else float(v)

    # -- the chain
    def _local_pose(self, pose):
        kind, args = (pose[0], pose[1]) if pose and isinstance(pose[0], str) and pose[0] in ("dh", "mdh", "matrix") \
            else ("motions", pose)
        if kind == "dh":
            return dh(*[self.parse(x) for x in args])
        if kind == "mdh":
            return mdh(*[self.parse(x) for x in args])
        if kind == "matrix":
            return self.matrix(args)
        out = sp.eye(4)
        for motion, text in args:
            out = out * MOTIONS[motion](self.parse(text))
        return out

    def pose(self, frame):
        """0M of `frame`: the product of the poses along the chain, from the base."""
        if frame not in self._poses:
            parent, local = self.frames[frame]
            self._poses[frame] = self.pose(parent) * local
        return self._poses[frame]

    def point0(self, name):
        """Coordinates in frame 0 of a named point."""
        frame, at = self.points[name]
        return (self.pose(frame) * sp.Matrix([*at, 1]))[:3, :]

    def time_derivative(self, expr):
        """d/dt of an expression in the joints and rates (q' = rate, rate' = acceleration)."""
        out = sp.zeros(*expr.shape) if hasattr(expr, "shape") else sp.Integer(0)
        for q, qd, qdd in zip(self.joints, self.rates, self.accelerations):
            out += sp.diff(expr, q) * qd + sp.diff(expr, qd) * qdd
        return out

    def velocity_matrices(self, frame):
        """W = M' M^-1 and H = M'' M^-1 of 0M_frame (in frame 0)."""
        M = self.pose(frame)
        dM = self.time_derivative(M)
        inv = inverse_pose(M)
        return dM * inv, self.time_derivative(dM) * inv

    def chain_at(self, at=None):
        """0M, 0L, 0W (Rivals) and 0H (Coriolis) of every frame, and the points, as numbers at the
        data and `at` (joints, rates, accelerations): robosolve's chain computation (forward.py's
        ChainData over numpy): chain.M(frame), chain.L(i, frame), chain.W(frame), chain.H(frame),
        chain.point(name)."""
        numbers = _ChainAt(self, at)
        return ChainData(numbers, numbers)

    def jacobian(self, coordinates):
        """The analytic Jacobian of coordinates (text expressions) in the joints."""
        return self.vector(coordinates).jacobian(self.joints)

    def angular_jacobian(self, frame):
        """J_w: the columns vex(d0M/dq_j 0M^-1)."""
        M = self.pose(frame)
        inv = inverse_pose(M)
        return sp.Matrix.hstack(*[vex((M.diff(q) * inv)[:3, :3]) for q in self.joints])

    def geometric_jacobian(self, point):
        """[J_v; J_w]: the point's velocity d0P/dq over the angular velocity of its frame."""
        return self.point0(point).jacobian(self.joints).col_join(self.angular_jacobian(self.points[point][0]))

    # -- statics and dynamics
    def weight_forces(self, at=None):
        """Fq = -sum J_G^T m g: what the joints exert to hold the bodies' weight."""
        fixed = self.fixed(at)
        out = sp.zeros(len(self.joints), 1)
        for frame, J in self.bodies.values():
            mG = (self.pose(frame) * J[:, 3])[:3, :]              # m G in frame 0
            out -= mG.jacobian(self.joints).T * self.gravity
        return out.subs(fixed)

    def external_forces(self, at=None):
        """The generalized forces Q of the external forces (J_P^T F + J_w^T tau)."""
        fixed = self.fixed(at)
        Q = sp.zeros(len(self.joints), 1)
        for frame, point, force, torque, in_frame in self.forces.values():
            R = self.pose(in_frame)[:3, :3]
            if force is not None:
                P = (self.pose(frame) * sp.Matrix([*point, 1]))[:3, :]
                Q += P.jacobian(self.joints).T * R * force
            if torque is not None:
                Q += self.angular_jacobian(frame).T * R * torque
        return Q.subs(fixed)

    def lagrange(self, at=None):
        """M(q), c(q, q'), g(q) and the external forces' Q, by Lagrange: T = 1/2 sum tr(dM J dM^T)
        over the bodies (J the pseudo-inertia, dM = d(0M_i)/dt), U = -sum m g.G, so that
        M q'' + c + g = tau + Q. Parameters are fixed from the data and `at`."""
        fixed = self.fixed(at)
        n = len(self.joints)
        T, U = sp.Integer(0), sp.Integer(0)
        for frame, J in self.bodies.values():
            M = self.pose(frame).subs(fixed)
            J = J.subs(fixed)
            dM = self.time_derivative(M)
            T += (dM * J * dM.T).trace() / 2
            U -= (self.gravity.subs(fixed).T * (M * J[:, 3])[:3, :])[0]
        mass = sp.Matrix(n, n, lambda i, j: sp.expand(T.diff(self.rates[i], self.rates[j])))
        grav = sp.Matrix([U.diff(q) for q in self.joints])
        momenta = sp.Matrix([T.diff(r) for r in self.rates])
        c = momenta.jacobian(self.joints) * sp.Matrix(self.rates) - sp.Matrix([T.diff(q) for q in self.joints])
        return mass, sp.expand(c), grav, self.external_forces(at)

    def _chain_at(self, at):
        """Per frame, at the numbers of `at`: 0M, its derivatives D[i] = d0M/dq_i and
        D2[i][k] = d2 0M/dq_i dq_k (numpy), by the product rule along the chain."""
        subs = self.values(at)
        n = len(self.joints)
        zero = np.zeros((4, 4))

        def num(m):
            return np.array(sp.N(m.subs(subs)).tolist(), dtype=float)

        chain = {"0": (np.eye(4), [zero] * n, [[zero] * n for _ in range(n)])}

        def of(frame):
            if frame not in chain:
                parent, local = self.frames[frame]
                P, DP, D2P = of(parent)
                used = [i for i, q in enumerate(self.joints) if local.has(q)]
                L = num(local)
                DL = [num(local.diff(self.joints[i])) if i in used else zero for i in range(n)]
                D2L = [[num(local.diff(self.joints[i], self.joints[k])) if i in used and k in used else zero
                        for k in range(n)] for i in range(n)]
                D = [DP[i] @ L + P @ DL[i] for i in range(n)]
                D2 = [[D2P[i][k] @ L + DP[i] @ DL[k] + DP[k] @ DL[i] + P @ D2L[i][k] for k in range(n)]
                      for i in range(n)]
                chain[frame] = (P @ L, D, D2)
            return chain[frame]

        return of, subs

    def dynamics_at(self, at):
        """M, c, g and Q as numbers at the configuration `at` (joints, rates), without a symbolic
        derivation (a six-joint arm in seconds): M_ik = sum tr(D_i J D_k^T), c from the
        derivatives of M (Christoffel), g_i = -sum g.(D_i J e4), Q from the forces' Jacobians."""
        of, subs = self._chain_at(at)
        n = len(self.joints)
        rates = np.array([float(sp.N(sp.sympify(r).subs(subs))) for r in self.rates])
        gravity = np.array(sp.N(self.gravity.subs(subs)).tolist(), dtype=float).ravel()
        mass, dmass, grav = np.zeros((n, n)), np.zeros((n, n, n)), np.zeros(n)
        for frame, J in self.bodies.values():
            J = np.array(sp.N(J.subs(subs)).tolist(), dtype=float)
            _, D, D2 = of(frame)
            for i in range(n):
                grav[i] -= gravity @ (D[i] @ J[:, 3])[:3]
                for k in range(n):
                    mass[i, k] += np.trace(D[i] @ J @ D[k].T)
                    for m in range(n):              # d M_ik / d q_m
                        dmass[i, k, m] += np.trace(D2[i][m] @ J @ D[k].T + D[i] @ J @ D2[k][m].T)
        c = np.array([sum((dmass[i, j, k] - dmass[j, k, i] / 2) * rates[j] * rates[k]
                          for j in range(n) for k in range(n)) for i in range(n)])
        Q = np.zeros(n)
        for frame, point, force, torque, in_frame in self.forces.values():
            M, D, _ = of(frame)
            R = of(in_frame)[0][:3, :3]
            for i in range(n):
                if force is not None:
                    F = np.array(sp.N(force.subs(subs)).tolist(), dtype=float).ravel()
                    p = np.array(sp.N(sp.Matrix([*point, 1]).subs(subs)).tolist(), dtype=float).ravel()
                    Q[i] += (D[i] @ p)[:3] @ (R @ F)
                if torque is not None:
                    tau = np.array(sp.N(torque.subs(subs)).tolist(), dtype=float).ravel()
                    S = D[i][:3, :3] @ M[:3, :3].T
                    Q[i] += np.array([S[2, 1], S[0, 2], S[1, 0]]) @ (R @ tau)
        return mass, c, grav, Q

    def energies_at(self, at):
        """T = 1/2 tr(M' J M'^T) and U = -g.(M J e4) of each body, as numbers at the configuration
        `at` (joints, rates): {body: T} and {body: U}, with their "total" last."""
        of, subs = self._chain_at(at)
        rates = np.array([float(sp.N(sp.sympify(r).subs(subs))) for r in self.rates])
        gravity = np.array(sp.N(self.gravity.subs(subs)).tolist(), dtype=float).ravel()
        kinetic, potential = {}, {}
        for name, (frame, J) in self.bodies.items():
            J = np.array(sp.N(J.subs(subs)).tolist(), dtype=float)
            M, D, _ = of(frame)
            dM = sum((D[i] * rates[i] for i in range(len(rates))), np.zeros((4, 4)))
            kinetic[name] = np.trace(dM @ J @ dM.T) / 2
            potential[name] = -gravity @ (M @ J[:, 3])[:3]
        kinetic["total"], potential["total"] = sum(kinetic.values()), sum(potential.values())
        return kinetic, potential

    def com_jacobian(self, body):
        """d G / dq of a body's centre of mass G = (0M J e4) / m, in frame 0 (3 x n)."""
        frame, J = self.bodies[body]
        return ((self.pose(frame) * J[:, 3])[:3, :] / J[3, 3]).jacobian(self.joints)

    def joint_actions(self, at=None):
        """tau = M q'' + c + g - Q: what the actuators exert at the configuration `at`."""
        mass, c, grav, Q = self.lagrange(at)
        return mass * sp.Matrix(self.accelerations) + c + grav - Q

    def numeric_dynamics(self, at=None, laws=None):
        """numpy functions of (t, q, q'): "mass" M, "c", "g", "Q" and "rest" = tau + Q - c - g
        with tau the actuator `laws` (text expressions; without laws, tau = 0)."""
        mass, c, grav, Q = self.lagrange(at)
        fixed = self.fixed(at)
        tau = sp.Matrix([self.parse((laws or {}).get(a, "0")) for a in self.actuators]).subs(fixed)
        args = [self.t, self.joints, self.rates]
        parts = {"mass": mass, "c": c, "g": grav, "Q": Q, "rest": tau + Q - c - grav}
        return {k: _numeric(sp.lambdify(args, v, "numpy"), k != "mass") for k, v in parts.items()}


class _ChainAt(NumpyOperations):
    """A robot's chain at one configuration, what forward.py's ChainData asks: the description
    (parents, the joints in each pose, the frame of a point) and the numpy algebra's inputs (each
    pose in its parent A, a joint's twist dA/dq A^-1, A'' A^-1, the rates), evaluated once each."""

    def __init__(self, robot, at):
        self.robot, self.subs, self._memo = robot, robot.values(at), {}

    def _num(self, key, build):
        if key not in self._memo:
            self._memo[key] = np.array(sp.N(sp.Matrix(build()).subs(self.subs)).tolist(), dtype=float)
        return self._memo[key]

    # -- the description
    def parent(self, frame):
        return None if frame == "0" else self.robot.frames[frame][0]

    def chain(self, frame):
        out = []
        while frame != "0":
            out.append(frame)
            frame = self.robot.frames[frame][0]
        return out[::-1]

    def moved_by(self, frame):
        local = self.robot.frames[frame][1]
        return [i for i, q in enumerate(self.robot.joints) if local.has(q)]

    def joint_frame(self, index):
        return next((f for f in self.robot.frames if index in self.moved_by(f)), None)

    def constant_twist(self, frame):
        return None                     # H of every pose from A'' A^-1

    def point_frame(self, name):
        return self.robot.points[name][0]

    # -- the inputs
    def pose(self, frame):
        return self._num(("A", frame), lambda: self.robot.frames[frame][1])

    def twist(self, frame, index):
        dA = self._num(("dA", frame, index), lambda: self.robot.frames[frame][1].diff(self.robot.joints[index]))
        return dA @ rigid_inverse(self.pose(frame))

    def acceleration(self, frame):
        robot = self.robot
        ddA = self._num(("ddA", frame), lambda: robot.time_derivative(robot.time_derivative(robot.frames[frame][1])))
        return ddA @ rigid_inverse(self.pose(frame))

    def rate(self, index, order):
        symbol = (self.robot.rates if order == 1 else self.robot.accelerations)[index]
        return float(self._num(("rate", index, order), lambda: [symbol])[0, 0])

    def coordinates(self, name):
        return self._num(("P", name), lambda: [*self.robot.points[name][1], 1]).ravel()


def _numeric(f, column):
    """A lambdified matrix function returning a float array (a column as a vector)."""
    def call(t, q, qd):
        out = np.asarray(f(t, q, qd), dtype=float)
        return out.ravel() if column else out
    return call


# -- showing --------------------------------------------------------------------------------------

def show(*exprs, max_ops=400):
    """Display sympy objects (in Jupyter, as formulas), simplified when they are small."""
    try:
        from IPython.display import display
    except ImportError:                            # outside Jupyter
        display = print
    for e in exprs:
        display(sp.simplify(e) if sp.count_ops(e) <= max_ops else e)


def _axes(count, title, ylabel):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.2), constrained_layout=True)
    ax.set_title(title)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    return plt, ax


def plot_joints(times, qs, names):
    """Each joint against time (a forward-dynamics run)."""
    plt, ax = _axes(len(names), "joint values against time (recomputed)", "q (rad or m)")
    for i, name in enumerate(names):
        ax.plot(times, qs[:, i], label=name)
    ax.legend()
    plt.show()


def plot_errors(times, errors, names, law):
    """The tracking error e = q_d - q of each joint against time (a closed loop)."""
    plt, ax = _axes(len(names), f"{law} control: tracking error (recomputed)", "e (rad or m)")
    for i, name in enumerate(names):
        ax.plot(times, errors[:, i], label=name)
    ax.legend()
    plt.show()


# -- comparing with robosolve's numbers -------------------------------------------------------

def _leaves(value):
    if isinstance(value, dict):
        return [x for v in value.values() for x in _leaves(v)]
    if isinstance(value, (list, tuple, np.ndarray)):
        return [x for v in value for x in _leaves(v)]
    if value is None or isinstance(value, (bool, str)):
        return []
    return [float(value)]


def agrees(got, want, rtol=1e-6, atol=1e-9):
    """Whether two numbers, or two nested lists / mappings of numbers, are the same values."""
    a, b = _leaves(got), _leaves(want)
    return len(a) == len(b) and bool(np.allclose(a, b, rtol=rtol, atol=atol, equal_nan=True))


def compare(name, got, want, rtol=1e-6, atol=1e-9):
    """Print a recomputed value and robosolve's (which hold for the data as robosolve read them:
    after a change, they differ)."""
    verdict = "agrees with robosolve" if agrees(got, want, rtol, atol) else "DIFFERS from robosolve's"
    print(f"recomputed {name} = {_plain(got)}\n    robosolve: {_plain(want)}   ({verdict})")


def _plain(value):
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, (float, np.floating)):
        return round(float(value), 10) + 0.0
    return value


# -- geometry ---------------------------------------------------------------------------------

def skew(u):
    return np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def canonical(u):
    """Of +u and -u, the one whose first non-zero component is positive."""
    first = next(x for x in u if abs(x) > 1e-9)
    return u if first > 0 else -u


def axis_angle(R):
    """alpha in [0, pi] and the unit axis u (None for the identity); near pi from R's symmetric part."""
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2
    alpha = np.arctan2(np.linalg.norm(v), (np.trace(R) - 1) / 2)
    if alpha < 1e-9:
        return 0.0, None
    if np.pi - alpha < 1e-6:
        w, V = np.linalg.eigh((R + R.T) / 2)
        return alpha, canonical(V[:, np.argmax(w)])
    return alpha, v / np.linalg.norm(v)


def helical_axis(Q):
    """u, alpha, h, P (nearest the origin) and the pitch of a displacement Q = [R, dT; 0, 1]."""
    R, dT = Q[:3, :3], Q[:3, 3]
    alpha, u = axis_angle(R)
    if u is None:                                  # pure translation (or the identity)
        h = np.linalg.norm(dT)
        return (dT / h if h > 1e-12 else None), 0.0, h, None, None
    h = u @ dT
    A = np.vstack([np.eye(3) - R, u])              # (I - R) P = dT - h u and P.u = 0
    P = np.linalg.lstsq(A, np.append(dT - h * u, 0), rcond=None)[0]
    return u, alpha, h, P, h / alpha


def screw_displacement(axis, alpha, through, h):
    """Q = [R, (I - R) P + h u; 0, 1], R = I + [u] sin(alpha) + [u]^2 (1 - cos(alpha))."""
    u = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = skew(u)
    R = np.eye(3) + K * np.sin(alpha) + K @ K * (1 - np.cos(alpha))
    Q = np.eye(4)
    Q[:3, :3], Q[:3, 3] = R, (np.eye(3) - R) @ np.asarray(through, dtype=float) + h * u
    return Q


def screw_matrix(u, P, pitch):
    """L = [[u], P x u + pitch u; 0, 0] (for a pure translation, L = [0, u; 0, 0])."""
    L = np.zeros((4, 4))
    if P is None:
        L[:3, 3] = np.zeros(3) if u is None else u
    else:
        L[:3, :3], L[:3, 3] = skew(u), np.cross(P, u) + pitch * u
    return L


def wrap(a):
    """An angle in (-pi, pi]."""
    a = (a + np.pi) % (2 * np.pi) - np.pi
    return np.pi if abs(a + np.pi) < 1e-12 else a


def euler_zyz(R):
    """R = Rz(phi) Ry(theta) Rz(psi): both solutions, or one (psi = 0) when theta is 0 or pi."""
    theta = np.arctan2(np.hypot(R[0, 2], R[1, 2]), R[2, 2])
    if abs(np.sin(theta)) > 1e-9:
        phi, psi = np.arctan2(R[1, 2], R[0, 2]), np.arctan2(R[2, 1], -R[2, 0])
        return [[wrap(phi), theta, wrap(psi)], [wrap(phi + np.pi), -theta, wrap(psi + np.pi)]]
    phi = np.arctan2(R[1, 0], R[0, 0]) if R[2, 2] > 0 else np.arctan2(-R[1, 0], -R[0, 0])
    return [[wrap(phi), theta, 0.0]]


def euler_rpy(R):
    """R = Rz(yaw) Ry(pitch) Rx(roll) as [roll, pitch, yaw]: both solutions, or one (yaw = 0)."""
    pitch = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
    if abs(np.cos(pitch)) > 1e-9:
        roll, yaw = np.arctan2(R[2, 1], R[2, 2]), np.arctan2(R[1, 0], R[0, 0])
        return [[roll, pitch, yaw], [wrap(roll + np.pi), wrap(np.pi - pitch), wrap(yaw + np.pi)]]
    return [[np.arctan2(R[0, 1], R[1, 1]) * np.sign(pitch), pitch, 0.0]]


def quaternion(R):
    """(w, x, y, z) = (cos(alpha/2), sin(alpha/2) u)."""
    alpha, u = axis_angle(R)
    return [np.cos(alpha / 2)] + ([0.0] * 3 if u is None else list(np.sin(alpha / 2) * u))


# -- inverse kinematics -----------------------------------------------------------------------

def newton_solutions(residual, joints, limits, revolute, starts=200):
    """Every solution of residual(q) = 0 within the joint limits, by Newton (least-squares) steps
    from a grid of starts; revolute joints wrapped into (-pi, pi]."""
    f = sp.lambdify([joints], residual, "numpy")
    jac = sp.lambdify([joints], residual.jacobian(joints), "numpy")
    limits, revolute = np.asarray(limits, dtype=float), np.asarray(revolute, dtype=bool)
    per_joint = max(2, int(round(starts ** (1 / len(joints)))))
    grid = np.meshgrid(*[np.linspace(lo, hi, per_joint + 2)[1:-1] for lo, hi in limits])
    solutions = []
    for start in np.stack([g.ravel() for g in grid], axis=1):
        x = start.astype(float)
        for _ in range(100):                       # until the step vanishes (linear at a double root)
            step = np.linalg.lstsq(np.asarray(jac(x), dtype=float), np.asarray(f(x), dtype=float).ravel(),
                                   rcond=None)[0]
            x = x - step
            if np.linalg.norm(step) < 1e-14 * max(1.0, np.linalg.norm(x)):
                break
        x = np.where(revolute, [wrap(v) for v in x], x)
        ok = np.linalg.norm(np.asarray(f(x), dtype=float)) < 1e-9
        inside = np.all((x >= limits[:, 0] - 1e-6) & (x <= limits[:, 1] + 1e-6))
        if ok and inside and not any(np.allclose(x, s, atol=1e-5) for s in solutions):
            solutions.append(x)
    return sorted(solutions, key=lambda s: tuple(np.round(s, 9)))


# -- ellipsoids ---------------------------------------------------------------------------------

def ellipsoid_axes(J, Kf=1.0, Kv=1.0, Ka=1.0, Kq=None):
    """Semi-axes (largest first) of the force (Kf / sqrt(nu)), velocity (Kv sqrt(nu)) and
    compliance (Ka kappa) ellipsoids, nu the eigenvalues of J J^T, kappa those of J Kq J^T;
    and the condition number max nu / min nu."""
    J = np.asarray(J, dtype=float)
    nu = np.linalg.eigvalsh(J @ J.T)
    nu = np.where(np.abs(nu) < 1e-12 * max(1.0, np.abs(nu).max()), 0.0, nu)
    with np.errstate(divide="ignore"):
        force = np.sort(Kf / np.sqrt(nu))[::-1]
    out = {"nu": nu, "force": force, "velocity": np.sort(Kv * np.sqrt(nu))[::-1],
           "condition_number": nu.max() / nu.min() if nu.min() > 0 else float("inf")}
    if Kq is not None:
        out["compliance"] = np.sort(Ka * np.linalg.eigvalsh(J @ np.diag(Kq) @ J.T))[::-1]
    return out


# -- motion profiles ------------------------------------------------------------------------------

class Profile:
    """Synchronized rest-to-rest profiles (bang-bang, trapezoidal, quintic), numerically.

    Each joint alone at its limits needs its own time; all end together at the largest, T:
    bang-bang joints rescale their acceleration (a = 4|D|/T^2), trapezoidal ones keep it and
    lower their cruise velocity, quintic ones report their peak acceleration 10|D|/(sqrt(3) T^2).
    """

    def __init__(self, start, end, max_acceleration, shape="bang-bang", max_velocity=None):
        self.shape = shape
        self.start, self.end = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
        self.delta = self.end - self.start
        D, a = np.abs(self.delta), np.asarray(max_acceleration, dtype=float)
        if shape == "bang-bang":
            own = np.sqrt(4 * D / a)
        elif shape == "quintic":
            own = np.sqrt(10 * D / (np.sqrt(3) * a))
        else:
            v = np.asarray(max_velocity, dtype=float)
            own = np.where(D >= v ** 2 / a, D / v + v / a, np.sqrt(4 * D / a))
        self.durations = own
        self.T = float(own.max())
        T = self.T
        if shape == "bang-bang":
            self.accelerations = 4 * D / T ** 2
        elif shape == "quintic":
            self.accelerations = 10 * D / (np.sqrt(3) * T ** 2)
        else:
            self.accelerations = np.where(D > 0, a, 0.0)
            self.velocities = np.where(D > 0, (a * T - np.sqrt(np.maximum(a ** 2 * T ** 2 - 4 * a * D, 0))) / 2, 0.0)
        self.breaks = self._breaks()

    def _breaks(self):
        if self.shape == "bang-bang":
            inner = [self.T / 2]
        elif self.shape == "quintic":
            inner = []
        else:
            inner = [float(x) for v, a in zip(self.velocities, self.accelerations) if a > 0
                     for x in (v / a, self.T - v / a)]
        return sorted({0.0, self.T, *[x for x in inner if 0 < x < self.T]})

    def evaluate(self, t):
        """(q, q', q'') at time t (the start before 0, the end after T)."""
        t = min(max(float(t), 0.0), self.T)
        sign, T = np.sign(self.delta), self.T
        if self.shape == "quintic":
            s = t / T
            shape = np.array([10 * s ** 3 - 15 * s ** 4 + 6 * s ** 5, (30 * s ** 2 - 60 * s ** 3 + 30 * s ** 4) / T,
                              (60 * s - 180 * s ** 2 + 120 * s ** 3) / T ** 2])
            return self.start + self.delta * shape[0], self.delta * shape[1], self.delta * shape[2]
        a = self.accelerations
        ramp = T / 2 * np.ones_like(a) if self.shape == "bang-bang" else \
            np.divide(self.velocities, a, out=np.zeros_like(a), where=a > 0)
        vmax = a * ramp
        up, down = np.minimum(t, ramp), np.maximum(t - (T - ramp), 0.0)
        cruise = np.clip(t - ramp, 0.0, T - 2 * ramp)
        q = a * up ** 2 / 2 + vmax * cruise + vmax * down - a * down ** 2 / 2
        qd = np.where(t < ramp, a * t, np.where(t >= T - ramp, vmax - a * down, vmax))
        qdd = np.where(t < ramp, a, np.where(t >= T - ramp, -a, 0.0))   # right-sided at a switch
        if t >= T:
            qd, qdd = np.zeros_like(a), np.zeros_like(a)
        return self.start + sign * q, sign * qd, sign * qdd


# -- integration ------------------------------------------------------------------------------------

_DP = ([], [1 / 5], [3 / 40, 9 / 40], [44 / 45, -56 / 15, 32 / 9],
       [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
       [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
       [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
_DP_C = [0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1, 1]
_DP_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


def integrate(rhs, t0, t1, y0, rtol=1e-10, atol=1e-12, max_step=None, max_steps=2_000_000):
    """y' = rhs(t, y) from t0 to t1 by Dormand-Prince 5(4) with step control: (times, states)."""
    t, y = float(t0), np.asarray(y0, dtype=float)
    h = min((t1 - t0) / 100, max_step or np.inf)
    times, states = [t], [y]
    k = [None] * 7
    for _ in range(max_steps):
        if t >= t1 - 1e-15 * max(1.0, abs(t1)):
            break
        h = min(h, t1 - t)
        k[0] = np.asarray(rhs(t, y), dtype=float)
        for i in range(1, 7):
            k[i] = np.asarray(rhs(t + _DP_C[i] * h, y + h * sum(c * kk for c, kk in zip(_DP[i], k))), dtype=float)
        new = y + h * sum(c * kk for c, kk in zip(_DP[6], k))
        err = h * sum(c * kk for c, kk in zip(_DP_E, k))
        scale = atol + rtol * np.maximum(np.abs(y), np.abs(new))
        ratio = np.sqrt(np.mean((err / scale) ** 2))
        if ratio <= 1:
            t, y = t + h, new
            times.append(t)
            states.append(y)
        h *= min(5.0, max(0.2, 0.9 * (ratio + 1e-300) ** -0.2))
        if max_step:
            h = min(h, max_step)
    else:
        raise RuntimeError(f"the integration needs more than {max_steps} steps")
    return np.array(times), np.array(states)


# -- along a profile: the actuators, the closed loop ----------------------------------------------

def torque_peaks(robot, profile, at=None, samples=4000):
    """The signed peak (value of largest magnitude) of each actuator along the profile, and when:
    tau = M q'' + c + g - Q sampled on each interval (both sides of every switching instant) and
    refined by golden-section search around the largest samples."""
    f = robot.numeric_dynamics(at)
    n = len(robot.joints)

    def tau(time, _=None):
        q, qd, qdd = profile.evaluate(time)
        return f["mass"](time, q, qd) @ qdd + f["c"](time, q, qd) + f["g"](time, q, qd) - f["Q"](time, q, qd)

    peaks, when = np.zeros(n), np.zeros(n)
    for a, b in zip(profile.breaks[:-1], profile.breaks[1:]):
        grid = np.linspace(a + 1e-12, b - 1e-12, max(3, samples // max(1, len(profile.breaks) - 1)))
        values = np.array([tau(x, None) for x in grid])
        for i in range(n):
            k = int(np.argmax(np.abs(values[:, i])))
            lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
            x, v = _golden_max(lambda s: abs(tau(s, None)[i]), lo, hi)
            v = tau(x, None)[i]
            if abs(values[k, i]) >= abs(v):
                x, v = grid[k], values[k, i]
            if abs(v) > abs(peaks[i]) + 1e-12 * max(1.0, abs(v)):
                peaks[i], when[i] = v, x
    return peaks, when


def _golden_max(f, lo, hi, steps=80):
    g = (np.sqrt(5) - 1) / 2
    a, b = lo, hi
    c, d = b - g * (b - a), a + g * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(steps):
        if fc > fd:
            b, d, fd = d, c, fc
            c = b - g * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + g * (b - a)
            fd = f(d)
    x = (a + b) / 2
    return x, f(x)


def control_torque(law, kp, kd, e, ed, qdd_desired, m, c, g):
    """p: Kp e;  pd: + Kd e';  pd_gravity: + g(q);  computed_torque: M (q''_d + Kd e' + Kp e) + c + g."""
    if law == "p":
        return kp * e
    if law == "pd":
        return kp * e + kd * ed
    if law == "pd_gravity":
        return kp * e + kd * ed + g
    return m @ (qdd_desired + kd * ed + kp * e) + c + g


def simulate_control(robot, profile, law, kp, kd=None, start=None, duration=None, at=None, rtol=1e-10):
    """The closed loop M q'' + c + g = tau + Q from `start` at rest (default the profile's start),
    integrated in error coordinates (e = q_d - q, e'), restarted at each switching instant:
    (max |e| per joint, when, e at the end, times, errors)."""
    f = robot.numeric_dynamics(at)
    n = len(robot.joints)
    kp = np.asarray(kp, dtype=float)
    kd = np.zeros(n) if kd is None else np.asarray(kd, dtype=float)
    duration = profile.T if duration is None else float(duration)
    start = profile.start if start is None else np.asarray(start, dtype=float)

    def rhs(time, y):
        q_d, qd_d, qdd_d = profile.evaluate(time)
        e, ed = y[:n], y[n:]
        q, qd = q_d - e, qd_d - ed
        m, c, g = f["mass"](time, q, qd), f["c"](time, q, qd), f["g"](time, q, qd)
        tau = control_torque(law, kp, kd, e, ed, qdd_d, m, c, g)
        return np.concatenate([ed, qdd_d - np.linalg.solve(m, tau + f["Q"](time, q, qd) - c - g)])

    cuts = sorted({0.0, duration, *[b for b in profile.breaks if 0 < b < duration]})
    y = np.concatenate([profile.evaluate(0.0)[0] - start, np.zeros(n)])
    times, states = [np.array([0.0])], [y[None, :]]
    for a, b in zip(cuts[:-1], cuts[1:]):
        tt, yy = integrate(rhs, a, b, y, rtol=rtol, atol=1e-13, max_step=(b - a) / 200)
        times.append(tt[1:])
        states.append(yy[1:])
        y = yy[-1]
    times, states = np.concatenate(times), np.concatenate(states)
    errors = states[:, :n]
    k = np.argmax(np.abs(errors), axis=0)
    return np.abs(errors[k, range(n)]), times[k], errors[-1], times, errors


def forward_run(robot, laws, start, start_rates, duration, at=None, rtol=1e-10):
    """The motion under the actuator `laws` ({actuator: text in t, the joints and rates}) from
    (start, start_rates): (times, joint values, rates)."""
    f = robot.numeric_dynamics(at, laws)
    n = len(robot.joints)

    def rhs(time, y):
        q, qd = y[:n], y[n:]
        return np.concatenate([qd, np.linalg.solve(f["mass"](time, q, qd), f["rest"](time, q, qd))])

    y0 = np.concatenate([np.asarray(start, dtype=float), np.asarray(start_rates, dtype=float)])
    times, states = integrate(rhs, 0.0, float(duration), y0, rtol=rtol, atol=1e-12, max_step=float(duration) / 400)
    return times, states[:, :n], states[:, n:]


def extremes(times, qs, rates):
    """The smallest and largest value of each joint over a run: the samples, and between two
    samples where the rate changes sign, the stationary point of the cubic Hermite interpolant."""
    low, high = qs.min(axis=0).copy(), qs.max(axis=0).copy()
    for i in range(qs.shape[1]):
        q, v = qs[:, i], rates[:, i]
        for k in np.nonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0)[0]:
            h = times[k + 1] - times[k]
            p = np.polynomial.Polynomial([q[k], h * v[k], 3 * (q[k + 1] - q[k]) - h * (2 * v[k] + v[k + 1]),
                                          2 * (q[k] - q[k + 1]) + h * (v[k] + v[k + 1])])
            for s in p.deriv().roots():
                if abs(s.imag) < 1e-12 and 0 <= s.real <= 1:
                    value = p(s.real)
                    low[i], high[i] = min(low[i], value), max(high[i], value)
    return low, high


# -- work-space trajectories ------------------------------------------------------------------------

class TaskPath:
    """A path of the task coordinates with s its arc length, 0 <= s <= L: the line
    x(s) = a + s u, u = (b - a) / L; or, given a centre c, the arc from a to b the shorter way,
    x(s) = c + r (cos(s/r) e1 + sin(s/r) e2), e1 = (a - c) / r, e2 in the arc's plane towards b
    (a half circle: e2 = normal x e1, or e1 turned counter-clockwise in the plane)."""

    def __init__(self, a, b, center=None, normal=None):
        self.a, self.b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        self.center = None if center is None else np.asarray(center, dtype=float)
        if self.center is None:
            self.kind, self.length = "line", float(np.linalg.norm(self.b - self.a))
            return
        ra, rb = self.a - self.center, self.b - self.center
        r = self.radius = float(np.linalg.norm(ra))
        self.e1 = ra / r
        perp = rb / r - float(np.dot(rb / r, self.e1)) * self.e1
        self.angle = float(np.arccos(np.clip(np.dot(ra, rb) / (r * r), -1.0, 1.0)))
        if np.linalg.norm(perp) > 1e-9:
            self.e2 = perp / np.linalg.norm(perp)
        elif self.a.size == 2:
            self.e2 = np.array([-self.e1[1], self.e1[0]])
        else:
            n = np.asarray(normal, dtype=float)
            self.e2 = np.cross(n / np.linalg.norm(n), self.e1)
        self.kind, self.length = "circle", r * self.angle

    def at(self, s):
        """(x, dx/ds, d2x/ds2) at arc length s."""
        if self.kind == "line":
            u = (self.b - self.a) / self.length
            return self.a + s * u, u, np.zeros_like(u)
        r, th = self.radius, s / self.radius
        c, sn = np.cos(th), np.sin(th)
        return (self.center + r * (c * self.e1 + sn * self.e2), -sn * self.e1 + c * self.e2,
                -(c * self.e1 + sn * self.e2) / r)


class Timing:
    """s(t) on [0, T] along a path of length L: with a `duration`, quintic
    s = L (10 u^3 - 15 u^4 + 6 u^5), u = t / T; else trapezoidal (accelerate at a_max, cruise at
    v_max, decelerate: T = L / v + v / a), bang-bang when L < v^2 / a (T = 2 sqrt(L / a))."""

    def __init__(self, length, max_velocity=None, max_acceleration=None, duration=None):
        L = self.length = float(length)
        if duration is not None:
            T = self.T = float(duration)
            self.kind, self.breaks = "quintic", [0.0, T]
            self.v_peak, self.a_max, self.t_acc = 1.875 * L / T, 5.773502691896258 * L / T ** 2, 0.0
            return
        v, a = float(max_velocity), float(max_acceleration)
        if L >= v * v / a:
            ta = v / a
            self.kind, self.T, self.v_peak = "trapezoidal", L / v + ta, v
            self.breaks = [0.0, ta, self.T - ta, self.T]
        else:
            ta = np.sqrt(L / a)
            self.kind, self.T, self.v_peak = "bang-bang", 2 * ta, a * ta
            self.breaks = [0.0, ta, 2 * ta]
        self.a_max, self.t_acc = a, ta

    def at(self, t, segment=None):
        """(s, s', s'') at t; `segment` (an interval of `breaks`) picks the side at a switch."""
        if segment is None:
            segment = max(0, min(int(np.searchsorted(self.breaks, t, side="right")) - 1, len(self.breaks) - 2))
        L, T = self.length, self.T
        if self.kind == "quintic":
            u = t / T
            return (L * (10 * u ** 3 - 15 * u ** 4 + 6 * u ** 5), L * (30 * u ** 2 - 60 * u ** 3 + 30 * u ** 4) / T,
                    L * (60 * u - 180 * u ** 2 + 120 * u ** 3) / T ** 2)
        a, v, ta = self.a_max, self.v_peak, self.t_acc
        if segment == 0:
            return 0.5 * a * t * t, a * t, a
        if segment == len(self.breaks) - 2:
            d = T - t
            return L - 0.5 * a * d * d, a * d, -a
        return 0.5 * a * ta * ta + v * (t - ta), v, 0.0


class TaskArm:
    """The task map of `coordinates` (text expressions such as E_y) at the data and `at`:
    x(q), J(q) = dx/dq and J'(q) q' = d(J q')/dq q', numerically."""

    def __init__(self, robot, coordinates, at=None):
        self.joints, self.m, self.n = robot.joints, len(coordinates), len(robot.joints)
        self.expr = robot.vector(coordinates).subs(robot.fixed(at))
        J = self.expr.jacobian(robot.joints)
        rates = sp.Matrix(robot.rates)
        self._x = sp.lambdify([robot.joints], list(self.expr), "numpy")
        self._J = sp.lambdify([robot.joints], J.tolist(), "numpy")
        jdot = (J * rates).jacobian(robot.joints)        # J' (J = dx/dq: symmetric derivatives)
        self._h = sp.lambdify([robot.joints, robot.rates], list(jdot * rates), "numpy")
        self._Jd = sp.lambdify([robot.joints, robot.rates], jdot.tolist(), "numpy")
        self.revolute = [kind == "revolute" for kind in robot.kinds]

    def x(self, q):
        return np.asarray(self._x(list(q)), dtype=float).reshape(self.m)

    def J(self, q):
        return np.asarray(self._J(list(q)), dtype=float).reshape(self.m, self.n)

    def jdot_qdot(self, q, qd):
        return np.asarray(self._h(list(q), list(qd)), dtype=float).reshape(self.m)

    def newton(self, target, q0, tol=1e-12, max_iter=30):
        """q with x(q) = target near q0 (minimum-norm steps, at most 0.5 per joint); None when
        it does not converge."""
        q, target = np.array(q0, dtype=float), np.asarray(target, dtype=float)
        scale = max(1.0, float(np.max(np.abs(target))))
        for _ in range(max_iter):
            r = target - self.x(q)
            if float(np.max(np.abs(r))) <= tol * scale:
                return q
            step = np.linalg.lstsq(self.J(q), r, rcond=None)[0]
            big = float(np.max(np.abs(step)))
            q = q + (step if big <= 0.5 else step * (0.5 / big))
        return q if float(np.max(np.abs(target - self.x(q)))) <= 1e3 * tol * scale else None

    def J_dot(self, q, qd):
        return np.asarray(self._Jd(list(q), list(qd)), dtype=float).reshape(self.m, self.n)

    def root_tolerance(self, q, target):
        """How far Newton's q may be from the exact solution of x(q) = target, in q: at a simple
        root the residual's round-off r over J's smallest singular value; at a double root (J
        singular there: the arm stretched) Newton converges linearly and stops where r, of order
        distance², is round-off, some √r away (6e-9 rad on a 2R arm stretched)."""
        if q is None:
            return 1e-9
        target = np.asarray(target, dtype=float)
        r = max(float(np.linalg.norm(target - self.x(q))), 1e-15 * max(1.0, float(np.linalg.norm(target))))
        smin = float(np.linalg.svd(self.J(q), compute_uv=False).min())
        return max(1e-9, 10 * r / smin if smin > np.sqrt(r) else 10 * np.sqrt(r))

    def min_norm_rates(self, q, xd):
        """J+ x' = J^T (J J^T)^-1 x' (J wide)."""
        J = self.J(q)
        return J.T @ np.linalg.solve(J @ J.T, xd)

    def rates(self, q, xd, xdd):
        """(q' = J+ x', q'' its time derivative, the smallest singular value of J) at q: q'' =
        J+ (x'' - J' q'), plus (I - J+ J) J'^T (J J^T)^-1 x' when J is wide (fewer coordinates
        than joints: the derivative of the minimum-norm rates has a part in J's null space)."""
        J = self.J(q)
        sv = np.linalg.svd(J, compute_uv=False)
        Jp = np.linalg.pinv(J)
        qd = Jp @ xd
        qdd = Jp @ (xdd - self.jdot_qdot(q, qd))
        if self.m < self.n and sv.size and sv[-1] > 0:
            qdd = qdd + (np.eye(self.n) - Jp @ J) @ (self.J_dot(q, qd).T @ np.linalg.solve(J @ J.T, xd))
        return qd, qdd, float(sv[-1]) if sv.size else 0.0

    def nearest(self, target, q0, tol=1e-12):
        """The solution of x(q) = target nearest q0 (J wide: a family of solutions): the least-
        distance iteration from Newton's point of q0 and of q0 moved by 0.5 along each joint both
        ways, the nearest result kept (an earlier one unless nearer by 1e-9)."""
        q_newton = self.newton(target, q0, tol)
        if q_newton is None:
            return None
        q0 = np.asarray(q0, dtype=float)
        best, best_distance = None, np.inf
        moves = [np.zeros_like(q0)] + [sign * 0.5 * e for e in np.eye(q0.size) for sign in (1.0, -1.0)]
        for move in moves:
            q_start = q_newton if not move.any() else self.newton(target, q0 + move, tol)
            q = None if q_start is None else self.least_distance(target, q0, q_start, tol)
            if q is not None and float(np.linalg.norm(q - q0)) < best_distance - 1e-9:
                best, best_distance = q, float(np.linalg.norm(q - q0))
        return q_newton if best is None else best

    def least_distance(self, target, q0, q, tol):
        """q <- q0 + J+(q) (target - x(q) + J(q) (q - q0)) (x linearised at q, the nearest point
        of that linear set to q0) until it settles (then half steps); None when it does not."""
        target = np.asarray(target, dtype=float)
        for iterations, share in ((200, 1.0), (400, 0.5)):
            p = q
            for _ in range(iterations):
                J = self.J(p)
                p_next = q0 + np.linalg.lstsq(J, target - self.x(p) + J @ (p - q0), rcond=None)[0]
                move = float(np.max(np.abs(p_next - p)))
                p = p + share * (p_next - p)
                if not np.all(np.isfinite(p)):
                    break
                if move <= 1e-14 * max(1.0, float(np.max(np.abs(p)))):
                    return self.newton(target, p, tol)
        return None

    def start(self, target, limits, given=None):
        """The configuration at `target` whose branch is followed: as many coordinates as joints,
        Newton from `given`, else the first of the sorted IK solutions within the limits; J
        wide, the solution nearest `given` (else nearest q = 0)."""
        if self.m < self.n:
            return self.nearest(target, np.zeros(self.n) if given is None else given)
        if given is not None:
            return self.newton(target, given)
        solutions = newton_solutions(self.expr - sp.Matrix(list(target)), self.joints, limits, self.revolute)
        return solutions[0] if solutions else None


class TaskTrajectory:
    """The joint motion along a timed path from the branch of `start`: at each sample q solves
    x(q) = x_d(t) by Newton from the previous sample (predicted with its rates; J wide: the
    minimum-norm motion q' = J+ x'_d integrated from it), then q' = J+ x'_d and q'' its
    derivative. The samples: `samples` over [0, T], shared out between the intervals of the
    timing law, whose ends are sampled on both sides. Stops at the first sample out of reach or
    at a singularity (`failure`: kind, t, x, q)."""

    def __init__(self, arm, path, timing, start, samples=401, sigma_tol=1e-6):
        self.arm, self.path, self.timing = arm, path, timing
        ts, segs = [], []
        for k, (a, b) in enumerate(zip(timing.breaks[:-1], timing.breaks[1:])):
            count = max(3, int(round(samples * (b - a) / timing.T)) + 1)
            ts += [float(t) for t in np.linspace(a, b, count)]
            segs += [k] * count
        self._follow(np.array(ts), np.array(segs), np.asarray(start, dtype=float), sigma_tol)

    def state(self, t, segment=None):
        """(s, x_d, x'_d, x''_d) at t."""
        s, sd, sdd = self.timing.at(t, segment)
        x, d1, d2 = self.path.at(s)
        return s, x, d1 * sd, d2 * sd * sd + d1 * sdd

    def desired(self, t, segment=None):
        """(x_d, x'_d, x''_d) at t; after T the end, at rest."""
        if t >= self.timing.T:
            x = self.path.at(self.path.length)[0]
            return x, np.zeros_like(x), np.zeros_like(x)
        return self.state(max(t, 0.0), segment)[1:]

    def _follow(self, ts, segs, q_prev, sigma_tol):
        arm, n = self.arm, len(q_prev)
        rows, qd_prev, t_prev, self.failure = [], np.zeros(n), 0.0, None
        scale = max(float(np.linalg.norm(arm.J(q_prev), 2)), 1e-300)
        # an exactly singular configuration (a stretched arm) shows sigma ~ sqrt(2 r |J|) once
        # Newton has solved it to the residual r = 1e-12 max(1, |x|): ten times that is singular
        reach = [self.path.a, self.path.b] + ([] if getattr(self.path, "center", None) is None else
                                              [np.abs(self.path.center) + self.path.radius])
        residual = 1e-12 * max(1.0, float(np.max(np.abs(np.concatenate(reach)))))
        floor = max(sigma_tol * scale, 10.0 * np.sqrt(residual * scale))
        for t, seg in zip(ts, segs):
            s, x, xd, xdd = self.state(t, seg)
            if arm.m < n:      # J wide: the minimum-norm motion, integrated, then Newton polishes it
                guess = self.min_norm_step(q_prev, t_prev, float(t), seg)
            else:
                guess = q_prev + qd_prev * (t - t_prev)
            q = arm.newton(x, guess)
            if q is None:
                self.failure = self._leaving(t_prev, float(t), seg, q_prev)
                break
            qd, qdd, sigma = arm.rates(q, xd, xdd)
            if sigma < floor or (t > 0 and float(np.max(np.abs(q - guess))) > 0.2):
                self.failure = {"kind": "singular", "t": float(t), "x": x.tolist(), "q": q.tolist()}
                break
            rows.append((t, seg, s, x, xd, xdd, q, qd, qdd, sigma))
            q_prev, qd_prev, t_prev = q, qd, t
        cols = list(zip(*rows)) if rows else [[]] * 10
        self.t, self.segment, self.s = np.array(cols[0]), np.array(cols[1], dtype=int), np.array(cols[2])
        self.x, self.xd, self.xdd, self.q, self.qd, self.qdd = (np.array(c, dtype=float).reshape(len(rows), w).T
                                                                for c, w in zip(cols[3:9], [arm.m] * 3 + [n] * 3))
        self.sigma = np.array(cols[9])
        if self.failure is None:
            self._singular_between(floor)

    def _leaving(self, t_in, t_out, seg, q_in):
        """Where the path leaves the reach: bisection between a reached and an unreached instant."""
        q_last = np.asarray(q_in, dtype=float)
        for _ in range(40):
            mid = 0.5 * (t_in + t_out)
            q = self.arm.newton(self.state(mid, seg)[1], q_last)
            if q is None:
                t_out = mid
            else:
                t_in, q_last = mid, q
        return {"kind": "unreachable", "t": float(t_out), "x": self.state(t_out, seg)[1].tolist(),
                "q": q_last.tolist()}

    def min_norm_step(self, q, t0, t1, segment, steps_per_T=800):
        """q at t1 on the motion q' = J+(q) x'_d(t) through q at t0 (one segment of the timing
        law): classical Runge-Kutta, sub-steps of at most T / steps_per_T."""
        q, span = np.asarray(q, dtype=float), t1 - t0
        if span == 0:
            return q
        count = max(1, int(np.ceil(abs(span) * steps_per_T / self.timing.T)))
        h = span / count
        f = lambda t, y: self.arm.min_norm_rates(y, self.state(t, segment)[2])   # noqa: E731
        for step in range(count):
            t = t0 + step * h
            k1 = f(t, q)
            k2 = f(t + h / 2, q + h / 2 * k1)
            k3 = f(t + h / 2, q + h / 2 * k2)
            k4 = f(t + h, q + h * k3)
            q = q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        return q

    def state_at(self, t, segment):
        """(q, q', q'', sigma) at any t of a segment, by Newton from the nearest sample (J wide:
        from the minimum-norm motion integrated from it)."""
        k = int(np.argmin(np.abs(self.t - t) + 1e9 * (self.segment != segment)))
        _, x, xd, xdd = self.state(t, segment)
        if self.arm.m < self.q.shape[0]:
            guess = self.min_norm_step(self.q[:, k], float(self.t[k]), float(t), segment)
        else:
            guess = self.q[:, k] + self.qd[:, k] * (t - self.t[k])
        q = self.arm.newton(x, guess)
        return (self.q[:, k] if q is None else q, *self.arm.rates(self.q[:, k] if q is None else q, xd, xdd))

    def _refine(self, fun, k, sign=1.0):
        """The largest sign * fun(t, segment) near sample k within its segment: (value, t)."""
        seg = self.segment[k]
        idx = np.nonzero(self.segment == seg)[0]
        lo, hi = self.t[max(k - 1, idx[0])], self.t[min(k + 1, idx[-1])]
        best = (sign * fun(self.t[k], seg), float(self.t[k]))
        if hi > lo:
            t, value = _golden_max(lambda tt: sign * fun(tt, seg), lo, hi)
            if value > best[0]:
                best = (float(value), float(t))
        return best

    def _singular_between(self, tol):
        """A singular configuration between samples (sigma dipping to 0 at a local minimum)."""
        sig = self.sigma
        for k in range(1, sig.size - 1):
            if sig[k] <= sig[k - 1] and sig[k] <= sig[k + 1] and self.segment[k - 1] == self.segment[k + 1]:
                value, t = self._refine(lambda tt, sg: self.state_at(tt, sg)[3], k, sign=-1.0)
                if -value < tol:
                    seg = self.segment[k]
                    self.failure = {"kind": "singular", "t": t, "x": self.state(t, seg)[1].tolist(),
                                    "q": self.state_at(t, seg)[0].tolist()}
                    return

    def extremes(self):
        """max |q'_i| and max |q''_i| over [0, T] (refined between samples), and the smallest
        singular value of J with its time: (velocities, accelerations, (sigma_min, t))."""
        n = self.q.shape[0]
        vel, acc = np.zeros(n), np.zeros(n)
        for i in range(n):
            for values, out, which in ((self.qd, vel, 1), (self.qdd, acc, 2)):
                k = int(np.argmax(np.abs(values[i])))
                out[i] = self._refine(lambda tt, sg, i=i, w=which: abs(self.state_at(tt, sg)[w][i]), k)[0]
        smin, tmin = self._refine(lambda tt, sg: self.state_at(tt, sg)[3], int(np.argmin(self.sigma)), sign=-1.0)
        return vel, acc, (-smin, tmin)

    def plan(self, every=5):
        """The joint reference of the ideal scheme: quintics matching q, q', q'' at every
        `every`-th sample of each interval of the timing law (and at its ends)."""
        knots = []
        for seg in range(len(self.timing.breaks) - 1):
            idx = np.nonzero(self.segment == seg)[0]
            if idx.size:
                knots += list(idx[::every]) + ([idx[-1]] if (idx.size - 1) % every else [])
        breaks, coeffs = [float(self.t[0])], []
        for a, b in zip(knots[:-1], knots[1:]):
            h = float(self.t[b] - self.t[a])
            if h > 0:
                coeffs.append(_hermite(self.q[:, a], self.qd[:, a], self.qdd[:, a],
                                       self.q[:, b], self.qd[:, b], self.qdd[:, b], h))
                breaks.append(float(self.t[b]))
        return JointPlan(breaks, coeffs)


def _hermite(q0, v0, a0, q1, v1, a1, h):
    """(n, 6) coefficients, about the interval's start, of the quintic with these ends."""
    A = np.array([[h ** 3, h ** 4, h ** 5], [3 * h ** 2, 4 * h ** 3, 5 * h ** 4], [6 * h, 12 * h ** 2, 20 * h ** 3]])
    rhs = np.vstack([q1 - (q0 + v0 * h + a0 * h * h / 2), v1 - (v0 + a0 * h), a1 - a0])
    return np.column_stack([q0, v0, a0 / 2, np.linalg.solve(A, rhs).T])


class JointPlan:
    """Piecewise polynomials of the joints: on interval k, q_i = sum_p coeffs[k][i, p] (t - breaks[k])^p;
    before 0 the start, after T the end, at rest."""

    def __init__(self, breaks, coeffs):
        self.breaks, self.coeffs = [float(b) for b in breaks], [np.asarray(c, dtype=float) for c in coeffs]
        self.T = self.breaks[-1]
        self.start, self.end = self.evaluate(0.0, 0)[0], self.evaluate(self.T, len(self.coeffs) - 1)[0]

    def evaluate(self, t, segment=None):
        """(q, q', q'') at t, on interval `segment` (one-sided at its ends)."""
        if segment is None:
            if t < 0 or t > self.T:
                end = self.evaluate(min(max(t, 0.0), self.T))[0]
                return end, np.zeros_like(end), np.zeros_like(end)
            segment = min(max(int(np.searchsorted(self.breaks, t, side="right")) - 1, 0), len(self.coeffs) - 1)
        c, u = self.coeffs[segment], t - self.breaks[segment]
        p = np.arange(c.shape[1])
        q = c @ u ** p
        qd = c[:, 1:] @ (p[1:] * u ** (p[1:] - 1))
        qdd = c[:, 2:] @ (p[2:] * (p[2:] - 1) * u ** (p[2:] - 2))
        return q, qd, qdd


# -- work-space closed loops --------------------------------------------------------------------------

def task_control_torque(law, kp, kd, arm, q, qd, xd, vd, ad, m, c, g):
    """The task laws on e = x_d - x(q), e' = x'_d - J q': task_pd_gravity: tau = J^T (Kp e + Kd e') + g;
    task_computed_torque: tau = M J^-1 (x''_d + Kd e' + Kp e - J' q') + c + g."""
    J = arm.J(q)
    e, ed = xd - arm.x(q), vd - J @ qd
    if law == "task_pd_gravity":
        return J.T @ (kp * e + kd * ed) + g
    return m @ np.linalg.solve(J, ad + kd * ed + kp * e - arm.jdot_qdot(q, qd)) + c + g


def simulate_task_control(robot, trajectory, law, kp, kd=None, start=None, duration=None, at=None,
                          rtol=1e-10, samples=2000):
    """A closed loop along a work-space trajectory, on M q'' + c + g = tau + Q from `start` at rest
    (default the trajectory's start), state (q, q'), over [0, duration] (default T): a task law
    (`task_control_torque`, restarted at each switch of the timing law), or a joint law following
    the converted trajectory (`trajectory.plan()`, the ideal scheme; restarted at each of its knots).
    Returns (max |e|, when, e at the end, times, e, x_d - x) with e per coordinate for a task law
    and per joint for a joint law; about `samples` steps or more."""
    f, arm, n = robot.numeric_dynamics(at), trajectory.arm, len(robot.joints)
    kp = np.asarray(kp, dtype=float)
    kd = np.zeros(n) if kd is None else np.asarray(kd, dtype=float)
    task = law.startswith("task_")
    plan = None if task else trajectory.plan()
    breaks = trajectory.timing.breaks if task else plan.breaks
    T = float(breaks[-1])
    duration = T if duration is None else float(duration)
    pieces = [(breaks[k], min(breaks[k + 1], duration), k) for k in range(len(breaks) - 1) if breaks[k] < duration]
    pieces += [(T, duration, None)] if duration > T else []

    def torque(t, seg, q, qd, m, c, g):
        if task:
            return task_control_torque(law, kp, kd, arm, q, qd, *trajectory.desired(t, seg), m, c, g)
        q_d, qd_d, qdd_d = plan.evaluate(t, seg)
        return control_torque(law, kp, kd, q_d - q, qd_d - qd, qdd_d, m, c, g)

    y = np.concatenate([trajectory.q[:, 0] if start is None else np.asarray(start, dtype=float), np.zeros(n)])
    out = []
    for a, b, seg in pieces:
        def rhs(t, yy, seg=seg):
            q, qd = yy[:n], yy[n:]
            m, c, g = f["mass"](t, q, qd), f["c"](t, q, qd), f["g"](t, q, qd)
            tau = torque(t, seg, q, qd, m, c, g)
            return np.concatenate([qd, np.linalg.solve(m, tau + f["Q"](t, q, qd) - c - g)])
        tt, yy = integrate(rhs, a, b, y, rtol=rtol, atol=1e-12, max_step=duration / samples)
        out += [(t, seg, state) for t, state in zip(tt[1:] if out else tt, yy[1:] if out else yy)]
        y = yy[-1]
    times = np.array([t for t, _, _ in out])
    x_err = np.array([trajectory.desired(t)[0] - arm.x(s[:n]) for t, _, s in out])     # x_d is continuous
    errors = x_err if task else np.array([plan.evaluate(t, seg)[0] - s[:n] for t, seg, s in out])
    k = np.argmax(np.abs(errors), axis=0)
    return np.abs(errors[k, range(errors.shape[1])]), times[k], errors[-1], times, errors, x_err


# -- mobility -----------------------------------------------------------------------------------------

def mobility(bodies, joints_1dof=0, joints_2dof=0, joints_3dof=0, planar=True):
    """Grübler (planar): 3 (m - 1) - 2 c1 - c2;  Kutzbach (spatial): 6 (m - 1) - 5 c1 - 4 c2 - 3 c3."""
    if planar:
        return 3 * (bodies - 1) - 2 * joints_1dof - joints_2dof
    return 6 * (bodies - 1) - 5 * joints_1dof - 4 * joints_2dof - 3 * joints_3dof
