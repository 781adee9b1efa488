"""The `equations_of_motion` question end to end (problem file -> answer), checked against
closed forms and sympy.physics.mechanics (Kane) built independently of the loader."""

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.run.pipeline import solve_file

from conftest import PROBLEMS


def _answer(name, qid="equations_of_motion"):
    report = solve_file(PROBLEMS / f"{name}.yaml")
    ans = {a.id: a for a in report.answers}[qid]
    assert ans.error is None, ans.error
    return ans


def test_one_link_eom_errata_c():
    ans = _answer("one-link-eom")
    L, m1, m2, g, F, C, th, thd, thdd = sp.symbols("L m1 m2 g F C theta theta_dot theta_ddot")
    lhs, rhs = ans.symbolic["equations"][0].split(" = ")
    lhs, rhs = sp.sympify(lhs), sp.sympify(rhs)
    expected = (m1 / 3 + m2) * L**2 * thdd + (m1 / 2 + m2) * g * L * sp.cos(th)
    assert sp.simplify(lhs - expected) == 0
    assert sp.simplify(rhs - (C - sp.Rational(2, 3) * F * L)) == 0
    # holding torque at theta = pi/6, at rest: C = (m1/2 + m2) g L cos(theta) + 2/3 F L
    c = (2 / 2 + 1) * 9.81 * 1 * math.cos(math.pi / 6) + 2 / 3 * 3 * 1
    assert ans.numeric["actuators"]["C"] == pytest.approx(c, rel=1e-12)
    assert set(ans.symbolic["kinetic_energy"]) == {"link1", "payload", "total"}
    assert ans.numeric["potential_energy"]["total"] == pytest.approx(
        (2 / 2 + 1) * 9.81 * math.sin(math.pi / 6), rel=1e-12)


def test_rp_vertical_holding_actions_closed_form():
    ans = _answer("rp-vertical-arm")
    m1, m2, L1, d2, g, th, d = 4, 2, 1, 0.5, 9.81, math.pi / 6, 0.8
    torque = g * math.cos(th) * (m1 * L1 / 2 + m2 * (d - d2 / 2))
    force = m2 * g * math.sin(th)
    assert ans.numeric["actuators"]["C1"] == pytest.approx(torque, rel=1e-12)
    assert ans.numeric["actuators"]["F2"] == pytest.approx(force, rel=1e-12)
    m = np.array(ans.numeric["mass_matrix"])
    # I about the joint: rod m1 L1^2/3 + rod m2 from d - d2 to d
    i_theta = m1 * L1**2 / 3 + m2 * (d**3 - (d - d2) ** 3) / (3 * d2)
    assert m == pytest.approx(np.array([[i_theta, 0], [0, m1 * 0 + m2]]), rel=1e-12)


def test_scara_payload_dynamics_against_kane():
    """The problem file is the same robot as examples.scara(loads=True): compare the
    actuator values with Kane's method at the question's state."""
    from tests.support import robots as ex
    from tests.support import mechanics as ref

    ans = _answer("scara-payload-dynamics")
    r = ex.scara(loads=True)
    model = ref.build(r)
    mk, fk = ref.kane(model)
    mk, fk = ref.to_plain(mk, model, r), ref.to_plain(fk, model, r)
    j1, j2, j3 = r.joints
    state = {j1.q: sp.pi / 6, j2.q: sp.pi / 3, j3.q: sp.Rational(1, 10),
             j1.qd: 1, j2.qd: 2, j3.qd: sp.Rational(1, 2),
             j1.qdd: 1, j2.qdd: -2, j3.qdd: sp.Rational(1, 2), **r.values}
    acts = [j.actuator for j in r.joints]
    # Kane: M qdd = forcing(actuators); solve for the actuators
    eqs = (mk * sp.Matrix([j.qdd for j in r.joints]) - fk).xreplace(state)
    sol = sp.solve(list(eqs), acts, dict=True)[0]
    for a in acts:
        assert ans.numeric["actuators"][a.name] == pytest.approx(float(sol[a]), rel=1e-10)
    assert np.array(ans.numeric["mass_matrix"]) == pytest.approx(
        np.array(mk.xreplace(state).evalf(), dtype=float), rel=1e-12)
    # generalized forces: actuator + J^T F + torque, per joint (mapping joint -> expr)
    assert list(ans.symbolic["generalized_forces"]) == ["theta1", "theta2", "l"]


def test_null_parameter_omits_actuators_with_note(write_problem):
    path = write_problem("""
        robosolve: 1
        name: pendulum
        parameters: {L: 1, m: 2, g: 9.81, F: ~}
        joints: [{name: q, type: revolute}]
        frames: {"1": {parent: "0", pose: "Rx(q) Ty(L)"}}
        bodies: [{name: bob, frame: "1", mass: m, point: [0, 0, 0]}]
        forces: [{name: F, frame: "1", force: [0, 0, F]}]
        questions: [{type: equations_of_motion, at: {q: 0}}]
    """)
    report = solve_file(path)
    ans = report.answers[0]
    assert ans.error is None
    assert "actuators" not in ans.numeric
    assert any("F" in n and "actuators" in n for n in ans.notes)
    assert ans.numeric["gravity_terms"] == pytest.approx([2 * 9.81 * 1])
    assert any("taken as 0" in n for n in ans.notes)


def test_numeric_only_fallback():
    """When the symbolic derivation is cut short (a budget no derivation meets), M, c, g
    and the actuators come from the numeric-only path, with a note."""
    from robosolve.load.loader import load_problem
    from robosolve.run.pipeline import solve_problem
    from robosolve.solvers.base import Budgets

    report = solve_problem(load_problem(PROBLEMS / "rp-vertical-arm.yaml"),
                           Budgets(dynamics_seconds=1e-6))
    ans = report.answers[0]
    assert ans.error is None
    assert any("numerically" in n for n in ans.notes)
    m1, m2, L1, d2, g, th, d = 4, 2, 1, 0.5, 9.81, math.pi / 6, 0.8
    assert ans.numeric["actuators"]["C1"] == pytest.approx(
        g * math.cos(th) * (m1 * L1 / 2 + m2 * (d - d2 / 2)), rel=1e-12)


@pytest.mark.slow
def test_puma560_problem_against_robotics_toolbox():
    rtb = pytest.importorskip("roboticstoolbox")
    ans = _answer("puma560-dynamics")
    p = rtb.models.DH.Puma560()
    for link in p.links:
        link.Jm = 0.0
    p = p.nofriction(coulomb=True, viscous=True)
    q = [0.1, 0.7, -0.4, 0.3, 0.9, -0.2]
    qd = [0.5, -0.3, 0.8, 0.1, -0.6, 0.4]
    qdd = [1, -0.5, 0.2, 0.7, -1, 0.3]
    tau = np.array([ans.numeric["actuators"][f"C{i}"] for i in range(1, 7)])
    ref = p.rne(q, qd, qdd)
    assert tau == pytest.approx(ref, rel=1e-9, abs=1e-9 * np.abs(ref).max())
    assert np.array(ans.numeric["mass_matrix"]) == pytest.approx(p.inertia(q), rel=1e-9,
                                                                 abs=1e-12)


def _frame0_pseudo_inertia(ans, body):
    step = next(s for s in ans.steps if s.title == "Pseudo-inertia of each body")
    head = f"{{}}^{{0}}J_{{\\mathrm{{{body}}}}}"
    return next(sp.Matrix(e) for name, e in step.equations if name.startswith(head))


def test_scara_payload_frame0_pseudo_inertia_compact_and_equal():
    """Issue 22: ⁰J entries were written with sin² as 1 - cos² (−L1² m c1² + … +
    m (L1² + L2²) for m (L1 s1 + L2 s12)²). The entry is now the short form, equal at
    random points to the old form and to m p pᵀ built by hand (p = the payload in frame 0)."""
    ans = _answer("scara-payload-dynamics")
    j0 = _frame0_pseudo_inertia(ans, "payload")
    syms = {s.name: s for s in j0.free_symbols}
    L1, L2, h, m = (syms.get(n, sp.Symbol(n)) for n in ("L1", "L2", "h", "m_p"))
    t1, t2, l = (syms.get(n, sp.Symbol(n)) for n in ("theta1", "theta2", "l"))
    entry = j0[1, 1]
    assert not entry.has(sp.cos(t1) ** 2), entry
    old = (-L1**2 * m * sp.cos(t1)**2 + L1 * L2 * m * sp.cos(t2)
           - L1 * L2 * m * sp.cos(2 * t1 + t2) - L2**2 * m * sp.cos(t1 + t2)**2
           + m * (L1**2 + L2**2))
    assert sp.count_ops(entry) < sp.count_ops(old), entry
    p = sp.Matrix([L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2),
                   L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2), h - l, 1])
    ref = m * p * p.T
    rng = np.random.default_rng(22)
    for _ in range(5):
        at = dict(zip((L1, L2, h, m, t1, t2, l), rng.uniform(-3, 3, 7)))
        assert float(entry.subs(at)) == pytest.approx(float(old.subs(at)), rel=1e-12, abs=1e-12)
        got = np.array(j0.subs(at), dtype=float)
        assert got == pytest.approx(np.array(ref.subs(at), dtype=float), rel=1e-12, abs=1e-12)
