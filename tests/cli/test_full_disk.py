"""A full disk (ENOSPC) during a write: one clear line with the path, exit 2, no traceback, and
nothing left behind (no temporary file or folder, no empty output folder) — for every command
that writes. The disk is a tiny tmpfs filled to the last byte (needs root: skipped otherwise).
"""

from __future__ import annotations

import contextlib
import os
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from conftest import MINI
from robosolve.cli import app
from tests._grading import dedent
from tests.workflows.test_grading_grade import ALICE, PROBLEM

runner = CliRunner()


@pytest.fixture
def full_disk(tmp_path):
    disk = tmp_path / "disk"
    disk.mkdir()
    try:
        done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(disk)],
                              capture_output=True, timeout=20)
    except (OSError, subprocess.SubprocessError):
        pytest.skip("cannot mount a tmpfs here")
    if done.returncode != 0:
        pytest.skip("cannot mount a tmpfs here (not root?)")
    try:
        with contextlib.suppress(OSError), open(disk / "filler", "wb") as fh:
            while True:
                fh.write(b"\0" * 4096)
                fh.flush()
        yield disk
    finally:
        subprocess.run(["umount", "-l", str(disk)], capture_output=True, timeout=20)


def _only_filler(disk: Path) -> None:
    assert sorted(p.name for p in disk.iterdir()) == ["filler"], "debris on the full disk"


def _clean_failure(result, path: Path) -> None:
    assert result.exit_code == 2, result.output
    assert "No space left on device" in result.output and str(path) in result.output
    assert "Traceback" not in result.output and "[Errno" not in result.output


def _classroom(tmp_path) -> Path:
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    (tmp_path / "subs").mkdir()
    sub = tmp_path / "subs" / "alice.yaml"
    sub.write_text(dedent(ALICE), encoding="utf-8")
    return sub


def test_solve_on_a_full_disk(full_disk, tmp_path):
    (tmp_path / "mini.yaml").write_text(MINI)
    target = full_disk / "out" / "mini"
    r = runner.invoke(app, ["solve", str(tmp_path / "mini.yaml"), "--out", str(target)])
    _clean_failure(r, target)
    _only_filler(full_disk)


def test_check_json_on_a_full_disk(full_disk, tmp_path):
    sub = _classroom(tmp_path)
    target = full_disk / "records" / "alice.json"
    r = runner.invoke(app, ["check", str(sub), "--json", str(target)])
    _clean_failure(r, target)
    _only_filler(full_disk)


def test_grade_on_a_full_disk(full_disk, tmp_path):
    sub = _classroom(tmp_path)
    target = full_disk / "grades"
    r = runner.invoke(app, ["grade", str(sub), "--out", str(target), "--jobs", "1"])
    _clean_failure(r, target)
    _only_filler(full_disk)


def test_variants_on_a_full_disk(full_disk, tmp_path):
    (tmp_path / "v.yaml").write_text(MINI + "variants:\n  parameters:\n    L: {choices: [1, 2, 3]}\n")
    target = full_disk / "V"
    r = runner.invoke(app, ["variants", str(tmp_path / "v.yaml"), "--count", "2", "--no-solve",
                            "--out", str(target), "--jobs", "1"])
    _clean_failure(r, target)
    _only_filler(full_disk)


def test_batch_on_a_full_disk(full_disk, tmp_path):
    src = tmp_path / "probs"
    src.mkdir()
    (src / "a.yaml").write_text(MINI.replace("name: mini", "name: a"))
    (src / "b.yaml").write_text(MINI.replace("name: mini", "name: b"))
    target = full_disk / "b-out"
    r = runner.invoke(app, ["batch", str(src), "--out", str(target), "--jobs", "1"])
    _clean_failure(r, target)
    lines = [ln for ln in r.output.splitlines() if "No space left on device" in ln]
    assert len(lines) == 2 and len(set(lines)) == 2       # one line per problem, each with its folder
    _only_filler(full_disk)
    assert not os.path.exists(target)
