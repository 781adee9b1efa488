"""Model and position/velocity solvers against independent references:
ERRATA §B closed forms, Robotics Toolbox ETS fkine, direct differentiation, finite differences."""

import numpy as np
import pytest
import sympy as sp

from conftest import PROBLEMS
from robosolve.core.transforms import rigid_inverse
from robosolve.load.loader import load_problem, load_problem_text
from robosolve.model import RobotModel
from robosolve.model.numeric import NumericChain
from robosolve.run.pipeline import solve_problem


@pytest.fixture(scope="module")
def scara():
    problem = load_problem(PROBLEMS / "scara-rrp.yaml")
    return problem, RobotModel(problem)


def test_scara_matches_errata_B(scara):
    problem, m = scara
    t1, t2, l = m.q
    L1, L2, h = sp.symbols("L1 L2 h", positive=True)
    expected = sp.Matrix([
        [sp.cos(t1 + t2), -sp.sin(t1 + t2), 0, L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2)],
        [sp.sin(t1 + t2), sp.cos(t1 + t2), 0, L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2)],
        [0, 0, 1, h - l], [0, 0, 0, 1]])
    assert sp.simplify(m.M0("3") - expected) == sp.zeros(4, 4)
    # 0L12 and 2L23 (l downward: -1 at [3,4], ERRATA item 64)
    assert m.L0(1) == sp.Matrix([[0, -1, 0, L1 * sp.sin(t1)], [1, 0, 0, -L1 * sp.cos(t1)], [0] * 4, [0] * 4])
    assert m.L0(2) == sp.Matrix([[0] * 4, [0] * 4, [0, 0, 0, -1], [0] * 4])


def test_scara_numeric_anchor(scara):
    problem, _ = scara
    report = solve_problem(problem)
    pos, vel = report.answers
    assert np.allclose(pos.numeric["position"], [np.sqrt(3) / 4, 13 / 20, 9 / 10], atol=1e-12)
    assert np.allclose(vel.numeric["velocity"], [-29 / 20, np.sqrt(3) / 4, -1 / 2], atol=1e-12)
    assert np.allclose(vel.numeric["angular_velocity"], [0, 0, 3], atol=1e-12)


def test_rigid_inverse_identity(scara):
    _, m = scara
    for f in m.frame_names():
        assert sp.simplify(m.M0(f) * rigid_inverse(m.M0(f))) == sp.eye(4)


def _direct_W_H(m, frame):
    """W = Mdot M^-1 and H = Mddot M^-1 by direct differentiation (no Rivals/Coriolis)."""
    M = m.M0(frame)
    md = m.time_derivative(M)
    mdd = m.time_derivative(md)
    inv = rigid_inverse(M)
    return md * inv, mdd * inv


def _vanishes(matrix, points=4, seed=3) -> bool:
    """Every entry is 0 at random values of all its symbols (a trigonometric polynomial that is
    not identically 0 does not vanish at random points); independent of robosolve's simplifier."""
    rng = np.random.default_rng(seed)
    symbols = sorted(matrix.free_symbols, key=lambda x: x.name)
    f = sp.lambdify(symbols, matrix, "numpy")
    return all(np.abs(np.asarray(f(*rng.uniform(-2, 2, len(symbols))), dtype=float)).max() < 1e-9
               for _ in range(points))


def test_rivals_and_coriolis_equal_direct_differentiation(scara):
    _, m = scara
    for f in m.frame_names():
        w, h = _direct_W_H(m, f)
        assert _vanishes(m.W0(f) - w)
        assert _vanishes(m.H0(f) - h)
        assert _vanishes(m.H0(f) - (m.time_derivative(m.W0(f)) + m.W0(f) ** 2))
    # the check sees a wrong formula: H is not Wdot alone (the W² term of H = Wdot + W²)
    last = m.frame_names()[-1]
    assert not _vanishes(m.H0(last) - m.time_derivative(m.W0(last)))


SPATIAL = """\
robosolve: 1
name: spatial
parameters: {a: 0.3, b: 0.2, c: 0.25, d: 0.1}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: q3, type: prismatic}
  - {name: q4, type: revolute}
frames:
  "1": {pose: "Tz(a) Rz(q1) Ry(pi/7)"}
  "2": {pose: "Tx(b) Ry(q2) Rx(0.3)"}
  "3": {pose: "Tz(q3) Tx(c)"}
  "4": {pose: "Rx(q4) Ty(d)"}
points:
  P: {frame: "4", at: [0.05, -0.02, 0.1]}
questions:
  - {type: position, point: P}
"""


def test_numeric_chain_velocity_and_acceleration_by_finite_differences():
    """Point velocity/acceleration of the numeric chain vs central differences of
    the position along a smooth joint trajectory q(t) = q0 + v t + a t^2 / 2."""
    problem = load_problem_text(SPATIAL)
    m = RobotModel(problem)
    rng = np.random.default_rng(1)
    params = {s: v for s, v in problem.parameters.items()}

    def pos(q):
        subs = dict(params) | dict(zip(m.q, q))
        return NumericChain(m, subs).point0("P")

    for _ in range(3):
        q0, v, a = rng.normal(size=4), rng.normal(size=4), rng.normal(size=4)
        subs = dict(params) | dict(zip(m.q, q0)) | dict(zip(m.qd, v)) | dict(zip(m.qdd, a))
        ch = NumericChain(m, subs)
        p = ch.point0("P")
        hom = np.append(p, 1.0)
        vel = (ch.W0("4") @ hom)[:3]
        acc = (ch.H0("4") @ hom)[:3]
        eps = 1e-4
        qt = lambda t: q0 + v * t + a * t * t / 2  # noqa: E731
        fd_v = (pos(qt(eps)) - pos(qt(-eps))) / (2 * eps)
        fd_a = (pos(qt(eps)) - 2 * p + pos(qt(-eps))) / eps ** 2
        assert np.allclose(vel, fd_v, atol=1e-7)
        assert np.allclose(acc, fd_a, atol=1e-5)


def test_symbolic_and_numeric_chains_agree():
    problem = load_problem_text(SPATIAL)
    m = RobotModel(problem)
    rng = np.random.default_rng(2)
    q0, v, a = rng.normal(size=4), rng.normal(size=4), rng.normal(size=4)
    subs = dict(problem.parameters) | dict(zip(m.q, q0)) | dict(zip(m.qd, v)) | dict(zip(m.qdd, a))
    ch = NumericChain(m, subs)
    for f in m.frame_names():
        for sym, num in ((m.M0(f), ch.M0(f)), (m.W0(f), ch.W0(f)), (m.H0(f), ch.H0(f))):
            assert np.allclose(np.array(sym.xreplace(subs).evalf(), dtype=float), num, atol=1e-12)
    for i in range(4):
        assert np.allclose(np.array(m.L0(i).xreplace(subs).evalf(), dtype=float), ch.L0(i), atol=1e-12)


def test_against_robotics_toolbox_ets():
    rtb = pytest.importorskip("roboticstoolbox")
    from roboticstoolbox import ET

    problem = load_problem(PROBLEMS / "scara-rrp.yaml")
    m = RobotModel(problem)
    L1, L2, h = 0.5, 0.4, 1.0
    ets = ET.tz(h) * ET.Rz() * ET.tx(L1) * ET.Rz() * ET.tx(L2) * ET.tz(jindex=2, flip=True)
    rng = np.random.default_rng(3)
    for _ in range(10):
        q = rng.uniform(-np.pi, np.pi, 3)
        q[2] = rng.uniform(0, 0.3)
        subs = dict(problem.parameters) | dict(zip(m.q, q))
        ours = np.array(m.M0("3").xreplace(subs).evalf(), dtype=float)
        assert np.allclose(ours, ets.fkine(q).A, atol=1e-12)
        # velocity of E against jacob0 * q_dot
        qd = rng.normal(size=3)
        subs |= dict(zip(m.qd, qd))
        ch = NumericChain(m, subs)
        v = (ch.W0("3") @ np.append(ch.point0("E"), 1))[:3]
        assert np.allclose(v, (ets.jacob0(q) @ qd)[:3], atol=1e-12)


def test_puma_dh_against_robotics_toolbox():
    rtb = pytest.importorskip("roboticstoolbox")
    puma = rtb.models.DH.Puma560()
    rows = []
    for link in puma.links:
        rows.append(f"    - {{theta: q{len(rows) + 1}, d: {link.d}, a: {link.a}, alpha: {link.alpha}}}")
    text = ("robosolve: 1\nname: puma\njoints:\n"
            + "".join(f"  - {{name: q{i}, type: revolute}}\n" for i in range(1, 7))
            + "dh:\n  rows:\n" + "\n".join(rows) + "\nquestions: [{type: position}]\n")
    problem = load_problem_text(text)
    m = RobotModel(problem)
    rng = np.random.default_rng(4)
    for _ in range(5):
        q = rng.uniform(-np.pi, np.pi, 6)
        ch = NumericChain(m, dict(zip(m.q, q)))
        assert np.allclose(ch.M0("6"), puma.fkine(q).A, atol=1e-12)
