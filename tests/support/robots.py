"""The robots of the tests and the benchmarks, in one place.

* Dynamics robots (`RobotDef`: plain sympy inputs of the dynamics engine, also built with
  sympy.physics.mechanics in `mechanics.py`): one_link, planar_2r, scara, anthropomorphic_3r,
  puma560, rp_vertical;
* kinematic chains from elementary transforms (`KinRobot`): kin_scara, kin_planar2r,
  kin_planar3r, kin_polar, kin_anthropomorphic;
* the vertical planar 2R arm of the motion tests, three independent ways:
  arm2r_symbolic (Lagrange by hand), arm2r_rtb (Robotics Toolbox), arm2r_pin (pinocchio).
  (The problems/*.yaml files describe some of the same robots for the pipeline.)

Reference robots for tests and the benchmark (plain sympy inputs of the engine).

Each robot is a :class:`RobotDef`: frames as lists of elementary motions (so that the same
robot can also be built with ``sympy.physics.mechanics``), joints, bodies given by mass,
centre of mass and classical inertia about the centre of mass, loads, gravity, and the
numeric values of its parameters.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from robosolve.core.matrices import pseudo_inertia_from_com, pseudo_inertia_rod
from robosolve.core.transforms import ELEMENTARY, dh_standard, rot_y, rot_z, trans_x, trans_z
from robosolve.dynamics.types import BodySpec, FrameSpec, JointSpec, LoadSpec

__all__ = ["RobotDef", "BodyDef", "planar_2r", "scara", "anthropomorphic_3r", "puma560",
           "one_link", "rp_vertical", "rod_com_inertia"]


@dataclass
class BodyDef:
    name: str
    frame: str
    mass: object
    com: list
    inertia: sp.Matrix  # classical tensor about the centre of mass, frame axes
    J: sp.Matrix | None = None  # pseudo-inertia override (rods: exact same matrix)

    def pseudo_inertia(self) -> sp.Matrix:
        if self.J is not None:
            return self.J
        return pseudo_inertia_from_com(self.mass, self.com, self.inertia)


@dataclass
class RobotDef:
    name: str
    frames: list  # (name, parent, [(kind, expr), ...])
    joints: list[JointSpec]
    bodies: list[BodyDef]
    gravity: list
    loads: list[LoadSpec] = field(default_factory=list)
    values: dict = field(default_factory=dict)

    def frame_specs(self) -> list[FrameSpec]:
        out = []
        for name, parent, motions in self.frames:
            m = sp.eye(4)
            for kind, e in motions:
                m = m * ELEMENTARY[kind](e)
            out.append(FrameSpec(name, parent, m))
        return out

    def body_specs(self) -> list[BodySpec]:
        return [BodySpec(b.name, b.frame, b.pseudo_inertia()) for b in self.bodies]

    def engine_inputs(self):
        return dict(frames=self.frame_specs(), joints=self.joints, bodies=self.body_specs(),
                    gravity=self.gravity, loads=self.loads)


def _joint(name, actuator=None, kind="revolute", index=1):
    q, qd, qdd = sp.symbols(f"{name} {name}_dot {name}_ddot", real=True)
    act = sp.Symbol(actuator or (f"C{index}" if kind == "revolute" else f"F{index}"))
    return JointSpec(name, q, qd, qdd, act, kind)


def rod_com_inertia(mass, start, end):
    """(com, classical inertia about com) of a thin rod, from its pseudo-inertia."""
    j = pseudo_inertia_rod(mass, start, end)
    c = sp.Matrix([(sp.Matrix(start)[i] + sp.Matrix(end)[i]) / 2 for i in range(3)])
    j3 = j[:3, :3] - mass * c * c.T
    ig = sp.expand(j3.trace()) * sp.eye(3) - j3
    return list(c), ig.applyfunc(sp.expand), j


def _rod(name, frame, mass, start, end):
    c, ig, j = rod_com_inertia(mass, start, end)
    return BodyDef(name, frame, mass, c, ig, J=j)


def _point(name, frame, mass, at):
    return BodyDef(name, frame, mass, list(at), sp.zeros(3, 3))


def one_link() -> RobotDef:
    """The seed's §6.5 arm (docs/course-notes.md#note-one-link-arm): rod + payload, follower force at 2L/3."""
    L, m1, m2, g, F = sp.symbols("L m1 m2 g F", positive=True)
    th = _joint("theta", "C")
    return RobotDef(
        "one-link",
        [("1", "0", [("Rx", th.q), ("Ty", L)])],
        [th],
        [_rod("link1", "1", m1, [0, -L, 0], [0, 0, 0]), _point("payload", "1", m2, [0, 0, 0])],
        [0, 0, -g],
        [LoadSpec("F", "1", force=[0, 0, -F], point=[0, -L / 3, 0])],
        {L: 1, m1: 2, m2: 1, g: sp.Rational(981, 100), F: 3},
    )


def planar_2r() -> RobotDef:
    """Planar 2R in the x-y plane with uniform rods, gravity along −y."""
    L1, L2, m1, m2, g = sp.symbols("L1 L2 m1 m2 g", positive=True)
    j1, j2 = _joint("theta1", index=1), _joint("theta2", index=2)
    return RobotDef(
        "planar-2r",
        [("1", "0", [("Rz", j1.q), ("Tx", L1)]), ("2", "1", [("Rz", j2.q), ("Tx", L2)])],
        [j1, j2],
        [_rod("link1", "1", m1, [-L1, 0, 0], [0, 0, 0]),
         _rod("link2", "2", m2, [-L2, 0, 0], [0, 0, 0])],
        [0, -g, 0],
        [],
        {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), m1: 3, m2: 2, g: sp.Rational(981, 100)},
    )


def scara(loads: bool = False) -> RobotDef:
    """The spec's SCARA RRP (course summary §4, with docs/course-notes.md#note-scara-frames) with rods, a vertical rod on the prismatic link and
    a payload at the end effector; `loads` adds a force on link 2 (in frame 0) and a torque
    on it."""
    L1, L2, h, m1, m2, m3, mp, g, d3 = sp.symbols("L1 L2 h m1 m2 m3 m_p g d3", positive=True)
    j1, j2, j3 = _joint("theta1", index=1), _joint("theta2", index=2), \
        _joint("l", kind="prismatic", index=3)
    extra = []
    values = {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), h: 1, m1: 10, m2: 6, m3: 2,
              mp: sp.Rational(3, 2), g: sp.Rational(981, 100), d3: sp.Rational(3, 10)}
    if loads:
        Fx, Cz = sp.symbols("F_x C_z")
        extra = [LoadSpec("push", "2", force=[Fx, 0, 0], point=[-L2 / 2, 0, 0], in_frame="0"),
                 LoadSpec("twist", "2", torque=[0, 0, Cz])]
        values.update({Fx: 20, Cz: 4})
    return RobotDef(
        "scara",
        [("1", "0", [("Tz", h), ("Rz", j1.q), ("Tx", L1)]),
         ("2", "1", [("Rz", j2.q), ("Tx", L2)]),
         ("3", "2", [("Tz", -j3.q)])],
        [j1, j2, j3],
        [_rod("link1", "1", m1, [-L1, 0, 0], [0, 0, 0]),
         _rod("link2", "2", m2, [-L2, 0, 0], [0, 0, 0]),
         _rod("link3", "3", m3, [0, 0, 0], [0, 0, d3]),
         _point("payload", "3", mp, [0, 0, 0])],
        [0, 0, -g],
        extra,
        values,
    )


def anthropomorphic_3r() -> RobotDef:
    """Anthropomorphic arm (DH: (q1, h, 0, π/2), (q2, 0, L2, 0), (q3, 0, L3, 0)), with a
    column of inertia Iz1 about its axis and rods for links 2 and 3."""
    h, L2, L3, m1, m2, m3, g, Iz1 = sp.symbols("h L2 L3 m1 m2 m3 g I_z1", positive=True)
    j1, j2, j3 = (_joint(f"theta{i}", index=i) for i in (1, 2, 3))
    col = BodyDef("link1", "1", m1, [0, -h / 2, 0], sp.diag(0, Iz1, 0))
    return RobotDef(
        "anthropomorphic-3r",
        [("1", "0", [("Rz", j1.q), ("Tz", h), ("Rx", sp.pi / 2)]),
         ("2", "1", [("Rz", j2.q), ("Tx", L2)]),
         ("3", "2", [("Rz", j3.q), ("Tx", L3)])],
        [j1, j2, j3],
        [col, _rod("link2", "2", m2, [-L2, 0, 0], [0, 0, 0]),
         _rod("link3", "3", m3, [-L3, 0, 0], [0, 0, 0])],
        [0, 0, -g],
        [],
        {h: sp.Rational(1, 2), L2: sp.Rational(2, 5), L3: sp.Rational(7, 20), m1: 8, m2: 5,
         m3: 3, g: sp.Rational(981, 100), Iz1: sp.Rational(1, 10)},
    )


# Corke's PUMA 560 (roboticstoolbox models/DH/Puma560.py, standard DH): d, a, alpha, m,
# r (centre of mass in the link frame), I (diagonal about the centre of mass).
_INCH = sp.Rational(254, 10000)
PUMA560_DH = [  # (d, a, alpha)
    (sp.Rational(2645, 100) * _INCH, 0, sp.pi / 2),
    (0, sp.Rational(4318, 10000), 0),
    (sp.Rational(15005, 100000), sp.Rational(203, 10000), -sp.pi / 2),
    (sp.Rational(4318, 10000), 0, sp.pi / 2),
    (0, 0, -sp.pi / 2),
    (0, 0, 0),
]
PUMA560_DYN = [  # (m, r, I diag)
    (0, (0, 0, 0), (0, 0.35, 0)),
    (17.4, (-0.3638, 0.006, 0.2275), (0.13, 0.524, 0.539)),
    (4.8, (-0.0203, -0.0141, 0.070), (0.066, 0.086, 0.0125)),
    (0.82, (0, 0.019, 0), (1.8e-3, 1.3e-3, 1.8e-3)),
    (0.34, (0, 0, 0), (0.3e-3, 0.4e-3, 0.3e-3)),
    (0.09, (0, 0, 0.032), (0.15e-3, 0.15e-3, 0.04e-3)),
]


def puma560(symbolic_parameters: bool = False) -> RobotDef:
    """PUMA 560 from its standard DH table with Corke's dynamic parameters (no motor
    inertia, no friction). With `symbolic_parameters`, every length, mass, centre-of-mass
    coordinate and inertia is a symbol (values in `.values`)."""
    joints = [_joint(f"q{i}", index=i) for i in range(1, 7)]
    frames, bodies, values = [], [], {}
    for i, ((d, a, alpha), (m, r, idiag)) in enumerate(zip(PUMA560_DH, PUMA560_DYN), 1):
        if symbolic_parameters:
            def sym(name, val):
                s = sp.Symbol(name, real=True)
                values[s] = sp.nsimplify(val) if not isinstance(val, sp.Basic) else val
                return s if val != 0 else 0
            d_, a_ = sym(f"d{i}", d), sym(f"a{i}", a)
            m_ = sym(f"m{i}", m)
            r_ = [sym(f"r{i}{c}", v) for c, v in zip("xyz", r)]
            i_ = [sym(f"I{i}{c}{c}", v) for c, v in zip("xyz", idiag)]
        else:
            d_, a_ = d, a
            m_ = sp.Float(m) if m else 0
            r_ = [sp.Float(v) if v else 0 for v in r]
            i_ = [sp.Float(v) if v else 0 for v in idiag]
        motions = [("Rz", joints[i - 1].q)]
        if d_ != 0:
            motions.append(("Tz", d_))
        if a_ != 0:
            motions.append(("Tx", a_))
        if alpha != 0:
            motions.append(("Rx", alpha))
        frames.append((str(i), str(i - 1), motions))
        bodies.append(BodyDef(f"link{i}", str(i), m_, r_, sp.diag(*i_)))
    g = sp.Symbol("g", positive=True)
    values[g] = sp.Rational(981, 100)
    return RobotDef("puma560", frames, joints, bodies, [0, 0, -g], [], values)


def rp_vertical() -> RobotDef:
    """RP arm in a vertical plane (x-z): revolute about y0, prismatic along the arm."""
    m1, m2, L1, g, d2 = sp.symbols("m1 m2 L1 g d2", positive=True)
    j1, j2 = _joint("theta", index=1), _joint("d", kind="prismatic", index=2)
    return RobotDef(
        "rp-vertical",
        [("1", "0", [("Ry", -j1.q)]), ("2", "1", [("Tx", j2.q)])],
        [j1, j2],
        [_rod("link1", "1", m1, [0, 0, 0], [L1, 0, 0]),
         _rod("link2", "2", m2, [-d2, 0, 0], [0, 0, 0])],
        [0, 0, -g],
        [],
        {m1: 4, m2: 2, L1: 1, g: sp.Rational(981, 100), d2: sp.Rational(1, 2)},
    )


# ------------------------------------------------ kinematic chains (elementary transforms)

t1, t2, t3, d, l = sp.symbols("theta1 theta2 theta3 d l")
L1, L2, L3, h, a2, a3 = sp.symbols("L1 L2 L3 h a2 a3")
R, P = "revolute", "prismatic"


def prod(ms):
    out = sp.eye(4)
    for m in ms:
        out = out * m
    return out


def _twist(m: sp.Matrix, q) -> sp.Matrix:
    r, p = m[:3, :3], m[:3, 3]
    inv = sp.Matrix(sp.BlockMatrix([[r.T, -r.T * p], [sp.zeros(1, 3), sp.ones(1, 1)]]))
    return (m.diff(q) * inv).applyfunc(lambda e: sp.trigsimp(sp.expand(e)))


class KinRobot:
    """frames: one list of elementary matrices per frame (frame i holds joint i)."""

    def __init__(self, q, kinds, frames, params):
        self.q = list(q)
        self.kinds = dict(zip(self.q, kinds))
        self.params = params
        self.local = [prod(f) for f in frames]
        self.M0 = []
        m = sp.eye(4)
        for loc in self.local:
            m = m * loc
            self.M0.append(m)
        self._l0 = None

    @property
    def L0(self):
        """L_i = (dM0_i/dq_i) M0_i^-1, written out here (not robosolve's l_matrix), so the
        tests that use it compare robosolve with an independent construction."""
        if self._l0 is None:
            self._l0 = [_twist(self.M0[i], qi) for i, qi in enumerate(self.q)]
        return self._l0

    @property
    def E(self):
        return self.M0[-1][:3, 3]


def kin_scara():
    return KinRobot([t1, t2, l], [R, R, P],
                 [[trans_z(h), rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)], [trans_z(-l)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), h: 1})


def kin_planar2r():
    return KinRobot([t1, t2], [R, R], [[rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(1, 2)})


def kin_planar3r():
    return KinRobot([t1, t2, t3], [R, R, R],
                 [[rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)], [rot_z(t3), trans_x(L3)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5), L3: sp.Rational(3, 10)})


def kin_polar():
    """Polar RRP: azimuth θ1 about z, elevation θ2 (positive up), radial extension d."""
    return KinRobot([t1, t2, d], [R, R, P], [[rot_z(t1)], [rot_y(-t2)], [trans_x(d)]], {})


def kin_anthropomorphic():
    return KinRobot([t1, t2, t3], [R, R, R],
                 [[dh_standard(t1, h, 0, sp.pi / 2)], [dh_standard(t2, 0, a2, 0)],
                  [dh_standard(t3, 0, a3, 0)]],
                 {h: sp.Rational(1, 2), a2: sp.Rational(2, 5), a3: sp.Rational(3, 10)})


# ------------------------------------------------ the motion tests' vertical 2R arm

ARM2R_VALUES = dict(L1=0.5, L2=0.4, m1=3.0, m2=2.0, I1=0.06, I2=0.03, g=9.81)
ARM2R_LC = dict(lc1=0.25, lc2=0.2)          # centres of mass from each joint, along the link


def arm2r_symbolic():
    """(M, c, g_vec, q, qd, qdd, params) of the 2R arm, by Lagrange from the COM positions."""
    q1, q2, dq1, dq2 = sp.symbols("q1 q2 q1_dot q2_dot")
    ddq1, ddq2 = sp.symbols("q1_ddot q2_ddot")
    L1, m1, m2, I1, I2, g, lc1, lc2 = sp.symbols("L1 m1 m2 I1 I2 g lc1 lc2", positive=True)
    t = sp.Symbol("t")
    f1, f2 = sp.Function("f1")(t), sp.Function("f2")(t)
    p1 = sp.Matrix([lc1 * sp.cos(f1), lc1 * sp.sin(f1)])
    p2 = sp.Matrix([L1 * sp.cos(f1) + lc2 * sp.cos(f1 + f2), L1 * sp.sin(f1) + lc2 * sp.sin(f1 + f2)])
    v1, v2 = p1.diff(t), p2.diff(t)
    T = (m1 * v1.dot(v1) + m2 * v2.dot(v2) + I1 * f1.diff(t) ** 2 + I2 * (f1.diff(t) + f2.diff(t)) ** 2) / 2
    U = g * (m1 * p1[1] + m2 * p2[1])
    Lg = T - U
    eqs = []
    for f in (f1, f2):
        eqs.append(sp.diff(Lg.diff(f.diff(t)), t) - Lg.diff(f))
    rep = {f1.diff(t, 2): ddq1, f2.diff(t, 2): ddq2}
    rep2 = {f1.diff(t): dq1, f2.diff(t): dq2}
    rep3 = {f1: q1, f2: q2}
    eqs = [sp.expand(e.subs(rep).subs(rep2).subs(rep3)) for e in eqs]
    qdd = [ddq1, ddq2]
    M = sp.Matrix(2, 2, lambda i, j: eqs[i].coeff(qdd[j]))
    rest = [sp.expand(e - sum(M[i, j] * qdd[j] for j in range(2))) for i, e in enumerate(eqs)]
    gv = sp.Matrix([r.subs({dq1: 0, dq2: 0}) for r in rest])
    c = sp.Matrix([sp.expand(r - gr) for r, gr in zip(rest, gv)])
    params = {L1: ARM2R_VALUES["L1"], m1: ARM2R_VALUES["m1"], m2: ARM2R_VALUES["m2"], I1: ARM2R_VALUES["I1"], I2: ARM2R_VALUES["I2"],
              g: ARM2R_VALUES["g"], lc1: ARM2R_LC["lc1"], lc2: ARM2R_LC["lc2"]}
    return M, c, gv, [q1, q2], [dq1, dq2], qdd, params


def arm2r_rtb():
    import pytest
    rtb = pytest.importorskip("roboticstoolbox")
    v = ARM2R_VALUES
    l1 = rtb.RevoluteDH(a=v["L1"], m=v["m1"], r=[ARM2R_LC["lc1"] - v["L1"], 0, 0], I=[0, 0, v["I1"]], Jm=0, G=1, B=0, Tc=[0, 0])
    l2 = rtb.RevoluteDH(a=v["L2"], m=v["m2"], r=[ARM2R_LC["lc2"] - v["L2"], 0, 0], I=[0, 0, v["I2"]], Jm=0, G=1, B=0, Tc=[0, 0])
    robot = rtb.DHRobot([l1, l2], gravity=[0, -v["g"], 0])
    return robot


def arm2r_pin():
    import pytest
    pin = pytest.importorskip("pinocchio")
    v = ARM2R_VALUES
    model = pin.Model()
    j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "j1")
    model.appendBodyToJoint(j1, pin.Inertia(v["m1"], np.array([ARM2R_LC["lc1"], 0, 0]), np.diag([0, 0, v["I1"]])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([v["L1"], 0, 0])), "j2")
    model.appendBodyToJoint(j2, pin.Inertia(v["m2"], np.array([ARM2R_LC["lc2"], 0, 0]), np.diag([0, 0, v["I2"]])), pin.SE3.Identity())
    model.gravity.linear = np.array([0, -v["g"], 0])
    return model
