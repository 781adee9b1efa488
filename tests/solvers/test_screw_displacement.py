"""`displacement` given a screw (axis, angle, through, translation) against independent
references: scipy's matrix exponential of the twist L, spatialmath's Twist3, and round trips
through the from/to form (robosolve's own inverse formulas, named as such)."""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.linalg import expm

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem

HEAD = "robosolve: 1\nname: s\nparameters: {a: 2, k: ~}\nquestions:\n"


def solve(*questions):
    text = HEAD + "".join(f"  - {q}\n" for q in questions)
    return {a.id: a for a in solve_problem(load_problem_text(text)).answers}


def screw(axis, angle, through=(0, 0, 0), h=0, qid="s"):
    q = (f"{{id: {qid}, type: displacement, axis: {list(axis)}, angle: '{angle}', through: {list(through)},"
         f" translation: '{h}'}}")
    return solve(q)[qid]


CASES = [((1, 1, 1), "2*pi/3", (1, 0, 0), "1"),
         ((0, 0, 2), "-pi/2", (1, 1, 5), "3"),
         ((3, -4, 12), "1.3", (0.2, -1, 0.5), "-0.7"),
         ((1, 2, 2), "5", (1, 1, 1), "0.25"),          # beyond pi: flips
         ((0, 1, 0), "pi", (1, 0, 0), "-1"),
         ((1, 0, 0), "-pi", (0, 2, 0), "0.5"),
         ((1, -1, 0), "7*pi/3", (0, 0, 1), "2")]       # more than a turn


@pytest.mark.parametrize("axis,angle,through,h", CASES)
def test_q_is_the_exponential_of_alpha_l(axis, angle, through, h):
    a = screw(axis, angle, through, h)
    assert a.error is None, a.error
    n = a.numeric
    assert 0 <= n["alpha"] <= math.pi + 1e-15
    assert np.allclose(expm(n["alpha"] * np.array(n["L"])), n["Q"], atol=1e-12)


@pytest.mark.parametrize("axis,angle,through,h", CASES)
def test_q_against_spatialmath_twist(axis, angle, through, h):
    sm = pytest.importorskip("spatialmath")
    th = float(sp.sympify(angle))
    w = np.array(axis, float) / np.linalg.norm(axis)
    tw = sm.Twist3.UnitRevolute(w, np.array(through, float), float(h) / th)   # pitch of the given screw
    a = screw(axis, angle, through, h)
    assert np.allclose(tw.exp(th).A, a.numeric["Q"], atol=1e-12)


@pytest.mark.parametrize("axis,angle,through,h", CASES)
def test_round_trip_through_the_from_to_form(axis, angle, through, h):
    # robosolve's own from/to form (itself checked against spatialmath elsewhere)
    a = screw(axis, angle, through, h)
    # the exact (symbolic) Q: the loader checks that a given matrix is a rototranslation
    q = [[f"'{x}'" for x in row] for row in sp.Matrix(a.symbolic["Q"]).tolist()]
    rows = "[" + ", ".join("[" + ", ".join(r) + "]" for r in q) + "]"
    eye = "[[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]"
    back = solve(f"{{id: b, type: displacement, from: {eye}, to: {rows}}}")["b"]
    for key in ("u", "alpha", "h", "P", "pitch"):
        assert np.allclose(back.numeric[key], a.numeric[key], atol=1e-9), key


def test_exact_data_give_exact_answers_and_the_spec_normalisation():
    a = screw((0, 0, 2), "-pi/2", (1, 1, 5), "1/10")
    s = a.symbolic
    assert [str(x) for x in s["u"]] == ["0", "0", "-1"]          # a negative angle flips u ...
    assert str(s["alpha"]) == "pi/2" and str(s["h"]) == "-1/10"   # ... and h with it
    assert [str(x) for x in s["P"]] == ["1", "1", "0"]           # the axis point nearest the origin
    assert str(s["pitch"]) == "-1/(5*pi)"
    rz = sp.Matrix([[0, 1, 0], [-1, 0, 0], [0, 0, 1]])            # rotation by -pi/2 about z
    assert sp.Matrix(s["Q"])[:3, :3] == rz
    # (I - R) P + h u with the given data
    assert list(sp.Matrix(s["Q"])[:3, 3]) == list((sp.eye(3) - rz) * sp.Matrix([1, 1, 5])
                                                   + sp.Rational(1, 10) * sp.Matrix([0, 0, 1]))


def test_half_turn_keeps_the_axis_with_a_positive_first_component():
    a = screw((-1, 0, 0), "pi", (0, 2, 0), "1")
    assert [str(x) for x in a.symbolic["u"]] == ["1", "0", "0"]
    assert str(a.symbolic["h"]) == "-1"


def test_whole_turns_are_a_translation_or_the_identity():
    a = screw((0, 2, 0), "2*pi", (1, 1, 1), "-3")
    assert a.numeric["u"] == [0.0, -1.0, 0.0] and a.numeric["h"] == 3.0 and a.numeric["alpha"] == 0.0
    assert a.numeric["P"] is None and a.numeric["pitch"] is None
    assert np.allclose(a.numeric["L"], [[0, 0, 0, 0], [0, 0, 0, -1], [0, 0, 0, 0], [0, 0, 0, 0]])
    assert np.allclose(expm(3 * np.array(a.numeric["L"])), a.numeric["Q"])
    b = screw((0, 0, 1), "0", (1, 1, 1), "0")
    assert b.numeric["Q"] == np.eye(4).tolist() and b.numeric["u"] is None and b.numeric["L"] == [[0.0] * 4] * 4


def test_parameters_and_null_parameters():
    a = solve("{id: p, type: displacement, axis: [0, 0, 1], angle: pi/a, translation: a}")["p"]
    assert str(a.symbolic["alpha"]) == "pi/a" and a.numeric["alpha"] == pytest.approx(math.pi / 2)
    b = solve("{id: p, type: displacement, axis: [0, 0, 1], angle: pi/3, translation: k}")["p"]
    assert b.numeric == {} and any("k" in n for n in b.notes) and str(b.symbolic["h"]) == "k"


def issues(*questions):
    with pytest.raises(InputError) as exc:
        load_problem_text(HEAD + "".join(f"  - {q}\n" for q in questions), "f.yaml")
    return [str(i) for i in exc.value.issues]


def test_input_errors():
    assert any("zero vector" in m for m in issues("{type: displacement, axis: [0, 0, 0], angle: 1}"))
    assert any("not both" in m for m in issues("{type: displacement, axis: [0, 0, 1], angle: 1,"
                                               " from: [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}"))
    assert any("missing required key 'angle'" in m for m in issues("{type: displacement, axis: [0, 0, 1]}"))
    assert any("give its axis" in m for m in issues("{type: displacement, angle: 1}"))
    msgs = issues("{type: displacement}")
    assert any("missing required keys 'from' and 'to'" in m for m in msgs) and all(m.startswith("f.yaml:") for m in msgs)


def test_principal_keys_depend_on_the_form():
    from robosolve.questions.registry import QUESTION_TYPES

    qt = QUESTION_TYPES["displacement"]
    assert qt.principal_keys_for({"axis": [0, 0, 1], "angle": 1}) == ("Q", "L")
    assert qt.principal_keys_for({"from": {}, "to": {}}) == ("u", "alpha", "h", "P")


def test_grading_reference_grades_q_and_l_given_a_screw():
    from robosolve.grading.reference import Reference

    text = HEAD + ("  - {id: s, type: displacement, axis: [0, 0, 1], angle: pi/2}\n"
                   "  - {id: m, type: displacement, from: [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]],"
                   " to: [[0,-1,0,0],[1,0,0,0],[0,0,1,0],[0,0,0,1]]}\n")
    ref = Reference.from_report(solve_problem(load_problem_text(text)))
    assert ref.question("s").graded_keys() == ("Q", "L")
    assert ref.question("m").graded_keys() == ("u", "alpha", "h", "P")
