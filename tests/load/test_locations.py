"""Every message about a file's bytes names the line (issue 22): a byte that is not UTF-8, a NUL
or another character YAML refuses, nesting thousands of levels deep (no RecursionError)."""

from __future__ import annotations

import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem, load_problem_text

HEAD = "robosolve: 1\nname: n\nparameters: {L: 1}\n"


def messages(text, name="p.yaml"):
    with pytest.raises(InputError) as exc:
        load_problem_text(text, name)
    return [str(i) for i in exc.value.issues]


def test_a_byte_that_is_not_utf8_is_reported_at_its_line(tmp_path):
    p = tmp_path / "p.yaml"
    p.write_bytes(HEAD.encode() + b"joints: []\n# caf\xe9\n")
    with pytest.raises(InputError) as exc:
        load_problem(p)
    assert str(exc.value) == f"{p}:5: the file is not UTF-8 text: byte 0xe9 at column 6 (save it as UTF-8)"


def test_a_nul_byte_is_reported_at_its_line_in_words():
    found = messages(HEAD + 'questions:\n  - {type: position, id: "a\x00b"}\n')
    assert found == ["p.yaml:5: a NUL character (byte 0) at column 28: YAML does not allow it in a file "
                     "(remove it; was the file saved as UTF-16 or binary?)"]
    assert "<unicode string>" not in found[0] and "position" not in found[0]


@pytest.mark.parametrize("limit", [None, 20000])
def test_deep_nesting_is_said_at_one_line_whatever_the_stack(limit):
    """Composing a file nested 600 deep runs out of Python's stack at the default recursion limit
    (the line then comes from a scan of the tokens) and not at a larger one (it comes from the
    converter): both say the same line, the first sequence 41 levels below the top mapping."""
    import sys

    deep = "x:\n" + "".join(" " * i + "- \n" for i in range(1, 600))
    old = sys.getrecursionlimit()
    sys.setrecursionlimit(limit or 1000)
    try:
        [m] = messages(HEAD + deep)
    finally:
        sys.setrecursionlimit(old)
    assert m == "p.yaml:45: x: nesting deeper than 40 levels"      # FILE:LINE: the section: what


def test_another_control_character():
    [m] = messages(HEAD + "x: \x07\n")
    assert m.startswith("p.yaml:4: the control character U+0007 at column 4")


@pytest.mark.parametrize("deep", [
    "x: " + "[" * 5000 + "]" * 5000 + "\n",                      # flow sequences
    "x: " + "{a: " * 3000 + "1" + "}" * 3000 + "\n",             # flow mappings
    "x:\n" + "".join(" " * i + "- \n" for i in range(1, 600)),   # block sequences, one per line
])
def test_deep_nesting_is_reported_where_it_gets_too_deep(deep):
    [m] = messages(HEAD + deep)
    line = int(m.split(":")[1])
    assert line >= 4 and m.endswith(": x: nesting deeper than 40 levels"), m
    if deep.startswith("x:\n"):
        assert line == 4 + 41, m                     # the first line past 40 levels below the top


@pytest.mark.parametrize("encoding", ["utf-16", "utf-16-le", "utf-16-be"])
def test_a_utf16_file_is_said_to_be_utf16(tmp_path, encoding):
    """Windows Notepad's "Unicode" (UTF-16 with its byte-order mark): named, not "byte 0xff"."""
    p = tmp_path / "p.yaml"
    text = HEAD + "joints: []\n"
    p.write_bytes(("\ufeff" + text).encode(encoding) if encoding != "utf-16" else text.encode(encoding))
    with pytest.raises(InputError) as exc:
        load_problem(p)
    assert str(exc.value) == f"{p}:1: the file is UTF-16 text, not UTF-8 (save it as UTF-8)"
