"""The `robosolve` command: solve, validate, batch. The only module that prints or exits.

Heavy modules (sympy, numpy, matplotlib) are imported inside the commands so
that `robosolve --help` answers at once.
"""

from __future__ import annotations

import os
import signal
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



# Options several commands share, defined once so that their names, bounds and help agree.
def _format_option():
    return typer.Option(None, "--format", "-f", help=FORMAT_HELP)


def _jobs_option():
    return typer.Option(0, "--jobs", "-j", min=0, help="Parallel processes (default: number of cores).")


def _scheduler_option():
    return typer.Option(None, "--scheduler", help=SCHEDULER_HELP)


def _problem_option(help_text: str):
    return typer.Option(None, "--problem", "-p", help=help_text)


def _tolerance_option(flag: str, kind: str, default: str):
    return typer.Option(None, flag, help=f"{kind} tolerance (default {default}, or the problem's grading:).")

def _err(text: str) -> None:
    sys.stderr.write(text + "\n")


FORMAT_HELP = ("Reports to write, comma-separated: md (report.md), html (report.html, one "
               "self-contained page), ipynb (report.ipynb, a notebook that recomputes the answers). "
               "Default: md. results.json and figures/ are always written.")


SCHEDULER_HELP = ("Solve on Dask: 'local' (a LocalCluster on this machine) or tcp://HOST:PORT (a "
                  "scheduler whose workers have robosolve installed; pip install \"robosolve[dask]\").")


def _formats(text: Optional[str]) -> tuple:
    from robosolve.render.formats import parse_formats

    try:
        return parse_formats(text)
    except ValueError as exc:
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)


@app.command()
def solve(
    files: List[Path] = typer.Argument(..., help="Problem files (YAML)."),
    out: Optional[str] = typer.Option(
        None, "--out", "-o",
        help="Output folder. With one file: the folder itself (DIR/report.md). "
             "With several: DIR/<problem name>/. Default: out/<problem name>/. "
             "robosolve only replaces folders that are new, empty or its own (marked .robosolve)."),
    format: Optional[str] = _format_option(),
) -> None:
    """Solve problem files: write report.md, results.json and figures/."""
    from robosolve.load.loader import load_problem
    from robosolve.pipeline import check_inputs
    from robosolve.render.drawing import figure_drawer

    formats = _formats(format)

    # Validate every file first: nothing is written when any input is invalid.
    problems, status = [], EXIT_OK
    for f in files:
        try:
            problems.append(check_inputs(load_problem(f)))
        except InputError as exc:
            _err(str(exc))
            status = EXIT_INPUT
    if status == EXIT_INPUT:
        raise typer.Exit(EXIT_INPUT)
    targets = _solve_targets(problems, out)
    with figure_drawer(background=True) as figures:    # drawn while the next question solves
        for problem, target in zip(problems, targets):
            status = max(status, _solve_one(problem, target, formats, files, figures))
    raise typer.Exit(status)


def _solve_one(problem, target, formats, files, figures) -> int:
    """Solve one problem, write its folder, print its summary line: its exit status."""
    from robosolve.outputs import OutputFolderError
    from robosolve.pipeline import render_outputs, solve_problem

    report = solve_problem(problem, figures=figures, split=True)
    try:
        render_outputs(report, target, formats, inputs=files, figures=figures)
    except (OutputFolderError, OSError) as exc:
        _err(_write_error(target, exc))
        raise typer.Exit(EXIT_INPUT)
    failed = [a for a in report.answers if a.error is not None]
    msg = f"{problem.file}: {len(report.answers) - len(failed)}/{len(report.answers)} questions answered -> {target}"
    typer.echo(msg)
    for a in failed:
        _err(f"{problem.file}: {a.id}: {a.error}")
    return report.exit_status


def _write_error(target, exc) -> str:
    if isinstance(exc, OSError):
        return f"{target}: cannot write the outputs ({exc.strerror or exc})"
    return str(exc)


def _solve_targets(problems, out: Optional[str]) -> list:
    """Each problem's output folder, every one checked before any work (exit 2 when refused)."""
    from robosolve.outputs import OutputFolderError, check_collection, check_output_folder

    names = [p.name for p in problems]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        for n in dup:
            _err("several problem files have the name '" + n + "' ("
                 + ", ".join(str(p.file) for p in problems if p.name == n)
                 + "): their outputs would overwrite each other; give each a different `name`")
        raise typer.Exit(EXIT_INPUT)
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
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)
    return targets


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
    out: Optional[str] = typer.Option(None, "--out", "-o", help="Output folder: one sub-folder per problem."),
    jobs: int = _jobs_option(),
    check: Optional[Path] = typer.Option(
        None, "--check", help="Golden folder: regenerate in memory and compare (with --update: rewrite it)."),
    update: bool = typer.Option(False, "--update", help="With --check: rewrite the golden folder."),
    format: Optional[str] = _format_option(),
    scheduler: Optional[str] = _scheduler_option(),
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
    _scheduler(scheduler)
    status = batch_mod.run(files, out=out, jobs=jobs, golden=check, update=update, formats=formats,
                           scheduler=scheduler)
    raise typer.Exit(status)


@app.command()
def variants(
    problem: Path = typer.Argument(..., help="A problem file with a `variants` section."),
    count: Optional[int] = typer.Option(None, "--count", "-n", help="Make variants 1..N (zero-padded ids)."),
    roster: Optional[Path] = typer.Option(None, "--roster", help="CSV with a `student` column: one variant each."),
    out: Path = typer.Option(..., "--out", "-o", help="Output folder (replaced as a whole)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the draws (same seed, same variants)."),
    no_solve: bool = typer.Option(False, "--no-solve", help="Write the problem files only."),
    format: Optional[str] = _format_option(),
    jobs: int = _jobs_option(),
    scheduler: Optional[str] = _scheduler_option(),
) -> None:
    """Individualized variants of a problem: variants.csv and one solved folder per variant."""
    from robosolve.variants import workflow

    if (count is None) == (roster is None) or (count is not None and count < 1):
        _err("give either --count N (N >= 1) or --roster ROSTER.csv")
        raise typer.Exit(EXIT_INPUT)
    formats = _formats(format)
    _scheduler(scheduler)
    raise typer.Exit(workflow.command(problem, count, roster, out, seed, not no_solve, formats, jobs, scheduler))


def _scheduler(scheduler: Optional[str]) -> None:
    """--scheduler usage checks (Dask installed, address well formed), before any work."""
    from robosolve.execution import SchedulerError, check_scheduler

    try:
        check_scheduler(scheduler)
    except SchedulerError as exc:
        _err(str(exc))
        raise typer.Exit(EXIT_INPUT)


@app.command()
def check(
    answers: Path = typer.Argument(..., help="An answers file (YAML, grading.md)."),
    problem: Optional[Path] = _problem_option("Problem file (default: the answers file's `problem:`)."),
    json_out: Optional[str] = typer.Option(None, "--json", help="Write the result record to FILE ('-': standard output)."),
    rtol: Optional[float] = _tolerance_option("--rtol", "Relative", "0.005"),
    atol: Optional[float] = _tolerance_option("--atol", "Absolute", "1e-6"),
) -> None:
    """Check a student's answers against robosolve's solution: a verdict per key, and what is wrong."""
    from robosolve.grading.commands import run_check

    raise typer.Exit(run_check(answers, problem, json_out, rtol, atol))


@app.command()
def grade(
    submissions: List[Path] = typer.Argument(..., help="Answers files, or folders of them (*.yaml, *.yml)."),
    out: Path = typer.Option(..., "--out", "-o", help="Output folder: grades.csv, summary.csv, <student>.json, feedback/."),
    problem: Optional[Path] = _problem_option("Grade every submission against this problem."),
    variants: Optional[Path] = typer.Option(None, "--variants", help="A `robosolve variants` folder: each student's own variant."),
    jobs: int = _jobs_option(),
    rtol: Optional[float] = _tolerance_option("--rtol", "Relative", "0.005"),
    atol: Optional[float] = _tolerance_option("--atol", "Absolute", "1e-6"),
) -> None:
    """Grade a class: every submission against its problem (solved once), with marks and feedback."""
    from robosolve.grading.commands import run_grade_command

    raise typer.Exit(run_grade_command(submissions, out, problem, variants, jobs, rtol, atol))


def main() -> None:
    from robosolve import interrupts

    interrupts.install()
    try:
        app()
        status = EXIT_OK
    except KeyboardInterrupt:
        status = interrupts.EXIT_SIGINT
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    # click turns KeyboardInterrupt into "Aborted!" and exit 1, and a library may swallow it:
    # a signal received at any point decides the status (spec §4: SIGINT exits 130).
    owed = interrupts.received()
    if owed is not None:
        _err("interrupted")
        # os._exit: the interpreter's own exit path turns a KeyboardInterrupt seen anywhere
        # into death by SIGINT (status -2), whatever was caught; the clean-up ran in finally
        # blocks already
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(owed)
    # The work is done and its outputs written: a signal from here on must not turn a finished
    # run into death by SIGINT (-2) during the interpreter's exit. One that came between the
    # check above and this line raises here, and robosolve.__main__ exits 130 for it.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _exit(status)


def _exit(status: int) -> None:
    """Exit without the interpreter's tear-down when nothing needs it.

    After a solve the heap holds the whole run's sympy expressions, and the interpreter's exit
    (a last garbage collection over them, then every module's objects freed one by one) took
    half a second of a 3R report's five (measured, bench/RESULTS-perf.md). When no other thread
    and no child process is left (robosolve's helpers are stopped and waited for by then; a Dask
    client or cluster keeps threads), there is nothing to wait for: the streams are flushed and
    the process ends. Otherwise, the ordinary exit."""
    import threading

    children = sys.modules.get("multiprocessing")
    if threading.active_count() == 1 and not (children and children.active_children()):
        if "logging" in sys.modules:
            sys.modules["logging"].shutdown()
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):   # a closed pipe or stream: nothing more to say
                pass
        os._exit(status)
    sys.exit(status)


__all__ = ["app", "main", "EXIT_ANSWER_ERROR"]
