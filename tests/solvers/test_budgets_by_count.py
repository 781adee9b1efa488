"""Whether a symbolic step is attempted is decided by counts (expression nodes, ring terms,
operation counts), never by the clock (spec §2): on a normal exam the time limits are safety nets
that are not reached, so the answers are the same with every time limit made huge, and a counted
budget made tiny changes the outcome the same way on every machine."""

from dataclasses import replace
from pathlib import Path

import pytest
import sympy as sp

from robosolve.load.loader import load_problem, load_problem_text
from robosolve.run.pipeline import solve_problem
from robosolve.solvers.base import Budgets

ROOT = Path(__file__).resolve().parents[2]
HUGE = Budgets(symbolic_seconds=1e6, closed_form_seconds=1e6, dynamics_seconds=1e6,
               question_seconds=1e6, file_seconds=1e6,
               simplify=replace(Budgets().simplify, chain_seconds=1e6))


def _flange_problem():
    """problems/ur5.yaml's robot with its flange position Jacobian (3×6) only."""
    text = (ROOT / "problems" / "ur5.yaml").read_text(encoding="utf-8")
    head, questions = text.split("\nquestions:\n")
    keep = questions.splitlines(keepends=True)
    start = next(i for i, line in enumerate(keep) if "jacobian-flange" in line)
    return load_problem_text(head + "\nquestions:\n" + keep[start], "ur5-flange.yaml")


def _outcome(report):
    return [(a.id, a.error, sp.srepr(a.symbolic) if a.symbolic else "", repr(a.numeric), [str(n) for n in a.notes])
            for a in report.answers]


@pytest.mark.parametrize("name", ["exam-2r-full"])
def test_a_normal_exam_does_not_depend_on_the_time_limits(name):
    problem = load_problem(ROOT / "problems" / f"{name}.yaml")
    assert _outcome(solve_problem(problem)) == _outcome(solve_problem(problem, HUGE))


@pytest.mark.slow
def test_the_wide_jacobian_rank_conditions_do_not_depend_on_the_time_limits():
    problem = _flange_problem()
    default = solve_problem(problem)
    (answer,) = default.answers
    assert answer.error is None and answer.symbolic.get("singularities")
    assert not any("not derived" in str(n) for n in answer.notes)
    assert _outcome(default) == _outcome(solve_problem(problem, HUGE))


def test_a_tiny_counted_budget_gives_the_distance_from_singularity():
    (answer,) = solve_problem(_flange_problem(), Budgets(rank_terms=10)).answers
    assert "singularities" not in answer.symbolic
    notes = " ".join(str(n) for n in answer.notes)
    assert "a count, so the outcome is the same on every machine" in notes
    assert "smallest singular value of J" in notes
    assert answer.numeric["manipulability"] > 0
