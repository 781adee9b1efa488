"""Rosters as spreadsheets save them: Excel's "Unicode text" is UTF-16 with a byte-order mark and
tabs between the fields (it was refused as 'UTF-16 text, not UTF-8'); UTF-8 with a byte-order
mark; a header with two `student` columns is refused (which one holds the ids?) — it used the
first silently."""

from __future__ import annotations

import codecs

import pytest

from robosolve.errors import InputError
from robosolve.variants.naming import read_roster

ROWS = [["Student", "Email"], ["Jo Smith", "jo@x.org"], ["Łukasz Ćwik", "l@x.org"]]


def _text(sep: str) -> str:
    return "\r\n".join(sep.join(r) for r in ROWS) + "\r\n"


@pytest.mark.parametrize("encoding, bom, sep", [
    ("utf-16-le", codecs.BOM_UTF16_LE, "\t"), ("utf-16-be", codecs.BOM_UTF16_BE, "\t"),
    ("utf-8", codecs.BOM_UTF8, ","), ("utf-8", b"", ";"),
])
def test_a_roster_in_the_encodings_spreadsheets_save_is_read(tmp_path, encoding, bom, sep):
    path = tmp_path / "roster.csv"
    path.write_bytes(bom + _text(sep).encode(encoding))
    assert read_roster(path) == [("jo-smith", "Jo Smith"), (read_roster(path)[1][0], "Łukasz Ćwik")]
    assert [student for _, student in read_roster(path)] == ["Jo Smith", "Łukasz Ćwik"]


def test_utf16_without_its_mark_and_two_student_columns_are_refused(tmp_path):
    path = tmp_path / "roster.csv"
    path.write_bytes(codecs.BOM_UTF16_LE + b"S\x00t\x00\x00\xd8")          # a lone surrogate
    with pytest.raises(InputError, match="starts as UTF-16 text but is not"):
        read_roster(path)
    path.write_text("student,Name,Student\ns1,Jo,s2\n")
    with pytest.raises(InputError) as exc:
        read_roster(path)
    assert [str(i) for i in exc.value.issues] == [
        f"{path}:1: the header has more than one `student` column (columns: student, Name, Student): keep one"]
