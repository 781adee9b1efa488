"""Whether the rank search of a Jacobian that is not square is attempted is a count (issue 22,
spec §2): the Jacobian's nodes times its maximal minors against `Budgets.rank_search_work`,
never the clock; an attempted search has the whole symbolic step time as its safety net, so a
UR5's 3×6 position Jacobian (7860) gives its singular conditions on every machine."""

from __future__ import annotations

import math

import pytest
import yaml

from conftest import PROBLEMS
from robosolve.core.simplify import expression_nodes
from robosolve.load.loader import load_problem, load_problem_text
from robosolve.model.chain import RobotModel
from robosolve.run.pipeline import solve_problem
from robosolve.solvers.base import Budgets, SolveContext
from robosolve.solvers.task_space import task_space


def _ur5_position_jacobian_text() -> str:
    data = yaml.safe_load((PROBLEMS / "ur5.yaml").read_text(encoding="utf-8"))
    q = next(q for q in data["questions"] if q["type"] == "jacobian")
    data["questions"] = [{"type": "jacobian", "coordinates": ["E.x", "E.y", "E.z"], "at": q["at"]}]
    data.pop("variants", None)
    return yaml.safe_dump(data, sort_keys=False)


def _jacobian(problem):
    ctx = SolveContext(problem, RobotModel(problem))
    q = problem.questions[0]
    return task_space(q, ctx, 60, geometric=q.options.get("geometric", False)).J


def test_the_ur5_position_jacobian_is_under_the_count():
    J = _jacobian(load_problem_text(_ur5_position_jacobian_text(), "ur5j.yaml"))
    assert J.shape == (3, 6)
    work = expression_nodes((J,)) * math.comb(6, 3)
    assert work <= Budgets().rank_search_work, work


def _redundant():
    problem = load_problem(PROBLEMS / "planar-3r-redundant.yaml")
    problem.questions = [q for q in problem.questions if q.id == "jacobian"]
    return problem


def test_past_the_count_the_search_is_not_attempted_and_says_so():
    problem = _redundant()
    J = _jacobian(problem)
    work = expression_nodes((J,)) * 3
    [ans] = solve_problem(problem, Budgets(rank_search_work=work - 1)).answers
    assert "singularities" not in ans.symbolic
    [note] = [n for n in ans.notes if "stopped" in str(n)]
    assert f"count {work:,}, above the budget of {work - 1:,}: a count" in str(note)
    [ans] = solve_problem(_redundant(), Budgets(rank_search_work=work)).answers
    assert "singularities" in ans.symbolic and not any("stopped" in str(n) for n in ans.notes)


def test_the_count_decides_not_the_step_seconds(monkeypatch):
    """The quarter step of a 5+ joint arm is not the net of an attempted rank search: the net
    of a counted search is the whole symbolic_seconds, whatever the step's."""
    from robosolve.solvers import base, jacobian

    seen = []
    real = jacobian.limited

    def spy(ctx, seconds, fn, *args, **kwargs):
        seen.append((fn.__name__, seconds))
        return real(ctx, seconds, fn, *args, **kwargs)

    monkeypatch.setattr(jacobian, "limited", spy)
    monkeypatch.setattr(base.SolveContext, "step_seconds", property(lambda self: 1e-9))
    [ans] = solve_problem(_redundant(), Budgets(symbolic_seconds=123.0)).answers
    assert ("find_singularities", 123.0) in seen
    assert "singularities" in ans.symbolic


@pytest.mark.slow
def test_the_ur5_position_jacobian_gets_its_singular_conditions():
    [ans] = solve_problem(load_problem_text(_ur5_position_jacobian_text(), "ur5j.yaml")).answers
    assert ans.error is None and not any("stopped" in str(n) for n in ans.notes), ans.notes
    assert ans.symbolic.get("singularities")
