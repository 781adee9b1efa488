"""Matrices and vectors typed as one string (papers.md "What students may write"):
MATLAB `"[1 0; 0 1]"`, `"[1, 0; 0, 1]"`, Python `"[[1, 0], [0, 1]]"`, `"[0.43, 0.65, 0]"`.

The text becomes the nested lists of strings a YAML answer would hold; each entry is then
read as an expression like any other (`^` for powers, `deg(…)`).
"""

from __future__ import annotations

OPERATORS = "+-*/^"


class ArrayTextError(ValueError):
    """The text is not a matrix or vector in MATLAB or Python notation."""


def split_top_level(text: str, sep: str, strict: bool = True) -> list[str]:
    """`text` split at `sep` outside brackets and parentheses; `strict`: unbalanced brackets
    are an ArrayTextError (else the text is split as far as it goes)."""
    parts, depth, cur = [], 0, ""
    for ch in text:
        if ch in "([":
            depth += 1
        elif ch in ")]":
            depth -= 1
            if depth < 0 and strict:
                raise ArrayTextError("unbalanced brackets")
        if ch == sep and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    if depth != 0 and strict:
        raise ArrayTextError("unbalanced brackets")
    parts.append(cur)
    return parts


def _split(text: str, sep: str) -> list[str]:
    return split_top_level(text, sep)


def row_entries(row: str) -> list[str]:
    """A MATLAB row without commas: entries separated by spaces or tabs, `1 - 2` one entry,
    `1 -2` two."""
    out: list[str] = []
    for token in _split(" ".join(row.split()), " "):
        if not token:
            continue
        joins = out and (out[-1][-1] in OPERATORS + "(" or token[0] in "*/^)"
                         or (token in ("+", "-")))
        if joins:
            out[-1] = f"{out[-1]} {token}"
        else:
            out.append(token)
    return out


def _row(row: str) -> list[str]:
    cells = _without_trailing(_split(row, ","))
    if len(cells) == 1:
        cells = row_entries(row)
    cells = [c.strip() for c in cells]
    if not cells or any(not c for c in cells):
        raise ArrayTextError("an empty entry")
    return cells


def _without_trailing(parts: list[str]) -> list[str]:
    """`[1, 2,]` and `[1 2;]` as Python and MATLAB read them: one trailing separator is no entry."""
    return parts[:-1] if len(parts) > 1 and not parts[-1].strip() else parts


def _transposed(a):
    if a and isinstance(a[0], list):
        return [list(col) for col in zip(*a)]
    return [[x] for x in a]                        # a row vector's transpose: a column


def parse_array(text: str):
    """'[1 0; 0 1]' -> [['1', '0'], ['0', '1']]; '[1, 2, 3]' -> ['1', '2', '3'];
    '[[1, 0], [0, 1]]' -> [['1', '0'], ['0', '1']]. MATLAB's ends of lines separate rows as
    `;` does, and a trailing `'` (or `.'`) transposes: `[1 2 3]'` is a column."""
    t = text.strip()
    for mark in (".'", "'"):
        if t.endswith("]" + mark):
            return _transposed(parse_array(t[: -len(mark)]))
    if not (t.startswith("[") and t.endswith("]")):
        raise ArrayTextError("a matrix or vector is written in brackets: [1 0; 0 1] or [[1, 0], [0, 1]]")
    inner = t[1:-1].strip()
    if not inner:
        return []
    if inner.startswith("["):                     # Python: a list of lists
        items = [i.strip() for i in _without_trailing(_split(inner, ","))]
        if not all(i.startswith("[") and i.endswith("]") for i in items):
            raise ArrayTextError("mixed rows and entries")
        return [parse_array(i) for i in items]
    rows = [r for line in _split(inner, "\n") for r in _split(line, ";")]
    rows = [r for i, r in enumerate(rows) if r.strip() or i == 0]   # `;` at an end of line
    if len(rows) == 1:
        return _row(rows[0])
    return [_row(r) for r in rows]
