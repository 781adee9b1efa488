"""`robosolve validate`: check problem files without solving them."""

from __future__ import annotations

from pathlib import Path
from typing import List

import typer

from robosolve.cli.common import counted, err, out, usable_paths, warnings_of
from robosolve.errors import ExitStatus, InputError


def validate(
    files: List[Path] = typer.Argument(..., callback=usable_paths, help="Problem files (YAML)."),
) -> None:
    """Check problem files without solving them (exit 2 on any problem)."""
    from robosolve.load.loader import load_problem
    from robosolve.run.pipeline import check_inputs

    status = ExitStatus.OK
    for f in files:
        try:
            p = check_inputs(load_problem(f))
            warnings_of(p)
            out(f"{f}: ok ({counted(len(p.questions), 'question')})")
        except InputError as exc:
            err(str(exc))
            status = ExitStatus.INPUT
    raise typer.Exit(status)
