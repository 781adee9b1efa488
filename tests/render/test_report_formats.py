"""--format md,html,ipynb: the HTML page is self-contained MathML with no TeX left, a
headless Chromium renders it (the notebook: tests/render/test_notebook.py)."""

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
