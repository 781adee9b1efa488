"""Checking and grading answers against robosolve's own solution (grading.md).

answers.py (answers files) -> values.py (trees by answer kind) -> points.py (sample
points, numeric evaluation) -> compare.py (rules) -> diagnose.py (mistakes) ->
grader.py (verdicts, scores) -> record.py (record, CSV, feedback); check.py and
grade.py are the two workflows the CLI calls.
"""
