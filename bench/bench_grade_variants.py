"""Benchmark `robosolve grade --variants` against one `robosolve check` process per student.

    python bench/bench_grade_variants.py [N] [--jobs J]

Makes N variants of a planar-arm exam with a roster of N students (`variants --roster
--no-solve`), one answers file per student (half of them with a negated Fq, found through
the roster's `email` column), then times, in the same run: `grade --variants DIR
--gradebook canvas,moodle,blackboard` over all of them, the same without gradebooks, and N
`robosolve check` processes one after another. Prints the times and the speed-up.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
PROBLEM = """\
robosolve: 1
name: exam
title: Two-link arm
parameters: {L1: 1/2, L2: 2/5, F: 5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}}
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}}
  - {type: statics, force: [0, -F], coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, marks: 2}
grading:
  partial: {negated: 1/2}
variants:
  parameters:
    L1: {range: [0.3, 0.8], step: 0.01}
    L2: {range: [0.2, 0.6], step: 0.01}
    F: {range: [1, 50], step: 1}
"""
FQ = {"q1": "F*(L1*cos(q1) + L2*cos(q1 + q2))", "q2": "F*L2*cos(q1 + q2)"}


def run(args, env):
    return subprocess.run([sys.executable, "-m", "robosolve", *map(str, args)], cwd=ROOT, env=env,
                          capture_output=True, text=True)


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 and sys.argv[1].isdigit() else 300
    jobs = sys.argv[sys.argv.index("--jobs") + 1] if "--jobs" in sys.argv else "0"
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        (tmp / "exam.yaml").write_text(PROBLEM)
        (tmp / "class.csv").write_text("Student,Email\n" + "".join(f"Student {k},s{k}@uni.edu\n" for k in range(n)))
        r = run(["variants", tmp / "exam.yaml", "--roster", tmp / "class.csv", "--out", tmp / "exams", "--no-solve"], env)
        assert r.returncode == 0, r.stderr
        subs = tmp / "subs"
        subs.mkdir()
        for k in range(n):
            fq = FQ if k % 2 else {j: f"-({e})" for j, e in FQ.items()}
            data = {"robosolve-answers": 1, "student": f"s{k}@uni.edu",
                    "answers": {"statics": {"Fq": fq}, "jacobian": {"det": "L1*L2*sin(q2)"}}}
            (subs / f"s{k:04d}.yaml").write_text(yaml.safe_dump(data))
        t = time.perf_counter()
        r = run(["grade", subs, "--variants", tmp / "exams", "--out", tmp / "g1", "--jobs", jobs,
                 "--gradebook", "canvas,moodle,blackboard"], env)
        grade_gb = time.perf_counter() - t
        assert r.returncode == 0, r.stderr
        t = time.perf_counter()
        run(["grade", subs, "--variants", tmp / "exams", "--out", tmp / "g2", "--jobs", jobs], env)
        grade_plain = time.perf_counter() - t
        t = time.perf_counter()
        for k in range(n):
            problem = tmp / "exams" / f"exam-student-{k}" / "problem.yaml"
            run(["check", subs / f"s{k:04d}.yaml", "--problem", problem, "--json", tmp / "c.json"], env)
        checks = time.perf_counter() - t
    print(f"| students | grade --variants (+ gradebooks) | grade --variants | {n} check processes | speed-up |")
    print("| --- | --- | --- | --- | --- |")
    print(f"| {n} | {grade_gb:.1f} s | {grade_plain:.1f} s | {checks:.1f} s | {checks / grade_gb:.1f}x |")


if __name__ == "__main__":
    main()
