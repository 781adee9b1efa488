"""The answers template round trip over every bundled problem (papers.md "The answers template"):
blank -> every graded key `missing` (exit 1, never 2); filled from the golden results.json ->
every graded key `correct`. The reference is rebuilt from the golden results.json (no solve)."""

from __future__ import annotations

import json
from types import SimpleNamespace

import pytest
import sympy as sp
import yaml

from conftest import PROBLEMS, ROOT
from robosolve.grading.answers import read_answers_text, resolve_answers
from robosolve.grading.grader import Grader
from robosolve.grading.reference import Reference, lookup
from robosolve.load.loader import load_problem
from robosolve.papers.keys import graded_keys
from robosolve.papers.template import render_template

FILES = sorted(PROBLEMS.glob("*.yaml"))


def _sym(tree, names):
    if isinstance(tree, dict):
        return {k: _sym(v, names) for k, v in tree.items()}
    if isinstance(tree, list):
        return [_sym(v, names) for v in tree]
    if isinstance(tree, str):
        try:
            return sp.sympify(tree, locals=names)
        except (sp.SympifyError, AttributeError, TypeError, SyntaxError):
            return tree
    return tree


def golden_reference(problem) -> tuple[Reference, dict]:
    results = json.loads((ROOT / "tests" / "golden" / problem.name / "results.json").read_text())["answers"]
    answers = []
    for q in problem.questions:
        r = results[q.id]
        extra = {k: v for k, v in r.items() if k not in ("type", "symbolic", "numeric", "figures", "notes", "error")}
        answers.append(SimpleNamespace(id=q.id, error=r.get("error"), symbolic=_sym(r.get("symbolic", {}), problem.names),
                                       numeric=r.get("numeric", {}), extra=extra))
    return Reference.from_report(SimpleNamespace(problem=problem, answers=answers, model=None)), results


def _grade(problem, ref, text):
    sub = resolve_answers(read_answers_text(text, "answers.yaml"), problem)
    return Grader(ref).grade(sub.student, sub.answers)


def _filled(problem, results) -> dict:
    data = {}
    for q in problem.questions:
        r = results[q.id]
        data[q.id] = {}
        for gk in graded_keys(q, problem):
            value = r.get(gk.key) if gk.answer_key.top else lookup(r.get("numeric", {}), gk.key)
            if value is None:
                value = lookup(r.get("symbolic", {}), gk.key)
            data[q.id][gk.key] = value
    return data


# the Panda's round trip (9 s: its 7x7 symbolic matrices) runs with the long checks
@pytest.mark.parametrize("file", [pytest.param(f, marks=pytest.mark.slow) if f.stem == "panda" else f
                                  for f in FILES], ids=[f.stem for f in FILES])
def test_template_round_trip(file):
    problem = load_problem(file)
    ref, results = golden_reference(problem)
    text = render_template(problem, "problem.yaml")
    # the template's keys are the graded keys of the reference, in order, and the keys the
    # reference lacks at these values (a singular configuration: no condition number)
    for q, qref in zip(problem.questions, ref.questions):
        keys = tuple(g.key for g in graded_keys(q, problem))
        assert tuple(k for k in keys if qref.has(k) or qref.error) == qref.graded_keys(), q.id
    blank = _grade(problem, ref, text)
    assert not blank.all_correct
    for qr in blank.questions:
        for key in qr.graded:
            assert qr.keys[key].verdict in ("missing", "no_reference"), (qr.id, key, qr.keys[key])
            if qr.keys[key].verdict == "missing":
                assert "still ~" in qr.keys[key].feedback
    data = yaml.safe_load(text)
    filled = _filled(problem, results)
    for qid, keys in data["answers"].items():
        for key in keys:
            if filled[qid][key] is not None:
                keys[key] = filled[qid][key]
    result = _grade(problem, ref, yaml.safe_dump(data, allow_unicode=True))
    bad = [(qr.id, k, qr.keys[k]) for qr in result.questions for k in qr.graded
           if qr.keys[k].verdict != "correct"]
    assert not bad
    assert result.all_correct


def test_every_key_a_question_may_grade_has_a_place_in_its_template(tmp_path):
    """A question may grade (`grade:`) exactly the keys an answers file can hold, so its
    template reads back with every key blank (check exits 1, never 2): a record's field
    (force.lengths) yes; a field of the records of a mapping (joint_torques' actuators.peak:
    one record per actuator) is refused where the problem is read — it was accepted, and `check`
    on the untouched template then exited 2 ('unknown answer key')."""
    import re

    from robosolve.errors import InputError
    from robosolve.grading.answers import known_keys
    from robosolve.load.loader import load_problem_text
    from robosolve.questions.registry import QUESTION_TYPES
    from test_statements import EXAM

    head, _, rest = EXAM.partition("questions:\n")
    items = []                                   # one line per question (flow mappings joined)
    for line in rest.splitlines():
        if line.startswith("  - "):
            items.append(line)
        elif line.strip():
            items[-1] += " " + line.strip()
    by_type = {}
    for item in items:
        by_type.setdefault(re.search(r"type: (\w+)", item).group(1), item)
    graded = []
    for name, qt in QUESTION_TYPES.items():
        for key in known_keys(qt):
            # a copy of the type's question grading `key` alone, where that question computes it
            # (a key it does not compute, max_task_error without a trajectory, is refused: its test
            # is tests/questions/test_type_checks.py)
            if not qt.key(key).top:
                line = re.sub(r"id: [\w-]+, ", "", by_type[name]).replace("{type:", f"{{grade: [{key}], type:", 1)
                try:
                    load_problem_text(head + "questions:\n" + "\n".join(items + [line]) + "\n", "one.yaml")
                except InputError as exc:
                    assert "is not an answer of this question" in str(exc), str(exc)
                    continue
                graded.append(line)
    text = head + "questions:\n" + "\n".join(items + graded) + "\n"
    problem = load_problem_text(text, str(tmp_path / "every-key.yaml"))
    blank = resolve_answers(read_answers_text(render_template(problem, "every-key.yaml"), "answers.yaml"), problem)
    assert len(blank.answers) == len(problem.questions)
    with pytest.raises(InputError, match=r"unknown answer key 'actuators.peak' for a joint_torques question"):
        load_problem_text(text.replace("grade: [profiles], type: joint_torques", "grade: [actuators.peak], type: joint_torques"),
                          str(tmp_path / "refused.yaml"))


def test_profiles_given_back_as_the_reference_writes_them():
    """A teacher may grade the profiles (`grade: [profiles]`): the reference's own piecewise
    profiles, given back from results.json, are right (they were `invalid`: the answers' parser
    had no Piecewise). Robosolve against itself, named as such; the profiles' correctness is
    checked against closed forms in tests/workflows/test_grading_profiles.py."""
    problem = load_problem(PROBLEMS / "exam-2r-full.yaml")
    for q in problem.questions:
        if q.type in ("motion_profile", "joint_torques"):
            q.grade = ["profiles"]
    ref, results = golden_reference(problem)
    answers = {q: {"profiles": results[q]["symbolic"]["profiles"]} for q in ("profile", "joint_torques")}
    text = yaml.safe_dump({"robosolve-answers": 1, "student": "s1", "answers": answers}, width=10**6)
    result = _grade(problem, ref, text)
    verdicts = {qr.id: qr.keys["profiles"].verdict for qr in result.questions if "profiles" in qr.keys}
    assert verdicts == {"profile": "correct", "joint_torques": "correct"}
