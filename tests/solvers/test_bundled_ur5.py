"""problems/ur5.yaml: the inverse-kinematics target does not give away another question's
numbers (it is reached from a configuration no other question uses), all 8 solutions exist,
and its closed forms print whole numbers as integers (no 1.0*px)."""

import re
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem

ROOT = Path(__file__).resolve().parents[2]
WHOLE_FLOAT = re.compile(r"(?<![\d.])\d+\.0+(?![\d])")


def _only(kind):
    text = (ROOT / "problems" / "ur5.yaml").read_text(encoding="utf-8")
    head, questions = text.split("\nquestions:\n")
    lines = questions.splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if f"type: {kind}" in line)
    end = next((i for i in range(start + 1, len(lines)) if lines[i].lstrip().startswith("- ")), len(lines))
    return load_problem_text(head + "\nquestions:\n" + "".join(lines[start:end]), f"ur5-{kind}.yaml")


@pytest.mark.slow
def test_the_target_is_not_the_position_answer_and_has_eight_solutions():
    ik = _only("inverse_kinematics")
    (answer,) = solve_problem(ik).answers
    assert answer.error is None and len(answer.numeric["solutions"]) == 8
    target = np.array(ik.questions[0].options["target"].p, dtype=float).reshape(3)
    # the configurations of the other questions: none of them reaches the target's position
    (pos,) = solve_problem(_only("position")).answers
    assert np.linalg.norm(np.array(pos.numeric["position"], dtype=float).reshape(3) - target) > 0.05
    at = [float(v) for v in _only("position").questions[0].at.values()]
    for sol in answer.numeric["solutions"]:
        assert np.linalg.norm(np.array(list(sol.values())) - np.array(at)) > 0.1
    for branch in answer.symbolic["closed_form"]:
        for expr in branch.values():
            assert not WHOLE_FLOAT.search(sp.sstr(expr)), sp.sstr(expr)
