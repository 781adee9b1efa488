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


def _default_out(problem_name: str) -> Path:
    return Path("out") / problem_name


@app.command()
def solve(
    files: List[Path] = typer.Argument(..., help="Problem files (YAML)."),
    out: Optional[Path] = typer.Option(
        None, "--out", "-o",
        help="Output folder. With one file: the folder itself (DIR/report.md). "
             "With several: DIR/<problem name>/. Default: out/<problem name>/."),
) -> None:
    """Solve problem files: write report.md, results.json and figures/."""
    from robosolve.load.loader import load_problem
    from robosolve.pipeline import solve_problem, write_outputs

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
        write_outputs(report, target)
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
    scheduler: Optional[str] = typer.Option(
        None, "--scheduler", help="Dask: 'local' (a LocalCluster) or tcp://HOST:PORT (workers with robosolve)."),
) -> None:
    """Solve many problem files in parallel; optionally compare with golden outputs."""
    from robosolve import batch as batch_mod

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
    from robosolve.execution import SchedulerError, check_scheduler

    try:
        check_scheduler(scheduler)
    except SchedulerError as exc:
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)
    status = batch_mod.run(files, out=out, jobs=jobs, golden=check, update=update, scheduler=scheduler)
    raise typer.Exit(status)


@app.command()
def variants(
    problem: Path = typer.Argument(..., help="A problem file with a `variants` section."),
    count: Optional[int] = typer.Option(None, "--count", "-n", help="Make variants 1..N (zero-padded ids)."),
    roster: Optional[Path] = typer.Option(None, "--roster", help="CSV with a `student` column: one variant each."),
    out: Path = typer.Option(..., "--out", "-o", help="Output folder (replaced as a whole)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the draws (same seed, same variants)."),
    no_solve: bool = typer.Option(False, "--no-solve", help="Write the problem files only."),
    formats: Optional[str] = typer.Option(None, "--format", help="Report formats: md,html,ipynb (default md)."),
    jobs: int = typer.Option(0, "--jobs", "-j", help="Parallel processes (default: number of cores)."),
    scheduler: Optional[str] = typer.Option(
        None, "--scheduler", help="Dask: 'local' (a LocalCluster) or tcp://HOST:PORT."),
) -> None:
    """Individualized variants of a problem: variants.csv, one folder per variant, solved."""
    from robosolve.execution import SchedulerError, check_scheduler
    from robosolve.variants import workflow

    if (count is None) == (roster is None) or (count is not None and count < 1):
        _err("give either --count N (N >= 1) or --roster ROSTER.csv")
        raise typer.Exit(EXIT_INPUT)
    try:
        fmts = workflow.parse_formats(formats)
        check_scheduler(scheduler)
    except (ValueError, SchedulerError) as exc:
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)
    raise typer.Exit(workflow.command(problem, count, roster, out, seed, not no_solve, fmts, jobs, scheduler))


def main() -> None:
    try:
        app()
    except KeyboardInterrupt:
        _err("interrupted")
        sys.exit(130)


__all__ = ["app", "main", "EXIT_ANSWER_ERROR"]
