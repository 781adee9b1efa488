"""Byte-identical outputs whatever PYTHONHASHSEED and however many processes (spec §2; issue 22):
report.md, .html, .ipynb, results.json and every PNG of `batch`, run with PYTHONHASHSEED=0 on one
process, =12345 on two, and unset (random) on two, compared file by file. The fast test takes
two small problems; the slow one every bundled problem."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import PROBLEMS, ROOT

RUNS = (("0", "1"), ("12345", "2"), (None, "2"))


def _batch(source: Path, out: Path, seed: str | None, jobs: str) -> dict:
    env = dict(os.environ)
    env.pop("PYTHONHASHSEED", None)
    if seed is not None:
        env["PYTHONHASHSEED"] = seed
    subprocess.run([sys.executable, "-m", "robosolve", "batch", str(source), "--out", str(out),
                    "--jobs", jobs, "--format", "md,html,ipynb"],
                   check=True, env=env, cwd=ROOT, capture_output=True, timeout=3000)
    return {p.relative_to(out).as_posix(): p.read_bytes() for p in sorted(out.rglob("*")) if p.is_file()}


def _same_bytes(runs: list[dict]) -> None:
    first = runs[0]
    assert any(k.endswith(".png") for k in first) and any(k.endswith("report.ipynb") for k in first)
    for other in runs[1:]:
        assert sorted(other) == sorted(first)
        differ = [k for k in first if first[k] != other[k]]
        assert not differ, differ


def test_two_small_problems_are_byte_identical_across_seeds_and_processes(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    for name in ("planar-2r-rods", "one-link-arm"):
        (src / f"{name}.yaml").write_bytes((PROBLEMS / f"{name}.yaml").read_bytes())
    _same_bytes([_batch(src, tmp_path / f"o{k}", seed, jobs) for k, (seed, jobs) in enumerate(RUNS)])


@pytest.mark.slow
def test_every_bundled_problem_is_byte_identical_across_seeds_and_processes(tmp_path):
    _same_bytes([_batch(PROBLEMS, tmp_path / f"o{k}", seed, jobs) for k, (seed, jobs) in enumerate(RUNS)])
