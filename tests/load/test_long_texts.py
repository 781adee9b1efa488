"""Long texts in answers files (which may hold 1 MB): read in linear time, quoted short.

An answers file's expressions are bounded only by the file's size, so the hints given for a text
that does not parse must not take quadratic time (a 100,001-digit number once hung `check`), and
a message quotes at most a few dozen characters of the text, not the whole megabyte.
"""

from __future__ import annotations

import time

import pytest
import sympy as sp

from robosolve.grading.values import ANSWER_MAX_CHARS, ANSWER_MAX_NODES, Reader, ValueProblem
from robosolve.load.expressions import ExpressionError, Namespace, shown
from robosolve.questions import registry as R
from robosolve.questions.schema import AnswerKey

N = 100_001


def _answers_ns():
    return Namespace({"q1": sp.Symbol("q1", real=True)}, ("E",), max_chars=ANSWER_MAX_CHARS,
                     max_nodes=ANSWER_MAX_NODES)


LONG = {"digits": "9" * N, "digits deg": "9" * N + " deg", "decimal comma": "9" * N + ",5",
        "dots": "1." * (N // 2), "parentheses": "(" * N, "a name": "a" * N, "brackets": "[" * N}


@pytest.mark.parametrize("text", LONG.values(), ids=LONG.keys())
def test_a_long_text_is_refused_quickly_with_a_short_message(text):
    start = time.process_time()
    with pytest.raises(ExpressionError) as err:
        _answers_ns().parse_text(text)
    assert time.process_time() - start < 2.0
    assert len(str(err.value)) < 700, str(err.value)[:300]


def test_the_degree_hint_and_the_decimal_hint_still_read_the_number():
    with pytest.raises(ExpressionError, match=r"write deg\(30\)"):
        _answers_ns().parse_text("30 deg")
    with pytest.raises(ExpressionError, match=r"write deg\(12.5\)"):
        _answers_ns().parse_text("q1 + 12.5°")
    with pytest.raises(ExpressionError, match=r"with a point: 1\.5"):
        _answers_ns().parse_text("1,5")


def test_a_long_typed_matrix_that_does_not_read_is_quoted_short():
    reader = Reader(_answers_ns())
    key = AnswerKey("position", R.VECTOR, "a point")
    with pytest.raises(ValueProblem) as err:
        reader.array_text(key, "[[" + "1;" * 50_000 + "], 0, 0]")
    assert len(str(err.value)) < 700


def test_shown_keeps_short_texts_and_elides_the_middle_of_long_ones():
    assert shown("L1*cos(q1)") == "L1*cos(q1)"
    long = "a" * 100 + "b" * 1000 + "c" * 100
    assert shown(long) == "a" * 100 + "…" + "c" * 100
