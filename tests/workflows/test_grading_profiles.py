"""Profiles piecewise in t (motion_profile and joint_torques `profiles`, graded when a question's
`grade:` asks for them): read as the course writes them (Maple's `piecewise(c1, e1, c2, e2, …)`,
the seed's own base profile) and as results.json does (sympy's `Piecewise((e1, c1), …)`), and
compared as functions of t on [0, T], piece by piece (grading.md).

Every expected profile here is written by hand from the profile's definition (problem-format.md
"Motion profiles": bang-bang over [0, T] with a = 4Δ/T², trapezoidal with the cruise at v) and
the torque of a point mass on a rod, τ = m·L²·q̈ + m·g·L·cos q — never copied from robosolve.
"""

from __future__ import annotations

import pytest
import yaml

from robosolve.errors import InputError
from robosolve.load.expressions import ExpressionError
from tests._grading import grade_text, key, reference_of

# One rod (a point mass m at L) in the vertical plane; a bang-bang profile 0 -> 1 at a = 4
# (T = √(4·1/4) = 1: q = 2t² up to 1/2, then 1 − 2(1 − t)²), a trapezoidal one 0 -> 1 at
# v = 3/2, a = 4 (T = 1/v + v/a = 25/24; accelerating up to v/a = 3/8, cruising at
# q = v·t − v²/(2a) = 3t/2 − 9/32 until T − 3/8 = 2/3, then 1 − 2(T − t)²).
ROD = """
robosolve: 1
name: rod
parameters: {m: 2, L: 1/2, g: 9.81}
joints:
  - {name: q, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q) Tx(L)"}
bodies:
  - {name: b, frame: "1", mass: m, point: [0, 0, 0]}
gravity: [0, -g, 0]
questions:
  - {type: motion_profile, id: bang, from: {q: 0}, to: {q: 1}, max_acceleration: {q: 4}, grade: [T, profiles]}
  - {type: motion_profile, id: trap, from: {q: 0}, to: {q: 1}, max_acceleration: {q: 4}, shape: trapezoidal,
     max_velocity: {q: 3/2}, grade: [profiles]}
  - {type: joint_torques, profile: bang, grade: [profiles]}
"""

SEED = "piecewise(t >= 0 and t <=1/2, 2*t^2, t >1/2 and t <=1, -2*t^2+4*t-1)"   # the seed's, verbatim
TRAP = "piecewise(t <= 3/8, 2*t^2, t <= 2/3, 3*t/2 - 9/32, 1 - 2*(25/24 - t)^2)"
# τ = m·L²·q̈ + m·g·L·cos q, with q̈ = ±4 and q as above
TORQUE = ("piecewise(t <= 1/2, 4*m*L^2 + m*g*L*cos(2*t^2), "
          "-4*m*L^2 + m*g*L*cos(1 - 2*(1 - t)^2))")


@pytest.fixture(scope="module")
def ref():
    return reference_of(ROD)


def profile(ref, question, value, name="q"):
    text = yaml.safe_dump({"robosolve-answers": 1, "student": "s1",
                           "answers": {question: {"profiles": {name: value}}}}, width=10**6)
    return key(grade_text(ref, text), question, "profiles")


@pytest.mark.parametrize("value", [
    SEED,
    "Piecewise((2*t**2, t <= 1/2), (1 - 2*(1 - t)**2, True))",          # sympy's form
    "Piecewise((0, t < 0), (2*t**2, t <= 1/2), (1 - 2*(1 - t)**2, t <= 1), (1, True))",
    "piecewise(t < 0.5, 2*t^2, 1 - 2*(1 - t)^2)",                       # the other side owns 1/2
    "piecewise(0 <= t <= 0.5, 2*t^2, 0.5 < t <= 1, 1 - 2*(1 - t)^2)",    # chained comparisons
    "piecewise((t >= 0) & (t <= 1/2), 2*t^2, -2*t^2 + 4*t - 1)",         # MATLAB's &, an otherwise
    "piecewise(t <= 0.4999, 2*t^2, 1 - 2*(1 - t)^2)",                   # a breakpoint rounded
    "piecewise(t < 1/4, 2*t^2, t <= 1/2, 2*t^2, 1 - 2*(1 - t)^2)",       # a piece cut in two
])
def test_a_right_bang_bang_profile_is_right_in_every_form(ref, value):
    r = profile(ref, "bang", value)
    assert r.verdict == "correct", (value, r)


@pytest.mark.parametrize("value, interval", [
    ("piecewise(t <= 1/2, 2*t^2, 1 + 2*(1 - t)^2)", "[0.5, 1]"),          # the second piece's sign
    ("piecewise(t <= 1/4, 2*t^2, 1 - 2*(1 - t)^2)", "[0.25, 0.5]"),       # a breakpoint wrong
    ("2*t^2", "[0.5, 1]"),                                               # the first piece only
    ("piecewise(t <= 1/2, 2*t^2, t <= 0.9, 1 - 2*(1 - t)^2)", "[0.9, 1]"),  # undefined before T
])
def test_a_wrong_piece_is_incorrect_and_named(ref, value, interval):
    r = profile(ref, "bang", value)
    assert r.verdict == "incorrect", (value, r)
    assert f"wrong for t in {interval}" in r.feedback, r.feedback


def test_a_negated_profile_is_diagnosed(ref):
    r = profile(ref, "bang", "piecewise(t <= 1/2, -2*t^2, -1 + 2*(1 - t)^2)")
    assert (r.verdict, r.diagnosis) == ("incorrect", "negated")


def test_a_trapezoidal_profile_three_pieces(ref):
    assert profile(ref, "trap", TRAP).verdict == "correct"
    assert profile(ref, "trap", TRAP.replace("3*t/2 - 9/32", "3*t/2 - 0.2812")).verdict == "correct"
    wrong = profile(ref, "trap", TRAP.replace("3*t/2 - 9/32", "3*t/2 - 1/4"))
    assert wrong.verdict == "incorrect" and "wrong for t in [0.375, 0.6667]" in wrong.feedback


def test_a_torque_profile_with_the_parameters_as_symbols(ref):
    """τ(t) of the rod along the bang-bang profile, by hand: right for every value of m, L, g
    (pieces compared at moved parameters too); with g's sign flipped in one piece, wrong."""
    assert profile(ref, "joint_torques", TORQUE, name="C1").verdict == "correct"
    wrong = profile(ref, "joint_torques", TORQUE.replace("-4*m*L^2 + m*g", "-4*m*L^2 - m*g"), name="C1")
    assert wrong.verdict == "incorrect" and "wrong for t in [0.5, 1]" in wrong.feedback
    numbers = profile(ref, "joint_torques", TORQUE.replace("m", "2").replace("L", "0.5").replace("g", "9.81"),
                      name="C1")
    assert (numbers.verdict, numbers.diagnosis) == ("incorrect", "parameters_substituted")


def test_a_condition_that_is_not_in_t_alone_is_invalid(ref):
    r = profile(ref, "bang", "piecewise(q < 1/2, 2*t^2, 1)")
    assert r.verdict == "invalid" and "cannot be decided in t alone" in r.feedback
    r = profile(ref, "bang", "t < 1")
    assert r.verdict == "invalid" and "piecewise" in r.feedback


def test_the_problem_file_parser_stays_strict():
    """Piecewise and comparisons are an answers file's: in a problem file they stay errors."""
    from robosolve.grading.values import answers_namespace
    from robosolve.load.expressions import Namespace
    from robosolve.load.loader import load_problem_text

    import sympy as sp

    t = sp.Symbol("t", real=True)
    with pytest.raises(ExpressionError, match="unknown function 'Piecewise'"):
        Namespace({"t": t}).parse("Piecewise((1, t < 1), (0, True))")
    with pytest.raises(ExpressionError, match="not allowed"):
        Namespace({"t": t}).parse("t < 1")
    assert answers_namespace(load_problem_text(ROD, "p.yaml")).piecewise
    laws = ROD.split("questions:")[0] + (
        "questions:\n  - {type: forward_dynamics, duration: 1, actuators: {C1: \"piecewise(t < 1, 1, 0)\"}}\n")
    with pytest.raises(InputError, match="piecewise"):
        load_problem_text(laws, "laws.yaml")
