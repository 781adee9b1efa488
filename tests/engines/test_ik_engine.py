"""IK engine: closed form vs numeric, counts, boundary, singular, limits, reasons, velocity.

References: the forward kinematics itself (every solution must reproduce the
target), the textbook closed forms written out by hand here, and finite
differences for velocity IK.  Robotics Toolbox comparisons: test_ik_rtb.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.ik import closed_form as cfm
from robosolve.ik.engine import IKJoint, solve_ik, velocity_ik
from robosolve.ik.numeric import lambdify_system, solve_all, wrap_angle
from robosolve.render.numbers import text  # reasons keep raw numbers; the renderer formats them

t1, t2, t3, l = sp.symbols("theta1 theta2 theta3 l")
L1, L2, L3, h, x, y, z, phi = sp.symbols("L1 L2 L3 h x y z phi")

P2R = [L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2), L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2)]
ANTHRO = [sp.cos(t1) * (L2 * sp.cos(t2) + L3 * sp.cos(t2 + t3)),
          sp.sin(t1) * (L2 * sp.cos(t2) + L3 * sp.cos(t2 + t3)),
          L1 + L2 * sp.sin(t2) + L3 * sp.sin(t2 + t3)]
P3R = [P2R[0] + L3 * sp.cos(t1 + t2 + t3), P2R[1] + L3 * sp.sin(t1 + t2 + t3), t1 + t2 + t3]


def fk(exprs, joints, q, values):
    subs = dict(values)
    subs.update({j.symbol: q[j.name] for j in joints})
    return [float(sp.sympify(e).evalf(subs=subs)) for e in exprs]


def check_all_verified(res, exprs, targets, joints, values, angular=None):
    for sol in res.all_solutions:
        got = fk(exprs, joints, sol, values)
        for k, (g, t) in enumerate(zip(got, targets)):
            d = g - t
            if angular and angular[k]:
                d = wrap_angle(d)
            assert abs(d) < 1e-9, (sol, got, targets)
        for j in joints:
            if j.revolute:
                assert -math.pi < sol[j.name] <= math.pi


def same_set(a, b, joints, tol=1e-7):
    if len(a) != len(b):
        return False
    for s in a:
        if not any(all(abs(wrap_angle(s[j.name] - o[j.name]) if j.revolute else s[j.name] - o[j.name]) < tol
                       for j in joints) for o in b):
            return False
    return True


J2 = [IKJoint(t1), IKJoint(t2)]
J3 = [IKJoint(t1), IKJoint(t2), IKJoint(t3)]


def test_2r_two_solutions_match_textbook_formula():
    vals = {L1: 0.6, L2: 0.5, x: 0.7, y: 0.4}
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert res.status == "ok" and len(res.solutions) == 2 and res.agree
    check_all_verified(res, P2R, [0.7, 0.4], J2, vals)
    # the textbook: cos θ2 = (x² + y² − L1² − L2²)/(2 L1 L2), θ1 = atan2(y, x) − atan2(L2 s2, L1 + L2 c2)
    c2 = (0.7**2 + 0.4**2 - 0.36 - 0.25) / (2 * 0.6 * 0.5)
    expect = []
    for s in (1, -1):
        q2 = s * math.acos(c2)
        q1 = math.atan2(0.4, 0.7) - math.atan2(0.5 * math.sin(q2), 0.6 + 0.5 * math.cos(q2))
        expect.append({"theta1": q1, "theta2": q2})
    assert same_set(res.solutions, expect, J2, 1e-12)
    # the derivation shows the cos θ2 step
    cos_stage = [st for st in res.closed_form.stages if st.rule == "cos"][0]
    assert sp.simplify(cos_stage.rhs - (x**2 + y**2 - L1**2 - L2**2) / (2 * L1 * L2)) == 0
    # sorted lexicographically
    assert res.solutions[0]["theta1"] < res.solutions[1]["theta1"]


def test_boundary_double_solution_and_just_outside():
    vals = {L1: 0.6, L2: 0.5, x: 1.1, y: 0.0}
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert len(res.solutions) == 1 and res.singular == [True]
    assert abs(res.solutions[0]["theta2"]) < 1e-12 and abs(res.solutions[0]["theta1"]) < 1e-12
    vals[x] = 1.1 + 1e-6
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert res.status == "unreachable" and res.solutions == []
    assert "L1 + L2" in text(res.reason) and "distance" in text(res.reason)


def test_unreachable_reason_distance():
    vals = {L1: 0.6, L2: 0.5, x: 1.31, y: 0.0}
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert res.status == "unreachable"
    assert "1.31 > L1 + L2 = 1.1" in text(res.reason)
    vals = {L1: 0.6, L2: 0.5, x: 0.05, y: 0.0}
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert res.status == "unreachable" and "too close" in text(res.reason)


def test_singular_configuration_continuum():
    # L1 = L2 and the target at the base: θ2 = π, θ1 arbitrary
    vals = {L1: 0.5, L2: 0.5, x: 0.0, y: 0.0}
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, target_symbols={x, y})
    assert res.status == "family"
    assert res.family["free"] == ["theta1"]
    assert abs(abs(res.family["fixed"]["theta2"]) - math.pi) < 1e-9


def test_limits_reject_and_select_nearest():
    vals = {L1: 0.6, L2: 0.5, x: 0.7, y: 0.4}
    joints = [IKJoint(t1, limits=(-1.0, 1.0)), IKJoint(t2, limits=(0.0, 2.0))]
    res = solve_ik(list(zip(P2R, [x, y])), joints, vals)
    assert len(res.solutions) == 1 and len(res.rejected) == 1
    assert res.solutions[0]["theta2"] > 0
    broken = res.rejected[0][1]
    assert any("theta2" in b and "lower limit" in b for b in map(text, broken))
    # every solution rejected: unreachable, with the limits as reason
    joints = [IKJoint(t1, limits=(-1.0, 1.0)), IKJoint(t2, limits=(0.0, 1.0))]
    res = solve_ik(list(zip(P2R, [x, y])), joints, vals)
    assert res.status == "unreachable" and "joint limit" in text(res.reason)
    # nearest
    res = solve_ik(list(zip(P2R, [x, y])), J2, vals, select={"theta1": 1.0, "theta2": -1.0})
    assert res.selected["theta2"] < 0


def test_anthropomorphic_four_solutions_closed_form_agrees():
    vals = {L1: 0.5, L2: 0.4, L3: 0.3, x: 0.3, y: 0.2, z: 0.6}
    res = solve_ik(list(zip(ANTHRO, [x, y, z])), J3, vals, target_symbols={x, y, z})
    assert len(res.solutions) == 4 and res.agree
    check_all_verified(res, ANTHRO, [0.3, 0.2, 0.6], J3, vals)
    rules = [st.rule for st in res.closed_form.stages]
    assert rules.count("tan") == 1 and rules.count("cos") == 1 and rules.count("atan2") == 1


def test_planar_3r_orientation_is_mod_2pi():
    vals = {L1: 0.5, L2: 0.4, L3: 0.1, x: 0.6, y: 0.4, phi: math.pi / 6}
    res = solve_ik(list(zip(P3R, [x, y, phi])), J3, vals, target_symbols={x, y})
    assert len(res.solutions) == 2 and res.agree
    assert res.angular == [False, False, True]
    check_all_verified(res, P3R, [0.6, 0.4, math.pi / 6], J3, vals, res.angular)


def test_scara_and_polar_closed_forms():
    scara = list(zip(P2R + [h - l], [x, y, z]))
    joints = [IKJoint(t1), IKJoint(t2), IKJoint(l, False, (0.0, 0.3))]
    vals = {L1: 0.5, L2: 0.4, h: 1.0, x: 0.6, y: 0.3, z: 0.9}
    res = solve_ik(scara, joints, vals)
    assert len(res.solutions) == 2 and res.agree
    assert all(abs(s["l"] - 0.1) < 1e-12 for s in res.solutions)
    polar = [(l * sp.cos(t1), x), (l * sp.sin(t1), y)]
    joints = [IKJoint(t1), IKJoint(l, False, None)]
    res = solve_ik(polar, joints, {x: 0.3, y: -0.4})
    assert len(res.solutions) == 2 and res.agree
    assert sorted(round(s["l"], 12) for s in res.solutions) == [-0.5, 0.5]
    joints = [IKJoint(t1), IKJoint(l, False, (0.0, 1.0))]
    res = solve_ik(polar, joints, {x: 0.3, y: -0.4})
    assert len(res.solutions) == 1 and abs(res.solutions[0]["theta1"] - math.atan2(-0.4, 0.3)) < 1e-12


def test_overdetermined_and_redundant_counts():
    vals = {L1: 0.6, L2: 0.5, x: 0.7, y: 0.4, phi: 0.5}
    res = solve_ik(list(zip(P2R + [t1 + t2], [x, y, phi])), J2, vals)
    assert res.status == "overdetermined" and "Choose 2 of the 3" in text(res.reason)
    assert len(res.subsets) == 3 and all(len(s["solutions"]) == 2 for s in res.subsets)
    # consistent extra equation: accepted
    vals = {L1: 0.6, L2: 0.5, x: 0.6 + 0.5 * math.cos(1.2), y: 0.5 * math.sin(1.2), phi: 1.2}
    res = solve_ik(list(zip(P2R + [t1 + t2], [x, y, phi])), J2, vals)
    assert res.status == "ok" and len(res.solutions) == 1
    # redundant: planar 3R with the position only -> θ3 free, family in closed form
    res = solve_ik(list(zip(P3R[:2], [x, y])), J3, {L1: 0.5, L2: 0.4, L3: 0.1, x: 0.6, y: 0.4})
    assert res.status == "redundant" and res.family is not None and res.family["free"] == ["theta3"]


def test_velocity_ik_inverse_and_singular():
    vals = {L1: 0.6, L2: 0.5}
    q = {"theta1": 0.3, "theta2": 1.1}
    v = velocity_ik(P2R, [0.1, -0.2], J2, q, vals)
    assert v.method == "inverse"
    # finite differences of the direct kinematics
    f = sp.lambdify([t1, t2], [e.subs(vals) for e in P2R])
    eps = 1e-7
    qd = np.array([v.q_dot["theta1"], v.q_dot["theta2"]])
    p0 = np.array(f(0.3, 1.1))
    p1 = np.array(f(0.3 + eps * qd[0], 1.1 + eps * qd[1]))
    assert np.allclose((p1 - p0) / eps, [0.1, -0.2], atol=1e-6)
    # stretched arm: singular, least squares with a note
    v = velocity_ik(P2R, [0.1, 0.0], J2, {"theta1": 0.0, "theta2": 0.0}, vals)
    assert v.method == "least_squares" and "singular" in text(v.note)


def test_numeric_deterministic_and_wrapped():
    vals = {L1: 0.5, L2: 0.4, L3: 0.3}
    exprs = [e.subs(vals) - t for e, t in zip(ANTHRO, [0.3, 0.2, 0.6])]
    sysm = lambdify_system(exprs, [t1, t2, t3], [True] * 3)
    a = solve_all(sysm, [(-math.pi, math.pi)] * 3)
    b = solve_all(sysm, [(-math.pi, math.pi)] * 3)
    assert [s.q for s in a.solutions] == [s.q for s in b.solutions]
    assert len(a.solutions) == 4


@pytest.mark.parametrize("seed", [0] + [pytest.param(k, marks=pytest.mark.slow) for k in range(1, 6)])
def test_closed_form_equals_numeric_random_targets(seed):
    rng = np.random.default_rng(seed)
    vals = {L1: 0.5, L2: 0.4, L3: 0.3}
    q = rng.uniform(-3, 3, 3)
    tgt = [float(e.subs(vals).subs({t1: q[0], t2: q[1], t3: q[2]})) for e in ANTHRO]
    v = dict(vals)
    v.update({x: tgt[0], y: tgt[1], z: tgt[2]})
    res = solve_ik(list(zip(ANTHRO, [x, y, z])), J3, v, target_symbols={x, y, z})
    assert res.agree and len(res.solutions) == 4
    assert any(all(abs(wrap_angle(s[n] - qq)) < 1e-8 for n, qq in zip(["theta1", "theta2", "theta3"], q))
               for s in res.solutions)


def test_closed_form_steps_are_data():
    cf = cfm.derive([e - t for e, t in zip(P2R, [x, y])], [t1, t2], [True, True])
    assert [st.joint for st in cf.stages] == [t2, t1]
    assert len(cf.branches()) == 2
    assert all(isinstance(s.title, str) and s.equations for s in cf.steps)


def test_cartesian_robot_linear():
    d1, d2, d3 = sp.symbols("d1 d2 d3")
    eqs = [(d2 + L1, x), (-d3, y), (h + d1, z)]
    joints = [IKJoint(d1, False, (0.0, 1.0)), IKJoint(d2, False, (0.0, 1.0)), IKJoint(d3, False, (0.0, 1.0))]
    res = solve_ik(eqs, joints, {L1: 0.2, h: 0.5, x: 0.7, y: -0.3, z: 0.9}, target_symbols={x, y, z})
    assert res.agree and len(res.solutions) == 1 and not res.rejected
    assert res.solutions[0] == {"d1": pytest.approx(0.4, abs=1e-12), "d2": pytest.approx(0.5, abs=1e-12),
                                "d3": pytest.approx(0.3, abs=1e-12)}
    assert all(st.rule in ("linear", "isolate") for st in res.closed_form.stages)


def test_whole_number_floats_of_a_chain_with_numbers_print_as_integers():
    """Poly / rem over floats give 1 as 1.0 (1.0*px in a closed form): the coefficients and
    the eliminated equations come back with whole numbers as integers, other floats kept."""
    import sympy as sp

    from robosolve.ik.closed_form import _reduce_pythagoras, trig_linear, whole_floats

    px, py, r13, q1 = sp.symbols("px py r13 q1")
    e = -px * sp.sin(q1) + py * sp.cos(q1) + sp.Float(0.0823) * r13 * sp.sin(q1) + sp.Float(0.10915)
    a, b, c = trig_linear(e, q1)
    assert sp.srepr(a) == sp.srepr(py) and b == -px + sp.Float(0.0823) * r13 and c == sp.Float(0.10915)
    C, S = sp.symbols("C S")
    red = _reduce_pythagoras(sp.Float(2.0) * S**2 + sp.Float(0.5) * C, [(C, S)])
    assert "2.0" not in sp.sstr(red) and "0.5" in sp.sstr(red)
    assert whole_floats(sp.Float(3.0) * px + sp.Float(1.5)) == 3 * px + sp.Float(1.5)


def test_a_pair_too_long_to_eliminate_is_decided_by_a_count():
    """A 3R arm whose DH twists are the decimal 1.5708 (cos 1.5708 = -3.7e-6 keeps every term)
    and whose first joint has an offset of 1/3 rad: each pair of its position equations has
    400-800 operations; eliminating a joint from it took seconds, and the derivation ended after
    20 s of CPU, as long as the safety net, so its note ("within 20 s" or "no pattern") followed
    the machine's load. Now a count stops it at once, with the reason; the numeric solutions
    reach the target (the forward kinematics evaluated here with numpy)."""
    import time

    from robosolve.core.transforms import dh_standard

    a1, a2, a3 = 0.5, 0.52, 0.2
    M = (dh_standard(t1 + sp.Rational(1, 3), 0, L1, sp.Float(1.5708))
         * dh_standard(t2, L2, L2, sp.Float(1.5708)) * dh_standard(t3, 0, L3, 0))
    exprs = [sp.expand(M[k, 3]) for k in range(3)]
    start = time.process_time()
    with pytest.raises(cfm.NoClosedForm, match="too long to eliminate a joint by hand"):
        cfm.derive([e - c for e, c in zip(exprs, (x, y, z))], [t1, t2, t3], [True] * 3)
    assert time.process_time() - start < 5

    def fk_numpy(q):
        out = np.eye(4)
        for theta, d, a, alpha in ((q[0] + 1 / 3, 0, a1, 1.5708), (q[1], a2, a2, 1.5708), (q[2], 0, a3, 0)):
            ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
            out = out @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                                  [0, sa, ca, d], [0, 0, 0, 1]])
        return out[:3, 3]

    target = fk_numpy([0.4, -0.9, 1.1])
    values = {L1: a1, L2: a2, L3: a3}
    res = solve_ik([(e, float(c)) for e, c in zip(exprs, target)], [IKJoint(t1), IKJoint(t2), IKJoint(t3)],
                   values)
    assert "too long" in res.closed_form_note and res.all_solutions
    for sol in res.all_solutions:
        assert np.allclose(fk_numpy([sol["theta1"], sol["theta2"], sol["theta3"]]), target, atol=1e-9)
