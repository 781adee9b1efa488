"""The `robosolve` command: solve, validate, batch. The only module that prints or exits.

Heavy modules (sympy, numpy, matplotlib) are imported inside the commands so
that `robosolve --help` answers at once.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import List, Optional

import typer

from robosolve.errors import EXIT_ANSWER_ERROR, EXIT_INPUT, EXIT_OK, InputError

app = typer.Typer(
    add_completion=False,
    pretty_exceptions_enable=False,
    no_args_is_help=True,
    help="Solve industrial-robotics exam problems written as YAML files, step by step.\n\n"
         "A problem file describes the robot (joints, frames, masses, forces) and the questions; "
         "robosolve writes report.md (the worked solution), results.json and figures/*.png.",
)


def _err(text: str) -> None:
    sys.stderr.write(text + "\n")


FORMAT_HELP = ("Reports to write, comma-separated: md (report.md), html (report.html, one "
               "self-contained page), ipynb (report.ipynb, a notebook that recomputes the answers). "
               "Default: md. results.json and figures/ are always written.")


def _formats(text: Optional[str]) -> tuple:
    from robosolve.render.formats import parse_formats

    try:
        return parse_formats(text)
    except ValueError as exc:
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)


def _default_out(problem_name: str) -> Path:
    return Path("out") / problem_name


@app.command()
def solve(
    files: List[Path] = typer.Argument(..., help="Problem files (YAML)."),
    out: Optional[Path] = typer.Option(
        None, "--out", "-o",
        help="Output folder. With one file: the folder itself (DIR/report.md). "
             "With several: DIR/<problem name>/. Default: out/<problem name>/."),
    format: Optional[str] = typer.Option(None, "--format", "-f", help=FORMAT_HELP),
) -> None:
    """Solve problem files: write report.md, results.json and figures/."""
    from robosolve.load.loader import load_problem
    from robosolve.pipeline import solve_problem, write_outputs

    formats = _formats(format)

    # Validate every file first: nothing is written when any input is invalid.
    problems, status = [], EXIT_OK
    for f in files:
        try:
            problems.append(load_problem(f))
        except InputError as exc:
            _err(str(exc))
            status = EXIT_INPUT
    if status == EXIT_INPUT:
        raise typer.Exit(EXIT_INPUT)
    names = [p.name for p in problems]
    if out is not None and len(files) > 1 and len(set(names)) != len(names):
        _err("several problem files have the same name; their outputs would overwrite each other")
        raise typer.Exit(EXIT_INPUT)
    for problem in problems:
        report = solve_problem(problem)
        if out is None:
            target = _default_out(problem.name)
        else:
            target = out if len(files) == 1 else out / problem.name
        write_outputs(report, target, formats)
        failed = [a for a in report.answers if a.error is not None]
        msg = f"{problem.file}: {len(report.answers) - len(failed)}/{len(report.answers)} questions answered -> {target}"
        typer.echo(msg)
        for a in failed:
            _err(f"{problem.file}: {a.id}: {a.error}")
        status = max(status, report.exit_status)
    raise typer.Exit(status)


@app.command()
def validate(files: List[Path] = typer.Argument(..., help="Problem files (YAML).")) -> None:
    """Check problem files without solving them (exit 2 on any problem)."""
    from robosolve.load.loader import load_problem

    status = EXIT_OK
    for f in files:
        try:
            p = load_problem(f)
            typer.echo(f"{f}: ok ({len(p.questions)} questions)")
        except InputError as exc:
            _err(str(exc))
            status = EXIT_INPUT
    raise typer.Exit(status)


@app.command()
def batch(
    source: str = typer.Argument(..., help="A folder of problem files, or a glob such as 'problems/*.yaml'."),
    out: Optional[Path] = typer.Option(None, "--out", "-o", help="Output folder: one sub-folder per problem."),
    jobs: int = typer.Option(0, "--jobs", "-j", help="Parallel processes (default: number of cores)."),
    check: Optional[Path] = typer.Option(
        None, "--check", help="Golden folder: regenerate into a temporary folder and compare."),
    update: bool = typer.Option(False, "--update", help="With --check: rewrite the golden folder."),
    format: Optional[str] = typer.Option(None, "--format", "-f", help=FORMAT_HELP),
) -> None:
    """Solve many problem files in parallel; optionally compare with golden outputs."""
    from robosolve import batch as batch_mod

    formats = _formats(format)

    files = batch_mod.collect(source)
    if not files:
        _err(f"{source}: no problem files found")
        raise typer.Exit(EXIT_INPUT)
    if update and check is None:
        _err("--update goes with --check GOLDEN_DIR")
        raise typer.Exit(EXIT_INPUT)
    if check is None and out is None:
        _err("give --out DIR (or --check GOLDEN_DIR)")
        raise typer.Exit(EXIT_INPUT)
    status = batch_mod.run(files, out=out, jobs=jobs, golden=check, update=update, formats=formats)
    raise typer.Exit(status)


def main() -> None:
    try:
        app()
    except KeyboardInterrupt:
        _err("interrupted")
        sys.exit(130)


__all__ = ["app", "main", "EXIT_ANSWER_ERROR"]
