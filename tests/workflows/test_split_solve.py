"""A problem's questions on two cores (robosolve/split_solve.py): the plan, the helper's
failures, the file budget's clock, and the same report as one process.

The references: the plan is checked against its rules (units together, every question once,
no split of a cheap problem); the reports against robosolve's own one-process solve (what
`batch` and the golden files give), which the solver tests check against independent tools —
these tests check that splitting changes no byte."""

from __future__ import annotations

import os
import time
from pathlib import Path
from types import SimpleNamespace

import pytest

from robosolve.load.loader import load_problem
from robosolve.run.pipeline import _FileClock, render_files, solve_problem
from robosolve.questions.registry import QUESTION_TYPES
from robosolve.solvers.base import Answer
from robosolve.run.split_solve import MIN_SPLIT_COST, QuestionHelper, plan, question_cost

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(autouse=True)
def _no_other_threads(monkeypatch):
    """Earlier tests of the session may leave a thread behind (a Dask client's event loop),
    and a helper is then not forked at all (robosolve.core.processes): these tests fork anyway."""
    import threading

    monkeypatch.setattr(threading, "active_count", lambda: 1)


def _questions(*types):
    return [SimpleNamespace(type=t) for t in types]


def test_the_plan_keeps_each_unit_together_and_every_question_once():
    qs = _questions("position", "velocity_acceleration", "motion_profile", "jacobian", "equations_of_motion",
                    "joint_torques", "inverse_kinematics", "statics")
    helper = plan(qs, 3)
    assert helper is not None and helper == sorted(helper)
    parent = [i for i in range(len(qs)) if i not in helper]
    units = {i for i, q in enumerate(qs) if QUESTION_TYPES[q.type].unit == "dynamics"}
    assert units <= set(helper) or units <= set(parent)
    cost = [question_cost(q, 3) for q in qs]
    assert sum(cost[i] for i in helper) <= sum(cost[i] for i in parent) + 1e-9
    assert sum(cost[i] for i in helper) >= MIN_SPLIT_COST


def test_no_split_when_it_does_not_pay():
    assert plan(_questions("position"), 3) is None
    assert plan(_questions("dof", "dof", "displacement"), 0) is None
    # one unit only: the dynamics' questions share one derivation
    assert plan(_questions("equations_of_motion", "joint_torques", "motion_profile"), 6) is None


def test_costs_grow_with_the_joints():
    q = _questions("equations_of_motion")[0]
    assert question_cost(q, 6) > 4 * question_cost(q, 3) > 0
    assert question_cost(_questions("no_such_type")[0], 3) == 0.0


def _answer(i):
    return Answer("position", f"q{i}", numeric={"value": i})


def test_the_helper_sends_what_it_can_and_nothing_else():
    def solve_one(i):
        if i == 2:
            os._exit(3)             # the helper dies on its third question
        answer = _answer(i)
        if i == 1:
            answer.extra["x"] = lambda: None        # not picklable
        return answer

    helper = QuestionHelper([0, 1, 2, 3], solve_one)
    got = helper.arrived(wait=True)
    assert sorted(got) == [0] and got[0].numeric == {"value": 0}
    assert helper._process is None      # stopped and waited for


def test_the_helpers_clock_counts_the_parents_time_before_the_fork():
    clock = _FileClock()
    end = time.process_time() + 0.2
    while time.process_time() < end:
        pass
    clock.mark_fork()
    helper = QuestionHelper([0], lambda i: Answer("position", "q", numeric={"spent": clock.spent()}))
    spent = helper.arrived(wait=True)[0].numeric["spent"]
    assert spent >= 0.2


PROBLEM = ROOT / "problems" / "planar-2r-rods.yaml"    # Jacobian, statics, ellipsoids: a split


@pytest.fixture(scope="module")
def whole_files():
    """The files of a solve in one process (the reference of the two tests below)."""
    return render_files(solve_problem(load_problem(PROBLEM)), ("md", "html"))


def test_a_split_solve_writes_the_same_files(whole_files):
    problem = load_problem(PROBLEM)
    assert plan(problem.questions, len(problem.joints)) is not None
    assert render_files(solve_problem(problem, split=True), ("md", "html")) == whole_files
    # results.json printed by a forked helper while the Markdown is printed here
    assert render_files(solve_problem(problem, split=True), ("md", "html"), parallel=True) == whole_files


def test_a_text_helper_that_fails_leaves_the_text_to_the_parent():
    from robosolve.run.split_solve import TextHelper

    assert TextHelper(lambda: "é" * 3).text() == "ééé"
    assert TextHelper(lambda: 1 / 0).text() is None


def test_a_question_the_helper_does_not_send_is_solved_by_the_parent(monkeypatch, whole_files):
    import robosolve.run.split_solve as split_solve

    monkeypatch.setattr(split_solve, "_unpickled", lambda data: None)     # every answer lost
    problem = load_problem(PROBLEM)
    split = solve_problem(problem, split=True)
    assert [a.id for a in split.answers] == [q.id for q in problem.questions]
    assert render_files(split, ("md", "html")) == whole_files


def test_no_helper_beside_another_thread(monkeypatch):
    import threading

    monkeypatch.setattr(threading, "active_count", lambda: 2)
    helper = QuestionHelper([0, 1], _answer)
    assert helper.indices == [] and helper.arrived(wait=True) == {}


def test_a_unit_is_solved_again_whole():
    """A joint_torques answer lost on the way needs its motion profile solved in the parent too."""
    from robosolve.run.split_solve import to_solve_again

    qs = _questions("position", "motion_profile", "joint_torques", "jacobian", "inverse_kinematics")
    assert to_solve_again(qs, {0, 1, 3, 4}) == [1, 2]
    assert to_solve_again(qs, {0, 1, 2, 4}) == [3]
    assert to_solve_again(qs, {0, 1, 2, 3, 4}) == []


def test_a_wide_jacobian_weighs_its_rank_search():
    """A 6R flange's 3×6 position Jacobian costs more than the arm's 6×6 geometric one (its rank
    conditions come from a search over many minors); the bundled Panda's 6×7 Jacobian goes to one
    process and its equations of motion and IK to the other (they took 2.6 + 9.1 s CPU split the
    other way, and the Jacobian's 6.7 s alone is the shortest a split can make it)."""
    from robosolve.load.loader import load_problem

    wide = SimpleNamespace(type="jacobian", options={"geometric": False})
    square = SimpleNamespace(type="jacobian", options={"geometric": True})
    assert question_cost(wide, 6) > 2 * question_cost(square, 6)
    assert question_cost(wide, 3) == question_cost(square, 3)
    problem = load_problem("problems/panda.yaml")
    helper = plan(problem.questions, len(problem.joints))
    kinds = lambda side: {problem.questions[i].type for i in side}  # noqa: E731
    parent = [i for i in range(len(problem.questions)) if i not in helper]
    jac_side = helper if "jacobian" in kinds(helper) else parent
    assert kinds(jac_side) <= {"jacobian", "position"}


def test_markdown_printed_early_is_the_report_s(monkeypatch, whole_files):
    """Answers' blocks printed before the report, in another order, by render.markdown's
    MarkdownPrinter: the report uses them (no answer printed again) and writes the same files."""
    import robosolve.render.markdown as markdown
    from robosolve.render.results_json import planned_figures

    report = solve_problem(load_problem(PROBLEM))
    printer = markdown.MarkdownPrinter(report.problem, report.model)
    for i, answer in reversed(list(enumerate(report.answers, 1))):
        printer.answer_blocks(i, answer, planned_figures(answer) if answer.figures else [])
    report.printer = printer
    calls = []
    real = markdown.render_answer
    monkeypatch.setattr(markdown, "render_answer", lambda *a, **k: calls.append(a[1].id) or real(*a, **k))
    assert render_files(report, ("md", "html")) == whole_files
    assert calls == []


def test_the_parent_prints_while_the_helper_still_solves(monkeypatch, whole_files):
    """A slow helper: it prints its answers' Markdown (but the last one's), the parent prints the
    Markdown of its own answers meanwhile, the report prints none of those again, and the files
    are the same."""
    import robosolve.run.pipeline as pipeline

    parent, real = os.getpid(), pipeline._solve_question

    def slow_in_helper(q, ctx, seconds):
        if os.getpid() != parent:
            time.sleep(0.3)
        return real(q, ctx, seconds)

    printed = []
    real_one = pipeline._EarlyMarkdown.print_one
    monkeypatch.setattr(pipeline, "_solve_question", slow_in_helper)
    monkeypatch.setattr(pipeline._EarlyMarkdown, "print_one", lambda self: printed.append(1) or real_one(self))
    import robosolve.render.markdown as markdown

    calls = []
    real_answer = markdown.render_answer
    monkeypatch.setattr(markdown, "render_answer", lambda *a, **k: calls.append(a[1].id) or real_answer(*a, **k))
    report = solve_problem(load_problem(PROBLEM), split=True)
    assert printed and report.printer is not None
    # the helper's answers came with their blocks but the last one (printed here, while the helper
    # prints its record, or with the report), every one with its results.json record (the last
    # one's after it)
    mine = plan(report.problem.questions, len(report.problem.joints))
    ahead = {report.answers[i].id for i in mine[:-1]}
    assert all(report.answers[i].printed_markdown is not None for i in mine[:-1])
    assert report.answers[mine[-1]].printed_markdown is None
    assert all(report.answers[i].printed_record is not None for i in mine)
    assert not ahead & set(calls)
    calls.clear()
    assert render_files(report, ("md", "html"), parallel=True) == whole_files
    assert set(calls) <= {report.answers[mine[-1]].id}      # printed again at most the last
