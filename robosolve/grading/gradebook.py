"""Gradebook files an LMS imports as they are (grading.md "Grading a class": gradebooks).

`grade --variants DIR --gradebook canvas,moodle,blackboard` writes, beside summary.csv,
DIR/gradebook/<lms>.csv: exactly the roster's students (DIR/roster.csv), one row each in
roster order, with the score (4 decimals at most; empty for a student who handed nothing
in). Columns copied from the roster are found without regard to case.

- Canvas (lib/gradebook_importer.rb): `Student,ID,SIS User ID,SIS Login ID,Section,<title>`;
  the importer needs `Student` and `ID` first, `SIS User ID` and `SIS Login ID` together,
  `Section` last of the student columns; a student is found by ID, then SIS ids, then name.
- Moodle (grade/import/csv): `email,idnumber,<title>,<title> feedback`; the teacher maps
  `email` (or `idnumber`) to the user, the score and feedback columns to the grade item.
- Blackboard (Grade Center upload): `Username,<title>` (roster `username`, else the id).
"""

from __future__ import annotations

import csv
import io

from robosolve.grading.record import number_text
from robosolve.load.expressions import did_you_mean

LMS = ("canvas", "moodle", "blackboard")
CANVAS_COLUMNS = ("Student", "ID", "SIS User ID", "SIS Login ID", "Section")


class GradebookError(ValueError):
    """A usage error: an unknown LMS name, or --gradebook without a roster."""


def parse_lms(text: str | None) -> tuple:
    """'canvas,moodle' -> ('canvas', 'moodle') in the order given; GradebookError on a bad name."""
    if text is None:                 # not given (an empty --gradebook "" is a mistake, said below)
        return ()
    names = [n.strip().lower() for n in text.split(",") if n.strip()]
    for n in names:
        if n not in LMS:
            hint = did_you_mean(n, LMS)
            raise GradebookError(f"--gradebook: unknown LMS '{n}'{hint} (expected some of: {', '.join(LMS)})")
    if not names:
        raise GradebookError(f"--gradebook: give some of {', '.join(LMS)}, separated by commas")
    return tuple(dict.fromkeys(names))


def missing_columns(names, table) -> str:
    """Why the roster cannot identify the students of one of these LMS files, or ''.

    Canvas finds a student by `ID`, the SIS ids or the name (`Student`, which every roster of
    `variants --roster` has); Blackboard by `Username` (else the student id); Moodle only by
    a user field: the roster needs `email` or `idnumber`."""
    if "moodle" in names and table.column("email") is None and table.column("idnumber") is None:
        header = ", ".join(h for h in table.header if h) or "none"
        return (f"--gradebook moodle: {table.folder}/roster.csv has no `email` or `idnumber` column, "
                f"by which Moodle identifies its users (columns: {header})")
    return ""


def summary_line(result) -> str:
    """'7.5/10: position.M transposed, statics.Fq negated' (the keys that lost marks)."""
    head = f"{number_text(result.score)}/{number_text(result.max_score)}"
    wrong = []
    for q in result.questions:
        for key in q.graded:
            r = q.keys[key]
            if r.verdict in ("correct", "no_reference"):
                continue
            wrong.append(f"{q.id}.{key} {r.diagnosis or r.verdict}")
    if result.error and not result.questions:
        wrong.append("invalid")
    return head + (": " + ", ".join(wrong) if wrong else "")


def _csv(rows) -> str:
    buf = io.StringIO()
    csv.writer(buf, lineterminator="\n").writerows(rows)
    return buf.getvalue()


def gradebooks(names, table, title: str, by_row: dict) -> dict:
    """{relative path: text}: one file per LMS; `by_row`: roster row -> SubmissionResult."""
    files = {}
    rows = range(len(table.rows))

    def score(r):
        return number_text(by_row[r].score) if r in by_row else ""

    for name in names:
        if name == "canvas":
            body = [list(CANVAS_COLUMNS) + [title]]
            body += [[table.cell(r, c) for c in CANVAS_COLUMNS] + [score(r)] for r in rows]
        elif name == "moodle":
            body = [["email", "idnumber", title, f"{title} feedback"]]
            body += [[table.cell(r, "email"), table.cell(r, "idnumber"), score(r),
                      summary_line(by_row[r]) if r in by_row else ""] for r in rows]
        else:
            body = [["Username", title]]
            body += [[table.cell(r, "username") or table.cell(r, "student"), score(r)] for r in rows]
        files[f"gradebook/{name}.csv"] = _csv(body)
    return files
