"""A/B benchmark: the rows of bench/RESULTS-perf.md and RESULTS-task.md for two trees of
robosolve (this one and a `--base` checkout, e.g. `git archive main | tar -x -C /tmp/base`), each
next to its reference, all interleaved in every round so that the three see the same machine load.

    python bench/ab_rows.py --base /tmp/base [--rounds 5] [--rows task,exam,3r,puma]

Prints, per row, the minimum and the median over the rounds of the wall and CPU seconds (user +
sys of the child and its waited helpers) of base, new and reference, and the ratios
tree / reference of the minima (on a shared machine the minimum is the run least disturbed by
the other jobs). Both trees are byte-compiled first (as `pip install .` does).
"""

from __future__ import annotations

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import IMPORT_FLOOR, PY, ROOT, load_note

ROWS = {   # label: (problem, reference command, goal)
    "task": ("bench/problems/task-2r-line.yaml", [PY, str(ROOT / "bench" / "task_rtb_reference.py")], 0.5),
    "exam": ("problems/exam-2r-full.yaml", [PY, str(ROOT / "bench" / "exam_rtb_lean.py")], 0.5),
    "3r": ("bench/problems/anthropomorphic-3r-5q.yaml", IMPORT_FLOOR, 1.3),
    "puma": ("bench/problems/puma560-4q.yaml", IMPORT_FLOOR, 2.0),
}


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, cwd) -> tuple[float, float]:
    c0, t0 = _cpu(), time.perf_counter()
    done = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=900)
    wall, cpu = time.perf_counter() - t0, _cpu() - c0
    if done.returncode not in (0, 1):
        raise SystemExit(f"{cmd} failed in {cwd}:\n{done.stderr[-2000:]}")
    return wall, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--base", required=True)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--rows", default="task,exam,3r,puma")
    args = ap.parse_args()
    base = Path(args.base).resolve()
    for tree in (ROOT, base):
        subprocess.run([PY, "-m", "compileall", "-q", str(tree / "robosolve")], check=True)
    out = Path(tempfile.mkdtemp(prefix="robosolve-ab-"))
    rows = args.rows.split(",")
    times = {(r, w): [] for r in rows for w in ("base", "new", "ref")}
    print(f"# A/B: {args.rounds} rounds, base = {base}")
    print(f"start: {load_note()}  ({time.strftime('%H:%M', time.gmtime())} UTC)")
    for k in range(args.rounds):
        for r in rows:
            problem, ref, _goal = ROWS[r]
            for who, cmd, cwd in (("base", [PY, "-m", "robosolve", "solve", problem, "--out", str(out / f"b-{r}-{k}")], base),
                                  ("new", [PY, "-m", "robosolve", "solve", problem, "--out", str(out / f"n-{r}-{k}")], ROOT),
                                  ("ref", ref + ([str(out / f"r-{r}-{k}")] if r == "exam" else []), ROOT)):
                times[(r, who)].append(run(cmd, cwd))
    print(f"end:   {load_note()}  ({time.strftime('%H:%M', time.gmtime())} UTC)\n")
    print("| row | base wall min / median | new wall min / median | reference wall min / median | "
          "ratio base → new (wall minima) | CPU min: base, new, reference | ratio base → new (CPU minima) | goal |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        w = {who: [t[0] for t in times[(r, who)]] for who in ("base", "new", "ref")}
        c = {who: [t[1] for t in times[(r, who)]] for who in ("base", "new", "ref")}
        mw = {k: min(v) for k, v in w.items()}
        mc = {k: min(v) for k, v in c.items()}
        med = {k: statistics.median(v) for k, v in w.items()}
        print(f"| {r} | {mw['base']:.2f} / {med['base']:.2f} s | {mw['new']:.2f} / {med['new']:.2f} s | "
              f"{mw['ref']:.2f} / {med['ref']:.2f} s | {mw['base'] / mw['ref']:.2f} → **{mw['new'] / mw['ref']:.2f}** | "
              f"{mc['base']:.2f}, {mc['new']:.2f}, {mc['ref']:.2f} s | {mc['base'] / mc['ref']:.2f} → "
              f"**{mc['new'] / mc['ref']:.2f}** | ≤ {ROWS[r][2]} |")
    print("\nall runs (wall, CPU):")
    for key, v in times.items():
        print(f"  {key[0]} {key[1]}: " + ", ".join(f"{a:.2f}/{b:.2f}" for a, b in v))


if __name__ == "__main__":
    sys.exit(main())
