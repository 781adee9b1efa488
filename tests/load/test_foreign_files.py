"""Another kind of file given where a problem or an answers file is expected (a compose file, a
results.json, a result record, a notebook, an empty mapping): one message that says what the file
is, not one for every key it has and every key it lacks (five for a compose file)."""

from __future__ import annotations

import json

import pytest

from robosolve.errors import InputError
from robosolve.grading.answers import read_answers_text
from robosolve.load.loader import load_problem_text

PROBLEM = "a problem file (a mapping with `robosolve: 1`, `name` and `questions`)"
ANSWERS = "an answers file (a mapping with `robosolve-answers: 1`, `problem` and `answers`)"
FILES = {
    "compose": ("version: '3'\nservices: {web: {image: nginx}}\nvolumes: {}\n",
                "not {}: none of its keys (version, services, volumes) is one of them"),
    "results.json": (json.dumps({"format": 1, "problem": "arm", "answers": {"position": {"type": "position"}}}),
                     "this is a results.json (the answers `robosolve solve` writes), not {}"),
    "record": (json.dumps({"format": 1, "problem": "arm", "student": "s1", "score": 1, "max_score": 2,
                           "questions": {}}),
               "this is a result record (what `robosolve check --json` and `grade` write), not {}"),
    "notebook": (json.dumps({"cells": [], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}),
                 "this is a Jupyter notebook, not {}"),
    "empty": ("{}\n", "the file is an empty mapping: expected {}"),
}


def issues(read, text) -> list[str]:
    with pytest.raises(InputError) as exc:
        read(text, "f.yaml")
    return [str(i) for i in exc.value.issues]


@pytest.mark.parametrize("kind", FILES)
def test_another_file_as_a_problem_is_one_message(kind):
    text, message = FILES[kind]
    assert issues(load_problem_text, text) == ["f.yaml:1: " + message.format(PROBLEM)]


@pytest.mark.parametrize("kind", FILES)
def test_another_file_as_answers_is_one_message(kind):
    text, message = FILES[kind]
    assert issues(read_answers_text, text) == ["f.yaml:1: " + message.format(ANSWERS)]


def test_a_file_with_one_key_of_ours_is_judged_key_by_key():
    assert issues(load_problem_text, "name: arm\nversion: 3\n") == [
        "f.yaml:1: missing required key 'robosolve'",
        "f.yaml:2: version: unknown key 'version' (did you mean 'questions'?) (expected one of: robosolve, "
        "name, title, description, parameters, joints, frames, dh, points, gravity, bodies, forces, questions, "
        "grading, variants, paper)"]
