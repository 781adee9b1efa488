"""Fuzz of everything a user hands robosolve besides a problem's keys (issue 22): names that
reach generated code and figures, encodings of every input file, special files in every place
a path goes, huge counts, and full disks at every point of a write (a small tmpfs: root only).

Every case runs a real command line (typer's runner, in this process) and must end cleanly:
exit 0, 1 or 2, never a traceback; on exit 2 nothing written; no input ever changed; a name
shown as written (a literal in the notebook's code, escaped in Markdown and figures). The
cases are drawn with fixed seeds, so a failure reproduces.
"""

from __future__ import annotations

import ast
import contextlib
import json
import os
import random
import subprocess
from pathlib import Path

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from tests.conftest import MINI

runner = CliRunner()


def invoke(args, cwd=None):
    """One command line: the result, after checking that it ended as a command should."""
    with contextlib.chdir(cwd) if cwd else contextlib.nullcontext():
        r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code in (0, 1, 2), (args, r.exit_code, r.output)
    assert r.exception is None or isinstance(r.exception, SystemExit), (args, repr(r.exception), r.output)
    assert "Traceback" not in r.output and "internal error" not in r.output, (args, r.output)
    return r


def snapshot(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): (p.read_bytes() if p.is_file() and not p.is_symlink() else None)
            for p in sorted(folder.rglob("*"))}


# -- names: quotes, code, TeX, HTML, mathtext, reaching report.md / .html / .ipynb and the PNGs

HOSTILE = ['b": open("X","w").write("x"), "c', 'arm "A"', "l'); import os; os.system('touch Y'); ('",
           '"""; open("Z") #', "$\\frac{$", "a|b", "<script>alert(1)</script>", "x}\\end{matrix}{",
           "_hidden", "50 % & # ~ ^", "tab\there", "Ω θ₁ →", "\\\\", "{0}", "%s %d", "__import__('os')"]

NAMED = """\
robosolve: 1
name: named
title: {title}
parameters: {{L: 1, m: 2, g: 9.81, F: 3}}
joints:
  - {{name: q1, type: revolute}}
  - {{name: q2, type: revolute}}
frames:
  {f1}: {{parent: "0", pose: "Rz(q1) Tx(L)"}}
  {f2}: {{parent: {f1}, pose: "Rz(q2) Tx(L)"}}
gravity: [0, -g, 0]
bodies:
  - {{name: {b1}, frame: {f1}, mass: m, rod: {{from: [-L, 0, 0], to: [0, 0, 0]}}}}
  - {{name: {b2}, frame: {f2}, mass: m, point: [0, 0, 0]}}
forces:
  - {{name: {force}, frame: {f2}, at: [0, 0, 0], force: [0, -F, 0]}}
questions:
  - {{type: position, at: {{q1: 0.3, q2: 0.4}}}}
  - {{type: jacobian, coordinates: [E.x, E.y], bodies: true, at: {{q1: 0.3, q2: 0.4}}}}
  - {{type: statics, weight: true, coordinates: [E.x, E.y], at: {{q1: 0.3, q2: 0.4}}}}
  - {{type: equations_of_motion, at: {{q1: 0.3, q2: 0.4, q1_dot: 0, q2_dot: 0, q1_ddot: 0, q2_ddot: 0}}}}
  - {{type: displacement, frame: {f1}, from: {{q1: 0, q2: 0}}, to: {{q1: 0.5, q2: 0.2}}}}
"""


def _named(rng: random.Random) -> tuple[str, dict]:
    names = rng.sample(HOSTILE, 6)
    if names[0] == names[1]:
        names[1] += "2"
    keys = ("f1", "f2", "b1", "b2", "force", "title")
    return NAMED.format(**{k: json.dumps(n) for k, n in zip(keys, names)}), dict(zip(keys, names))


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow), pytest.param(2, marks=pytest.mark.slow),
                                  pytest.param(3, marks=pytest.mark.slow)])
def test_fuzz_names_reach_every_output_as_written(tmp_path, seed):
    text, names = _named(random.Random(seed))
    (tmp_path / "p.yaml").write_text(text, encoding="utf-8")
    r = invoke(["solve", tmp_path / "p.yaml", "--out", tmp_path / "o", "--format", "md,html,ipynb"])
    assert r.exit_code == 0, r.output
    out = tmp_path / "o"
    report = (out / "report.md").read_text(encoding="utf-8")
    assert "could not be drawn" not in report
    strings = set()
    for cell in json.loads((out / "report.ipynb").read_text(encoding="utf-8"))["cells"]:
        if cell["cell_type"] != "code":
            continue
        tree = ast.parse("".join(cell["source"]))
        calls = {n.func.id for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Name)}
        assert not calls & {"open", "exec", "eval", "__import__"}, calls
        strings |= {n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)}
    assert {names["f1"], names["f2"], names["b1"], names["b2"], names["force"]} <= strings
    assert "<script" not in (out / "report.html").read_text(encoding="utf-8").lower()
    assert sorted(p.name for p in (out / "figures").iterdir())           # the figures were drawn
    r = invoke(["paper", tmp_path / "p.yaml", "--out", tmp_path / "paper", "--format", "md,html"])
    assert r.exit_code == 0 and (tmp_path / "paper" / "figures" / "robot.png").exists(), r.output


# -- encodings of the other inputs: answers files, variants.csv, rosters --------------------

ANSWERS = "robosolve-answers: 1\nproblem: p.yaml\nstudent: s1\nanswers:\n  position:\n    position: [1, 0, 0]\n"


def _garbled(raw: bytes, rng: random.Random) -> bytes:
    k = rng.randrange(len(raw))
    kind = rng.randrange(7)
    if kind == 0:
        return raw[:k] + b"\x00" + raw[k:]
    if kind == 1:
        return raw[:k] + bytes([rng.choice([0xff, 0xe9, 0xc3, 0x80])]) + raw[k:]
    if kind == 2:
        return b"\xef\xbb\xbf" + raw
    if kind == 3:
        return raw.decode("utf-8").encode(rng.choice(["utf-16", "utf-32"]))
    if kind == 4:
        return raw.replace(b"\n", b"\r\n")
    if kind == 5:
        return raw.decode("utf-8").encode("latin-1", "replace") + "é".encode("latin-1")
    return raw[:k] + bytes([rng.choice([1, 7, 8, 11, 12, 27, 127])]) + raw[k:]


def test_fuzz_encodings_of_answers_files(tmp_path):
    (tmp_path / "p.yaml").write_text(MINI, encoding="utf-8")
    rng = random.Random(22)
    for k in range(24):
        a = tmp_path / f"a{k}.yaml"
        a.write_bytes(_garbled(ANSWERS.encode(), rng))
        before = a.read_bytes()
        r = invoke(["check", a])
        if r.exit_code == 2:
            assert r.output.startswith(f"{a}:") or f"\n{a}:" in r.output, r.output
        assert a.read_bytes() == before


def _variants_folder(tmp_path) -> Path:
    (tmp_path / "v.yaml").write_text(MINI + "variants:\n  parameters:\n    L: {choices: [1, 2, 3]}\n",
                                     encoding="utf-8")
    r = invoke(["variants", tmp_path / "v.yaml", "--count", "2", "--no-solve", "--out", tmp_path / "V"])
    assert r.exit_code == 0, r.output
    return tmp_path / "V"


def test_fuzz_encodings_of_the_variants_table_and_the_roster(tmp_path):
    folder = _variants_folder(tmp_path)
    table = (folder / "variants.csv").read_bytes()
    sub = tmp_path / "s.yaml"
    sub.write_text(ANSWERS.replace("problem: p.yaml\n", "").replace("s1", "1"), encoding="utf-8")
    rng = random.Random(5)
    for k in range(10):
        (folder / "variants.csv").write_bytes(_garbled(table, rng))
        invoke(["grade", sub, "--variants", folder, "--out", tmp_path / f"g{k}"])
        roster = tmp_path / f"r{k}.csv"
        roster.write_bytes(_garbled(b"student,email\nJo Smith,jo@x\nAl,al@x\n", rng))
        r = invoke(["variants", tmp_path / "v.yaml", "--roster", roster, "--no-solve", "--out", tmp_path / f"R{k}"])
        if r.exit_code == 2:
            assert str(roster) in r.output and not (tmp_path / f"R{k}").exists(), r.output


# -- special files wherever a path goes --------------------------------------------------------

def _specials(tmp_path) -> dict:
    s = tmp_path / "special"
    s.mkdir()
    os.mkfifo(s / "fifo.yaml")
    (s / "dir.yaml").mkdir()
    (s / "zero.yaml").symlink_to("/dev/zero")
    (s / "null.yaml").symlink_to("/dev/null")
    (s / "dangling.yaml").symlink_to(s / "nowhere")
    with open(s / "sparse.yaml", "wb") as fh:
        fh.truncate(10 ** 10)
    return {p.stem: p for p in s.iterdir()}


def test_fuzz_special_files_in_every_place_a_path_goes(tmp_path):
    """A FIFO, a folder, /dev/zero, /dev/null, a dangling link, a 10 GB sparse file: as a problem,
    an answers file, a `problem:`, a roster, a variants table, an output: refused or read within
    the limits at once (no hang, no memory growth), never a traceback, the special file kept."""
    (tmp_path / "p.yaml").write_text(MINI, encoding="utf-8")
    good = tmp_path / "a.yaml"
    good.write_text(ANSWERS, encoding="utf-8")
    folder = _variants_folder(tmp_path)
    table = folder / "variants.csv"
    saved = table.read_bytes()
    for name, path in sorted(_specials(tmp_path).items()):
        kind = os.lstat(path).st_mode
        answers = tmp_path / f"to-{name}.yaml"
        answers.write_text(ANSWERS.replace("problem: p.yaml", f"problem: {path}"), encoding="utf-8")
        table.unlink()
        table.symlink_to(path)
        inputs = [["solve", path, "--out", tmp_path / "o"], ["validate", path],
                  ["paper", path, "--out", tmp_path / "o"], ["check", path], ["check", answers],
                  ["grade", path, "--out", tmp_path / "o"], ["grade", answers, "--out", tmp_path / "o"],
                  ["variants", tmp_path / "v.yaml", "--roster", path, "--out", tmp_path / "o"],
                  ["grade", good, "--variants", folder, "--out", tmp_path / "o"]]
        for args in inputs:
            r = invoke(args)
            assert r.exit_code in (1, 2), (name, args, r.output)
            if r.exit_code == 2:
                assert not (tmp_path / "o").exists(), (name, args)
            subprocess.run(["rm", "-rf", str(tmp_path / "o")], check=True)
            assert os.lstat(path).st_mode == kind, (name, args)
        for args in (["check", good, "--json", path], ["solve", tmp_path / "p.yaml", "--out", path]):
            invoke(args)                                          # outputs: no traceback, and
            if name not in ("dir", "dangling"):                   # a device or pipe kept as it is
                assert os.lstat(path).st_mode == kind, (name, args)
        table.unlink()
        table.write_bytes(saved)


# -- huge counts -------------------------------------------------------------------------------

@pytest.mark.parametrize("count", ["30000000", "10000000000000000000", "100001", "4", "0", "-1"])
def test_fuzz_huge_counts_are_refused_before_anything_is_made(tmp_path, count):
    """A count beyond the variants that exist, or beyond the cap, is refused at once (before any id
    is made: 10⁷ ids were 1.4 GB), on a grid of 10¹⁸ values as on one of 3."""
    big, small = tmp_path / "big.yaml", tmp_path / "small.yaml"
    big.write_text(MINI + "variants:\n  parameters:\n    L: {range: [1, 2], step: 1e-9}\n", encoding="utf-8")
    small.write_text(MINI + "variants:\n  parameters:\n    L: {choices: [1, 2, 3]}\n", encoding="utf-8")
    for problem in (big, small):
        r = invoke(["variants", problem, "--count", count, "--no-solve", "--out", tmp_path / "o"])
        expected = 0 if (count == "4" and problem == big) else 2
        assert r.exit_code == expected, (problem.name, count, r.output)
        if problem == small and int(count) > 3:
            assert "only 3 distinct variants exist" in r.output, r.output
        assert expected == 0 or not (tmp_path / "o").exists()
        subprocess.run(["rm", "-rf", str(tmp_path / "o")], check=True)


# -- full disks at every point of a write ------------------------------------------------------

@pytest.fixture
def small_disk(tmp_path):
    disk = tmp_path / "disk"
    disk.mkdir()
    try:
        done = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(disk)],
                              capture_output=True, timeout=20)
    except (OSError, subprocess.SubprocessError):
        pytest.skip("cannot mount a tmpfs here")
    if done.returncode != 0:
        pytest.skip("cannot mount a tmpfs here (not root?)")
    try:
        yield disk
    finally:
        subprocess.run(["umount", "-l", str(disk)], capture_output=True, timeout=20)


def _leave_free(disk: Path, free: int) -> None:
    """Fill `disk` so that about `free` bytes are left."""
    filler = disk / "filler"
    filler.unlink(missing_ok=True)
    stat = os.statvfs(disk)
    with contextlib.suppress(OSError), open(filler, "wb") as fh:
        fh.write(b"\0" * max(stat.f_bavail * stat.f_frsize - free, 0))


@pytest.mark.parametrize("runs", [6, pytest.param(18, marks=pytest.mark.slow)])
def test_fuzz_full_disks_at_every_point_of_a_write(small_disk, tmp_path, runs):
    """Each command on a disk with 0 to 200 kB free: it writes everything (exit 0 or 1), or says
    "No space left on device" with the path (exit 2) and leaves nothing behind."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "p.yaml").write_text(MINI, encoding="utf-8")
    (src / "v.yaml").write_text(MINI + "variants:\n  parameters:\n    L: {choices: [1, 2, 3]}\n", encoding="utf-8")
    (src / "a.yaml").write_text(ANSWERS, encoding="utf-8")
    before = snapshot(src)
    rng = random.Random(28)
    commands = [lambda o: ["solve", src / "p.yaml", "--out", o, "--format", "md,html"],
                lambda o: ["check", src / "a.yaml", "--json", o / "r.json"],
                lambda o: ["grade", src / "a.yaml", "--out", o, "--jobs", "1"],
                lambda o: ["variants", src / "v.yaml", "--count", "2", "--out", o, "--jobs", "1", "--no-solve"],
                lambda o: ["batch", src / "p.yaml", "--out", o, "--jobs", "1"],
                lambda o: ["paper", src / "p.yaml", "--out", o]]
    for k in range(runs):
        free = rng.choice([0, 4096, 20_000, 60_000, 120_000, 200_000])
        make = commands[k % len(commands)]
        _leave_free(small_disk, free)
        target = small_disk / f"out{k}"
        r = invoke(make(target))
        if r.exit_code == 2:
            assert "No space left on device" in r.output and str(target) in r.output, (free, r.output)
            assert sorted(p.name for p in small_disk.iterdir()) == ["filler"], (free, r.output)
        else:
            assert target.exists(), (free, r.output)
            subprocess.run(["rm", "-rf", str(target)], check=True)
        assert snapshot(src) == before
