"""Stage 3: one module per question type, each with `solve(question, ctx) -> Answer`.

Which module answers which type is the registry's business
(`robosolve.questions.registry`): adding a type = a module here, a type module
`robosolve/questions/<type>.py` (named in the registry's `MODULES`), a doc page.
"""

from __future__ import annotations

from robosolve.questions.registry import QUESTION_TYPES
from robosolve.solvers.base import Answer


def solver_for(qtype: str):
    """The `solve` function of a question type, or None when the registry has no such type."""
    qt = QUESTION_TYPES.get(qtype)
    return qt.solver() if qt is not None else None


__all__ = ["Answer", "solver_for"]
