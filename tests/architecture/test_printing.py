"""Only the command-line package prints (docs/architecture.md): nothing outside robosolve/cli/
calls print(), builds a rich Console, writes to sys.stdout / sys.stderr, or calls typer.echo /
rich.print. Everything else returns records the CLI prints.

Read from the AST of every module, so a call in a function nobody runs in the tests is seen too.
One exception, the entry point `robosolve/__main__.py`: it says "interrupted" when Ctrl-C comes
while the CLI package itself is still being imported (there is no CLI yet to say it). And
the notebook's runtime `robosolve/render/notebook_runtime.py`, which robosolve never runs: it is
copied into report.ipynb, where printing the recomputed values is its job.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"
CLI = PACKAGE / "cli"
NOTEBOOK_RUNTIME = PACKAGE / "render" / "notebook_runtime.py"

# dotted call targets that print; names imported `from rich import print` etc. are resolved below
PRINTING = {"print", "Console", "rich.console.Console", "sys.stdout.write", "sys.stderr.write",
            "sys.__stdout__.write", "sys.__stderr__.write", "typer.echo", "typer.secho", "click.echo",
            "click.secho", "rich.print", "pprint.pprint"}
# what `from MODULE import NAME` makes of a bare NAME
FROM_IMPORTS = {("rich", "print"): "rich.print", ("rich.console", "Console"): "Console",
                ("typer", "echo"): "typer.echo", ("typer", "secho"): "typer.secho",
                ("click", "echo"): "click.echo", ("sys", "stdout"): "sys.stdout",
                ("sys", "stderr"): "sys.stderr", ("pprint", "pprint"): "pprint.pprint"}


def _dotted(node) -> str | None:
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute):
        base = _dotted(node.value)
        return f"{base}.{node.attr}" if base else None
    return None


def printing_calls(source: str, filename: str = "<src>") -> list[tuple[int, str]]:
    """(line, call) of every printing call in `source`."""
    tree = ast.parse(source, filename)
    aliases = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            for a in node.names:
                target = FROM_IMPORTS.get((node.module, a.name))
                if target:
                    aliases[a.asname or a.name] = target
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.asname:
                    aliases[a.asname] = a.name
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        name = _dotted(node.func)
        if name is None:
            continue
        head, _, rest = name.partition(".")
        full = aliases.get(head, head) + (f".{rest}" if rest else "")
        if full in PRINTING or name in PRINTING:
            found.append((node.lineno, full))
    return found


def test_nothing_outside_the_cli_package_prints():
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if CLI in path.parents or path in (PACKAGE / "__main__.py", NOTEBOOK_RUNTIME):
            continue
        for line, call in printing_calls(path.read_text(encoding="utf-8"), str(path)):
            bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {call}(...)")
    assert not bad, "printing outside robosolve/cli/ (return a record the CLI prints):\n" + "\n".join(bad)


def test_the_printing_check_can_fail():
    src = ("import sys\nimport typer\nfrom rich.console import Console as C\nfrom rich import print as rp\n"
           "def f():\n    print('x')\n    sys.stderr.write('y')\n    C(stderr=True)\n    typer.echo('z')\n"
           "    rp('w')\n    sys.stdout.flush()\n")
    assert [c for _, c in printing_calls(src)] == ["print", "sys.stderr.write", "Console", "typer.echo",
                                                   "rich.print"]


def test_the_cli_package_does_print():
    """The check looks where printing happens: the CLI package has such calls (or the walker is blind)."""
    calls = [c for p in CLI.rglob("*.py") for _, c in printing_calls(p.read_text(encoding="utf-8"))]
    assert "sys.stderr.write" in calls and "Console" in calls
