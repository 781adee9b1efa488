"""The question-type registry: it collects the question types, one module each.

Every type lives in `robosolve/questions/<type>.py`, which builds its `QuestionType`
(`robosolve/questions/schema.py`): its option keys with their validators
(`robosolve/load/validators.py`), its cross-field checks, required keys and defaults,
whether it needs a robot or the dynamics, its title, its figures, its doc page, and its
**answer schema** — every key of results.json with its kind — so that the loader, the
renderers, the schema tests and the grader read one table instead of knowing question
types by name.

Adding a question type = a solver module `robosolve/solvers/<type>.py`, a type module
`robosolve/questions/<type>.py` named in `MODULES` below, and a page `docs/questions/<type>.md`.
"""

from __future__ import annotations

import importlib

from robosolve.questions.schema import (  # noqa: F401  (the vocabulary, re-exported)
    ACTUATOR_MAP, ACTUATOR_RECORDS, AXES, BODY_MAP, BOOL, EQUATIONS, JOINT_MAP, JOINT_MAP_LIST,
    JOINT_MAP_SET, KINDS, MATRIX, MATRIX_LIST, MATRIX_MAP, RECORD, SCALAR, TEXT, VECTOR, VECTOR_SET,
    AnswerKey, M, N, QuestionType, R,
)

# The type modules, in the order of the course (the order of every listing of the types).
MODULES = (
    "position", "velocity_acceleration", "jacobian", "statics", "ellipsoids", "inverse_kinematics",
    "motion_profile", "equations_of_motion", "joint_torques", "p_control", "forward_dynamics",
    "displacement", "orientation", "dof",
)


def _collect() -> dict[str, QuestionType]:
    types = {}
    for module in MODULES:
        qt = importlib.import_module(f"robosolve.questions.{module}").TYPE
        if qt.name != module:
            raise TypeError(f"robosolve/questions/{module}.py defines the type {qt.name!r}")
        types[qt.name] = qt
    return types


QUESTION_TYPES: dict[str, QuestionType] = _collect()

# Keys every question may have, whatever its type (problem-format.md "Questions").
COMMON_KEYS = ("type", "id", "at", "point", "frame", "marks", "grade", "text")


def question_type(name: str) -> QuestionType:
    return QUESTION_TYPES[name]


def title(name: str) -> str:
    t = QUESTION_TYPES.get(name)
    return t.title if t is not None else name


def types_where(flag: str) -> list[QuestionType]:
    """The types whose `flag` attribute is set, in registry order."""
    return [t for t in QUESTION_TYPES.values() if getattr(t, flag)]
