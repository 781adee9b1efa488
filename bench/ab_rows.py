"""A/B benchmark: the rows of bench/RESULTS-perf.md and RESULTS-task.md for two trees of
robosolve (this one and a `--base` checkout, e.g. `git archive main | tar -x -C /tmp/base`), each
next to its reference, all interleaved in every round so that the three see the same machine load.

    python bench/ab_rows.py --base /tmp/base [--rounds 5] [--rows task,exam,3r,puma]
    python bench/ab_rows.py --base /tmp/base --batch [--rounds 1]

Prints, per row, the minimum and the median over the rounds of the wall and CPU seconds (user +
sys of the child and its waited helpers) of base, new and reference, and the ratios
tree / reference of the minima (on a shared machine the minimum is the run least disturbed by
the other jobs). Both trees are byte-compiled first (as `pip install .` does).
With `--batch`: `robosolve batch` of the problems of bench_rows.py's batch row vs the same
`solve`s one after another, for both trees, interleaved (wall seconds: the speed-up is the
ratio sequence / batch).
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
    ap.add_argument("--batch", action="store_true")
    args = ap.parse_args()
    base = Path(args.base).resolve()
    for tree in (ROOT, base):
        subprocess.run([PY, "-m", "compileall", "-q", str(tree / "robosolve")], check=True)
    out = Path(tempfile.mkdtemp(prefix="robosolve-ab-"))
    if args.batch:
        return batch_ab(base, out, args.rounds)
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


def batch_ab(base: Path, out: Path, rounds: int) -> None:
    import shutil

    from bench_rows import batch_files

    files = batch_files()
    folder = out / "batch-in"
    folder.mkdir()
    for f in files:
        shutil.copy(f, folder / f.name)
    res = {k: [] for k in ("base batch", "new batch", "base sequence", "new sequence")}
    print(f"# A/B batch of {len(files)} problems, {rounds} round(s), base = {base}")
    print(f"start: {load_note()}  ({time.strftime('%H:%M', time.gmtime())} UTC)")
    for k in range(rounds):
        for who, tree in (("base", base), ("new", ROOT)):
            res[f"{who} batch"].append(run([PY, "-m", "robosolve", "batch", str(folder), "--out",
                                            str(out / f"{who}-batch-{k}")], tree))
        for who, tree in (("base", base), ("new", ROOT)):
            walls = [run([PY, "-m", "robosolve", "solve", str(f), "--out", str(out / f"{who}-seq-{k}" / f.stem)], tree)
                     for f in files]
            res[f"{who} sequence"].append((sum(w for w, _c in walls), sum(c for _w, c in walls)))
    print(f"end:   {load_note()}  ({time.strftime('%H:%M', time.gmtime())} UTC)\n")
    print("| tree | batch wall (CPU) | the same solves one after another, wall (CPU) | speed-up (wall minima) | goal |")
    print("| --- | --- | --- | --- | --- |")
    for who in ("base", "new"):
        b, q = min(res[f"{who} batch"]), min(res[f"{who} sequence"])
        print(f"| {who} | {b[0]:.2f} s ({b[1]:.2f} s) | {q[0]:.2f} s ({q[1]:.2f} s) | **{q[0] / b[0]:.2f}×** | ≥ 2.5× |")
    print("\nall runs (wall, CPU):", {k: [f"{a:.2f}/{c:.2f}" for a, c in v] for k, v in res.items()})


if __name__ == "__main__":
    sys.exit(main())
