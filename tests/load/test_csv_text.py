"""The delimiter of a teacher's CSV (core/csv_text.py) against the csv module's own writer."""

from __future__ import annotations

import csv
import io

import pytest

from robosolve.core.csv_text import csv_reader, delimiter

ROWS = [["Student", "Name, first", "Grade"], ["Jo Smith", "Jo", "1,5"], ["Ann \"A\" B", "Ann; B", ""]]


@pytest.mark.parametrize("sep", [",", ";", "\t"])
def test_rows_written_with_any_delimiter_read_back(sep):
    buf = io.StringIO()
    csv.writer(buf, delimiter=sep, lineterminator="\n").writerows(ROWS)
    text = buf.getvalue()
    assert delimiter(text) == sep
    assert list(csv_reader(text)) == ROWS


def test_one_column_and_blank_first_lines():
    assert delimiter("student\nJo\n") == ","
    assert delimiter("\n\nstudent;email\nJo;a\n") == ";"
    assert list(csv_reader("student\nJo Smith\n")) == [["student"], ["Jo Smith"]]
