"""End-to-end jacobian / statics / ellipsoids answers on the exam problems, against
independent references (ERRATA §B, Robotics Toolbox, SVD, finite differences)."""

import functools
import json
import math

import numpy as np
import pytest
import sympy as sp

from robosolve.load.loader import load_problem, load_problem_text
from robosolve.run.pipeline import solve_problem
from robosolve.render.results_json import answer_record

S5 = math.sqrt(5)


@functools.lru_cache(maxsize=None)
def _answers(name):
    report = solve_problem(load_problem(f"problems/{name}.yaml"))
    return {a.id: json.loads(json.dumps(answer_record(a, []), allow_nan=False))
            for a in report.answers}


def test_planar_2r_jacobian_and_singularities():
    a = _answers("planar-2r-rods")["jacobian"]
    assert "error" not in a
    assert sp.simplify(sp.sympify(a["symbolic"]["det"]) - sp.sympify("L1*L2*sin(theta2)")) == 0
    assert a["symbolic"]["singularities"] == [{"theta2": "0"}, {"theta2": "pi"}]
    np.testing.assert_allclose(a["numeric"]["J"], [[-0.5, -0.5], [0.5, 0.0]], atol=1e-12)
    assert a["numeric"]["det"] == pytest.approx(0.25)
    assert set(a["numeric"]["com_jacobians"]) == {"link1", "link2"}
    np.testing.assert_allclose(a["numeric"]["com_jacobians"]["link2"],
                               [[-0.25, -0.25], [0.5, 0.0], [0.0, 0.0]], atol=1e-12)


def test_planar_2r_ellipsoids_errata_numbers():
    a = _answers("planar-2r-rods")["ellipsoids"]
    n = a["numeric"]
    np.testing.assert_allclose(n["force"]["lengths"], [1 + S5, S5 - 1])
    np.testing.assert_allclose(n["velocity"]["lengths"], [(S5 + 1) / 4, (S5 - 1) / 4])
    np.testing.assert_allclose(n["compliance"]["lengths"],
                               [0.5 + math.sqrt(2) / 4, 0.5 - math.sqrt(2) / 4])
    assert n["condition_number"] == pytest.approx((7 + 3 * S5) / 2)
    assert sp.simplify(sp.sympify(a["symbolic"]["condition_number"])
                       - (7 + 3 * sp.sqrt(5)) / 2) == 0
    # q̇ for V = (0.1, 0.2): J q̇ = V
    qd = [n["q_dot"]["theta1"], n["q_dot"]["theta2"]]
    np.testing.assert_allclose(np.array([[-0.5, -0.5], [0.5, 0.0]]) @ qd, [0.1, 0.2])
    assert a["figures"] == [] or len(a["figures"]) == 1


def test_planar_2r_singular_ellipsoids_no_nan():
    a = _answers("planar-2r-rods")["ellipsoids-singular"]
    n = a["numeric"]
    assert n["force"]["lengths"][0] is None and n["force"]["semi_axes"][0] is None
    assert n["velocity"]["lengths"][1] == 0.0
    assert n["condition_number"] is None
    assert any("Singular" in x for x in a["notes"])


def test_planar_2r_statics_by_hand_and_rtb_gravload():
    ans = _answers("planar-2r-rods")
    # 10 N downwards at E = (1/2, 1/2) with q = (0, π/2): joint 1 must give +5 N·m
    # (lever arm 1/2), joint 2 (at (1/2, 0), E straight above it) nothing.
    f = ans["statics-load"]["numeric"]["Fq"]
    assert f["theta1"] == pytest.approx(5.0) and f["theta2"] == pytest.approx(0.0, abs=1e-12)
    rtb = pytest.importorskip("roboticstoolbox")
    robot = rtb.DHRobot([rtb.RevoluteDH(a=0.5, m=4, r=[-0.25, 0, 0]),
                         rtb.RevoluteDH(a=0.5, m=3, r=[-0.25, 0, 0])], gravity=[0, -9.81, 0])
    w = ans["statics-weight"]["numeric"]["Fq"]
    np.testing.assert_allclose([w["theta1"], w["theta2"]],
                               robot.gravload([math.pi / 6, math.pi / 3]), atol=1e-9)


def test_polar_jacobian_vs_rtb_and_statics():
    ans = _answers("polar-rrp")
    a = ans["jacobian"]
    assert a["symbolic"]["singularities"] == [{"theta2": "-pi/2"}, {"theta2": "pi/2"}, {"d": "0"}]
    assert sp.simplify(sp.sympify(a["symbolic"]["det"]) - sp.sympify("d**2*cos(theta2)")) == 0
    q = [math.pi / 4, math.pi / 6, 0.5]
    rtb = pytest.importorskip("roboticstoolbox")
    robot = rtb.Robot(rtb.ET.tz(1.0) * rtb.ET.Rz() * rtb.ET.Ry(flip=True) * rtb.ET.tx())
    J0 = robot.jacob0(q)
    np.testing.assert_allclose(a["numeric"]["J"], J0[:3], atol=1e-12)
    np.testing.assert_allclose(ans["jacobian-geometric"]["numeric"]["J"], J0, atol=1e-12)
    # a 50 N downward load: Fq = -J^T F
    f = ans["statics-load"]["numeric"]["Fq"]
    np.testing.assert_allclose([f["theta1"], f["theta2"], f["d"]],
                               -J0[:3].T @ np.array([0, 0, -50.0]), atol=1e-9)
    # weight: virtual work with finite differences of U = g·Σ m z_G
    w = ans["statics-weight"]["numeric"]["Fq"]

    def U(q):
        t1, t2, d = q
        zs = [1 + (d - 0.25) * math.sin(t2), 1 + d * math.sin(t2)]
        return 9.81 * (5 * zs[0] + 2 * zs[1])
    eps = 1e-6
    du = [(U(np.add(q, e * eps)) - U(np.subtract(q, e * eps))) / (2 * eps) for e in np.eye(3)]
    np.testing.assert_allclose([w["theta1"], w["theta2"], w["d"]], du, atol=1e-6)


def test_polar_ellipsoids_3d_against_svd():
    a = _answers("polar-rrp")["ellipsoids"]
    n = a["numeric"]
    J = np.array(_answers("polar-rrp")["jacobian"]["numeric"]["J"])
    sig = np.sort(np.linalg.svd(J, compute_uv=False))
    np.testing.assert_allclose(n["force"]["lengths"], 10 / sig)
    np.testing.assert_allclose(n["velocity"]["lengths"], sig[::-1])
    Ks = J @ np.diag([1e-3, 1e-3, 2e-4]) @ J.T
    np.testing.assert_allclose(n["compliance"]["lengths"], np.sort(np.linalg.eigvalsh(Ks))[::-1])
    qd = [n["q_dot"][k] for k in ("theta1", "theta2", "d")]
    np.testing.assert_allclose(J @ qd, [0, 0, 0.1], atol=1e-12)
    assert [s for s in a["symbolic"]["eigenvalues"]] == ["3/16", "1/4", "1"]


def test_redundant_3r():
    ans = _answers("planar-3r-redundant")
    a = ans["jacobian"]
    assert "manipulability" in a["symbolic"] and "det" not in a["symbolic"]
    assert a["symbolic"]["singularities"] == [{"theta2": x, "theta3": y}
                                              for x in ("0", "pi") for y in ("0", "pi")]
    J = np.array(a["numeric"]["J"])
    assert a["numeric"]["manipulability"] == pytest.approx(
        float(np.prod(np.linalg.svd(J, compute_uv=False))))
    e = ans["ellipsoids"]["numeric"]
    qd = np.array([e["q_dot"][k] for k in ("theta1", "theta2", "theta3")])
    np.testing.assert_allclose(qd, np.linalg.pinv(J) @ [0.2, -0.1], atol=1e-12)
    assert ans["jacobian-orientation"]["symbolic"]["singularities"] == [{"theta2": "0"},
                                                                       {"theta2": "pi"}]


_TEXT = """
robosolve: 1
name: t
parameters: {L1: 1, L2: 1}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: jacobian, coordinates: [E.x, E.y], at: {theta1: 0.3, theta2: 0.4}}
"""


def test_time_limit_falls_back_to_numbers():
    from robosolve.solvers.base import Budgets

    # the search's own safety net too (its outcome is otherwise decided by counts)
    report = solve_problem(load_problem_text(_TEXT), Budgets(symbolic_seconds=1e-6, rank_search_seconds=1e-6))
    a = report.answers[0]
    assert a.error is None
    assert any("not derived symbolically" in str(n) for n in a.notes)
    assert "det" in a.numeric and "singularities" not in a.symbolic


_PUMA = """
robosolve: 1
name: r6
parameters: {a2: 0.4318, a3: 0.0203, d3: 0.15, d4: 0.4318}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: q3, type: revolute}
  - {name: q4, type: revolute}
  - {name: q5, type: revolute}
  - {name: q6, type: revolute}
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0, a: 0, alpha: pi/2}
    - {theta: q2, d: 0, a: a2, alpha: 0}
    - {theta: q3, d: d3, a: a3, alpha: -pi/2}
    - {theta: q4, d: d4, a: 0, alpha: pi/2}
    - {theta: q5, d: 0, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0, a: 0, alpha: 0}
questions:
  - {type: jacobian, geometric: true, at: {q1: 0.2, q2: 0.5, q3: 0.3, q4: 0.1, q5: 0.7, q6: -0.4}}
"""


@pytest.mark.slow
def test_six_joints_numeric_fallback_vs_rtb():
    """Beyond 4 joints the symbolic search may stop at its (shorter) budget; the numeric
    geometric Jacobian is still given and matches Robotics Toolbox."""
    rtb = pytest.importorskip("roboticstoolbox")
    a = solve_problem(load_problem_text(_PUMA)).answers[0]
    assert a.error is None
    robot = rtb.DHRobot([rtb.RevoluteDH(alpha=math.pi / 2), rtb.RevoluteDH(a=0.4318),
                         rtb.RevoluteDH(d=0.15, a=0.0203, alpha=-math.pi / 2),
                         rtb.RevoluteDH(d=0.4318, alpha=math.pi / 2),
                         rtb.RevoluteDH(alpha=-math.pi / 2), rtb.RevoluteDH()])
    q = [0.2, 0.5, 0.3, 0.1, 0.7, -0.4]
    np.testing.assert_allclose(a.numeric["J"], robot.jacob0(q), atol=1e-12)
    assert a.numeric["det"] == pytest.approx(np.linalg.det(robot.jacob0(q)), abs=1e-12)


def test_geometric_self_check_can_fail():
    from robosolve.model.chain import RobotModel
    from robosolve.run.pipeline import solve_context
    from robosolve.solvers.base import Answer
    from robosolve.solvers.jacobian import _check_geometric

    prob = load_problem("problems/polar-rrp.yaml")
    ctx = solve_context(prob, RobotModel(prob))
    q = prob.questions[1]
    good = solve_problem(prob).answers[1].numeric["J"]
    subs = ctx.substitutions(q.at)
    ans = Answer(q.type, q.id)
    _check_geometric(ans, ctx, q, good, subs)
    assert ans.notes == []
    bad = [row[:] for row in good]
    bad[0][1] += 0.01
    _check_geometric(ans, ctx, q, bad, subs)
    assert any("internal check failed" in n for n in ans.notes)


STATICS_WRENCH = """
robosolve: 1
name: wrench
parameters: {L1: 0.5, L2: 0.3}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames: {"1": {pose: "Rz(q1) Tx(L1)"}, "2": {pose: "Rz(q2) Tx(L2)"}}
questions:
  - {type: statics, id: plain, force: [1, 0, 2], torque: [0, 1, 3], at: {q1: 0.4, q2: 0.9}}
  - {type: statics, id: written, force: [1, 0, 2], torque: [0, 1, 3], coordinates: [E.x, E.y, E.z],
     at: {q1: 0.4, q2: 0.9}}
"""


def test_a_torque_with_the_default_coordinates_written_out_is_the_same_wrench():
    """`coordinates: [E.x, E.y, E.z]` is the default written out: a torque beside it is accepted
    (it was 'a torque needs the default coordinates'). Reference: Fq = −(J_Pᵀ·F + J_ωᵀ·τ) of the
    planar 2R by hand (J_ω rows: both joints about z)."""
    report = solve_problem(load_problem_text(STATICS_WRENCH))
    fq = [json.loads(json.dumps(answer_record(a, [])))["numeric"]["Fq"] for a in report.answers]
    q1, q2, L1, L2 = 0.4, 0.9, 0.5, 0.3
    JP = np.array([[-L1 * math.sin(q1) - L2 * math.sin(q1 + q2), -L2 * math.sin(q1 + q2)],
                   [L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L2 * math.cos(q1 + q2)], [0, 0]])
    Jw = np.array([[0, 0], [0, 0], [1, 1]])
    want = -(JP.T @ [1, 0, 2] + Jw.T @ [0, 1, 3])
    for got in fq:
        assert list(got) == ["q1", "q2"]
        assert np.allclose([got["q1"], got["q2"]], want, atol=1e-9), (got, want)
