import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PROBLEMS = ROOT / "problems"

# The smallest robot problem: one revolute joint, one position question (CLI and output tests).
MINI = """\
robosolve: 1
name: mini
parameters: {L: 1}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(L)"}
questions:
  - {type: position, at: {q: 0}}
"""


@pytest.fixture
def write_problem(tmp_path):
    """Write a YAML problem text (dedented) to a file and return its path."""

    def _write(text: str, name: str = "p.yaml") -> Path:
        path = tmp_path / name
        path.write_text(textwrap.dedent(text).lstrip("\n"), encoding="utf-8")
        return path

    return _write
