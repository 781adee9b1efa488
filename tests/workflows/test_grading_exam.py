"""The example answers of the full exam (problems/answers/), graded against a single solve.

The answers were worked by hand from the problem statement (docs/grading.md shows the
session); five mistakes are deliberate, and every other answer is right though written in
another form than robosolve's (expanded addition formulas, factored masses, grouped rates).
"""

from __future__ import annotations

from fractions import Fraction

import pytest

from robosolve.grading.answers import read_answers, resolve_answers
from robosolve.grading.grader import Grader
from robosolve.grading.reference import Reference
from robosolve.load.loader import load_problem
from robosolve.run.pipeline import solve_problem
from tests._grading import key

from conftest import PROBLEMS

EXAMPLE = PROBLEMS / "answers" / "exam-2r-full-student.yaml"


@pytest.fixture(scope="module")
def result():
    sub = read_answers(EXAMPLE)
    problem = load_problem(sub.problem_file)
    resolve_answers(sub, problem)
    ref = Reference.from_report(solve_problem(problem))
    return Grader(ref).grade(sub.student, sub.answers)


MISTAKES = {
    ("position", "M"): ("incorrect", "transposed"),
    ("jacobian", "det"): ("incorrect", "parameters_substituted"),
    ("statics", "Fq"): ("incorrect", "negated"),
    ("inverse_kinematics", "solutions"): ("incorrect", "degrees"),
    ("profile", "T"): ("incorrect", ""),
}


def test_the_deliberate_mistakes_are_named(result):
    for (q, k), (verdict, diagnosis) in MISTAKES.items():
        r = key(result, q, k)
        assert (r.verdict, r.diagnosis) == (verdict, diagnosis), (q, k, r)


def test_everything_else_is_right(result):
    for q in result.questions:
        for k, r in q.keys.items():
            if (q.id, k) not in MISTAKES:
                assert r.verdict == "correct", (q.id, k, r)
    assert result.student == "s123456"
    # 11 questions of 1 mark; lost: half of position, a third of jacobian, statics, IK, a third of profile
    assert result.max_score == 11
    assert result.score == 11 - (Fraction(1, 2) + Fraction(1, 3) + 1 + 1 + Fraction(1, 3))
