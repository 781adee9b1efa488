"""`robosolve grade`: a class's submissions, each against its problem, with marks and feedback."""

from __future__ import annotations

import contextlib
from pathlib import Path
from typing import List, Optional

import typer

from robosolve.cli.common import console, err, jobs_option, problem_option, tolerance_option, usable_paths
from robosolve.errors import ExitStatus


def grade(
    submissions: List[Path] = typer.Argument(..., callback=usable_paths,
        help="Answers files, or folders of them (*.yaml, *.yml)."),
    out: Path = typer.Option(..., "--out", "-o", callback=usable_paths,
        help="Output folder: grades.csv, summary.csv, <student>.json, feedback/."),
    problem: Optional[Path] = problem_option("Grade every submission against this problem."),
    variants: Optional[Path] = typer.Option(None, "--variants", callback=usable_paths,
        help="A `robosolve variants` folder: each student's own variant."),
    jobs: int = jobs_option(),
    rtol: Optional[float] = tolerance_option("--rtol", "Relative", "0.005"),
    atol: Optional[float] = tolerance_option("--atol", "Absolute", "1e-6"),
    gradebook: Optional[str] = typer.Option(
        None, "--gradebook", help="LMS gradebook files to write (canvas,moodle,blackboard); needs --variants with a roster."),
    no_expected: bool = typer.Option(False, "--no-expected", help="Feedback pages never show an expected value."),
) -> None:
    """Grade a class: every submission against its problem (solved once), with marks and feedback."""
    raise typer.Exit(run_grade_command(submissions, out, problem, variants, jobs, rtol, atol,
                                       gradebook=gradebook, no_expected=no_expected))


def run_grade_command(sources, out, problem, variants_dir, jobs, rtol, atol, gradebook=None,
                      no_expected=False) -> int:
    from robosolve.grading.grade import UsageError, run_grade
    from robosolve.run.outputs import OutputFolderError

    con = console()
    if problem is not None and variants_dir is not None:
        err("give --problem or --variants, not both")
        return ExitStatus.INPUT

    @contextlib.contextmanager
    def progress_factory(total):
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        with Progress(TextColumn("grading"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                      console=con, transient=True) as progress:
            task = progress.add_task("grading", total=total)
            yield lambda n: progress.advance(task, n)

    try:
        outcome = run_grade(sources, out, problem, variants_dir, jobs, rtol, atol,
                            progress_factory=progress_factory, gradebook=gradebook, no_expected=no_expected)
    except (UsageError, OutputFolderError) as exc:
        err(str(exc))
        return ExitStatus.INPUT
    show(outcome, out, con)
    return outcome.status


def show(outcome, out, con) -> None:
    from rich.table import Table

    from robosolve.grading.record import number_text, percent_text

    jobs, results = outcome.jobs, outcome.results
    table = Table(title=f"robosolve grade -> {out}")
    for col in ("student", "score", "max", "percent", "file"):
        table.add_column(col)
    for i in sorted(range(len(jobs)), key=lambda k: (results[k].student, k)):
        r = results[i]
        table.add_row(r.student, number_text(r.score), number_text(r.max_score),
                      percent_text(r.score, r.max_score), jobs[i].file)
    con.print(table)
    for w in outcome.warnings:
        err(w)
    for j in jobs:
        if j.answers is None:
            con.print(j.error, markup=False, highlight=False)
