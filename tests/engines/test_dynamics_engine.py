"""Equations of motion engine (robosolve.dynamics) against independent references:
the errata's closed forms, textbook formulas, sympy.physics.mechanics (Kane, Lagrange),
Robotics Toolbox (`inertia`, `rne`) and pinocchio (`crba`, `rnea`)."""

import numpy as np
import pytest
import sympy as sp

from robosolve.dynamics import derive_dynamics, numeric_dynamics
from tests.support import robots as ex
from robosolve.dynamics.engine import DynamicsEngine
from robosolve.dynamics.numeric import lambdify_dynamics


def _derive(robot, **kw):
    return derive_dynamics(**robot.engine_inputs(), **kw)


def _random_point(d, seed, values):
    rng = np.random.default_rng(seed)
    syms = d.q + d.qd + d.qdd + d.actuators
    pt = {s: sp.Float(v) for s, v in zip(syms, rng.uniform(-1.5, 1.5, len(syms)))}
    pt.update({k: sp.sympify(v) for k, v in values.items()})
    return pt


# ----------------------------------------------------------------- one-link arm (ERRATA §C)
def test_one_link_equation_of_motion_errata_c():
    r = ex.one_link()
    L, m1, m2, g, F = sp.symbols("L m1 m2 g F", positive=True)
    th = r.joints[0]
    d = _derive(r)
    expected_lhs = (m1 / 3 + m2) * L**2 * th.qdd + (m1 / 2 + m2) * g * L * sp.cos(th.q)
    assert sp.simplify(d.lhs()[0] - expected_lhs) == 0
    assert sp.simplify(d.generalized_forces[0] - (th.actuator - sp.Rational(2, 3) * F * L)) == 0
    # the course's literal f = (sum of 0Phi) (x) 0L gives the same
    assert sp.simplify(d.engine.course_generalized_forces()[0] - d.generalized_forces[0]) == 0
    # energies of ERRATA §C
    assert sp.simplify(d.kinetic_energy["link1"] - m1 * L**2 * th.qd**2 / 6) == 0
    assert sp.simplify(d.kinetic_energy["payload"] - m2 * L**2 * th.qd**2 / 2) == 0
    assert sp.simplify(d.potential_energy["link1"] - m1 * g * L * sp.sin(th.q) / 2) == 0
    assert sp.simplify(d.potential_energy["payload"] - m2 * g * L * sp.sin(th.q)) == 0
    # numeric anchor: theta'' = 9/5 - 2943 sqrt(3)/500 at m1=2, m2=1, L=1, g=9.81, C=5, F=3
    vals = {**r.values, th.q: sp.pi / 6, th.qd: 0, th.actuator: 5}
    thdd = sp.solve(d.equations()[0].subs(vals), th.qdd)[0]
    assert sp.simplify(thdd - (sp.Rational(9, 5) - 2943 * sp.sqrt(3) / 500)) == 0


def test_one_link_force_in_frame_0_reads_differently():
    """(0, 0, -F) given in frame 0 (fixed direction): f = C - 2/3 F L cos(theta)."""
    from robosolve.dynamics.api import LoadSpec

    r = ex.one_link()
    F, L = sp.symbols("F L", positive=True)
    r.loads = [LoadSpec("F", "1", force=[0, 0, -F], point=[0, -L / 3, 0], in_frame="0")]
    d = _derive(r)
    th = r.joints[0]
    expected = th.actuator - sp.Rational(2, 3) * F * L * sp.cos(th.q)
    assert sp.simplify(d.generalized_forces[0] - expected) == 0
    assert sp.simplify(d.engine.course_generalized_forces()[0] - expected) == 0


# ----------------------------------------------------------------- planar 2R
def test_planar_2r_textbook_closed_form():
    r = ex.planar_2r()
    L1, L2, m1, m2, g = sp.symbols("L1 L2 m1 m2 g", positive=True)
    j1, j2 = r.joints
    c2, s2 = sp.cos(j2.q), sp.sin(j2.q)
    M = sp.Matrix([
        [m1 * L1**2 / 3 + m2 * (L1**2 + L2**2 / 3 + L1 * L2 * c2), m2 * (L2**2 / 3 + L1 * L2 * c2 / 2)],
        [m2 * (L2**2 / 3 + L1 * L2 * c2 / 2), m2 * L2**2 / 3]])
    h = m2 * L1 * L2 * s2 / 2
    c = sp.Matrix([-h * (2 * j1.qd * j2.qd + j2.qd**2), h * j1.qd**2])
    gv = sp.Matrix([(m1 / 2 + m2) * g * L1 * sp.cos(j1.q) + m2 * g * L2 / 2 * sp.cos(j1.q + j2.q),
                    m2 * g * L2 / 2 * sp.cos(j1.q + j2.q)])
    d = _derive(r)
    assert sp.simplify(d.mass_matrix - M) == sp.zeros(2, 2)
    assert sp.simplify(sp.expand_trig(d.velocity_terms - c)) == sp.zeros(2, 1)
    assert sp.simplify(sp.expand_trig(d.gravity_terms - gv)) == sp.zeros(2, 1)
    assert d.external_forces == sp.zeros(2, 1)


def test_planar_2r_lagranges_method():
    from tests.support import mechanics as ref

    r = ex.planar_2r()
    d = _derive(r)
    model = ref.build(r)
    ml, fl = ref.lagrange(model)
    ml, fl = ref.to_plain(ml, model, r), ref.to_plain(fl, model, r)
    assert sp.simplify(sp.expand_trig(ml - d.mass_matrix)) == sp.zeros(2, 2)
    rhs = d.generalized_forces - d.velocity_terms - d.gravity_terms
    assert sp.simplify(sp.expand_trig(fl - rhs)) == sp.zeros(2, 1)


# ----------------------------------------------------------------- Kane, several robots
@pytest.mark.parametrize("robot", [
    pytest.param(lambda: ex.scara(loads=True), id="scara-payload-loads"),
    pytest.param(ex.rp_vertical, id="rp-vertical"),
    pytest.param(ex.anthropomorphic_3r, id="anthropomorphic-3r"),
])
def test_against_kanes_method(robot):
    from tests.support import mechanics as ref

    r = robot()
    d = _derive(r)
    model = ref.build(r)
    mk, fk = ref.kane(model)
    mk, fk = ref.to_plain(mk, model, r), ref.to_plain(fk, model, r)
    rhs = d.generalized_forces - d.velocity_terms - d.gravity_terms
    for seed in range(3):
        pt = _random_point(d, seed, r.values)
        assert np.allclose(np.array((mk - d.mass_matrix).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)
        assert np.allclose(np.array((fk - rhs).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)


def test_scara_loads_course_formula_and_values():
    """Force (F_x, 0, 0) in frame 0 at the middle of link 2 and a torque C_z on link 2."""
    r = ex.scara(loads=True)
    d = _derive(r)
    L1, L2 = sp.symbols("L1 L2", positive=True)
    Fx, Cz = sp.symbols("F_x C_z")
    j1, j2, j3 = r.joints
    # J^T F of the point (L1 c1 + L2/2 c12, L1 s1 + L2/2 s12) plus the torque on both joints
    x = L1 * sp.cos(j1.q) + L2 / 2 * sp.cos(j1.q + j2.q)
    expected = sp.Matrix([Fx * x.diff(j1.q) + Cz, Fx * x.diff(j2.q) + Cz, 0])
    assert sp.simplify(d.external_forces - expected) == sp.zeros(3, 1)
    assert sp.simplify(d.engine.course_generalized_forces() - d.generalized_forces) == \
        sp.zeros(3, 1)


# ----------------------------------------------------------------- algebra paths agree
@pytest.mark.parametrize("robot", [ex.one_link, ex.planar_2r,
                                   pytest.param(lambda: ex.scara(loads=True), marks=pytest.mark.slow)])
def test_sympy_fallback_algebra_agrees(robot):
    r = robot()
    fast = DynamicsEngine(**r.engine_inputs())
    slow = DynamicsEngine(**r.engine_inputs(), algebra="sympy")
    assert type(slow.alg).__name__ == "SympyAlgebra"
    for a, b in [(fast.mass_matrix(), slow.mass_matrix()),
                 (fast.velocity_terms(), slow.velocity_terms()),
                 (fast.gravity_terms(), slow.gravity_terms()),
                 (fast.external_forces(), slow.external_forces())]:
        assert sp.simplify(sp.expand_trig(a - b)) == sp.zeros(*a.shape)


def test_non_polynomial_joint_use_falls_back():
    """A joint inside sin(q/2) cannot go to the cos/sin ring: the sympy path answers."""
    from robosolve.core.transforms import rot_z, trans_x
    from robosolve.dynamics.api import BodySpec, FrameSpec, JointSpec
    from robosolve.core.matrices import pseudo_inertia_point

    q, qd, qdd, C, m, g = sp.symbols("q q_dot q_ddot C m g")
    frames = [FrameSpec("1", "0", rot_z(q) * trans_x(1 + sp.sin(q / 2)))]
    eng = DynamicsEngine(frames, [JointSpec("q", q, qd, qdd, C)],
                         [BodySpec("b", "1", pseudo_inertia_point(m, [0, 0, 0]))], [0, -g, 0],
                         simplify=False)
    assert type(eng.alg).__name__ == "SympyAlgebra"
    r = 1 + sp.sin(q / 2)
    expected_m = m * (r**2 + r.diff(q) ** 2)
    diff = (eng.mass_matrix()[0, 0] - expected_m).subs(m, 2)
    for v in (0.3, 1.1, -2.0):
        assert abs(float(diff.subs(q, v))) < 1e-12


# ----------------------------------------------------------------- properties
def test_mass_matrix_symmetric_positive_definite():
    for robot in (ex.anthropomorphic_3r(), ex.scara()):
        d = _derive(robot)
        nd = lambdify_dynamics(d, robot.values)
        rng = np.random.default_rng(5)
        for _ in range(20):
            m = nd.mass(rng.uniform(-3, 3, len(d.q)))
            assert np.allclose(m, m.T, atol=1e-14)
            assert np.linalg.eigvalsh(m).min() > 0


def test_energy_conserved_free_motion():
    from scipy.integrate import solve_ivp

    r = ex.anthropomorphic_3r()
    d = _derive(r)
    nd = lambdify_dynamics(d, r.values)
    n = len(d.q)
    rhs = lambda t, x: np.concatenate([x[n:], nd.forward(x[:n], x[n:], np.zeros(n))])  # noqa
    energy_expr = sp.Add(*d.kinetic_energy.values(), *d.potential_energy.values())
    energy = sp.lambdify([d.q, d.qd], energy_expr.subs(r.values))
    x0 = np.array([0.3, 0.8, -0.5, 1.0, -0.5, 2.0])
    sol = solve_ivp(rhs, (0, 2.0), x0, rtol=1e-10, atol=1e-12)
    e = [energy(x[:n], x[n:]) for x in sol.y.T]
    assert sol.success
    assert np.ptp(e) < 1e-7 * max(1.0, abs(e[0]))


# ----------------------------------------------------------------- PUMA 560
def _rtb_puma():
    rtb = pytest.importorskip("roboticstoolbox")
    p = rtb.models.DH.Puma560()
    for link in p.links:
        link.Jm = 0.0
    return p.nofriction(coulomb=True, viscous=True)


def _pin_puma():
    pin = pytest.importorskip("pinocchio")
    model = pin.Model()
    parent = 0
    placement = pin.SE3.Identity()
    for i, ((d, a, alpha), (m, r, idiag)) in enumerate(zip(ex.PUMA560_DH, ex.PUMA560_DYN)):
        jid = model.addJoint(parent, pin.JointModelRZ(), placement, f"j{i + 1}")
        # frame i = joint frame . Tz(d) Tx(a) Rx(alpha)
        fixed = pin.SE3(np.eye(3), np.array([float(a), 0.0, float(d)])) * pin.SE3(
            pin.utils.rotate("x", float(alpha)), np.zeros(3))
        inertia = pin.Inertia(float(m), np.array(r, dtype=float), np.diag(idiag).astype(float))
        model.appendBodyToJoint(jid, fixed.act(inertia), pin.SE3.Identity())
        parent, placement = jid, fixed
    return pin, model, model.createData()


@pytest.fixture(scope="module")
def puma():
    r = ex.puma560()
    d = _derive(r)
    return r, d, lambdify_dynamics(d, r.values)


def test_puma560_against_robotics_toolbox(puma):
    r, d, nd = puma
    p = _rtb_puma()
    rng = np.random.default_rng(42)
    for _ in range(10):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 6))
        m_ref = p.inertia(q)
        assert np.allclose(nd.mass(q), m_ref, rtol=1e-9, atol=1e-9 * np.abs(m_ref).max())
        tau_ref = p.rne(q, qd, qdd)
        tau = nd.actuators(q, qd, qdd)
        assert np.allclose(tau, tau_ref, rtol=1e-9, atol=1e-9 * np.abs(tau_ref).max())


def test_puma560_against_pinocchio(puma):
    r, d, nd = puma
    pin, model, data = _pin_puma()
    rng = np.random.default_rng(7)
    for _ in range(10):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 6))
        m_ref = pin.crba(model, data, q)
        m_ref = np.triu(m_ref) + np.triu(m_ref, 1).T
        assert np.allclose(nd.mass(q), m_ref, rtol=1e-9, atol=1e-9 * np.abs(m_ref).max())
        tau_ref = pin.rnea(model, data, q, qd, qdd)
        assert np.allclose(nd.actuators(q, qd, qdd), tau_ref, rtol=1e-9,
                           atol=1e-9 * np.abs(tau_ref).max())
        # gravity and velocity terms separately
        g_ref = pin.rnea(model, data, q, np.zeros(6), np.zeros(6))
        assert np.allclose(nd.gravity(q), g_ref, rtol=1e-9, atol=1e-9 * np.abs(g_ref).max())


def test_puma560_numeric_only_path(puma):
    r, d, nd = puma
    num = numeric_dynamics(**r.engine_inputs(), subs=r.values)
    rng = np.random.default_rng(3)
    for _ in range(5):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 6))
        assert np.allclose(num.mass(q), nd.mass(q), atol=1e-12)
        assert np.allclose(num.velocity_terms(q, qd), nd.velocity_terms(q, qd), atol=1e-12)
        assert np.allclose(num.actuators(q, qd, qdd), nd.actuators(q, qd, qdd), atol=1e-11)


@pytest.mark.slow
def test_puma560_symbolic_parameters_against_numeric():
    r = ex.puma560(symbolic_parameters=True)
    d = _derive(r)
    nd = lambdify_dynamics(d, r.values)
    p = _rtb_puma()
    rng = np.random.default_rng(11)
    q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 6))
    tau_ref = p.rne(q, qd, qdd)
    assert np.allclose(nd.actuators(q, qd, qdd), tau_ref, rtol=1e-9,
                       atol=1e-9 * np.abs(tau_ref).max())


def test_tree_two_branches_against_kane():
    """A base joint carrying two independent arms (a tree): each branch's joint moves only
    its own bodies."""
    from tests.support import mechanics as ref
    from tests.support.robots import RobotDef, _joint, _rod, _point

    L1, L2, L3, m1, m2, m3, g, F = sp.symbols("L1 L2 L3 m1 m2 m3 g F", positive=True)
    j1, j2, j3 = (_joint(f"q{i}", index=i) for i in (1, 2, 3))
    from robosolve.dynamics.api import LoadSpec
    r = RobotDef(
        "tree",
        [("1", "0", [("Rz", j1.q), ("Tx", L1)]),
         ("2", "1", [("Ry", j2.q), ("Tx", L2)]),
         ("3", "1", [("Rz", sp.pi / 2), ("Rx", j3.q), ("Ty", L3)])],
        [j1, j2, j3],
        [_rod("base", "1", m1, [-L1, 0, 0], [0, 0, 0]), _rod("left", "2", m2, [-L2, 0, 0], [0, 0, 0]),
         _point("right", "3", m3, [0, 0, 0])],
        [0, 0, -g],
        [LoadSpec("F", "3", force=[0, 0, F], in_frame="0")],
        {L1: 1, L2: sp.Rational(1, 2), L3: sp.Rational(3, 4), m1: 3, m2: 2, m3: 1,
         g: sp.Rational(981, 100), F: 5},
    )
    d = _derive(r)
    assert d.mass_matrix[1, 2] == 0  # the branches do not couple
    model = ref.build(r)
    mk, fk = ref.kane(model)
    mk, fk = ref.to_plain(mk, model, r), ref.to_plain(fk, model, r)
    rhs = d.generalized_forces - d.velocity_terms - d.gravity_terms
    assert d.engine.course_forces_agree()
    for seed in range(3):
        pt = _random_point(d, seed, r.values)
        assert np.allclose(np.array((mk - d.mass_matrix).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)
        assert np.allclose(np.array((fk - rhs).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)


def test_offsets_and_symbolic_angles_against_kane():
    """Joint angles with offsets and a symbolic fixed twist stay in the cos/sin ring."""
    from tests.support import mechanics as ref
    from tests.support.robots import RobotDef, _joint, _rod, _point

    L1, L2, m1, m2, g, alpha = sp.symbols("L1 L2 m1 m2 g alpha", positive=True)
    j1, j2 = _joint("q1", index=1), _joint("q2", index=2)
    r = RobotDef(
        "offsets",
        [("1", "0", [("Rz", j1.q + sp.pi / 3), ("Tx", L1), ("Rx", alpha)]),
         ("2", "1", [("Rz", j2.q - alpha), ("Tx", L2)])],
        [j1, j2],
        [_rod("a", "1", m1, [-L1, 0, 0], [0, 0, 0]), _point("b", "2", m2, [0, 0, 0])],
        [0, 0, -g], [],
        {L1: 1, L2: sp.Rational(1, 2), m1: 2, m2: 1, g: sp.Rational(981, 100), alpha: 0.4},
    )
    eng = DynamicsEngine(**r.engine_inputs())
    assert type(eng.alg).__name__ == "TrigAlgebra"
    d = eng.dynamics()
    model = ref.build(r)
    mk, fk = ref.kane(model)
    mk, fk = ref.to_plain(mk, model, r), ref.to_plain(fk, model, r)
    rhs = d.generalized_forces - d.velocity_terms - d.gravity_terms
    for seed in range(3):
        pt = _random_point(d, seed, r.values)
        assert np.allclose(np.array((mk - d.mass_matrix).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)
        assert np.allclose(np.array((fk - rhs).xreplace(pt).evalf(), dtype=float), 0,
                           atol=1e-12)


# ----------------------------------------------------------------- the one chain computation
@pytest.mark.parametrize("algebra", ["trig", "sympy"])
def test_engine_chain_is_the_one_chain_computation(algebra):
    """The engine's relative poses and body-frame L come from core/chain/forward.py (the engine
    its own description), and equal an independent route: the plain sympy product of the local
    poses and ᵇLᵢ = M₀ⱼ⁻¹ ∂M₀ⱼ/∂qᵢ differentiated as a whole, at random numbers."""
    from robosolve.core.chain.forward import ChainData

    r = ex.planar_2r()
    eng = DynamicsEngine(**r.engine_inputs(), algebra=algebra)
    assert isinstance(eng.chain_data, ChainData) and eng.chain_data.description is eng
    assert eng.parent(eng.order[0]) == "0" and eng.parent("0") is None
    rng = np.random.default_rng(21)
    subs = {**{k: sp.Float(v) for k, v in r.values.items()}, **dict(zip(eng.q, rng.uniform(-2, 2, eng.n)))}

    def num(m):
        return np.array(sp.Matrix(m).xreplace(subs).evalf(), dtype=float)

    for frame in eng.order:
        m0 = sp.eye(4)
        for f in eng.path(frame):
            m0 = m0 * eng.local(f)
        np.testing.assert_allclose(num(eng.M0(frame)), num(m0), atol=1e-12)
        m0_inv = num(m0.inv())
        for i in eng.moving(frame):
            np.testing.assert_allclose(num(eng.Lb(i, frame)), m0_inv @ num(m0.diff(eng.q[i])), atol=1e-12)
            np.testing.assert_allclose(num(eng.L0(i, frame)), num(m0.diff(eng.q[i])) @ m0_inv, atol=1e-12)
