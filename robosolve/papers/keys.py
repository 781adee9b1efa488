"""The graded keys of a question and the layout of their answers, known before solving.

The keys are the question's `grade` list, else its type's principal keys for its form
(`QuestionType.template_keys`); each key's shape comes from the registry's answer schema
(`AnswerKey.kind`, `shape`) with the tokens n (joints), m (coordinates), r (rows of J).
"""

from __future__ import annotations

from dataclasses import dataclass

from robosolve.questions import registry as R
from robosolve.questions.registry import question_type

MAP_KINDS = (R.JOINT_MAP, R.ACTUATOR_MAP)


@dataclass(frozen=True)
class GradedKey:
    key: str                      # dotted path, e.g. "force.lengths"
    answer_key: object            # its AnswerKey


def graded_keys(question, problem) -> list[GradedKey]:
    """The graded keys of `question` in grading order (grading.md)."""
    qt = question_type(question.type)
    keys = question.grade or qt.template_keys(question.options, len(problem.joints))
    return [GradedKey(k, qt.key(k)) for k in keys if qt.key(k) is not None]


def dimensions(question, problem) -> dict:
    """Values of the shape tokens: n joints, m coordinates, r rows of the Jacobian."""
    coords = question.options.get("coordinates")
    m = len(coords) if coords else 3
    return {R.N: len(problem.joints), R.M: m, R.R: 6 if question.options.get("geometric") else m}


def shape(ak, question, problem) -> tuple:
    dims = dimensions(question, problem)
    return tuple(dims.get(s, s) if isinstance(s, str) else s for s in ak.shape)


def decided(ak, question, problem) -> tuple:
    """(entries, unit) the question decides for the key (its type's `paper_layout`), else (None, None)."""
    layout = question_type(question.type).paper_layout
    return (layout(question, problem) if layout is not None else {}).get(ak.name, (None, None))


def placeholder(ak, question, problem):
    """The answer's shape with None (YAML `~`) in every entry a student fills."""
    kind, dims = ak.kind, shape(ak, question, problem)
    entries = decided(ak, question, problem)[0]
    if entries is not None:
        return {e: None for e in entries}
    joints = [j.name for j in problem.joints]
    if kind == R.MATRIX and len(dims) == 2:
        return [[None] * dims[1] for _ in range(dims[0])]
    if kind == R.VECTOR and len(dims) == 1:
        return [None] * dims[0]
    if kind == R.JOINT_MAP:
        return {j: None for j in joints}
    if kind == R.ACTUATOR_MAP:
        return {str(j.actuator): None for j in problem.joints}
    if kind == R.ACTUATOR_RECORDS:
        fields = {f.name: None for f in ak.fields}
        return {str(j.actuator): dict(fields) for j in problem.joints}
    if kind == R.RECORD:
        return {f.name: placeholder(f, question, problem) for f in ak.fields}
    return None
