"""The rows of a CSV text a teacher hands in: a roster or a table exported by a spreadsheet or an LMS.

Spreadsheets in many locales (Excel in French, German, Spanish, Italian...) save "CSV" with `;`
between the fields, since `,` is their decimal mark; some LMS exports use tabs. The delimiter is
read off the header line: the one of `,`, `;` and tab found most often outside its quoted fields
(`,` on a tie, and for a one-column file).
Quoting is the csv module's (a field with the delimiter in it is quoted).
"""

from __future__ import annotations

import csv
import io
import re

_QUOTED = re.compile(r'"(?:[^"]|"")*"')


def delimiter(text: str) -> str:
    """The field delimiter of the CSV `text`, from its first non-blank line."""
    header = next((line for line in text.splitlines() if line.strip()), "")
    header = _QUOTED.sub("", header)          # a delimiter inside a quoted field does not count
    counts = {c: header.count(c) for c in (",", ";", "\t")}
    best = max(counts.values())
    return next(c for c, n in counts.items() if n == best) if best else ","


def csv_reader(text: str):
    """A csv.reader over `text` with its delimiter (see `delimiter`); `line_num` as csv's."""
    return csv.reader(io.StringIO(text), delimiter=delimiter(text))
