"""Exact numbers of many digits are refused where they are written: exact arithmetic grows with
the size of its numbers, which no operation count sees (a 2R arm with a link of L1**999 m, 301
digits, spent 90 s of CPU in its equations of motion before the safety net answered numerically)."""

from __future__ import annotations

import pytest
import sympy as sp

from robosolve.errors import InputError
from robosolve.load.expressions import MAX_EXACT_DIGITS, exact_digits
from robosolve.load.loader import load_problem_text

ARM = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: %s}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: 0, q2: %s}}
"""


def issues(length, angle="0") -> list[str]:
    try:
        load_problem_text(ARM % (length, angle), "f.yaml")
    except InputError as exc:
        return [str(i) for i in exc.issues]
    return []


def test_an_exact_number_of_many_digits_is_refused_at_its_line():
    assert issues("'L1**999'") == [
        "f.yaml:3: parameters.L2: L1**999 is an exact number of 301 digits (about 1.87e-301): robosolve keeps "
        f"exact numbers of at most {MAX_EXACT_DIGITS} digits, whose arithmetic stays fast; write it as a "
        "decimal number"]
    assert issues("2/5", "'10**40'")[0].startswith("f.yaml:9: questions[0].at.q2: 10**40 is an exact number of 41")


@pytest.mark.parametrize("value", ["'L1**60'", "0.0125", "'deg(30)'", "'sqrt(2)/2'", "999999999999999999999999",
                                   "1e-300", "'1/3**20'"])
def test_the_numbers_of_an_exam_are_kept(value):
    assert issues(value) == []


def test_exact_digits_counts_the_longest_numerator_or_denominator():
    assert exact_digits(sp.Rational(1, 80) * sp.pi) == 2
    assert exact_digits(sp.Rational(1, 2) ** 999) == 301
    assert exact_digits(sp.sqrt(2) * 12345) == 5
