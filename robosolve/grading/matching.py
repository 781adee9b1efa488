"""Which variant a submission answers (grading.md "Grading a class": matching).

`grade --variants DIR` reads DIR/variants.csv (variant -> DIR/<name>-<variant>/problem.yaml)
and DIR/roster.csv when `variants --roster` wrote it (the roster as read, a first column
`variant` added; headers matched without regard to case, so an LMS export serves). A
submission is matched, in this order: by its `problem:` when it names a problem.yaml inside
DIR; by its `student` (trimmed, ignoring case) against every column of the roster; by the
variant ids (the roster's `variant` column). Matched through the roster (either way), it is
filed under its row's `student`. By `problem:`, the variant is the one named but the student
is who the id says: the id's roster row when it matches one (filed as above, its own variant
noted when it differs), else the variant's row stands for it, filed under the id. No match,
or two variants, is a `MatchError` saying so, with a did-you-mean.
Without roster.csv (a folder of `variants --count`, or an older one), variants.csv's own
`student` column is the roster.
"""

from __future__ import annotations

import csv
import difflib
from dataclasses import dataclass, field
from pathlib import Path

from robosolve.core.csv_text import csv_reader
from robosolve.grading.answers import safe_name


class TableError(Exception):
    """The variants folder cannot be read (a usage error: exit 2)."""


class MatchError(ValueError):
    """This submission matches no variant, or two (its `invalid` reason)."""


@dataclass
class Match:
    variant: str
    problem: Path
    student: str                   # the id the submission is filed under
    row: int | None = None         # its roster row (0-based), when there is one
    own_variant: str = ""          # the student's own variant, when `problem:` names another one


@dataclass
class VariantsTable:
    folder: Path
    problems: dict                 # variant id -> problem.yaml, in variants.csv order
    header: list                   # the roster's header as written (first column `variant`)
    rows: list                     # the roster's rows, each as long as the header
    has_roster: bool               # DIR/roster.csv exists (gradebooks need it)
    name: str = ""                 # the problem's name: DIR/<name>-<variant>/
    _by_problem: dict = field(default_factory=dict, repr=False)

    def __post_init__(self):
        self._by_problem = {_resolved(p): v for v, p in self.problems.items()}

    def column(self, name: str) -> int | None:
        """The roster column of this name, ignoring case and surrounding blanks."""
        wanted = name.strip().casefold()
        return next((i for i, h in enumerate(self.header) if h.strip().casefold() == wanted), None)

    def cell(self, row: int, name: str) -> str:
        i = self.column(name)
        return self.rows[row][i].strip() if i is not None else ""

    def row_of(self, variant: str) -> int | None:
        i = self.column("variant")
        if i is None:
            return None
        return next((r for r, row in enumerate(self.rows) if row[i].strip() == variant), None)

    def match(self, student: str, problem_file: Path | None) -> Match:
        if problem_file is not None:
            variant = self._by_problem.get(_resolved(problem_file))
            if variant is not None:
                return self._named(variant, student)
        hits = self._student_hits(student)
        if len(hits) > 1:
            raise MatchError(f"student '{student}' matches {len(hits)} variants in the roster of "
                             f"{self.folder} ({', '.join(hits)}): give `problem:` or a unique id")
        if hits:
            (variant, row), = hits.items()
            return Match(variant, self.problems[variant], self._filed(row, student), row)
        raise MatchError(f"student '{student}' is not in the roster of {self.folder}" + self._close(student))

    def _named(self, variant: str, student: str) -> Match:
        """The variant `problem:` names, answered by the student the id says: the id's roster
        row (the variant's own among several), so another student's variant never takes that
        student's row; only an id that matches no row, or several others, leaves the variant's
        row standing for it (filed under the id)."""
        hits = self._student_hits(student)
        if variant in hits or len(hits) != 1:
            row = hits.get(variant, self.row_of(variant))
            return Match(variant, self.problems[variant], self._filed(row, student) if variant in hits else student, row)
        (own, row), = hits.items()
        return Match(variant, self.problems[variant], self._filed(row, student), row, own)

    def _student_hits(self, student: str) -> dict:
        """variant -> roster row of `student`: by the roster's columns, else by the variant ids."""
        key = student.strip().casefold()
        hits = self._roster_hits(key)
        if hits:
            return hits
        for variant in self.problems:     # the variant ids: the roster's `variant` column
            if variant.casefold() == key or variant == safe_name(student):
                return {variant: self.row_of(variant)}
        return {}

    def _filed(self, row: int | None, student: str) -> str:
        """The id a submission matched through the roster is filed under: its row's `student`
        (the submission's own id when it has no row or the row no student)."""
        return (self.cell(row, "student") if row is not None else "") or student

    def _roster_hits(self, key: str) -> dict:
        """variant -> first roster row with a cell equal to `key` (trimmed, case ignored)."""
        vcol = self.column("variant")
        hits: dict = {}
        if not key or vcol is None:
            return hits
        for r, row in enumerate(self.rows):
            if any(c.strip().casefold() == key for i, c in enumerate(row) if i != vcol):
                hits.setdefault(row[vcol].strip(), r)
        return hits

    def _close(self, student: str) -> str:
        values = sorted({c.strip() for row in self.rows for c in row if c.strip()} | set(self.problems))
        folded = {v.casefold(): v for v in values}
        close = difflib.get_close_matches(student.strip().casefold(), sorted(folded), n=1, cutoff=0.6)
        return f"; did you mean '{folded[close[0]]}'?" if close else ""


def _resolved(path) -> str:
    try:
        return str(Path(path).resolve())
    except OSError:
        return str(path)


def _read_csv(path: Path, what: str) -> list:
    from robosolve.errors import InputError
    from robosolve.load.yamlsource import read_table_file

    try:         # bounded, regular files only, a bad byte reported at its line
        text = read_table_file(path, what=f"the {what}")
    except InputError as exc:
        raise TableError(str(exc)) from None
    try:
        return [row for row in csv_reader(text) if any(c.strip() for c in row)]
    except csv.Error as exc:
        raise TableError(f"{path}: CSV error in the {what}: {exc}")


def read_table(folder: Path) -> VariantsTable:
    """DIR/variants.csv (and DIR/roster.csv when present) -> VariantsTable; TableError otherwise."""
    folder = Path(folder)
    table = folder / "variants.csv"
    rows = _read_csv(table, "variants table")
    header = [h.strip() for h in rows[0]] if rows else []
    if rows and not {"variant", "student"} <= set(header):
        raise TableError(f"{table}: expected the columns variant,student,seed,…")
    records = [dict(zip(header, r + [""] * (len(header) - len(r)))) for r in rows[1:]]
    variants = [rec["variant"].strip() for rec in records]
    name = _base_name(folder, variants, table)
    problems = {v: folder / f"{name}-{v}" / "problem.yaml" for v in variants}
    roster = folder / "roster.csv"
    if roster.is_file():
        rrows = _read_csv(roster, "roster")
        rheader = [h for h in rrows[0]] if rrows else []
        width = len(rheader)
        body = [(r + [""] * width)[:max(width, len(r))] for r in rrows[1:]]
        out = VariantsTable(folder, problems, rheader, body, True, name)
        if out.column("variant") is None:
            raise TableError(f"{roster}: no `variant` column (robosolve variants --roster writes it first)")
        return out
    body = [[rec["variant"].strip(), rec["student"]] for rec in records if rec["student"].strip()]
    return VariantsTable(folder, problems, ["variant", "student"], body, False, name)


def _base_name(folder: Path, variants: list, table: Path) -> str:
    """The problem name <name> such that every variant has DIR/<name>-<variant>/problem.yaml.

    (A folder name alone is ambiguous: `exam-jo-smith` ends with `-smith` too.)
    """
    if not variants:
        return ""
    first = variants[0]
    candidates = sorted(p.parent.name[: -len(first) - 1] for p in folder.glob(f"*-{first}/problem.yaml"))
    for name in candidates:
        if all((folder / f"{name}-{v}" / "problem.yaml").is_file() for v in variants):
            return name
    raise TableError(f"{table}: no folder <name>-<variant>/problem.yaml for every variant in {folder}")
