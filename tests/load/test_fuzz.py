"""Fuzz: mutated problem files are answered or refused cleanly, never a traceback or a hang.

A few hundred deterministic mutations of the bundled problems (odd values, deleted,
duplicated or re-indented lines, tabs, misspelt keys, truncations) are validated, and a few
dozen mutations of small problems are solved. Each must end as a valid problem, a clean
refusal (InputError whose every message starts with `FILE:LINE:` or `FILE:`), or - when
solved - answers without an "internal error". The files run in a worker process; the harness
kills a worker that does not answer within a generous limit and reports the file as a hang
(it asserts nothing about speed).
"""

from __future__ import annotations

import json
import os
import random
import re
import selectors
import subprocess
import sys
import time
from pathlib import Path

import pytest

from conftest import PROBLEMS, ROOT

N_VALIDATE = 240
N_SOLVE = 24
HANG_SECONDS = {"validate": 120, "solve": 300}   # a hang detector, not a speed check

WEIRD = ["0", "-1", "1e400", "acos(2)", "1/0", "log(0)", "exp(exp(exp(100)))", "'((9**999)**999)**999'",
         "~", "[]", "{}", "[1, 2]", "30deg", "nan", ".inf", "-.inf", "true", "'sqrt(-1)'", "1e-300",
         "1e300", "999999999999999999999999", "q1", "'ok\\n'", "''", "&a [*a]", "'1/a'", "-0.0",
         "deg(30)", "'x' * 3", "\"\\t\"", "2L", "E.x", "!!python/object:os.system ls"]

SMALL = """\
robosolve: 1
name: small
parameters: {L1: 1/2, L2: 2/5, m1: 2, m2: 1, g: 9.81, F: 10}
joints:
  - {name: q1, type: revolute, limits: [-pi, pi]}
  - {name: d2, type: prismatic, limits: [0, 1]}
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Tx(d2)"}
points:
  G: {frame: "1", at: [-L1/2, 0, 0]}
bodies:
  - {name: link1, frame: "1", mass: m1, rod: {from: [-L1, 0, 0], to: [0, 0, 0]}}
  - {name: slider, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: position, at: {q1: pi/6, d2: 0.2}}
  - {type: jacobian, at: {q1: 0.3, d2: 0.1}}
  - {type: statics, force: [0, -F, 0], at: {q1: 0.3, d2: 0.1}}
  - {type: inverse_kinematics, target: {E.x: 0.6, E.y: 0.3}}
  - {type: motion_profile, from: {q1: 0, d2: 0}, to: {q1: 1, d2: 0.2}, max_acceleration: {q1: 2, d2: 1}}
  - {type: dof, bodies: 3, joints_1dof: 2}
  - {type: orientation, matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}
  - {type: displacement, from: {q1: 0, d2: 0}, to: {q1: pi/2, d2: 0.1}}
"""

WORKER = r'''
import json, sys, traceback
from robosolve.errors import InputError
from robosolve.load.loader import load_problem
for line in sys.stdin:
    mode, path = line.rstrip("\n").split("\t", 1)
    out = {"path": path}
    try:
        problem = load_problem(path)
        out["status"] = "valid"
        if mode == "solve":
            from robosolve.run.pipeline import solve_problem
            from robosolve.render.markdown import render_report
            from robosolve.render.results_json import render_results_json
            report = solve_problem(problem)
            render_results_json(report, {})
            render_report(report, {})
            bad = [f"{a.id}: {a.error}" for a in report.answers if a.error and "internal error" in a.error]
            if bad:
                out["status"], out["detail"] = "internal", bad
    except InputError as exc:
        out["status"] = "refused"
        out["messages"] = [str(i) for i in exc.issues]
    except BaseException:
        out["status"], out["detail"] = "crash", traceback.format_exc()[-3000:]
    sys.stdout.write(json.dumps(out) + "\n")
    sys.stdout.flush()
'''


# for the solved files: values that keep a file valid but take solvers to odd places (zero
# lengths and masses, huge and tiny scales, negative values)
GENTLE = ["0", "-1", "1e-300", "1e300", "2", "-0.5", "pi", "100", "1e6", "0.001", "deg(30)", "1e-9"]


def mutate_value(text: str, rng: random.Random) -> str:
    lines = text.splitlines()
    for _ in range(rng.choice((1, 2))):
        i = rng.randrange(len(lines))
        tokens = list(re.finditer(r"(?<=[:\[,{] )[-0-9.][^,\[\]{}\n#]*?(?=[,\]}]|$)", lines[i]))
        if tokens:
            m = rng.choice(tokens)
            lines[i] = lines[i][:m.start()] + rng.choice(GENTLE) + lines[i][m.end():]
    return "\n".join(lines) + "\n"


def mutate(text: str, rng: random.Random) -> str:
    lines = text.splitlines()
    for _ in range(rng.choice((1, 1, 2, 3))):
        if not lines:
            break
        i = rng.randrange(len(lines))
        kind = rng.randrange(9)
        if kind <= 2:       # an odd value in place of a scalar
            tokens = list(re.finditer(r"(?<=[:\[,{] )[^,\[\]{}\n#]+?(?=[,\]}]|$)", lines[i]))
            if tokens:
                m = rng.choice(tokens)
                lines[i] = lines[i][:m.start()] + rng.choice(WEIRD) + lines[i][m.end():]
        elif kind == 3:
            del lines[i]
        elif kind == 4:
            lines.insert(i, lines[i])
        elif kind == 5:
            lines[i] = "\t" + lines[i].lstrip() if rng.random() < 0.5 else "  " + lines[i]
        elif kind == 6:     # a misspelt key
            m = re.search(r"[A-Za-z_]{3,}(?=:)", lines[i])
            if m:
                k = m.start() + rng.randrange(m.end() - m.start())
                lines[i] = lines[i][:k] + lines[i][k + 1:]
        elif kind == 7:
            cut = rng.randrange(len(text))
            return text[:cut]
        elif len(lines[i]) > 2:  # two characters swapped
            k = rng.randrange(len(lines[i]) - 1)
            s = lines[i]
            lines[i] = s[:k] + s[k + 1] + s[k] + s[k + 2:]
    return "\n".join(lines) + "\n"


class Harness:
    """One worker process answering file after file; killed and replaced when it hangs."""

    def __init__(self):
        self.proc = None

    def _start(self):
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        self.proc = subprocess.Popen([sys.executable, "-c", WORKER], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, cwd=ROOT, env=env)

    def run(self, mode: str, path: Path) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.proc.stdin.write(f"{mode}\t{path}\n")
        self.proc.stdin.flush()
        sel = selectors.DefaultSelector()
        sel.register(self.proc.stdout, selectors.EVENT_READ)
        deadline = time.monotonic() + HANG_SECONDS[mode]
        while True:
            if sel.select(timeout=max(deadline - time.monotonic(), 0)):
                line = self.proc.stdout.readline()
                sel.close()
                if not line:  # the worker died (e.g. out of memory)
                    self.proc = None
                    return {"path": str(path), "status": "crash", "detail": "the worker process died"}
                return json.loads(line)
            if time.monotonic() >= deadline:
                sel.close()
                self.close()
                return {"path": str(path), "status": "hang",
                        "detail": f"no answer within {HANG_SECONDS[mode]} s: killed"}

    def close(self):
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait()
            self.proc = None


def _check(result: dict, path: Path) -> str | None:
    status = result["status"]
    if status in ("crash", "hang", "internal"):
        return f"{path.name}: {status}: {result.get('detail')}"
    if status == "refused":
        for m in result["messages"]:
            if not re.match(re.escape(str(path)) + r"(:\d+)?: \S", m):
                return f"{path.name}: message without FILE:LINE: {m!r}"
    return None


@pytest.fixture(scope="module")
def harness():
    h = Harness()
    yield h
    h.close()


def _corpus(seeds: list[tuple[str, str]], n: int, rng: random.Random, folder: Path, how=mutate) -> list[Path]:
    out = []
    for k in range(n):
        name, text = seeds[k % len(seeds)]
        path = folder / f"{k:03d}-{name}.yaml"
        path.write_text(how(text, rng), encoding="utf-8")
        out.append(path)
    return out


def test_fuzz_validate(harness, tmp_path):
    seeds = [(p.stem, p.read_text(encoding="utf-8")) for p in sorted(PROBLEMS.glob("*.yaml"))] + [("small", SMALL)]
    files = _corpus(seeds, N_VALIDATE, random.Random(20261201), tmp_path)
    results = [(f, harness.run("validate", f)) for f in files]
    problems = [m for f, r in results if (m := _check(r, f))]
    assert not problems, "\n".join(problems[:10]) + f"\n({len(problems)} of {len(files)})"
    statuses = [r["status"] for _, r in results]
    assert statuses.count("refused") > len(files) // 4 and "valid" in statuses  # the mutations bite


def test_fuzz_solve_small(harness, tmp_path):
    seeds = [("small", SMALL), ("eom", (PROBLEMS / "one-link-eom.yaml").read_text(encoding="utf-8"))]
    files = _corpus(seeds, N_SOLVE, random.Random(7), tmp_path, how=mutate_value)
    results = [(f, harness.run("solve", f)) for f in files]
    problems = [m for f, r in results if (m := _check(r, f))]
    assert not problems, "\n".join(problems[:10])
    assert any(r["status"] == "valid" for _, r in results)  # some mutations still solve
