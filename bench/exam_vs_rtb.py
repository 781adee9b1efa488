"""Benchmark: the full exam with robosolve vs the numeric toolbox, whole processes, one run.

    python bench/exam_vs_rtb.py [N] [--old]        (median of N, default 3)

Times `python -m robosolve solve problems/exam-2r-full.yaml --out <tmp>` (10 questions,
symbolic + numeric + 7 figures) next to bench/exam_rtb_lean.py (Robotics Toolbox + scipy +
matplotlib written for speed: the same exam's numeric work with 3 plots; issue 26's goal is
robosolve ≤ 0.5× it), interleaved, and prints the ratio robosolve / reference. With `--old`,
bench/exam_rtb_reference.py (the slower script of issue 15, goal ≤ 1.0) runs in the same rounds.
"""

from __future__ import annotations

import sys
import tempfile

from _timing import CPU, PY, ROOT, interleaved, load_note, median, robosolve


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    n = int(args[0]) if args else 3
    out = tempfile.mkdtemp(prefix="robosolve-bench-")
    commands = {
        "robosolve": robosolve("solve", "problems/exam-2r-full.yaml", "--out", f"{out}/rs"),
        "lean": [PY, str(ROOT / "bench" / "exam_rtb_lean.py"), f"{out}/lean"],
    }
    if "--old" in sys.argv:
        commands["old"] = [PY, str(ROOT / "bench" / "exam_rtb_reference.py"), f"{out}/rtb"]
    before = load_note()
    times = interleaved(commands, n)
    print(f"# exam-2r-full vs Robotics Toolbox scripts, median of {n}")
    print(f"before: {before}\nafter:  {load_note()}\n")
    print("| work | robosolve | reference in the same run | ratio | goal |")
    print("| --- | --- | --- | --- | --- |")
    rs, crs = median(times["robosolve"]), median(CPU["robosolve"])
    for key, what, goal in (("lean", "lean RTB + scipy + matplotlib script (bench/exam_rtb_lean.py), 3 plots", 0.5),
                            ("old", "RTB script of issue 15 (bench/exam_rtb_reference.py), 3 plots", 1.0)):
        if key not in times:
            continue
        ref, cref = median(times[key]), median(CPU[key])
        print(f"| `problems/exam-2r-full.yaml` (10 questions, symbolic + numeric + figures), wall | "
              f"{rs:.2f} s | {what}: {ref:.2f} s | {rs / ref:.2f} | ≤ {goal} |")
        print(f"| same, CPU time (user + sys) | {crs:.2f} s | {cref:.2f} s | {crs / cref:.2f} | ≤ {goal} |")
    print("\nall runs (wall):", {k: [round(x, 2) for x in v] for k, v in times.items()})
    print("all runs (CPU):", {k: [round(x, 2) for x in v] for k, v in CPU.items()})


if __name__ == "__main__":
    main()
