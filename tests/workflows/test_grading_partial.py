"""Partial credit (grading.md "Grading a class"): `grading: {partial, entries}` in the problem
file, exact fractions, the verdict staying `incorrect`; bad sections are FILE:LINE errors."""

from __future__ import annotations

from fractions import Fraction

import pytest

from robosolve.errors import InputError
from robosolve.grading.record import grade_rows, record, summary_row
from robosolve.load.loader import load_problem_text
from tests._grading import dedent, grade_text, key, reference_of

ARM = """
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5, F: 5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}, grade: [M]}
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, marks: 3}
"""
M = [["cos(q1 + q2)", "-sin(q1 + q2)", 0, "L1*cos(q1) + L2*cos(q1 + q2)"],
     ["sin(q1 + q2)", "cos(q1 + q2)", 0, "L1*sin(q1) + L2*sin(q1 + q2)"],
     [0, 0, 1, 0], [0, 0, 0, 1]]
FQ_NEG = '{q1: "-F*(L1*cos(q1) + L2*cos(q1 + q2))", q2: "-F*L2*cos(q1 + q2)"}'


def answers(m) -> str:
    return f"robosolve-answers: 1\nstudent: s1\nanswers:\n  position: {{M: {m}}}\n  statics: {{Fq: {FQ_NEG}}}\n"


@pytest.fixture(scope="module")
def ref_partial():
    return reference_of(ARM + "grading:\n  partial: {negated: 1/3, transposed: 3/4}\n  entries: proportional\n")


@pytest.fixture(scope="module")
def ref_plain():
    return reference_of(ARM)


def test_diagnosis_share_is_exact_and_verdict_stays_incorrect(ref_partial, ref_plain):
    wrong_one = [row[:] for row in M]
    wrong_one[0][3] = "L1*cos(q1)"          # 1 of 16 entries wrong
    result = grade_text(ref_partial, answers(wrong_one))
    fq = key(result, "statics", "Fq")
    assert (fq.verdict, fq.diagnosis) == ("incorrect", "negated")
    statics = next(q for q in result.questions if q.id == "statics")
    assert statics.score == Fraction(1)     # 3 marks x 1/3, exactly
    pos = next(q for q in result.questions if q.id == "position")
    assert key(result, "position", "M").verdict == "incorrect"
    assert pos.score == Fraction(15, 16)    # entries: proportional
    assert result.score == Fraction(31, 16)
    rows = {(r[1], r[2]): r for r in grade_rows(result)}
    assert rows[("statics", "Fq")][5:] == ("1", "3")
    assert rows[("position", "M")][5:] == ("0.9375", "1")
    assert summary_row(result) == ("s1", "1.9375", "4", "48.4")
    assert record(result)["score"] == 1.9375
    # without a `grading.partial`, the same answers earn nothing
    plain = grade_text(ref_plain, answers(wrong_one))
    assert plain.score == 0


def test_diagnosis_share_wins_when_larger(ref_partial):
    # M transposed: 6 of 16 entries wrong (the off-diagonal sines and the origin), 10/16 = 5/8 right;
    # the diagnosis share 3/4 is larger
    transposed = [list(col) for col in zip(*M)]
    result = grade_text(ref_partial, answers(transposed))
    assert key(result, "position", "M").diagnosis == "transposed"
    assert next(q for q in result.questions if q.id == "position").score == Fraction(3, 4)
    # a negated M: `negated` earns 1/3, but its 8 zero entries of 16 stay right: 1/2 wins
    negated = [[f"-({x})" for x in row] for row in M]
    result = grade_text(ref_partial, answers(negated))
    assert key(result, "position", "M").diagnosis == "negated"
    assert next(q for q in result.questions if q.id == "position").score == Fraction(1, 2)


@pytest.mark.parametrize("section, message", [
    ("partial: {negated: 1.5}", "grading.partial.negated: expected a share between 0 and 1, got 1.5"),
    ("partial: {negated: -0.5}", "grading.partial.negated: expected a share between 0 and 1"),
    ("partial: {negatd: 0.5}", "unknown diagnosis 'negatd' (did you mean 'negated'?)"),
    ("entries: proportionl", "grading.entries: expected one of: all, proportional, got 'proportionl' "
                             "(did you mean 'proportional'?)"),
    ("partial: [negated]", "grading.partial: expected a mapping diagnosis -> share"),
])
def test_bad_grading_sections(section, message):
    text = dedent(ARM) + f"grading:\n  {section}\n"
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    line = text.splitlines().index(f"  {section}") + 1
    assert str(exc.value).startswith(f"p.yaml:{line}: ") and message in str(exc.value)
    assert len(exc.value.issues) == 1


def test_diagnoses_of_the_loader_are_the_graders():
    from robosolve.grading.diagnose import ORDER
    from robosolve.load.grading_options import DIAGNOSES

    assert set(ORDER) <= set(DIAGNOSES)


def test_a_wrong_shape_earns_its_share_however_it_is_found():
    """`wrong_shape` is one diagnosis whether the shape is refused as the value is read (three
    values for the two joints of Fq) or found comparing (a 4x3 M for the 4x4): with a share for
    it, both earn it (the first earned nothing)."""
    ref = reference_of(ARM + "grading:\n  partial: {wrong_shape: 1/4}\n")
    m_cut = [row[:3] for row in M]
    text = (f"robosolve-answers: 1\nstudent: s1\nanswers:\n  position: {{M: {m_cut}}}\n"
            "  statics: {Fq: [2.165, 0, 0]}\n")
    result = grade_text(ref, text)
    for question, name in (("position", "M"), ("statics", "Fq")):
        k = key(result, question, name)
        assert (k.verdict, k.diagnosis) == ("invalid", "wrong_shape"), (question, k)
    scores = {q.id: q.score for q in result.questions}
    assert scores == {"position": Fraction(1, 4), "statics": Fraction(3, 4)}
