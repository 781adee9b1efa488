"""Variant ids: zero-padded positions (--count) or students' ids made safe (--roster)."""

from __future__ import annotations

import csv
import hashlib
import io
import re

from robosolve.core.csv_text import csv_reader
from robosolve.errors import InputError, InputIssue
from robosolve.load.expressions import did_you_mean, shown
from robosolve.load.yamlsource import read_table_file

UNSAFE_RUN = re.compile(r"[^a-z0-9_-]+")


MAX_NAME = 64                   # characters of a name made from a student id (a file name part)


def safe_name(student: str) -> str:
    """variants.md: lower case, each run outside [a-z0-9_-] -> one '-', no leading/trailing '-';
    a name longer than MAX_NAME keeps its first characters and ends with 8 hexadecimal digits of
    the SHA-256 of the whole id (file systems refuse names over 255 bytes)."""
    name = UNSAFE_RUN.sub("-", student.lower()).strip("-")
    if len(name) <= MAX_NAME:
        return name
    digest = hashlib.sha256(student.encode("utf-8")).hexdigest()[:8]
    return f"{name[:MAX_NAME - 9].rstrip('-')}-{digest}"


def count_ids(n: int) -> list[str]:
    width = len(str(n))
    return [str(k).zfill(width) for k in range(1, n + 1)]


class CountedIds:
    """The (variant id, "") pairs of `--count n`, made one at a time: `len` is known before any
    id exists, so a count larger than the variants that exist is refused without allocating."""

    def __init__(self, n: int):
        self.n = n
        self.width = len(str(n))

    def __len__(self) -> int:       # a count beyond sys.maxsize has no len(): see `asked`
        return self.n

    @property
    def asked(self) -> int:
        return self.n

    def __iter__(self):
        for k in range(1, self.n + 1):
            yield str(k).zfill(self.width), ""


def read_roster(path) -> list[tuple[str, str]]:
    """(variant id, student id as written), in roster order; InputError for a bad roster."""
    return roster_table(path)[0]


def roster_csv(path) -> bytes:
    """DIR/roster.csv: the roster as read (blank lines left out), a first column `variant` added."""
    ids, header, rows = roster_table(path)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["variant"] + header)
    for (vid, _), row in zip(ids, rows):
        w.writerow([vid] + row)
    return buf.getvalue().encode("utf-8")


def roster_table(path):
    """(ids as read_roster gives them, the header as written, each student's row as written)."""
    file = str(path)
    text = read_table_file(path, line=1, what="the roster")
    reader = csv_reader(text)          # `,` or, from a spreadsheet in many locales, `;`
    rows, lines, last = [], [], 0      # each row, and the line it starts on (a quoted cell may hold lines)
    try:
        for row in reader:
            lines.append(last + 1)
            rows.append(row)
            last = reader.line_num
    except csv.Error as exc:
        raise InputError([InputIssue(file, reader.line_num, "", f"CSV error: {exc}")])
    if not rows:
        raise InputError([InputIssue(file, 1, "", "the roster is empty (expected a header with a `student` column)")])
    header = [h.strip() for h in rows[0]]
    if "student" not in [h.casefold() for h in header]:
        raise InputError([InputIssue(file, 1, "", "no `student` column" + did_you_mean("student", header)
                                     + f" (columns: {', '.join(header) or 'none'})")])
    folded = [h.casefold() for h in header]
    if folded.count("student") > 1:          # which one holds the ids? (a merged export, say)
        raise InputError([InputIssue(file, 1, "", "the header has more than one `student` column "
                                     "(columns: " + ", ".join(header) + "): keep one")])
    col = folded.index("student")
    out, seen, issues, kept = [], {}, [], []
    for line, row in zip(lines[1:], rows[1:]):
        if not any(c.strip() for c in row):
            continue                     # a blank line
        student = row[col].strip() if col < len(row) else ""
        name = safe_name(student)
        if not name:
            issues.append(InputIssue(file, line, "student",
                                     f"student id {shown(student)!r} gives an empty folder name"
                                     " (it needs a letter or a digit)"))
            continue
        if name in seen:
            first_line, first = seen[name]
            issues.append(InputIssue(file, line, "student",
                                     f"{shown(student)!r} and {shown(first)!r} (line {first_line}) give the "
                                     f"same folder name '{name}'"))
            continue
        seen[name] = (line, student)
        out.append((name, student))
        kept.append(row)
    if issues:
        raise InputError(issues)
    if not out:
        raise InputError([InputIssue(file, 1, "", "the roster has no students")])
    return out, rows[0], kept
