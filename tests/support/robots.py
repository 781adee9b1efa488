"""Reference robots for tests and the benchmark (plain sympy inputs of the engine).

Each robot is a :class:`RobotDef`: frames as lists of elementary motions (so that the same
robot can also be built with ``sympy.physics.mechanics``), joints, bodies given by mass,
centre of mass and classical inertia about the centre of mass, loads, gravity, and the
numeric values of its parameters.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from robosolve.core.matrices import pseudo_inertia_from_com, pseudo_inertia_rod
from robosolve.core.transforms import ELEMENTARY
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
