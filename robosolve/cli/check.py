"""`robosolve check`: one student's answers against robosolve's solution (docs/grading.md)."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

import typer

from robosolve.cli.common import console, err, problem_option, tolerance_option, usable_paths, write_stdout
from robosolve.errors import ExitStatus, InputError

VERDICT_STYLE = {"correct": "green", "incorrect": "red", "missing": "yellow", "invalid": "magenta",
                 "no_reference": "dim"}


def check(
    answers: Path = typer.Argument(..., callback=usable_paths, help="An answers file (YAML, grading.md)."),
    problem: Optional[Path] = problem_option("Problem file (default: the answers file's `problem:`)."),
    json_out: Optional[str] = typer.Option(None, "--json", callback=usable_paths,
        help="Write the result record to FILE ('-': standard output)."),
    rtol: Optional[float] = tolerance_option("--rtol", "Relative", "0.005"),
    atol: Optional[float] = tolerance_option("--atol", "Absolute", "1e-6"),
    json_format: str = typer.Option("record", "--json-format", help="Layout of --json: record, or gradescope (results.json)."),
    echo: bool = typer.Option(False, "--echo", help="First print how each given value was read."),
    no_expected: bool = typer.Option(False, "--no-expected",
                                     help="Verdicts and diagnoses only: never print an expected value."),
) -> None:
    """Check a student's answers against robosolve's solution: a verdict per key, and what is wrong."""
    raise typer.Exit(run_check(answers, problem, json_out, rtol, atol, json_format=json_format,
                               echo=echo, no_expected=no_expected))


def echo_table(lines):
    from rich.markup import escape
    from rich.table import Table

    table = Table(title="your answers, as robosolve read them")
    for col in ("question", "key", "read as"):
        table.add_column(col, overflow="fold", no_wrap=col != "read as")
    for qid, key, text in lines:
        table.add_row(qid, key, escape(text))
    return table


def result_table(result, title: str):
    from rich.markup import escape
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
                          escape(what))
    return table


def run_check(answers: Path, problem: Path | None, json_out: str | None,
              rtol: float | None, atol: float | None, json_format: str = "record",
              echo: bool = False, no_expected: bool = False) -> int:
    """`json_format`: record or gradescope; `echo`: print how each value was read first;
    `no_expected`: no expected value anywhere."""
    from robosolve.grading.check import check_file, read_back
    from robosolve.grading.gradescope import format_issue, gradescope_json
    from robosolve.grading.record import number_text, percent_text, record_json
    from robosolve.run.outputs import OutputFolderError, check_output_file, write_file

    issue = format_issue(json_out, json_format)
    if issue:
        err(issue)
        return ExitStatus.INPUT

    read: list = []          # the answers file and its problem: --json must not overwrite them

    def guard(inputs):
        read.extend(inputs)
        if json_out not in (None, "-"):
            check_output_file(json_out, inputs)

    try:
        def on_read(sub, prob):
            if echo:
                console(stderr=json_out == "-").print(echo_table(read_back(sub, prob)))

        result, _ = check_file(answers, problem, rtol=rtol, atol=atol, before_solving=guard,
                               reveal=not no_expected, on_read=on_read)
    except (InputError, OutputFolderError) as exc:
        err(str(exc))
        return ExitStatus.INPUT
    if no_expected:
        result = result.without_expected()
    to_stdout = json_out == "-"
    con = console(stderr=to_stdout)
    con.print(result_table(result, f"{answers} — {result.student} — {result.problem}"))
    con.print(f"score {number_text(result.score)} / {number_text(result.max_score)} "
              f"({percent_text(result.score, result.max_score)} %)", markup=False, highlight=False)
    text = gradescope_json(result) if json_format == "gradescope" else record_json(result)
    if to_stdout:
        write_stdout(text)
    elif json_out:
        try:
            write_file(Path(json_out), text.encode("utf-8"), read)
        except OutputFolderError as exc:
            err(str(exc))
            return ExitStatus.INPUT
    return ExitStatus.OK if result.all_correct else ExitStatus.ANSWER_ERROR
