"""`robosolve batch`: many problem files in parallel, and the golden check."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from robosolve.cli.common import (
    STATUS_LABEL, check_scheduler, console, counted, err, format_option, formats as parse_formats, jobs_option, out,
    progress_bars, scheduler_option, usable_paths,
)
from robosolve.errors import ExitStatus


def batch(
    source: str = typer.Argument(..., callback=usable_paths,
        help="A folder of problem files, or a glob such as 'problems/*.yaml'."),
    out: Optional[str] = typer.Option(None, "--out", "-o", callback=usable_paths,
        help="Output folder: one sub-folder per problem."),
    jobs: int = jobs_option(),
    check: Optional[Path] = typer.Option(
        None, "--check", callback=usable_paths,
            help="Golden folder: regenerate in memory and compare (with --update: rewrite it)."),
    update: bool = typer.Option(False, "--update", help="With --check: rewrite the golden folder."),
    format: Optional[str] = format_option(),
    scheduler: Optional[str] = scheduler_option(),
) -> None:
    """Solve many problem files in parallel; optionally compare with golden outputs."""
    from robosolve.run import batch as batch_mod

    formats = parse_formats(format)

    files = batch_mod.collect(source)
    if not files:
        err(f"{source}: {batch_mod.why_no_files(source)}")
        raise typer.Exit(ExitStatus.INPUT)
    if update and check is None:
        err("--update goes with --check GOLDEN_DIR")
        raise typer.Exit(ExitStatus.INPUT)
    if check is not None and out is not None:
        err("--out and --check do not go together: --check regenerates in memory and compares "
            "(with --update it writes the golden folder); run --out separately to keep the outputs")
        raise typer.Exit(ExitStatus.INPUT)
    if check is None and out is None:
        err("give --out DIR (or --check GOLDEN_DIR)")
        raise typer.Exit(ExitStatus.INPUT)
    if check is not None and not update and not Path(check).is_dir():
        # nothing to compare with: a mistyped path, not a set of differences
        err(f"--check {check}: no such golden folder (to make one, add --update)" if not Path(check).exists()
            else f"--check {check}: not a folder")
        raise typer.Exit(ExitStatus.INPUT)
    check_scheduler(scheduler)
    con = console()
    outcome = batch_mod.run(files, out=out, jobs=jobs, golden=check, update=update, formats=formats,
                            scheduler=scheduler, progress=progress_bars("solving", con))
    show(outcome, check, update, con)
    raise typer.Exit(outcome.status)


def show(outcome, golden, update, con) -> None:
    """The summary table, every message (plain lines: an editor jumps to FILE:LINE), the golden check."""
    from rich.table import Table

    for m in outcome.refused:
        err(m)
    if outcome.refused:
        return
    table = Table(title="robosolve batch")
    for col in ("file", "problem", "answered", "status"):
        table.add_column(col)
    for r in outcome.results:
        table.add_row(r.file, r.name or "—", f"{r.answered}/{r.total}", STATUS_LABEL[r.status])
    con.print(table)
    for r in outcome.results:
        for m in r.warnings + r.messages:
            err(m)
    for m in outcome.write_errors:
        err(m)
    for d in outcome.orphans:
        if outcome.unnamed:     # its problem may be one whose name could not be read: not removed
            err(f"golden check: {d}: not checked: {', '.join(outcome.unnamed)} could not be read, and "
                f"'{d.name}' may be its name (fix the file, then check again)")
            continue
        err(f"golden check: {d}: no problem file checked has the name '{d.name}' (was its problem "
            "removed or renamed? delete the folder, or check it with its problem file)")
    if golden is not None and update:
        err(f"golden folder {golden} updated ({counted(outcome.solved - len(outcome.write_errors), 'problem')})")
    elif golden is not None:
        for line in outcome.diff_lines:
            out(line)
        if outcome.diff_lines:
            err("golden check: differences found (rerun with --update to accept them)")
        else:
            err(f"golden check: {counted(outcome.solved, 'problem')} identical")

