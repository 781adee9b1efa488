"""Shared helpers of the grading tests: small problems solved once, answers graded from text."""

from __future__ import annotations

import textwrap

from robosolve.grading.answers import read_answers_text, resolve_answers
from robosolve.grading.grader import Grader
from robosolve.grading.reference import Reference
from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem

# A planar 2R arm in the x-y plane, the textbook one: every reference below is written
# from its closed forms (M, J, det J = L1·L2·sin q2, Fq = −Jᵀ·Fs, the IK by the law of
# cosines), not from robosolve's output.
TWO_R = """
robosolve: 1
name: two-r
parameters: {L1: 1/2, L2: 2/5, F: 5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}}
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}}
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, marks: 2}
  - {type: inverse_kinematics, target: {E.x: 0.6, E.y: 0.3}}
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, grade: [force.semi_axes, condition_number]}
  - type: orientation
    matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
"""


def dedent(text: str) -> str:
    return textwrap.dedent(text).lstrip("\n")


def reference_of(problem_text: str, name="p.yaml", **tol) -> Reference:
    problem = load_problem_text(dedent(problem_text), name)
    return Reference.from_report(solve_problem(problem), **tol)


def grade_text(ref: Reference, answers_text: str, file="answers.yaml", tolerance=None):
    sub = read_answers_text(dedent(answers_text), file)
    resolve_answers(sub, ref.problem)
    return Grader(ref, tolerance).grade(sub.student, sub.answers)


def key(result, question, name):
    q = next(q for q in result.questions if q.id == question)
    return q.keys[name]
