"""Comparison rules and diagnoses (grading.md), on the textbook planar 2R arm.

The given answers are written from the arm's closed forms (independent of robosolve's
solvers): M = Rz(q1)Tx(L1)Rz(q2)Tx(L2), J, det J = L1·L2·sin q2, Fq = −Jᵀ·Fs, the IK by the
law of cosines, the ellipse from numpy's eigen-decomposition of J·Jᵀ.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from robosolve.grading.compare import Tolerance
from tests._grading import TWO_R, grade_text, key, reference_of

L1, L2, F = 0.5, 0.4, 5.0
Q1, Q2 = math.pi / 6, math.pi / 3

M_SYM = [["cos(q1 + q2)", "-sin(q1 + q2)", 0, "L1*cos(q1) + L2*cos(q1 + q2)"],
         ["sin(q1 + q2)", "cos(q1 + q2)", 0, "L1*sin(q1) + L2*sin(q1 + q2)"],
         [0, 0, 1, 0], [0, 0, 0, 1]]


def ik_solutions(x=0.6, y=0.3):
    c2 = (x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    out = []
    for q2 in (math.acos(c2), -math.acos(c2)):
        q1 = math.atan2(y, x) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2))
        out.append((q1, q2))
    return out


def jac(q1=Q1, q2=Q2):
    return np.array([[-L1 * math.sin(q1) - L2 * math.sin(q1 + q2), -L2 * math.sin(q1 + q2)],
                     [L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L2 * math.cos(q1 + q2)]])


@pytest.fixture(scope="module")
def ref():
    return reference_of(TWO_R)


def answers(body: str) -> str:
    return "robosolve-answers: 1\nstudent: s1\nanswers:\n" + body


def yaml_matrix(rows) -> str:
    def cell(v):
        return f'"{v}"' if isinstance(v, str) else repr(v)
    return "[" + ", ".join("[" + ", ".join(cell(v) for v in r) + "]" for r in rows) + "]"


def one(ref, question, name, value_yaml, **kw):
    res = grade_text(ref, answers(f"  {question}:\n    {name}: {value_yaml}\n"), **kw)
    return key(res, question, name)


# -- expressions -----------------------------------------------------------------
def test_symbolic_pose_correct(ref):
    r = one(ref, "position", "M", yaml_matrix(M_SYM))
    assert (r.verdict, r.compared) == ("correct", "symbolic")


def test_expanded_trig_equals_reference(ref):
    rows = [list(r) for r in M_SYM]
    rows[0][3] = "L1*cos(q1) + L2*(cos(q1)*cos(q2) - sin(q1)*sin(q2))"
    rows[1][3] = "L1*sin(q1) + L2*(sin(q1)*cos(q2) + cos(q1)*sin(q2))"
    rows[0][0] = "cos(q1)*cos(q2) - sin(q1)*sin(q2)"
    assert one(ref, "position", "M", yaml_matrix(rows)).verdict == "correct"


def test_rounded_coefficients_within_rtol(ref):
    # 0.866*L2 for sqrt(3)/2*L2 is right (3 significant digits)
    assert one(ref, "jacobian", "det", '"L1*L2*sin(q2)"').verdict == "correct"
    r = one(ref, "position", "position",
            '["L1*cos(q1) + L2*cos(q1 + q2)", "L1*sin(q1) + L2*sin(q1 + q2)", 0]')
    assert r.verdict == "correct"


def test_wrong_expression_names_entries(ref):
    rows = [list(r) for r in M_SYM]
    rows[0][3] = "L1*cos(q1) + L2*cos(q2)"
    r = one(ref, "position", "M", yaml_matrix(rows))
    assert (r.verdict, r.diagnosis) == ("incorrect", "")
    assert r.feedback.startswith("entry (1, 4) is L1*cos(q1) + L2*cos(q2); expected L1*cos(q1) + L2*cos(q1 + q2)")


def test_parameters_substituted(ref):
    r = one(ref, "jacobian", "det", '"0.2*sin(q2)"')
    assert (r.verdict, r.diagnosis) == ("incorrect", "parameters_substituted")
    assert "L1, L2" in r.feedback


def test_unknown_symbol_is_invalid(ref):
    r = one(ref, "jacobian", "det", '"L1*L3*sin(q2)"')
    assert r.verdict == "invalid"
    assert "unknown name 'L3'" in r.feedback and "did you mean" in r.feedback


# -- diagnoses --------------------------------------------------------------------
def test_transposed_pose(ref):
    rows = [list(c) for c in zip(*M_SYM)]
    r = one(ref, "position", "M", yaml_matrix(rows))
    assert (r.verdict, r.diagnosis) == ("incorrect", "transposed")
    assert r.feedback.startswith("this is ⁰M₂ transposed: the columns of R are the axes of frame 2 in frame 0")
    assert "expected ⁰M₂ = " in r.feedback


def test_inverse_pose(ref):
    c, s = math.cos(Q1 + Q2), math.sin(Q1 + Q2)
    px, py = L1 * math.cos(Q1) + L2 * c, L1 * math.sin(Q1) + L2 * s
    inv = [[c, s, 0, -(c * px + s * py)], [-s, c, 0, s * px - c * py], [0, 0, 1, 0], [0, 0, 0, 1]]
    r = one(ref, "position", "M", yaml_matrix(inv))
    assert (r.verdict, r.compared, r.diagnosis) == ("incorrect", "numeric", "inverse")


def test_negated_fq(ref):
    r = one(ref, "statics", "Fq", '{q1: "-F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "-F*L2*cos(q1 + q2)"}')
    assert (r.verdict, r.diagnosis) == ("incorrect", "negated")
    assert "Fq = −Jᵀ·Fs" in r.feedback
    ok = one(ref, "statics", "Fq", '{q1: "F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "F*L2*cos(q1 + q2)"}')
    assert ok.verdict == "correct"


def test_ik_in_another_order_and_plus_two_pi_is_correct(ref):
    (a1, a2), (b1, b2) = ik_solutions()
    value = f"[{{q1: {b1 + 2 * math.pi:.5f}, q2: {b2:.5f}}}, {{q1: {a1:.5f}, q2: {a2 - 2 * math.pi:.5f}}}]"
    r = one(ref, "inverse_kinematics", "solutions", value)
    assert (r.verdict, r.compared) == ("correct", "numeric")


def test_ik_in_degrees(ref):
    sols = ik_solutions()
    value = "[" + ", ".join(f"{{q1: {math.degrees(a):.3f}, q2: {math.degrees(b):.3f}}}" for a, b in sols) + "]"
    r = one(ref, "inverse_kinematics", "solutions", value)
    assert (r.verdict, r.diagnosis) == ("incorrect", "degrees")


def test_ik_incomplete_and_extra(ref):
    (a1, a2), (b1, b2) = ik_solutions()
    r = one(ref, "inverse_kinematics", "solutions", f"[{{q1: {a1:.5f}, q2: {a2:.5f}}}]")
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set")
    value = f"[{{q1: {a1:.5f}, q2: {a2:.5f}}}, {{q1: {b1:.5f}, q2: {b2:.5f}}}, {{q1: 0, q2: 0}}]"
    r = one(ref, "inverse_kinematics", "solutions", value)
    assert (r.verdict, r.diagnosis) == ("incorrect", "extra_in_set")


def test_a_set_element_naming_no_joint_is_invalid_with_a_did_you_mean(ref):
    """An IK solution or a singular condition keyed by a name that is no joint (`q3` on a 2R arm)
    cannot be read (grading.md: a value naming a symbol the problem does not know is `invalid`
    with the reason), as in a per-joint mapping; it was graded `incorrect` without a word."""
    (a1, a2), (b1, b2) = ik_solutions()
    r = one(ref, "inverse_kinematics", "solutions", f"[{{q1: {a1:.5f}, q2: {a2:.5f}}}, {{q1: {b1:.5f}, q3: {b2:.5f}}}]")
    assert r.verdict == "invalid"
    assert "element 2" in r.feedback and "'q3' is not a joint" in r.feedback and "did you mean" in r.feedback
    r = one(ref, "jacobian", "singularities", "[{q2: 0}, {theta2: pi}]")
    assert r.verdict == "invalid" and "element 2" in r.feedback and "'theta2' is not a joint" in r.feedback


def test_an_ik_solution_without_a_value_for_a_joint_says_so(ref):
    (a1, a2), (b1, b2) = ik_solutions()
    r = one(ref, "inverse_kinematics", "solutions", f"[{{q1: {a1:.5f}, q2: {a2:.5f}}}, {{q1: {b1:.5f}}}]")
    assert r.verdict == "incorrect" and "element 2: no value for q2" in r.feedback


def test_a_missing_matrix_shows_its_expected_value_as_rows(ref):
    """The expected J of a key not given is written as rows, as every other feedback writes a
    matrix (and as an answer would be typed), not as sympy's `Matrix([[…]])`."""
    symbolic_only = reference_of(TWO_R.replace("name: two-r", "name: two-r-symbolic").replace(
        "{type: jacobian, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}}", "{type: jacobian, coordinates: [E.x, E.y]}"))
    res = grade_text(symbolic_only, answers("  jacobian:\n    det: L1*L2*sin(q2)\n"))
    r = key(res, "jacobian", "J")
    assert r.verdict == "missing"
    assert "Matrix" not in r.feedback and "J = [[-L1*sin(q1) - L2*sin(q1 + q2), -L2*sin(q1 + q2)], [" in r.feedback


def test_singularities_any_order_and_form(ref):
    assert one(ref, "jacobian", "singularities", "[{q2: pi}, {q2: 0}]").verdict == "correct"
    # as numbers, and -pi for pi (modulo 2π)
    assert one(ref, "jacobian", "singularities", "[{q2: -3.1416}, {q2: 0.0}]").verdict == "correct"
    r = one(ref, "jacobian", "singularities", "[{q2: 0}]")
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set")
    r = one(ref, "jacobian", "singularities", "[{q2: 0}, {q2: 180}]")
    assert r.verdict == "incorrect"


def test_singularities_written_as_equations_of_one_joint(ref):
    """`q2 = pi` states the condition {q2: pi}: it was graded `incorrect` (an equation never
    matched a mapping), a right answer graded wrong."""
    for value in ('[q2 = 0, q2 = pi]', '["pi = q2", "q2 = 0"]', '["-q2 = 0", "q2 - pi = 0"]'):
        r = one(ref, "jacobian", "singularities", value)
        assert r.verdict == "correct", (value, r)
    r = one(ref, "jacobian", "singularities", '[q2 = 0, q2 = pi/2]')
    assert r.verdict == "incorrect"
    r = one(ref, "jacobian", "singularities", '[q2 = 0, "2*q2 = pi"]')     # not isolated: an equation
    assert r.verdict == "incorrect"


def test_joint_values_written_as_a_vector_in_joint_order(ref):
    """Fq = −Jᵀ·Fs is a vector in the course: `[a, b]` (or typed `"[a; b]"`) is read in joint
    order, one value per joint; IK solutions as lists likewise. Reference: −Jᵀ·F by hand."""
    fq = -jac().T @ np.array([0.0, -F])
    for value in (f"[{fq[0]:.6f}, {fq[1]:.6f}]", f'"[{fq[0]:.6f}; {fq[1]:.6f}]"', f'"[{fq[0]:.6f} {fq[1]:.6f}]"'):
        r = one(ref, "statics", "Fq", value)
        assert r.verdict == "correct", (value, r)
    r = one(ref, "statics", "Fq", f"[{fq[1]:.6f}, {fq[0]:.6f}]")
    assert r.verdict == "incorrect"
    r = one(ref, "statics", "Fq", f"[{fq[0]:.6f}, {fq[1]:.6f}, 0]")
    assert r.verdict == "invalid"                      # three values for two joints
    (a1, a2), (b1, b2) = ik_solutions()
    r = one(ref, "inverse_kinematics", "solutions", f"[[{b1:.5f}, {b2:.5f}], [{a1:.5f}, {a2:.5f}]]")
    assert r.verdict == "correct", r


def test_wrong_shape(ref):
    r = one(ref, "position", "M", "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]")
    assert (r.verdict, r.diagnosis) == ("invalid", "wrong_shape")
    r = one(ref, "position", "position", "[0.1, 0.2]")
    assert (r.verdict, r.diagnosis) == ("invalid", "wrong_shape")


def test_transposed_jacobian(ref):
    jt = jac().T.tolist()
    r = one(ref, "jacobian", "J", yaml_matrix(jt))
    assert (r.verdict, r.diagnosis) == ("incorrect", "transposed")
    assert one(ref, "jacobian", "J", yaml_matrix(jac().tolist())).verdict == "correct"


# -- numbers, tolerances ---------------------------------------------------------------
def test_numbers_with_tolerance(ref):
    det = L1 * L2 * math.sin(Q2)
    assert one(ref, "jacobian", "det", f"{det * 1.004}").verdict == "correct"
    r = one(ref, "jacobian", "det", f"{det * 1.006}")
    assert (r.verdict, r.compared) == ("incorrect", "numeric")
    # --rtol wins
    assert one(ref, "jacobian", "det", f"{det * 1.006}", tolerance=Tolerance(0.01, 1e-6)).verdict == "correct"


def test_problem_grading_tolerances():
    text = TWO_R.replace("questions:", "grading: {rtol: 0.02}\nquestions:")
    ref = reference_of(text)
    assert ref.tolerance == Tolerance(0.02, 1e-6)
    det = L1 * L2 * math.sin(Q2)
    assert one(ref, "jacobian", "det", f"{det * 1.015}").verdict == "correct"
    ref2 = reference_of(text, rtol=0.001)
    assert ref2.tolerance.rtol == 0.001


def test_position_numbers_feedback(ref):
    x = L1 * math.cos(Q1) + L2 * math.cos(Q1 + Q2)
    y = L1 * math.sin(Q1) + L2 * math.sin(Q1 + Q2)
    assert one(ref, "position", "position", f"[{x:.4f}, {y:.4f}, 0]").verdict == "correct"
    r = one(ref, "position", "position", f"[{x:.4f}, 0.9, 0]")
    assert r.feedback.startswith(f"entry 2 is 0.9; expected {y:.4g}")


def test_ellipse_axes_ignore_sign(ref):
    J = jac()
    w, v = np.linalg.eigh(J @ J.T)
    order = np.argsort(-(1 / np.sqrt(w)))
    axes = [(v[:, i] / math.sqrt(w[i])).tolist() for i in order]
    flipped = [[-c for c in axes[0]], axes[1]]
    r = one(ref, "ellipsoids", "force.semi_axes", yaml_matrix(flipped))
    assert r.verdict == "correct"
    swapped = [axes[1], axes[0]]
    assert one(ref, "ellipsoids", "force.semi_axes", yaml_matrix(swapped)).verdict == "incorrect"
    cond = max(w) / min(w)
    assert one(ref, "ellipsoids", "condition_number", f"{cond:.4f}").verdict == "correct"


def test_nested_and_dotted_keys_agree(ref):
    J = jac()
    w = sorted(np.linalg.eigvalsh(J @ J.T))
    lengths = f"[{1 / math.sqrt(w[0]):.5f}, {1 / math.sqrt(w[1]):.5f}]"
    a = grade_text(ref, answers(f"  ellipsoids:\n    force.lengths: {lengths}\n"))
    b = grade_text(ref, answers(f"  ellipsoids:\n    force: {{lengths: {lengths}}}\n"))
    assert key(a, "ellipsoids", "force.lengths") == key(b, "ellipsoids", "force.lengths")
    assert key(a, "ellipsoids", "force.lengths").verdict == "correct"


def test_euler_angle_sets_ignore_order(ref):
    # R = Rz(90°): RPY (roll, pitch, yaw) = (0, 0, pi/2) or (pi, pi, -pi/2)
    r = one(ref, "orientation", "rpy", "{solutions: [[pi, pi, -pi/2], [0, 0, pi/2]], singular: false}")
    assert r.verdict == "correct"
    r = one(ref, "orientation", "rpy", "{solutions: [[0, 0, pi/2]], singular: false}")
    assert r.verdict == "incorrect"


def test_graded_keys_scores_and_extra_keys(ref):
    res = grade_text(ref, answers('  statics:\n    Fq: {q1: "F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "F*L2*cos(q1 + q2)"}\n'
                                  '  position:\n    chain: []\n'))
    statics = next(q for q in res.questions if q.id == "statics")
    assert statics.score == 2 and statics.marks == 2
    position = next(q for q in res.questions if q.id == "position")
    assert list(position.keys) == ["M", "position", "chain"]          # graded first, then extras
    assert position.keys["M"].verdict == "missing"
    assert position.keys["chain"].verdict == "invalid"                 # 0 matrices where 2 are expected
    ell = next(q for q in res.questions if q.id == "ellipsoids")
    assert ell.graded == ("force.semi_axes", "condition_number")        # the question's grade list
    assert res.max_score == 7


NULL_F = """
robosolve: 1
name: null-load
parameters: {L1: 1/2, F: ~}
joints: [{name: q1, type: revolute}]
frames: {"1": {parent: "0", pose: "Rz(q1) Tx(L1)"}}
questions:
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6}}
"""


def test_null_parameter():
    ref = reference_of(NULL_F)
    assert one(ref, "statics", "Fq", '{q1: "F*L1*cos(q1)"}').verdict == "correct"
    r = one(ref, "statics", "Fq", "{q1: 2.165}")
    assert r.verdict == "invalid" and "F" in r.feedback
    r = one(ref, "statics", "Fq", '{q1: "F*L1*sin(q1)"}')
    assert r.verdict == "incorrect"


ONE_LINK = """
robosolve: 1
name: one-link
parameters: {L: 1, m1: 2, m2: 1, g: 9.81, F: 3}
joints: [{name: theta, type: revolute, actuator: C}]
frames: {"1": {parent: "0", pose: "Rx(theta) Ty(L)"}}
bodies:
  - {name: link1, frame: "1", mass: m1, rod: {from: [0, -L, 0], to: [0, 0, 0]}}
  - {name: payload, frame: "1", mass: m2, point: [0, 0, 0]}
forces:
  - {name: F, frame: "1", at: [0, -L/3, 0], force: [0, 0, -F]}
questions:
  - {type: equations_of_motion, at: {theta: pi/6, theta_dot: 0, theta_ddot: 0}, grade: [equations, mass_matrix]}
"""


def test_equations_up_to_a_constant_factor():
    # rod about its end: m1·L²/3, tip mass m2·L²; weight (m1/2 + m2)·g·L·cos θ; F at 2L/3
    ref = reference_of(ONE_LINK)
    eq = "(m1/3 + m2)*L**2*theta_ddot + (m1/2 + m2)*g*L*cos(theta) = C - 2*F*L/3"
    res = grade_text(ref, answers(f'  equations_of_motion:\n    equations: ["{eq}"]\n'
                                  '    mass_matrix: [["L**2*(m1/3 + m2)"]]\n'))
    assert key(res, "equations_of_motion", "equations").verdict == "correct"
    assert key(res, "equations_of_motion", "mass_matrix").verdict == "correct"
    twice = "2*(m1/3 + m2)*L**2*theta_ddot + (m1 + 2*m2)*g*L*cos(theta) - 2*C = -4*F*L/3"
    assert one(ref, "equations_of_motion", "equations", f'["{twice}"]').verdict == "correct"
    wrong = "(m1/3 + m2)*L**2*theta_ddot + (m1 + m2)*g*L*cos(theta) = C - 2*F*L/3"
    assert one(ref, "equations_of_motion", "equations", f'["{wrong}"]').verdict == "incorrect"
    bad = one(ref, "equations_of_motion", "equations", '["C"]')
    assert bad.verdict == "invalid" and "lhs = rhs" in bad.feedback


def test_points_are_seeded_and_cover_the_rules(ref):
    from robosolve.grading.points import sample

    qref = ref.question("jacobian")
    syms = {ref.problem.names[n] for n in ("L1", "L2", "q1", "q2")}
    a = sample(syms, qref.roles, "x/jacobian/det")
    b = sample(syms, qref.roles, "x/jacobian/det")
    assert all((a.columns[s] == b.columns[s]).all() for s in syms)
    L1s = ref.problem.names["L1"]
    fixed, moved = a.columns[L1s][a.fixed], a.columns[L1s][~a.fixed]
    assert (fixed == 0.5).all() and len(fixed) >= 2
    assert len(moved) >= 2 and ((moved >= 0.4) & (moved <= 0.625) & (moved != 0.5)).all()
    q1 = a.columns[ref.problem.names["q1"]]
    assert ((q1 > -math.pi) & (q1 <= math.pi)).all() and a.size >= 6


def test_direct_evaluator_agrees_with_sympy_evalf():
    import sympy as sp

    from robosolve.grading.points import tree_values

    x, y = sp.symbols("x y", real=True)
    e = (sp.sqrt(x ** 2 + 1) * sp.cos(x - y) / (2 + sp.sin(y)) ** 2 + sp.atan2(y, x + 3)
         - sp.Rational(3, 7) * sp.exp(-x) * sp.Abs(y) + sp.log(x ** 2 + 2) ** sp.Rational(3, 2) - sp.pi * x ** -1)
    xs, ys = np.array([0.3, -1.2, 2.5]), np.array([1.1, 0.4, -2.0])
    got = tree_values(e, {x: xs, y: ys}, {})
    want = [float(e.subs({x: a, y: b}).evalf(30)) for a, b in zip(xs, ys)]
    assert np.allclose(got, want, rtol=1e-12, atol=0)


def _rules(revolute=("q1",), rtol=0.005, atol=1e-6, n=1):
    from robosolve.grading.compare import Rules

    return Rules(Tolerance(rtol, atol), np.ones(n, dtype=bool), frozenset(revolute))


def _arr(x, n=1):
    return np.full(n, float(x))


def test_only_revolute_joint_values_wrap():
    from robosolve.grading.compare import compare
    from robosolve.questions.registry import JOINT_MAP_SET, AnswerKey

    ak = AnswerKey("solutions", JOINT_MAP_SET, angle=True, unordered=True)
    e = [{"q1": _arr(0.4), "d": _arr(0.3)}]
    assert compare(ak, [{"q1": _arr(0.4 + 2 * math.pi), "d": _arr(0.3)}], e, _rules()).ok
    assert not compare(ak, [{"q1": _arr(0.4), "d": _arr(0.3 + 2 * math.pi)}], e, _rules()).ok


def test_unwrapped_values_when_the_schema_says_not_angle():
    # forward-dynamics `final`/`max`/`min` are joint maps without `angle`: 4π is not 0
    from robosolve.grading.compare import compare
    from robosolve.questions.registry import JOINT_MAP, AnswerKey

    ak = AnswerKey("final", JOINT_MAP)
    e = {"q1": _arr(4 * math.pi)}
    assert compare(ak, {"q1": _arr(4 * math.pi * 1.001)}, e, _rules()).ok
    assert not compare(ak, {"q1": _arr(0.0)}, e, _rules()).ok
    wrapped = AnswerKey("final", JOINT_MAP, angle=True)
    assert compare(wrapped, {"q1": _arr(0.0)}, e, _rules()).ok


def test_booleans_and_null_exact():
    from robosolve.grading.compare import compare
    from robosolve.questions.registry import BOOL, SCALAR, AnswerKey

    assert compare(AnswerKey("singular", BOOL), True, True, _rules()).ok
    assert not compare(AnswerKey("singular", BOOL), False, True, _rules()).ok
    assert compare(AnswerKey("x", SCALAR), None, None, _rules()).ok
    assert not compare(AnswerKey("x", SCALAR), _arr(0.0), None, _rules()).ok


def test_tolerance_formula_at_the_boundary():
    from robosolve.grading.compare import leaf_ok

    r = _rules(rtol=0.01, atol=0.001)
    assert leaf_ok(_arr(10.0 + 0.1 + 0.001 - 1e-9), _arr(10.0), False, r)      # atol + rtol·|e|
    assert not leaf_ok(_arr(10.0 + 0.1 + 0.001 + 1e-6), _arr(10.0), False, r)
    assert leaf_ok(_arr(-math.pi), _arr(math.pi), True, r)
    assert not leaf_ok(_arr(-math.pi), _arr(math.pi), False, r)


def test_maximum_matching_not_greedy():
    from robosolve.grading.compare import max_matching

    # given 0 matches both expected; given 1 only the first: a greedy match would find 1
    assert max_matching([[True, True], [True, False]]) == 2


def test_sympy_proof_when_points_fail(ref):
    # an expected value undefined at the sample points is settled by sympy, briefly
    import sympy as sp

    from robosolve.grading.grader import Grader
    from robosolve.questions.registry import question_type

    g = Grader(ref)
    qref = ref.question("jacobian")
    ak = question_type("jacobian").key("det")
    L1 = ref.problem.names["L1"]
    e = sp.sqrt(-L1) * sp.sqrt(-L1)            # = -L1, but nan at every point with numpy
    assert g._prove(qref, ak, "det", -L1, e).verdict == "correct"
    assert g._prove(qref, ak, "det", L1, e).verdict == "incorrect"


def test_sampling_ranges_of_every_role():
    import sympy as sp

    from robosolve.grading.points import SymbolRoles, sample

    L, F, q, qd, C, t = sp.symbols("L F q q_dot C t", real=True)
    roles = SymbolRoles(parameters={L: 2.0, F: None}, joints={q: (-0.5, 1.0)}, rates={qd},
                        actuators={C}, t_symbol=t, t_range=(0.0, 1.7))
    s = sample({L, F, q, qd, C, t}, roles, "seed")
    col = s.columns
    assert ((col[F] >= 0.5) & (col[F] <= 2)).all()                       # null parameter
    assert ((col[q] >= -0.5) & (col[q] <= 1.0)).all()                    # joint limits
    assert ((col[qd] >= -2) & (col[qd] <= 2)).all()
    assert ((col[C] >= -5) & (col[C] <= 5)).all()
    assert ((col[t] >= 0) & (col[t] <= 1.7)).all()
    assert (col[L][s.fixed] == 2.0).all() and ((col[L][~s.fixed] >= 1.6) & (col[L][~s.fixed] <= 2.5)).all()
    # a symbol's values do not depend on the other symbols sampled with it
    alone = sample({q}, roles, "seed")
    assert (alone.columns[q] == col[q]).all()


def test_expression_for_a_numeric_reference_is_evaluated_at_the_values(ref):
    # ellipse quantities are numbers (at `at`) even in symbolic form: an expression of the
    # parameters is evaluated at their values, not diagnosed as substituted
    J = jac()
    w = np.linalg.eigvalsh(J @ J.T)
    cond = max(w) / min(w)
    r = one(ref, "ellipsoids", "condition_number", f'"{cond / (2 * 0.5 / 1.1)}*2*L1/(L1 + 0.6)"')
    assert (r.verdict, r.compared) == ("correct", "numeric")
    r = one(ref, "ellipsoids", "condition_number", f'"{cond}*3*L1"')
    assert (r.verdict, r.diagnosis) == ("incorrect", "")


def test_parameters_substituted_needs_a_missing_parameter(ref):
    # wrong at the moved points but every parameter kept: not "substituted"
    r = one(ref, "jacobian", "det", '"L1*L2*sin(q2) + (L1 - 1/2)"')
    assert (r.verdict, r.diagnosis) == ("incorrect", "")


def test_question_without_reference_is_not_graded(ref):
    import copy

    from robosolve.grading.record import grade_rows

    broken = copy.deepcopy(ref)
    broken.question("jacobian").error = "the Jacobian could not be derived"
    res = grade_text(broken, answers('  jacobian: {det: "L1*L2*sin(q2)"}\n'))
    jac_q = next(q for q in res.questions if q.id == "jacobian")
    assert {k: r.verdict for k, r in jac_q.keys.items()} == {
        "J": "no_reference", "det": "no_reference", "manipulability": "no_reference",
        "singularities": "no_reference"}
    assert res.max_score == 6 and jac_q.score == 0
    rows = [r for r in grade_rows(res) if r[1] == "jacobian"]
    assert all(r[3] == "no_reference" and r[5:] == ("0", "0") for r in rows)


SINGULAR_ELLIPSE = """
robosolve: 1
name: two-r-stretched
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {q1: 0, q2: 0}, grade: [force.semi_axes, force.lengths]}
"""


def test_an_infinite_force_semi_axis_given_as_null_is_right():
    """At q2 = 0 the force ellipse is unbounded along x (its semi-axis null, papers.md's `~` rule
    says so too): giving null back was `invalid` ("expected a list (a vector), got null").
    Reference by hand: J = [[0, 0], [L1 + L2, L2]], A = J·Jᵀ has eigenvalues 0 and (L1+L2)² + L2²
    along y, so the finite force semi-axis is 1/sqrt(0.81 + 0.16) along ±y."""
    ref = reference_of(SINGULAR_ELLIPSE)
    finite = 1 / math.sqrt(0.9 ** 2 + 0.4 ** 2)
    for axes in (f"[null, [0, {finite:.6f}]]", f"[~, [0, {-finite:.6f}]]"):
        text = answers(f"  ellipsoids:\n    force.semi_axes: {axes}\n    force.lengths: [null, {finite:.6f}]\n")
        res = grade_text(ref, text)
        assert key(res, "ellipsoids", "force.semi_axes").verdict == "correct", axes
        assert key(res, "ellipsoids", "force.lengths").verdict == "correct"
    for axes in (f"[[1, 0], [0, {finite:.6f}]]", "[null, [0, 0.5]]"):
        res = grade_text(ref, answers(f"  ellipsoids:\n    force.semi_axes: {axes}\n"))
        assert key(res, "ellipsoids", "force.semi_axes").verdict == "incorrect", axes


PENDULUM_2 = """
robosolve: 1
name: two-pendula
parameters: {L: 1/2, m: 2, g: 9.81}
joints: [{name: a, type: revolute, actuator: Ta}, {name: b, type: revolute, actuator: Tb}]
frames:
  "1": {parent: "0", pose: "Rz(a) Tx(L)"}
  "2": {parent: "0", pose: "Rz(b) Tx(L)"}
gravity: [0, -g, 0]
bodies: [{name: p1, frame: "1", mass: m, point: [0, 0, 0]}, {name: p2, frame: "2", mass: m, point: [0, 0, 0]}]
questions:
  - {type: equations_of_motion, at: {a: 0.3, b: -0.8, a_dot: 0, b_dot: 0, a_ddot: 1, b_ddot: 2}}
"""


def test_actuator_values_written_as_a_vector_in_joint_order():
    """Two independent pendula: T = m L² q̈ + m g L cos q for each (closed form); [Ta, Tb] as a
    vector is read in joint order."""
    ref = reference_of(PENDULUM_2)
    m, L, g = 2, 0.5, 9.81
    ta, tb = (m * L * L * qdd + m * g * L * math.cos(q) for q, qdd in ((0.3, 1), (-0.8, 2)))
    res = grade_text(ref, answers(f"  equations_of_motion:\n    actuators: [{ta:.6f}, {tb:.6f}]\n"))
    assert key(res, "equations_of_motion", "actuators").verdict == "correct"
    res = grade_text(ref, answers(f"  equations_of_motion:\n    actuators: [{tb:.6f}, {ta:.6f}]\n"))
    assert key(res, "equations_of_motion", "actuators").verdict == "incorrect"


def test_a_wrong_entry_and_a_missing_one_are_each_named(ref):
    """Fq = −Jᵀ·(0, −F) = F·(L1·cos q1 + L2·cos(q1 + q2), L2·cos(q1 + q2)) = (2.165, 0): with q1
    wrong and q2 not given, the feedback quoted q1's value under q2's name ("no value for q2 is
    3")."""
    r = one(ref, "statics", "Fq", "{q1: 3.0}")
    assert r.verdict == "incorrect"
    assert r.feedback.startswith("q1 is 3; expected 2.165; no value for q2"), r.feedback


def test_a_set_typed_as_one_string(ref):
    """IK solutions typed as a MATLAB matrix, one row per solution in joint order (law of
    cosines, by hand), and a singular set as one string joined by `or` (det J = L1·L2·sin q2):
    both were `invalid` ("expected a list, got a string")."""
    (a1, a2), (b1, b2) = ik_solutions()
    r = one(ref, "inverse_kinematics", "solutions", f'"[{a1:.4f} {a2:.4f}; {b1:.4f} {b2:.4f}]"')
    assert r.verdict == "correct", r
    r = one(ref, "inverse_kinematics", "solutions", f'"[{a1:.4f} {a2:.4f}]"')
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set")
    assert one(ref, "jacobian", "singularities", '"q2 = 0 or q2 = pi"').verdict == "correct"
    assert one(ref, "jacobian", "singularities", '[{q2: "0°"}, {q2: "180°"}]').verdict == "correct"


def test_unreachable_true_alone_is_the_empty_set_of_solutions():
    """The reference of an unreachable target writes `solutions: []` and `unreachable: true`; a
    student who writes only `unreachable: true` has said the set is empty. The 2R's reach is
    L1 + L2 = 0.9 (by hand): (1.2, 0.3) lies beyond it, (0.6, 0.3) within."""
    far = reference_of(TWO_R.replace("target: {E.x: 0.6, E.y: 0.3}", "target: {E.x: 1.2, E.y: 0.3}"))
    for written in ("unreachable: true", "unreachable: true\n    solutions: []"):
        result = grade_text(far, f"robosolve-answers: 1\nanswers:\n  inverse_kinematics:\n    {written}\n")
        assert key(result, "inverse_kinematics", "solutions").verdict == "correct", written
    near = reference_of(TWO_R)
    result = grade_text(near, "robosolve-answers: 1\nanswers:\n  inverse_kinematics:\n    unreachable: true\n")
    assert key(result, "inverse_kinematics", "solutions").verdict == "incorrect"
    result = grade_text(near, "robosolve-answers: 1\nanswers:\n  inverse_kinematics:\n    unreachable: false\n")
    assert key(result, "inverse_kinematics", "solutions").verdict == "missing"


@pytest.fixture(scope="module")
def far():
    """The 2R with a target beyond its reach L1 + L2 = 0.9 (by hand): no IK solution."""
    return reference_of(TWO_R.replace("target: {E.x: 0.6, E.y: 0.3}", "target: {E.x: 1.2, E.y: 0.3}"))


def test_one_solution_written_as_a_mapping_is_the_set_of_it(ref):
    """`solutions: {q1: …, q2: …}` is the set of that one solution, graded as the list of one
    would be (it was `invalid`, wrong_shape). The target (0.6, 0.3) has two solutions (law of
    cosines, by hand), so one is `incomplete_set`; a one-joint target with one solution, and a
    singular set of one condition (det J = L1·L2·sin q2 = 0 at q2 = 0 and π), likewise."""
    (a1, a2), (b1, b2) = ik_solutions()
    for q1, q2 in ((a1, a2), (b1, b2)):
        r = one(ref, "inverse_kinematics", "solutions", f"{{q1: {q1:.4f}, q2: {q2:.4f}}}")
        assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set"), r
    r = one(ref, "inverse_kinematics", "solutions", f"{{q1: {a1 + 0.3:.4f}, q2: {a2:.4f}}}")
    assert r.verdict == "incorrect" and r.diagnosis != "incomplete_set", r
    r = one(ref, "jacobian", "singularities", "{q2: 0}")
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set"), r


def test_one_solution_as_a_mapping_is_right_when_the_reference_has_one():
    """A 1R arm of length L (E.x = L·cos q1, E.y = L·sin q1) reaching (0, L) has the one solution
    q1 = π/2 (by hand): written as a mapping it is right."""
    one_r = reference_of("""
        robosolve: 1
        name: one-r
        parameters: {L: 1/2}
        joints: [{name: q1, type: revolute}]
        frames: {"1": {parent: "0", pose: "Rz(q1) Tx(L)"}}
        questions:
          - {type: inverse_kinematics, target: {E.x: 0, E.y: 0.5}}
    """)
    r = one(one_r, "inverse_kinematics", "solutions", "{q1: pi/2}")
    assert r.verdict == "correct", r
    r = one(one_r, "inverse_kinematics", "solutions", "{q1: -pi/2}")
    assert r.verdict == "incorrect", r


@pytest.mark.parametrize("written", ["none", "None", "no solution", "No solutions.", '"[]"', "'none'", "'{}'",
                                     "{}", "∅", "empty set", "[none]"])
def test_no_solution_written_in_words_is_the_empty_set(far, ref, written):
    """`solutions: none` (and its kin) says the set is empty: right for a target beyond the
    reach L1 + L2 = 0.9 (by hand), wrong within it; it was `invalid` ('expected an equation')."""
    r = one(far, "inverse_kinematics", "solutions", written)
    assert r.verdict == "correct", (written, r)
    r = one(ref, "inverse_kinematics", "solutions", written)
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set"), (written, r)


def test_an_unreadable_set_speaks_of_joint_values(far):
    """Text that says nothing readable is `invalid`, and the feedback speaks of the set of
    joint mappings asked for, not of an equation nobody wrote."""
    for written in ("hello", "42", "true"):
        r = one(far, "inverse_kinematics", "solutions", written)
        assert r.verdict == "invalid", (written, r)
        assert "a list of mappings joint -> value" in r.feedback and "lhs = rhs" not in r.feedback, r.feedback
        assert "[] for none" in r.feedback, r.feedback
    r = one(far, "jacobian", "singularities", "hello")       # conditions may be equations
    assert r.verdict == "invalid" and "a list of mappings joint -> value" in r.feedback, r.feedback
    r = one(far, "jacobian", "singularities", '"q2 = 0 = pi"')    # an equation mistyped is told so
    assert r.verdict == "invalid" and "lhs = rhs" in r.feedback, r.feedback


@pytest.mark.parametrize("written, said", [("'true'", True), ("'yes'", True), ("'True'", True), ("'YES'", True),
                                           ("'on'", True), ("'false'", False), ("'no'", False), ("'Off'", False)])
def test_true_and_false_typed_as_text(far, ref, written, said):
    """`unreachable: 'true'` (quoted) is true, as `unreachable: true` is: the flag is right for
    the target beyond the reach L1 + L2 = 0.9 (by hand) and alone stands for `solutions: []`
    (it was `invalid`, and the solutions `missing`)."""
    text = f"  inverse_kinematics:\n    unreachable: {written}\n"
    far_result, near_result = grade_text(far, answers(text)), grade_text(ref, answers(text))
    flag = key(far_result, "inverse_kinematics", "unreachable")
    assert flag.verdict == ("correct" if said else "incorrect"), (written, flag)
    solutions = key(far_result, "inverse_kinematics", "solutions")
    assert solutions.verdict == ("correct" if said else "missing"), (written, solutions)
    solutions = key(near_result, "inverse_kinematics", "solutions")     # two solutions within the reach
    assert solutions.verdict == ("incorrect" if said else "missing"), (written, solutions)
    r = one(far, "inverse_kinematics", "unreachable", "'maybe'")
    assert r.verdict == "invalid" and "true or false" in r.feedback, r


def test_a_record_flag_typed_as_text(ref):
    """R = Rz(90°): RPY (roll, pitch, yaw) = (0, 0, pi/2) or (pi, pi, -pi/2), pitch ≠ ±pi/2 so not
    singular (by hand): `singular: 'No'` is false (it was `invalid`)."""
    sols = "[[pi, pi, -pi/2], [0, 0, pi/2]]"
    assert one(ref, "orientation", "rpy", f"{{solutions: {sols}, singular: 'No'}}").verdict == "correct"
    assert one(ref, "orientation", "rpy", f"{{solutions: {sols}, singular: 'yes'}}").verdict == "incorrect"


PENDULUM_1 = """
robosolve: 1
name: pendulum-1
parameters: {L: 0.8, m: 3, g: 9.81}
joints: [{name: q, type: revolute}]
frames: {"1": {parent: "0", pose: "Rz(q) Tx(L)"}}
gravity: [0, -g, 0]
bodies: [{name: rod, frame: "1", mass: m, rod: {from: [-L, 0, 0], to: [0, 0, 0]}}]
questions:
  - {type: inverse_kinematics, target: {E.y: 0.4}}
  - {type: statics, force: [5], coordinates: [E.y], at: {q: 0.3}}
  - {type: jacobian, coordinates: [E.y], at: {q: 0.3}, grade: [singularities]}
  - {type: equations_of_motion, at: {q: 0.3, q_dot: 1, q_ddot: 2}, grade: [actuators, generalized_forces]}
"""


def test_one_joint_values_written_alone():
    """A one-joint arm (a rod pendulum, I = m·L²/3 about the pivot): a per-joint value written as
    the number (or expression) alone is the mapping of that joint, and a set of IK solutions a
    list of numbers (was `invalid`, "expected a mapping name -> value, got a number"). Closed
    forms: L·sin q = 0.4 gives q = asin(1/2) and pi − asin(1/2); Fq = −Jᵀ·F = −5·L·cos q;
    C1 = (m·L²/3)·q̈ + m·g·(L/2)·cos q; J = L·cos q is singular at ±pi/2."""
    ref = reference_of(PENDULUM_1)
    L, m, g = 0.8, 3, 9.81
    q1, q2 = math.asin(0.4 / L), math.pi - math.asin(0.4 / L)
    c1 = m * L * L / 3 * 2 + m * g * L / 2 * math.cos(0.3)
    res = grade_text(ref, answers(
        f"  inverse_kinematics:\n    solutions: [{q2:.5f}, {q1:.5f}]\n"
        f"  statics:\n    Fq: {-5 * L * math.cos(0.3):.5f}\n"
        "  jacobian:\n    singularities: [\"q = pi/2\", -pi/2]\n"
        f"  equations_of_motion:\n    actuators: {c1:.5f}\n    generalized_forces: C1\n"))
    verdicts = {(q.id, k): v.verdict for q in res.questions for k, v in q.keys.items()}
    assert set(verdicts.values()) == {"correct"}, verdicts
    res = grade_text(ref, answers(f"  statics:\n    Fq: {5 * L * math.cos(0.3):.5f}\n"))
    assert (key(res, "statics", "Fq").verdict, key(res, "statics", "Fq").diagnosis) == ("incorrect", "negated")
