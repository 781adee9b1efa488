"""A question type is named only in its own rooms (issue 21): its solver
`robosolve/solvers/<type>.py` and its type module `robosolve/questions/<type>.py`.

Everything else asks the registry (flags such as `needs_dynamics`, `makes_profile`,
`has_jacobian`, ...). Checked on the tokens of every source file of the package: a type
name with an underscore (`motion_profile`) may not appear as a word in any string or
comment; a plain word (`position`, `statics`) may not be compared with (`==`, `in`) nor
listed with another type name: the same words are ordinary prose, labels and function
names elsewhere.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

from robosolve.questions.registry import MODULES, QUESTION_TYPES

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"

# Files allowed to name every type, and why.
ALLOWED = {
    # the registry lists its type modules by name
    "robosolve/questions/registry.py",
}


# (file, type) pairs of prose that points the reader to another type, and why.
PROSE = {
    # the report says the plant is the same derivation as the equations-of-motion question
    ("robosolve/solvers/forward_dynamics.py", "equations_of_motion"),
}


def _own(path: str, name: str) -> bool:
    return (path in (f"robosolve/solvers/{name}.py", f"robosolve/questions/{name}.py")
            or (path, name) in PROSE)


def type_name_uses(source: str, names) -> list[tuple[int, str]]:
    """(line, name) of each use of a type name in the tokens of `source`."""
    words = [n for n in names if "_" in n]
    word_re = re.compile(r"(?<![A-Za-z0-9_])(" + "|".join(map(re.escape, words)) + r")(?![A-Za-z0-9_])")
    plain = {n for n in names if "_" not in n}
    out = []
    texts = {tokenize.STRING, tokenize.COMMENT, getattr(tokenize, "FSTRING_MIDDLE", tokenize.STRING)}
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in texts:
            continue
        out += [(tok.start[0], m.group(1)) for m in word_re.finditer(tok.string)]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
            named = [(c.lineno, c.value) for c in node.elts if isinstance(c, ast.Constant) and c.value in plain]
            if len(named) > 1:      # a list of types
                out += named
        if isinstance(node, ast.Compare):
            for side in [node.left, *node.comparators]:
                items = side.elts if isinstance(side, (ast.Tuple, ast.List, ast.Set)) else [side]
                out += [(c.lineno, c.value) for c in items
                        if isinstance(c, ast.Constant) and c.value in plain]
    return sorted(out)


def test_a_type_is_named_only_by_its_solver_and_its_type_module():
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).as_posix()
        if rel in ALLOWED:
            continue
        for line, name in type_name_uses(path.read_text(encoding="utf-8"), QUESTION_TYPES):
            if not _own(rel, name):
                bad.append(f"{rel}:{line}: names the question type {name!r}")
    assert not bad, "ask the registry instead:\n" + "\n".join(bad)


def test_every_type_has_its_module_and_solver():
    for name in MODULES:
        assert (PACKAGE / "questions" / f"{name}.py").is_file()
        assert (PACKAGE / "solvers" / f"{name}.py").is_file()
    assert list(QUESTION_TYPES) == list(MODULES)


def test_the_name_check_can_fail():
    src = ('x = t == "position"\n# a motion_profile here\ny = f"{a} statics"\nz = "position"\n'
           'w = t in ("dof", "x")\nv = ["dof", "statics"]\n')
    assert type_name_uses(src, ("position", "motion_profile", "statics", "dof")) == [
        (1, "position"), (2, "motion_profile"), (5, "dof"), (6, "dof"), (6, "statics")]
