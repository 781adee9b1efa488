"""--format md,html,ipynb: the HTML page is self-contained MathML with no TeX left, a
headless Chromium renders it, and the notebook validates and runs top to bottom in a fresh
kernel, recomputing the answers with sympy alone (compared with results.json)."""

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.render.html import render_html

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = ROOT / "tests" / "golden"
runner = CliRunner()

HTML_PROBLEMS = ["scara-rrp", "exam-2r-full", "rigid-displacements", "puma560-dynamics",
                 "planar-2r-rods", "one-link-eom"]
EXTERNAL = re.compile(r"<script|<link|<iframe|<object|@import|url\(|src=\"(?!data:|\")|https?://",
                      re.IGNORECASE)


def _text_outside_math(page: str) -> str:
    page = re.sub(r"<style>.*?</style>", "", page, flags=re.S)
    return re.sub(r"<math\b.*?</math>", "", page, flags=re.S)


@pytest.mark.parametrize("name", HTML_PROBLEMS)
def test_html_has_no_raw_tex_and_no_external_resources(name):
    md = (GOLDEN / name / "report.md").read_text(encoding="utf-8")
    page = render_html(md, None, name)
    outside = _text_outside_math(page)
    assert "$" not in outside
    assert not re.search(r"\\[A-Za-z]+", outside), re.search(r".{40}\\[A-Za-z]+.{40}", outside)
    # inside the MathML, no TeX command survived as text
    for m in re.finditer(r">([^<>]*)<", "".join(re.findall(r"<math\b.*?</math>", page, flags=re.S))):
        assert "\\" not in m.group(1), m.group(1)
    assert not EXTERNAL.search(re.sub(r"<style>.*?</style>", "", page, flags=re.S))
    assert page.count("<math") >= md.count("$$") // 2
    # the notes' anchors survive, and every in-page link has its target
    for target in re.findall(r'href="#([^"]+)"', page):
        assert f'id="{target}"' in page, target


def _solve(tmp_path, name, formats):
    out = tmp_path / name
    result = runner.invoke(app, ["solve", str(ROOT / "problems" / f"{name}.yaml"), "--out", str(out),
                                 "--format", formats])
    assert result.exit_code == 0, result.output
    return out


def test_solve_writes_the_formats_asked_for_with_embedded_figures(tmp_path):
    out = _solve(tmp_path, "scara-rrp", "html,ipynb")
    assert sorted(p.name for p in out.iterdir() if p.is_file() and not p.name.startswith(".")) == \
        ["report.html", "report.ipynb", "results.json"]
    page = (out / "report.html").read_text(encoding="utf-8")
    assert 'src="data:image/png;base64,' in page and "figures/" not in page
    assert not EXTERNAL.search(re.sub(r"<style>.*?</style>", "", page, flags=re.S))
    assert (out / "figures").is_dir()


def test_unknown_format_is_a_usage_error_and_nothing_is_written(tmp_path):
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(ROOT / "problems" / "scara-rrp.yaml"), "--out", str(out),
                                 "--format", "md,htm"])
    assert result.exit_code == 2
    assert "did you mean 'html'" in result.output
    assert not out.exists()


def _chromium():
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    return None


def test_chromium_renders_the_html_report(tmp_path):
    browser = _chromium()
    if browser is None:
        pytest.skip("no Chromium on this machine (.ci/run installs it where apt-get can)")
    out = _solve(tmp_path, "scara-rrp", "html")
    shot = tmp_path / "shot.png"
    subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--window-size=900,2400", f"--screenshot={shot}", (out / "report.html").as_uri()],
                   check=True, capture_output=True, timeout=180)
    from PIL import Image

    import numpy as np

    img = np.asarray(Image.open(shot).convert("L"))
    assert img.shape == (2400, 900)
    assert (img < 100).mean() > 0.005          # text, rules and formulas were drawn          # text, rules and formulas were drawn


def test_notebook_validates_runs_and_recomputes_the_answers(tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    out = _solve(tmp_path, "scara-rrp", "ipynb")
    text = (out / "report.ipynb").read_text(encoding="utf-8")
    nb = nbformat.reads(text, as_version=4)
    nbformat.validate(nb)
    ids = [c.id for c in nb.cells]
    assert len(set(ids)) == len(ids) and ids[0] == "md-001"
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    imported = set(re.findall(r"^\s*(?:import|from) (\w+)", code, flags=re.M))
    assert imported <= {"numpy", "sympy", "matplotlib", "json"}
    # same problem, same bytes
    again = _solve(tmp_path / "again", "scara-rrp", "ipynb")
    assert (again / "report.ipynb").read_text(encoding="utf-8") == text

    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(out)}}).execute()
    printed = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.outputs)
    results = json.loads((out / "results.json").read_text())["answers"]

    def numbers_after(label):          # printed with numpy's 6 decimals
        m = re.search(re.escape(label) + r"\s*\[([^\]]*)\]", printed)
        return [float(x) for x in m.group(1).split()]

    assert numbers_after("position =") == pytest.approx(results["position"]["numeric"]["position"], abs=2e-6)
    assert numbers_after("velocity =") == pytest.approx(
        results["velocity_acceleration"]["numeric"]["velocity"], abs=2e-6)
    assert numbers_after("acceleration =") == pytest.approx(
        results["velocity_acceleration"]["numeric"]["acceleration"], abs=2e-6)


MINI = """
robosolve: 1
name: mini
parameters: {L: 1}
joints:
  - {name: q, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q) Tx(L)"}
questions:
  - {type: position, at: {q: pi/3}}
"""


def test_batch_passes_the_formats_to_every_problem(write_problem, tmp_path):
    write_problem(MINI, "mini.yaml")
    out = tmp_path / "out"
    result = runner.invoke(app, ["batch", str(tmp_path), "--out", str(out), "--jobs", "1",
                                 "--format", "md,html"])
    assert result.exit_code == 0, result.output
    assert (out / "mini" / "report.md").is_file() and (out / "mini" / "report.html").is_file()
    assert not (out / "mini" / "report.ipynb").exists()
    page = (out / "mini" / "report.html").read_text(encoding="utf-8")
    assert "<math" in page and "0.866025" in page          # sin(pi/3), the y of E


def _executed_notebook_output(tmp_path, name, not_rebuilt=()):
    """Solve `name` to ipynb, run the notebook in a fresh kernel, return (printed text, results).
    Only the types in `not_rebuilt` may fall back to printing robosolve's numbers."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    out = _solve(tmp_path, name, "ipynb")
    nb = nbformat.read(out / "report.ipynb", as_version=4)
    nbformat.validate(nb)
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    assert set(re.findall(r"does not recompute `(\w+)`", code)) <= set(not_rebuilt)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(out)}}).execute()
    printed = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.outputs)
    return printed, json.loads((out / "results.json").read_text())["answers"]


def _floats(text):
    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", text)]


def test_notebook_recomputes_dynamics_and_inverse_kinematics_of_the_full_exam(tmp_path):
    """The notebook's own Lagrange (pseudo-inertia traces) and Newton IK, not robosolve's code,
    agree with results.json."""
    import ast
    printed, results = _executed_notebook_output(tmp_path, "exam-2r-full", ("joint_torques", "p_control"))
    eom = results["equations_of_motion"]["numeric"]
    mass = re.search(r"recomputed M =\s*(\[\[.*?\]\])", printed, flags=re.S).group(1)
    assert _floats(mass) == pytest.approx([x for row in eom["mass_matrix"] for x in row], abs=2e-6)
    for label, key in (("recomputed c =", "velocity_terms"), ("recomputed g =", "gravity_terms")):
        got = re.search(re.escape(label) + r"\s*(\[[^\]]*\])", printed).group(1)
        assert _floats(got) == pytest.approx(eom[key], abs=2e-6)
    actions = ast.literal_eval(re.search(r"recomputed joint actions[^{]*(\{[^}]*\})", printed).group(1))
    assert list(actions.values()) == pytest.approx(list(eom["actuators"].values()), abs=1e-9)
    solutions = [ast.literal_eval(m) for m in re.findall(r"recomputed solution: (\{[^}]*\})", printed)]
    expected = sorted(results["inverse_kinematics"]["numeric"]["solutions"], key=lambda s: tuple(s.values()))
    assert len(solutions) == len(expected)
    for got, want in zip(solutions, expected):
        assert list(got.values()) == pytest.approx(list(want.values()), abs=1e-9)


def test_notebook_recomputes_displacements_and_orientations(tmp_path):
    printed, results = _executed_notebook_output(tmp_path, "rigid-displacements")
    displacements = [a["numeric"] for a in results.values() if a["type"] == "displacement"]
    found = re.findall(r"recomputed u = (.*?)  alpha = (\S+)  h = (\S+)  P = (.*?)  pitch", printed)
    assert len(found) == len(displacements)
    for (u, alpha, h, point), want in zip(found, displacements):
        assert _floats(u) == pytest.approx(want["u"], abs=2e-6)
        assert float(alpha) == pytest.approx(want["alpha"], abs=1e-9)
        assert float(h) == pytest.approx(want["h"], abs=1e-9)
        assert (point == "None") == (want["P"] is None)
        if want["P"] is not None:
            assert _floats(point) == pytest.approx(want["P"], abs=2e-6)
    orientations = [a["numeric"] for a in results.values() if a["type"] == "orientation"]
    quaternions = re.findall(r"recomputed quaternion = (\[[^\]]*\])", printed)
    zyz = re.findall(r"recomputed zyz = (\[\[.*?\]\])", printed)
    assert len(quaternions) == len(orientations) == len(zyz)
    for q, angles, want in zip(quaternions, zyz, orientations):
        assert _floats(q) == pytest.approx(want["quaternion"], abs=1e-9)
        assert _floats(angles) == pytest.approx([x for s in want["zyz"]["solutions"] for x in s], abs=1e-9)
