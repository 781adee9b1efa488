"""`robosolve paper`: a student's exam paper and answers template (docs/classroom.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from robosolve.cli.common import counted, err, usable_paths
from robosolve.errors import ExitStatus, InputError


def paper(
    problem: Path = typer.Argument(..., callback=usable_paths, help="A problem file (YAML)."),
    out: Optional[str] = typer.Option(None, "--out", "-o", callback=usable_paths,
        help="Output folder (default: out/<name>-paper/)."),
    format: Optional[str] = typer.Option(None, "--format", "-f",
                                         help="md (paper.md, always written) and html (paper.html), comma-separated."),
    student: Optional[str] = typer.Option(None, "--student", help="The student's id, printed on the paper."),
) -> None:
    """An exam paper: paper.md (the questions, no answers), answers.yaml (the template to fill in),
    figures/robot.png; paper.html with --format html."""
    from robosolve.papers.workflow import parse_paper_formats, write_paper
    from robosolve.run.outputs import OutputFolderError

    try:
        formats = parse_paper_formats(format)
    except ValueError as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)
    try:
        loaded, target = write_paper(problem, out, formats, student)
    except (InputError, OutputFolderError) as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)
    except OSError as exc:
        err(f"{out}: cannot write the paper ({exc.strerror or exc})")
        raise typer.Exit(ExitStatus.INPUT)
    err(f"{problem}: paper of {counted(len(loaded.questions), 'question')} -> {target}")
    raise typer.Exit(ExitStatus.OK)
