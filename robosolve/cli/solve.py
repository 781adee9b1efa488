"""`robosolve solve`: problem files -> report.md, results.json, figures/ (one folder each)."""

from __future__ import annotations

from pathlib import Path
from typing import List, Optional

import typer

from robosolve.cli.common import (
    err, format_option, formats as parse_formats, out as say, usable_paths, warnings_of,
)
from robosolve.errors import ExitStatus, InputError


def solve(
    files: List[Path] = typer.Argument(..., callback=usable_paths, help="Problem files (YAML)."),
    out: Optional[str] = typer.Option(
        None, "--out", "-o",
        callback=usable_paths, help="Output folder. With one file: the folder itself (DIR/report.md). "
             "With several: DIR/<problem name>/. Default: out/<problem name>/. "
             "robosolve only replaces folders that are new, empty or its own (marked .robosolve)."),
    format: Optional[str] = format_option(),
) -> None:
    """Solve problem files: write report.md, results.json and figures/."""
    from robosolve.load.loader import load_problem
    from robosolve.render.drawing import figure_drawer
    from robosolve.run.pipeline import check_inputs, may_draw

    formats = parse_formats(format)

    # Validate every file first: nothing is written when any input is invalid. The figure
    # helper starts as soon as a problem with figures is read: it imports matplotlib while this
    # process checks the inputs and solves (the PNGs are drawn while the next question solves).
    problems, status = [], ExitStatus.OK
    with figure_drawer(background=True) as figures:
        for f in files:
            try:
                problem = load_problem(f)
                if may_draw(problem):
                    figures.expect()
                problems.append(check_inputs(problem))
            except InputError as exc:
                err(str(exc))
                status = ExitStatus.INPUT
        if status == ExitStatus.INPUT:
            raise typer.Exit(ExitStatus.INPUT)
        for problem in problems:
            warnings_of(problem)
        targets = _solve_targets(problems, out)
        for problem, target in zip(problems, targets):
            status = max(status, _solve_one(problem, target, formats, files, figures))
    raise typer.Exit(status)


def _solve_one(problem, target, formats, files, figures) -> int:
    """Solve one problem, write its folder, print its summary line: its exit status."""
    from robosolve.run.outputs import OutputFolderError, write_output_folder
    from robosolve.run.pipeline import solve_loaded

    result = solve_loaded(problem, formats, figures=figures, split=True)
    try:
        write_output_folder(target, result.files, inputs=files)
    except OutputFolderError as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)
    say(f"{problem.file}: {result.answered}/{result.total} questions answered -> {target}")
    for m in result.messages:
        err(m)
    return result.status


def _solve_targets(problems, out: Optional[str]) -> list:
    """Each problem's output folder, every one checked before any work (exit 2 when refused)."""
    from robosolve.run.outputs import OutputFolderError, check_collection, check_output_folder

    names = [p.name for p in problems]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        for n in dup:
            err("several problem files have the name '" + n + "' ("
                + ", ".join(str(p.file) for p in problems if p.name == n)
                + "): their outputs would overwrite each other; give each a different `name`")
        raise typer.Exit(ExitStatus.INPUT)
    if out is not None and len(problems) == 1:
        collection, targets = None, [out]
    else:
        collection = "out" if out is None else out
        targets = [Path(collection) / n for n in names]
    try:
        if collection is not None:
            check_collection(collection)
        for target in targets:
            check_output_folder(target, inputs=[p.file for p in problems])
    except OutputFolderError as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)
    return targets
