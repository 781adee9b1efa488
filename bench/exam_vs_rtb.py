"""Benchmark: the full exam with robosolve vs the numeric toolbox, whole processes, one run.

    python bench/exam_vs_rtb.py [N]          (median of N, default 3)

Times `python -m robosolve solve problems/exam-2r-full.yaml --out <tmp>` (10 questions,
symbolic + numeric + 7 figures) next to bench/exam_rtb_reference.py (Robotics Toolbox +
scipy + matplotlib: the same exam's numeric work with 3 plots), interleaved, and prints the
ratio robosolve / reference (goal ≤ 1.0).
"""

from __future__ import annotations

import sys
import tempfile

from _timing import CPU, PY, ROOT, interleaved, load_note, median, robosolve


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    out = tempfile.mkdtemp(prefix="robosolve-bench-")
    commands = {
        "robosolve": robosolve("solve", "problems/exam-2r-full.yaml", "--out", f"{out}/rs"),
        "reference": [PY, str(ROOT / "bench" / "exam_rtb_reference.py"), f"{out}/rtb"],
    }
    before = load_note()
    times = interleaved(commands, n)
    rs, ref = median(times["robosolve"]), median(times["reference"])
    print(f"# exam-2r-full vs Robotics Toolbox script, median of {n}")
    print(f"before: {before}\nafter:  {load_note()}\n")
    print("| work | robosolve | reference in the same run | ratio | goal |")
    print("| --- | --- | --- | --- | --- |")
    print(f"| `problems/exam-2r-full.yaml` (10 questions, symbolic + numeric + figures) | "
          f"{rs:.2f} s | RTB + scipy + matplotlib script, 3 plots: {ref:.2f} s | "
          f"{rs / ref:.2f} | ≤ 1.0 |")
    crs, cref = median(CPU["robosolve"]), median(CPU["reference"])
    print(f"| same, CPU time (user + sys) | {crs:.2f} s | {cref:.2f} s | {crs / cref:.2f} | ≤ 1.0 |")
    print("\nall runs (wall):", {k: [round(x, 2) for x in v] for k, v in times.items()})
    print("all runs (CPU):", {k: [round(x, 2) for x in v] for k, v in CPU.items()})


if __name__ == "__main__":
    main()
