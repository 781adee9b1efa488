"""Benchmark: the other rows of bench/RESULTS-perf.md (issues 15 and 26), whole processes, one run.

    python bench/bench_rows.py [N] [--rows scara,3r,puma,batch]   (median of N, default 3)

* SCARA position + velocity_acceleration (problems/scara-rrp.yaml) vs the import floor
  (`import sympy, numpy, scipy.integrate, matplotlib.pyplot`), goal ≤ 1.3;
* anthropomorphic 3R, 5 questions (bench/problems/anthropomorphic-3r-5q.yaml) vs the
  import floor, goal ≤ 1.3 (issue 26; 2.0 in issue 15);
* PUMA 560 position + geometric 6×6 Jacobian + orientation + EOM
  (bench/problems/puma560-4q.yaml) vs the import floor, goal ≤ 2.0 (issue 26; 5.0 in issue 15);
* the UR5 (problems/ur5.yaml: position, geometric 6×6 Jacobian with its singular families, the
  flange's 3×6 position Jacobian with its rank conditions, IK of a pose, the equations of motion)
  vs the import floor, goal ≤ 3.0 (issue 26);
* the Franka Panda (problems/panda.yaml: position, 6×7 Jacobian, IK of frame 6's pose, the
  equations of motion of 7 point masses) vs the import floor, goal ≤ 8.0 (issue 26);
* a batch of 14 problems (problems/*.yaml + the 3R bench problem) with `robosolve batch`
  vs the same 14 solved one process after another, goal ≥ 2.5× faster.
Every row's commands are interleaved with the import floor in the same round.
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
from pathlib import Path

from _timing import CPU, IMPORT_FLOOR, ROOT, interleaved, load_note, median, robosolve

SINGLE = {
    "scara": ("position + velocity_acceleration of a 3-joint SCARA", "problems/scara-rrp.yaml", 1.3),
    "3r": ("anthropomorphic 3R, 5 questions (position, vel/acc, jacobian, IK, EOM)",
           "bench/problems/anthropomorphic-3r-5q.yaml", 1.3),
    "puma": ("PUMA 560: position, geometric 6×6 Jacobian, orientation, EOM",
             "bench/problems/puma560-4q.yaml", 2.0),
    "ur5": ("UR5: position, geometric 6×6 Jacobian, flange 3×6 Jacobian, IK of a pose, EOM",
            "problems/ur5.yaml", 3.0),
    "panda": ("Franka Panda: position, geometric 6×7 Jacobian, IK of a pose, EOM (7 joints)",
              "problems/panda.yaml", 8.0),
}


def batch_files() -> list[Path]:
    files = sorted((ROOT / "problems").glob("*.yaml"))
    files.append(ROOT / "bench/problems/anthropomorphic-3r-5q.yaml")
    return files


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("n", nargs="?", type=int, default=3)
    ap.add_argument("--rows", default="scara,3r,puma,batch")
    args = ap.parse_args()
    rows = args.rows.split(",")
    out = tempfile.mkdtemp(prefix="robosolve-bench-")
    commands = {"floor": IMPORT_FLOOR}
    for key in rows:
        if key in SINGLE:
            commands[key] = robosolve("solve", SINGLE[key][1], "--out", f"{out}/{key}")
    before = load_note()
    times = interleaved(commands, args.n)
    floor = median(times["floor"])
    print(f"# rows of bench/RESULTS-perf.md, median of {args.n}")
    print(f"before: {before}")
    lines = []
    for key in rows:
        if key in SINGLE:
            label, path, goal = SINGLE[key]
            t = median(times[key])
            lines.append(f"| {label} | {t:.2f} s | import floor: {floor:.2f} s | {t / floor:.2f} | ≤ {goal} |")
            c, cf = median(CPU[key]), median(CPU["floor"])
            lines.append(f"| same, CPU time (user + sys) | {c:.2f} s | {cf:.2f} s | {c / cf:.2f} | ≤ {goal} |")
    if "batch" in rows:
        lines.append(batch_row(args.n, out))
    print(f"after:  {load_note()}\n")
    print("| work | robosolve | reference in the same run | ratio | goal |")
    print("| --- | --- | --- | --- | --- |")
    print("\n".join(lines))
    print("\nall runs (wall):", {k: [round(x, 2) for x in v] for k, v in times.items()})
    print("all runs (CPU):", {k: [round(x, 2) for x in v] for k, v in CPU.items()})


def batch_row(n: int, out: str) -> str:
    files = batch_files()
    folder = Path(out) / "batch-in"
    folder.mkdir()
    for f in files:
        shutil.copy(f, folder / f.name)
    one_by_one = {f"seq-{f.stem}": robosolve("solve", f, "--out", f"{out}/seq/{f.stem}") for f in files}
    # `solve` itself uses both cores (a figure helper, a question helper): the same sequence on
    # one core, as each process ran when the goal was set, is the second reference
    one_core = ({f"core-{f.stem}": ["taskset", "-c", "0", *robosolve("solve", f, "--out", f"{out}/core/{f.stem}")]
                 for f in files} if shutil.which("taskset") else {})
    batch_times, seq_times, core_times = [], [], []
    for i in range(n):
        batch_times += interleaved({"batch": robosolve("batch", folder, "--out", f"{out}/batch{i}")}, 1)["batch"]
        seq_times.append(sum(v[0] for v in interleaved(one_by_one, 1).values()))
        if one_core:
            core_times.append(sum(v[0] for v in interleaved(one_core, 1).values()))
    b, s = median(batch_times), median(seq_times)
    row = (f"| a batch of {len(files)} problems | {b:.2f} s with `robosolve batch` | the same "
           f"{len(files)} one `solve` after another: {s:.2f} s | {s / b:.2f}× faster | ≥ 2.5× faster |")
    if core_times:
        c = median(core_times)
        row += (f"\n| same | {b:.2f} s | the same {len(files)} one after another, each on one core "
                f"(`taskset -c 0`): {c:.2f} s | {c / b:.2f}× faster | ≥ 2.5× faster |")
    return row


if __name__ == "__main__":
    main()
