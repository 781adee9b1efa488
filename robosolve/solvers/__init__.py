"""Stage 3: one module per question type, each with `solve(question, ctx) -> Answer`.

Solvers are found by name (`robosolve.solvers.<type>`), so adding a question
type means adding a module; nothing else to register.
"""

from __future__ import annotations

import importlib

from robosolve.solvers.base import Answer


def solver_for(qtype: str):
    """The `solve` function of a question type, or None when not implemented yet."""
    try:
        module = importlib.import_module(f"robosolve.solvers.{qtype}")
    except ModuleNotFoundError as exc:
        if exc.name == f"robosolve.solvers.{qtype}":
            return None
        raise
    return getattr(module, "solve", None)


__all__ = ["Answer", "solver_for"]
