"""Prose with numbers left raw: what solvers and engines write, the renderer formats.

A solver never formats or rounds a number (the number policy lives in
``robosolve/render/numbers.py``). Where a number sits inside a sentence, a table cell, a
figure title, a note or a reason, the solver writes a :class:`Text`, a sequence of
strings and :class:`Num` values; the renderer turns each `Num` into digits for its
output (report.md, results.json notes, a PNG title).

    Text("peak ", Num(12.345678, unit="N·m"), " at t = ", Num(0.5), " s")
    Text.join(", ", [Num(x) for x in xs])
    "max |e| = " + Text(Num(e))          # str + Text -> Text

`Num.digits` is the precision the value has (a condition number is worth 3 digits); None
means the report's default.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["Num", "Text", "name_tex", "name_md"]

# A name from the problem file (a frame, a body, a force) is any string: in LaTeX and in
# Markdown its special characters are escaped, so that `$`, `\\`, `{`, `_` or `<script>` in a
# name neither breaks a formula nor becomes markup. Plain names (letters, digits) are unchanged.
_TEX_SPECIAL = {"\\": "\\backslash{}", "{": "\\{", "}": "\\}", "$": "\\$", "&": "\\&", "#": "\\#",
                "%": "\\%", "_": "\\_", "^": "\\hat{}", "~": "\\sim{}", " ": "\\ ", "<": "\\lt{}",
                ">": "\\gt{}"}
_MD_SPECIAL = set("\\`*_[]<>$~&")          # (a table cell escapes its | itself)
# A line break in a name (YAML "a\nb") is shown as a space: a formula and a sentence stay on their
# line (an inline formula never spans lines; "a\n# b" would start a heading).
_LINE_BREAK = re.compile("\r\n|[\n\r\v\f\x1c\x1d\x1e\x85\u2028\u2029]")


def name_tex(name: str, plain_digits: bool = True) -> str:
    """A name inside a formula, upright (\\mathrm); a frame's number as it is (frame 1)."""
    if plain_digits and name.isdigit():
        return name
    return "\\mathrm{" + "".join(_TEX_SPECIAL.get(c, c) for c in _LINE_BREAK.sub(" ", name)) + "}"


def name_md(name: str) -> str:
    """A name inside Markdown prose or a table cell: its ASCII punctuation backslash-escaped
    (CommonMark), so it shows as written."""
    return "".join("\\" + c if c in _MD_SPECIAL else c for c in _LINE_BREAK.sub(" ", name))


def name_plot(name: str) -> str:
    """A name (any string) in a figure's plain text: its `$` escaped, so that matplotlib never
    reads it as mathtext (`$\\frac{$` would stop the figure) and shows it as written."""
    return name.replace("$", "\\$")


PLAIN_NAME = re.compile(r"[A-Za-z0-9]+")   # a name mathtext shows as written inside \mathrm{}


@dataclass(frozen=True)
class Num:
    """A raw number in prose, formatted by the renderer (`unit` follows after a space)."""

    value: float
    unit: str = ""
    digits: int | None = None


class Text(tuple):
    """Pieces of prose: strings and `Num` (or nested `Text`), joined by the renderer."""

    def __new__(cls, *pieces):
        return super().__new__(cls, pieces)

    def __getnewargs__(self):
        # pickle (a figure sent to the drawing process) rebuilds Text(*pieces), not Text(pieces)
        return tuple(self)

    def __add__(self, other):
        return Text(*self, *(other if isinstance(other, Text) else (other,)))

    def __radd__(self, other):
        return Text(other, *self)

    def __contains__(self, item) -> bool:
        """`"words" in text` looks for the words in the prose (numbers are not words),
        so a note reads as the str it becomes."""
        if isinstance(item, str):
            return item in self.words()
        return super().__contains__(item)

    def words(self) -> str:
        """The prose with every number replaced by '#'."""
        return "".join(p.words() if isinstance(p, Text) else p if isinstance(p, str) else "#"
                       for p in self)

    def __repr__(self) -> str:
        return "Text" + super().__repr__()

    @staticmethod
    def join(sep: str, items) -> "Text":
        out: list = []
        for k, item in enumerate(items):
            if k:
                out.append(sep)
            out.append(item)
        return Text(*out)
