"""Memory stays bounded on every input (issue 22): a device, a pipe or a huge file is never read
whole, and a variant count is compared with what exists before any id is made."""

from __future__ import annotations

import os
import resource
import subprocess
import sys
import textwrap

import pytest

from conftest import MINI, ROOT
from robosolve.errors import InputError
from robosolve.load.yamlsource import MAX_FILE_BYTES, read_input_bytes, read_text_file

CAP = 1_500_000_000          # bytes of address space: the unbounded reads of before went past it


def _capped():
    resource.setrlimit(resource.RLIMIT_AS, (CAP, CAP))


def run_capped(*args, cwd=None, timeout=120):
    """robosolve in a child whose memory is capped: a MemoryError or a kill shows as a failure."""
    return subprocess.run([sys.executable, "-m", "robosolve", *map(str, args)], cwd=cwd or ROOT,
                          capture_output=True, text=True, timeout=timeout, preexec_fn=_capped)


def test_solve_refuses_a_device_without_reading_it(tmp_path):
    out = tmp_path / "out"
    r = run_capped("solve", "/dev/zero", "--out", out)
    assert r.returncode == 2, r.stderr
    assert "/dev/zero: the file is a device, pipe or socket, not a regular file" in r.stderr + r.stdout
    assert "Traceback" not in r.stderr and not out.exists()


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "p.yaml"
    os.mkfifo(fifo)
    with pytest.raises(InputError, match="not a regular file"):
        read_text_file(fifo)


def test_a_huge_file_is_read_only_up_to_the_limit(tmp_path, monkeypatch):
    big = tmp_path / "big.yaml"
    with open(big, "wb") as fh:          # sparse: 20 GB of zeros that take no disk
        fh.truncate(20 * 10**9)
    sizes = []
    real_read = os.read
    monkeypatch.setattr(os, "read", lambda fd, n: sizes.append(n) or real_read(fd, n))
    with pytest.raises(InputError, match=f"larger than {MAX_FILE_BYTES} bytes"):
        read_input_bytes(big)
    assert sum(sizes) <= MAX_FILE_BYTES + 1


def test_a_folder_is_refused_with_what_it_is(tmp_path):
    with pytest.raises(InputError, match="is a folder, not a regular file"):
        read_text_file(tmp_path)


def test_answers_naming_a_device_as_problem(tmp_path):
    answers = tmp_path / "a.yaml"
    answers.write_text("robosolve-answers: 1\nproblem: /dev/zero\nanswers:\n  q1: {T: 1}\n",
                       encoding="utf-8")
    r = run_capped("check", answers)
    assert r.returncode == 2, r.stderr
    text = r.stderr + r.stdout
    assert f"{answers}:2: problem: '/dev/zero' is a device, pipe or socket, not a problem file" in text
    assert "no problem" not in text and "Traceback" not in r.stderr


VARIED = MINI.replace("parameters: {L: 1}", "parameters: {L: 1, M: 2}") + textwrap.dedent("""\
    variants:
      parameters:
        L: {range: [1, 7], step: 1}
        M: {choices: [1, 2, 3, 4, 5, 6, 7, 8, 9]}
    """)


def test_a_count_beyond_the_variants_that_exist_is_refused_before_allocating(tmp_path):
    p = tmp_path / "v.yaml"
    p.write_text(VARIED, encoding="utf-8")
    out = tmp_path / "out"
    r = run_capped("variants", p, "--count", "30000000", "--no-solve", "--out", out, timeout=60)
    assert r.returncode == 2, r.stderr
    assert "only 63 distinct variants exist (30000000 asked)" in r.stderr
    assert "MemoryError" not in r.stderr and not out.exists()


def test_a_count_beyond_the_limit_on_a_huge_grid_is_refused(tmp_path):
    p = tmp_path / "v.yaml"
    p.write_text(VARIED.replace("step: 1}", "step: 0.000001}"), encoding="utf-8")
    out = tmp_path / "out"
    r = run_capped("variants", p, "--count", "30000000", "--no-solve", "--out", out, timeout=60)
    assert r.returncode == 2, r.stderr
    assert "30000000 variants asked: robosolve makes at most 100000 at once" in r.stderr
    assert not out.exists()
