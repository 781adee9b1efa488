"""`robosolve variants`: individualized variants of a problem (docs/variants.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from robosolve.cli.common import (
    STATUS_LABEL, Steps, check_scheduler, console, counted, err, format_option, formats as parse_formats,
    jobs_option, scheduler_option, usable_paths, warnings_of,
)
from robosolve.errors import ExitStatus, InputError


def variants(
    problem: Path = typer.Argument(..., callback=usable_paths,
        help="A problem file with a `variants` section."),
    count: Optional[int] = typer.Option(None, "--count", "-n", help="Make variants 1..N (zero-padded ids)."),
    roster: Optional[Path] = typer.Option(None, "--roster", callback=usable_paths,
        help="CSV with a `student` column: one variant each."),
    out: Path = typer.Option(..., "--out", "-o", callback=usable_paths,
        help="Output folder (replaced as a whole)."),
    seed: int = typer.Option(0, "--seed", help="Seed of the draws (same seed, same variants)."),
    no_solve: bool = typer.Option(False, "--no-solve", help="Write the problem files only."),
    format: Optional[str] = format_option(),
    jobs: int = jobs_option(),
    scheduler: Optional[str] = scheduler_option(),
) -> None:
    """Individualized variants of a problem: variants.csv and one solved folder per variant."""
    if (count is None) == (roster is None) or (count is not None and count < 1):
        err("give either --count N (N >= 1) or --roster ROSTER.csv")
        raise typer.Exit(ExitStatus.INPUT)
    formats = parse_formats(format)
    check_scheduler(scheduler)
    raise typer.Exit(command(problem, count, roster, out, seed, not no_solve, formats, jobs, scheduler))


def command(problem: Path, count, roster, out: Path, seed: int, solve: bool, formats: tuple,
            jobs: int, scheduler) -> int:
    from rich.progress import Progress

    from robosolve.run.execution import SchedulerError
    from robosolve.run.outputs import OutputFolderError
    from robosolve.variants.naming import CountedIds, read_roster, roster_csv
    from robosolve.variants.workflow import VariantInvalid, check_out, plan_variants, run

    con = console()
    inputs = [problem] + ([roster] if roster is not None else [])
    reason = check_out(out, inputs)
    if reason:
        err(reason)
        return ExitStatus.INPUT
    try:
        ids = CountedIds(count) if roster is None else read_roster(roster)
        with Progress(console=con, transient=True) as bar:
            plan = plan_variants(problem, ids, seed, Steps(bar))
            plan.roster = roster_csv(roster) if roster is not None else b""
            status, results = run(plan, out, formats, solve, jobs, scheduler, Steps(bar), inputs)
    except (InputError, SchedulerError, OutputFolderError) as exc:
        err(str(exc))
        return ExitStatus.INPUT
    except VariantInvalid as exc:
        err("\n".join(exc.messages))
        return ExitStatus.INPUT
    summary(con, plan, results, solve)
    warnings_of(plan.problem)
    err(f"{counted(len(plan.variants), 'variant')} of {plan.problem.name} (seed {seed}) -> {out}")
    return status


def summary(con, plan, results, solved: bool):
    from rich.table import Table

    table = Table(title=f"robosolve variants of {plan.problem.name}")
    for col in ("variant", "student", "answered" if solved else "questions", "status"):
        table.add_column(col)
    for v, r in zip(plan.variants, results):
        answered = f"{r.answered}/{r.total}" if solved else str(r.total)
        table.add_row(v.folder, v.student or "—", answered, STATUS_LABEL[r.status] if solved else "valid")
    con.print(table)
    for r in results:
        for m in r.messages:
            err(m)
