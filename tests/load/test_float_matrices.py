"""Matrices written with floats (1.0, 0.0) are the matrices they mean.

sympy does not take Float(1.0) for 1, so a file that writes an identity or a pose matrix
with decimal points was once refused as "not a rototranslation". The references here are
numpy products written out by hand, not robosolve's own chain.
"""

import math

import numpy as np
import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem

FLOAT_POSE = """\
robosolve: 1
name: float-matrices
joints: [{name: q1, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1)"}
  "2": {parent: "1", matrix: [[1.0, 0.0, 0.0, 0.5], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.25], [0.0, 0.0, 0.0, 1.0]]}
questions:
  - {id: where, type: position, frame: "2", at: {q1: 0.3}}
  - id: move
    type: displacement
    from: [[1.0, 0, 0, 0], [0, 1.0, 0, 0], [0, 0, 1.0, 0], [0, 0, 0, 1.0]]
    to: [[0.8, -0.6, 0, 0.5], [0.6, 0.8, 0, 0], [0, 0, 1.0, 0], [0.0, 0.0, 0.0, 1.0]]
  - {id: turn, type: orientation, matrix: [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]}
"""


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def test_float_pose_and_displacement_matrices_are_accepted_and_solved():
    problem = load_problem_text(FLOAT_POSE, "float.yaml")
    answers = {a.id: a for a in solve_problem(problem).answers}
    offset = np.eye(4)
    offset[:3, 3] = [0.5, 0, 0.25]
    expected = _rz(0.3) @ offset
    assert np.allclose(np.array(answers["where"].numeric["M"], dtype=float), expected, atol=1e-12)
    # the whole-number entries became exact: no 1.0*cos(q1) in the symbolic pose
    assert "1.0" not in str(answers["where"].symbolic["M"])
    q = np.array(answers["move"].numeric["Q"], dtype=float)
    assert np.allclose(q[:3, :3], [[0.8, -0.6, 0], [0.6, 0.8, 0], [0, 0, 1]], atol=1e-12)
    assert np.allclose(q[:3, 3], [0.5, 0, 0], atol=1e-12)
    assert answers["turn"].numeric     # Rx(pi/2) written with floats: a rotation


@pytest.mark.parametrize("last_row", ["[0.0, 0.0, 0.5, 1.0]", "[0.0, 0.0, 0.0, 2.0]"])
def test_a_float_last_row_that_is_not_0001_is_still_refused(last_row):
    text = FLOAT_POSE.replace("[0.0, 0.0, 0.0, 1.0]]}", f"{last_row}]}}", 1)
    assert text != FLOAT_POSE
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "float.yaml")
    assert "last row" in str(exc.value)
