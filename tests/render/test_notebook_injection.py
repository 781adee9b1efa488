"""Strings from a problem file reach report.ipynb's code only as literals (issue 22): body,
force, frame and point names that look like code neither run nor break a cell."""

import ast
import json
import re

import pytest

from robosolve.load.loader import load_problem
from robosolve.run.pipeline import render_files, solve_problem
from robosolve.render.drawing import InlineFigures

EVIL = 'b": open("X","w").write("x"), "c'
QUOTED = 'arm "A"'
FORCE = "f\\\"); open('X','w').write('x'); (\\\""       # YAML-escaped: f"); open('X','w')...
LATEX = "$\\\\{_<script>x|y"                              # YAML-escaped: $\{_<script>x|y

PROBLEM = f"""\
robosolve: 1
name: evil
parameters: {{L: 1, m: 2, g: 9.81, F: 3}}
joints:
  - {{name: q1, type: revolute}}
  - {{name: q2, type: revolute}}
frames:
  '{QUOTED}': {{parent: "0", pose: "Rz(q1) Tx(L)"}}
  '{EVIL}': {{parent: '{QUOTED}', pose: "Rz(q2) Tx(L)"}}
points:
  P: {{frame: '{EVIL}', at: [0, 0, 0]}}
gravity: [0, -g, 0]
bodies:
  - {{name: '{EVIL}', frame: '{QUOTED}', mass: m, point: [0, 0, 0]}}
  - {{name: "{LATEX}", frame: '{EVIL}', mass: m, rod: {{from: [-L, 0, 0], to: [0, 0, 0]}}}}
forces:
  - {{name: "{FORCE}", frame: '{QUOTED}', at: [0, 0, 0], force: [0, F, 0], in: '{EVIL}'}}
questions:
  - {{type: position, frame: '{EVIL}', at: {{q1: 0, q2: 0}}}}
  - {{type: velocity_acceleration, frame: '{QUOTED}', point: P,
     at: {{q1: 0, q2: 0, q1_dot: 1, q2_dot: 1, q1_ddot: 0, q2_ddot: 0}}}}
  - {{type: orientation, frame: '{QUOTED}', at: {{q1: 0.3}}}}
  - {{type: equations_of_motion, at: {{q1: 0, q2: 0, q1_dot: 0, q2_dot: 0, q1_ddot: 0, q2_ddot: 0}}}}
  - {{type: statics, weight: true, at: {{q1: 0, q2: 0}}}}
"""


@pytest.fixture(scope="module")
def evil_files(tmp_path_factory):
    path = tmp_path_factory.mktemp("evil") / "evil.yaml"
    path.write_text(PROBLEM, encoding="utf-8")
    problem = load_problem(path)
    assert {b.name for b in problem.bodies} == {EVIL, "$\\{_<script>x|y"}
    assert {f.name for f in problem.forces} == {"f\"); open('X','w').write('x'); (\""}
    assert set(problem.frames) == {QUOTED, EVIL}
    return render_files(solve_problem(problem), ("md", "html", "ipynb"), InlineFigures())


def _code_cells(files):
    nb = json.loads(files["report.ipynb"])
    return [("".join(c["source"]) if isinstance(c["source"], list) else c["source"])
            for c in nb["cells"] if c["cell_type"] == "code"]


def test_every_code_cell_parses_and_holds_the_names_only_as_literals(evil_files):
    cells = _code_cells(evil_files)
    strings = set()
    for source in cells:
        tree = ast.parse(source)
        strings |= {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}
        calls = {n.func.id for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
        assert "open" not in calls, source
    assert {EVIL, QUOTED, "f\"); open('X','w').write('x'); (\""} <= strings


def test_running_the_notebook_creates_no_file(evil_files, tmp_path, monkeypatch):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    folder, elsewhere = tmp_path / "report", tmp_path / "elsewhere"
    folder.mkdir()
    elsewhere.mkdir()
    (folder / "report.ipynb").write_bytes(evil_files["report.ipynb"])
    nb = nbformat.read(folder / "report.ipynb", as_version=4)
    monkeypatch.chdir(elsewhere)
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(elsewhere)}}).execute()
    assert [p.name for p in folder.iterdir()] == ["report.ipynb"]
    assert list(elsewhere.iterdir()) == []


def _balanced(tex: str) -> bool:
    depth = 0
    for m in re.finditer(r"\\.|[{}]", tex):
        if m.group() == "{":
            depth += 1
        elif m.group() == "}":
            depth -= 1
            if depth < 0:
                return False
    return depth == 0


def test_the_names_are_escaped_in_the_markdown_and_the_html(evil_files):
    from robosolve.render.html import DISPLAY, INLINE

    md = evil_files["report.md"].decode("utf-8")
    assert not re.search(r"(?<!\\)<script", md)        # in prose, tables and formulas
    formulas = DISPLAY.findall(md) + INLINE.findall(DISPLAY.sub("", md))
    assert formulas and all(_balanced(f) for f in formulas), [f for f in formulas if not _balanced(f)][:3]
    assert "\\mathrm{\\$\\backslash{}\\{\\_\\lt{}script\\gt{}x|y}" in md
    for line in md.splitlines():                            # a name with | does not split a table row
        if line.startswith("| ") and "script" in line:
            assert len(re.findall(r"(?<!\\)\|", line)) == 5, line     # the bodies: 4 columns
    html = evil_files["report.html"].decode("utf-8")
    assert "<script" not in html.lower()
    assert "&lt;script&gt;x|y" in html                    # shown as written in the bodies' table
