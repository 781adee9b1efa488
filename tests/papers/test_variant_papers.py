"""Every variant gets its paper and answers template (variants.md, papers.md): the same bytes
with and without --no-solve; papers.html holds every paper, one per printed page."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app

runner = CliRunner()

ARM = """\
robosolve: 1
name: arm
title: Planar 2R arm
parameters: {L1: 1/2, L2: 2/5, x: 0.6}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: theta2, type: revolute, limits: [-deg(150), deg(150)]}
frames:
  "1": {pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: position, at: {theta1: pi/6, theta2: pi/2}}
  - {type: inverse_kinematics, id: ik, target: {E.x: x, E.y: 0.3}}
variants:
  parameters:
    L1: {range: [0.4, 0.6], step: 0.05}
    L2: {range: [0.2, 0.4], step: 0.05}
    x: {range: [0.3, 0.7], step: 0.1}
  require:
    - "L1 > L2"
    - {reachable: ik}
"""
# a one-page paper: the print test counts one page per student
ONE_PAGE = ARM.replace("  - {type: inverse_kinematics, id: ik, target: {E.x: x, E.y: 0.3}}\n", "").replace(
    "    - {reachable: ik}\n", "").replace("L1: {range: [0.4, 0.6], step: 0.05}", "L1: {range: [0.4, 0.8], step: 0.05}")
PAPER_FILES = ("paper.md", "answers.yaml", "figures/robot.png", "paper.html")


def _run(tmp_path, name, *extra, text=ARM):
    src = tmp_path / "arm.yaml"
    src.write_text(text)
    out = tmp_path / name
    r = runner.invoke(app, ["variants", str(src), "--out", str(out), *extra])
    assert r.exit_code == 0, r.output
    return out


def test_papers_same_with_and_without_solving(tmp_path):
    solved = _run(tmp_path, "solved", "--count", "2", "--format", "md,html", text=ONE_PAGE)
    bare = _run(tmp_path, "bare", "--count", "2", "--no-solve", "--format", "md,html", text=ONE_PAGE)
    for v in ("arm-1", "arm-2"):
        for f in PAPER_FILES:
            assert (solved / v / f).read_bytes() == (bare / v / f).read_bytes(), (v, f)
        assert (solved / v / "results.json").exists() and not (bare / v / "results.json").exists()
        template = (bare / v / "answers.yaml").read_text()
        assert 'problem: "problem.yaml"' in template and f"# Answers for {v} " in template
        assert f"**Variant:** `{v}`" in (bare / v / "paper.md").read_text()
    assert (solved / "papers.html").read_bytes() == (bare / "papers.html").read_bytes()
    html = (bare / "papers.html").read_text()
    assert html.count('<section class="rs-paper') == 2 and html.count("rs-paper-sep") == 2  # css + 2nd
    # check on an untouched variant template: every key missing, exit 1 (never 2)
    r = runner.invoke(app, ["check", str(solved / "arm-1" / "answers.yaml")])
    assert r.exit_code == 1, r.output
    assert "missing" in r.output and "invalid" not in r.output


def test_roster_student_on_paper_and_template(tmp_path):
    roster = tmp_path / "roster.csv"
    roster.write_text("student,email\nJo Smith,jo@x\n")
    out = _run(tmp_path, "class", "--roster", str(roster), "--no-solve")
    assert "**Student:** Jo Smith" in (out / "arm-jo-smith" / "paper.md").read_text()
    assert 'student: "Jo Smith"' in (out / "arm-jo-smith" / "answers.yaml").read_text()
    assert not (out / "papers.html").exists()     # only with --format html


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


@pytest.mark.slow
@pytest.mark.skipif(CHROMIUM is None or shutil.which("pdfinfo") is None, reason="needs chromium and pdfinfo")
def test_class_of_25_prints_one_paper_per_page(tmp_path):
    out = _run(tmp_path, "class", "--count", "25", "--no-solve", "--format", "html", text=ONE_PAGE)
    pdf = tmp_path / "papers.pdf"
    subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                    f"--print-to-pdf={pdf}", (out / "papers.html").as_uri()], check=True,
                   capture_output=True, timeout=300)
    info = subprocess.run(["pdfinfo", str(pdf)], check=True, capture_output=True, text=True).stdout
    pages = int(next(line.split()[-1] for line in info.splitlines() if line.startswith("Pages:")))
    assert pages == 25
    shot = tmp_path / "paper.png"
    subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                    "--window-size=900,1300", f"--screenshot={shot}", (out / "arm-01" / "paper.html").as_uri()],
                   check=True, capture_output=True, timeout=300)
    assert shot.read_bytes()[:4] == b"\x89PNG"
