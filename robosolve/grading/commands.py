"""What `robosolve check` and `robosolve grade` do, for cli.py's thin wrappers.

Returns exit statuses; prints only through rich consoles given by the caller.
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from robosolve.errors import EXIT_ANSWER_ERROR, EXIT_INPUT, EXIT_OK, InputError

VERDICT_STYLE = {"correct": "green", "incorrect": "red", "missing": "yellow", "invalid": "magenta",
                 "no_reference": "dim"}


def result_table(result, title: str):
    from rich.table import Table

    table = Table(title=title, show_lines=False)
    table.add_column("question", no_wrap=True)
    table.add_column("key", no_wrap=True)
    table.add_column("verdict", no_wrap=True)
    table.add_column("what is wrong", overflow="fold", ratio=1)
    for q in result.questions:
        for key, r in q.keys.items():
            label = key if key in q.graded else f"{key} (not graded)"
            what = (f"[{r.diagnosis}] " if r.diagnosis else "") + r.feedback
            style = VERDICT_STYLE.get(r.verdict, "")
            table.add_row(q.id, label, f"[{style}]{r.verdict}[/{style}]" if style else r.verdict,
                          _escape(what))
    return table


def _escape(text: str) -> str:
    from rich.markup import escape

    return escape(text)


def write_text_atomic(path: Path, text: str) -> None:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        mode = 0o666 & ~_umask()
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def check_usage(json_out: str | None, json_format: str) -> str:
    """Why the --json / --json-format pair is a usage error, or ''."""
    from robosolve.grading.gradescope import FORMATS
    from robosolve.load.expressions import did_you_mean

    if json_format not in FORMATS:
        return (f"--json-format: unknown format '{json_format}'" + did_you_mean(json_format, FORMATS)
                + f" (expected one of: {', '.join(FORMATS)})")
    if json_format != "record" and not json_out:
        return "--json-format goes with --json FILE"
    return ""


def run_check(answers: Path, problem: Path | None, json_out: str | None,
              rtol: float | None, atol: float | None, json_format: str = "record",
              no_expected: bool = False) -> int:
    """`no_expected`: no expected value in the table, the record or the Gradescope output."""
    from rich.console import Console

    from robosolve.grading.check import check_file
    from robosolve.grading.gradescope import gradescope_json
    from robosolve.grading.record import number_text, percent_text, record_json

    err = Console(stderr=True)
    usage = check_usage(json_out, json_format)
    if usage:
        sys.stderr.write(usage + "\n")
        return EXIT_INPUT
    try:
        result, _ = check_file(answers, problem, rtol=rtol, atol=atol)
    except InputError as exc:
        sys.stderr.write(str(exc) + "\n")
        return EXIT_INPUT
    if no_expected:
        result = result.without_expected()
    to_stdout = json_out == "-"
    console = err if to_stdout else Console()
    console.print(result_table(result, f"{answers} — {result.student} — {result.problem}"))
    console.print(f"score {number_text(result.score)} / {number_text(result.max_score)} "
                  f"({percent_text(result.score, result.max_score)} %)", markup=False, highlight=False)
    text = gradescope_json(result) if json_format == "gradescope" else record_json(result)
    if to_stdout:
        sys.stdout.write(text)
    elif json_out:
        write_text_atomic(Path(json_out), text)
    return EXIT_OK if result.all_correct else EXIT_ANSWER_ERROR


def run_grade_command(sources, out, problem, variants_dir, jobs, rtol, atol, gradebook=None,
                      no_expected=False) -> int:
    import contextlib

    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from robosolve.grading.grade import UsageError, run_grade
    from robosolve.outputs import OutputFolderError
    from robosolve.grading.record import number_text, percent_text

    err = Console(stderr=True)
    if problem is not None and variants_dir is not None:
        sys.stderr.write("give --problem or --variants, not both\n")
        return EXIT_INPUT

    @contextlib.contextmanager
    def progress_factory(total):
        with Progress(TextColumn("grading"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                      console=err, transient=True) as progress:
            task = progress.add_task("grading", total=total)
            yield lambda n: progress.advance(task, n)

    def report(jobs_, results):
        from rich.table import Table

        table = Table(title=f"robosolve grade -> {out}")
        for col in ("student", "score", "max", "percent", "file"):
            table.add_column(col)
        for i in sorted(range(len(jobs_)), key=lambda k: (results[k].student, k)):
            r = results[i]
            table.add_row(r.student, number_text(r.score), number_text(r.max_score),
                          percent_text(r.score, r.max_score), jobs_[i].file)
        err.print(table)
        for j in jobs_:
            if j.answers is None:
                err.print(j.error, markup=False, highlight=False)

    try:
        return run_grade(sources, out, problem, variants_dir, jobs, rtol, atol,
                         progress_factory=progress_factory, report=report, gradebook=gradebook,
                         no_expected=no_expected)
    except (UsageError, OutputFolderError) as exc:
        sys.stderr.write(str(exc) + "\n")
        return EXIT_INPUT
