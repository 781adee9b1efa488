"""Benchmark `robosolve grade`: N generated submissions of the full exam.

    python bench/bench_grade.py [N] [--jobs J]

Generates N answers files for problems/exam-2r-full.yaml from the example answers
(problems/answers/exam-2r-full-student.yaml, its mistakes corrected), each with a seeded
random choice of the usual mistakes (a transposed M, a negated Fq, IK in degrees, the
lengths substituted, a key left out, a number off by 3 %), then measures: the one solve of
the problem, the grading of every submission (serial, then with --jobs), and the whole
`robosolve grade` command. Prints a Markdown table for docs/grading.md.
"""

from __future__ import annotations

import copy
import math
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
EXAMPLE = ROOT / "problems" / "answers" / "exam-2r-full-student.yaml"
PROBLEM = ROOT / "problems" / "exam-2r-full.yaml"


def correct_answers() -> dict:
    data = yaml.safe_load(EXAMPLE.read_text(encoding="utf-8"))
    a = data["answers"]
    a["position"]["M"] = [list(r) for r in zip(*a["position"]["M"])]
    a["jacobian"]["det"] = "L1*L2*sin(theta2)"
    a["statics"]["Fq"] = {"theta1": "20*(L1*cos(theta1) + L2*cos(theta1 + theta2))",
                          "theta2": "20*L2*cos(theta1 + theta2)"}
    a["inverse_kinematics"]["solutions"] = [
        {k: math.radians(v) for k, v in s.items()} for s in a["inverse_kinematics"]["solutions"]]
    a["profile"]["T"] = "sqrt(pi)"
    return data


def _transpose(a):
    a["position"]["M"] = [list(r) for r in zip(*a["position"]["M"])]


def _negate_fq(a):
    a["statics"]["Fq"] = {k: f"-({v})" for k, v in a["statics"]["Fq"].items()}


def _degrees(a):
    a["inverse_kinematics"]["solutions"] = [
        {k: math.degrees(v) for k, v in s.items()} for s in a["inverse_kinematics"]["solutions"]]


def _substitute(a):
    a["jacobian"]["det"] = "0.2*sin(theta2)"


def _leave_out(a):
    a["equations_of_motion"].pop("gravity_terms")


def _off(a):
    a["ellipsoids"]["condition_number"] = 17.71 * 1.03


MISTAKES = (_transpose, _negate_fq, _degrees, _substitute, _leave_out, _off)


def generate(folder: Path, n: int) -> None:
    base = correct_answers()
    rng = random.Random("bench-grade")
    for i in range(n):
        data = copy.deepcopy(base)
        data["student"] = f"s{i + 1:04d}"
        data["problem"] = str(PROBLEM)
        for mistake in MISTAKES:
            if rng.random() < 0.3:
                mistake(data["answers"])
        (folder / f"s{i + 1:04d}.yaml").write_text(yaml.safe_dump(data, sort_keys=False, allow_unicode=True),
                                                   encoding="utf-8")


def main() -> None:
    args = sys.argv[1:]
    jobs = 2
    if "--jobs" in args:
        jobs = int(args[args.index("--jobs") + 1])
        del args[args.index("--jobs"):args.index("--jobs") + 2]
    n = int(args[0]) if args else 100
    from robosolve.grading.grade import collect, grade_all, prepare

    with tempfile.TemporaryDirectory() as tmp:
        subs = Path(tmp) / "subs"
        subs.mkdir()
        generate(subs, n)
        files = collect([subs])
        t0 = time.perf_counter()
        jobs_list, refs = prepare(files)
        t_prepare = time.perf_counter() - t0
        t0 = time.perf_counter()
        results = grade_all(jobs_list, refs, 1)
        t_serial = time.perf_counter() - t0
        t0 = time.perf_counter()
        grade_all(jobs_list, refs, jobs)
        t_parallel = time.perf_counter() - t0
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "robosolve", "grade", str(subs), "--out",
                               str(Path(tmp) / "out"), "--jobs", str(jobs)], cwd=ROOT,
                              capture_output=True, text=True)
        t_cli = time.perf_counter() - t0
        scores = sorted(float(r.score) for r in results)
        print(f"| submissions | solve + read (once) | grading, serial | per submission | grading, --jobs {jobs} "
              f"| `robosolve grade` end to end |")
        print("| --- | --- | --- | --- | --- | --- |")
        print(f"| {n} | {t_prepare:.1f} s | {t_serial:.1f} s | {1000 * t_serial / n:.0f} ms | "
              f"{t_parallel:.1f} s | {t_cli:.1f} s (exit {proc.returncode}) |")
        print(f"\nscores: min {scores[0]:.2f}, median {scores[len(scores) // 2]:.2f}, max {scores[-1]:.2f}")


if __name__ == "__main__":
    main()
