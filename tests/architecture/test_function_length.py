"""No function over 80 lines in robosolve/ unless a `# long: <why>` comment says why.

The comment sits on the line above the `def` (above its decorators) or on the first line of
the body. A reason is a sentence, not a bare tag.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"
MAX_LINES = 80


def long_functions(path: Path) -> list[tuple[str, int, int, str | None]]:
    """(name, line, length, reason or None) of every function over MAX_LINES."""
    text = path.read_text(encoding="utf-8")
    lines = text.splitlines()
    out = []
    for node in ast.walk(ast.parse(text, str(path))):
        if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        length = node.end_lineno - node.lineno + 1
        if length <= MAX_LINES:
            continue
        top = min([node.lineno] + [d.lineno for d in node.decorator_list])
        body = node.body[0].lineno if node.body else node.lineno + 1
        candidates = [lines[top - 2] if top >= 2 else ""] + lines[node.lineno:body]
        reason = next((c.split("# long:", 1)[1].strip() for c in candidates if "# long:" in c), None)
        out.append((node.name, node.lineno, length, reason))
    return out


def test_long_functions_say_why():
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for name, line, length, reason in long_functions(path):
            if not reason or len(reason.split()) < 4:
                bad.append(f"{path.relative_to(PACKAGE.parent)}:{line} {name} ({length} lines)")
    assert not bad, ("functions over 80 lines without a `# long: <why>` comment "
                     "(split them into compute / steps, or say why not):\n" + "\n".join(bad))


def test_the_check_can_fail(tmp_path):
    body = "\n".join(f"    x{i} = {i}" for i in range(85))
    (tmp_path / "m.py").write_text(f"def f():\n{body}\n\n\n# long: one table of cases, read top to bottom\n"
                                   f"def g():\n{body}\n")
    found = {n: r for n, _, _, r in long_functions(tmp_path / "m.py")}
    assert found == {"f": None, "g": "one table of cases, read top to bottom"}
