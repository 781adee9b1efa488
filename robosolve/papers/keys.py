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
    parent: object = None         # the AnswerKey of its record, for a field ("force" of "force.lengths")

    @property
    def doc(self) -> str:
        """What the key is: a field's own words after its record's ("total energy T + U: at the
        end of the run")."""
        own = self.answer_key.doc
        return f"{self.parent.doc}: {own}" if self.parent is not None and self.parent.doc else own

    @property
    def unit(self) -> str:
        """The key's unit, a field's that of its record unless it has its own."""
        return self.answer_key.unit or (self.parent.unit if self.parent is not None else "")


def graded_keys(question, problem) -> list[GradedKey]:
    """The graded keys of `question` in grading order (grading.md)."""
    qt = question_type(question.type)
    keys = question.grade or qt.template_keys(question.options, len(problem.joints))
    return [GradedKey(k, qt.key(k), qt.key(k.rpartition(".")[0]) if "." in k else None)
            for k in keys if qt.key(k) is not None]


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
    if kind == R.MATRIX_LIST and entries is not None:       # one 4×4 pose per frame of a chain
        return [[[None] * 4 for _ in range(4)] for _ in entries]
    if entries is not None and kind != R.JOINT_MAP_SET:     # a set is one `~` (its element in the comment)
        return {e: None for e in entries}
    joints = [j.name for j in problem.joints]
    bodies = [b.name for b in problem.bodies]
    if kind == R.BODY_MAP:
        return {**{b: None for b in bodies}, "total": None}
    if kind == R.MATRIX_MAP and len(dims) == 2:
        return {b: [[None] * dims[1] for _ in range(dims[0])] for b in bodies}
    if kind == R.EQUATIONS:
        return [None] * len(joints)
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
