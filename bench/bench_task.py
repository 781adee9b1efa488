"""Benchmark (issue 25, Speed): a 2R line with its work-space PD simulation over 2 s, robosolve
vs a Robotics Toolbox script doing the same numerically, whole processes, one run.

    python bench/bench_task.py [N]          (median of N, default 3)

Times `python -m robosolve solve bench/problems/task-2r-line.yaml --out <tmp>` (the line of
problems/workspace-2r-line.yaml and its `task_pd_gravity` question with `duration: 2`; robosolve
has no sample-count option: the line is converted at its fixed 401 samples, the extremes refined
between them, the loop integrated with DOP853 rtol 1e-10; report.md, results.json and 3 PNG
figures are written) next to bench/task_rtb_reference.py (`ctraj` on 200 samples +
`ikine_LM` per sample + `solve_ivp` of the same law with `rne`/`inertia`/`gravload`, no plots),
interleaved, checks that both give the same answers, and prints the ratio robosolve / reference
(goal ≤ 0.5).
"""

from __future__ import annotations

import json
import subprocess
import sys
import tempfile

from _timing import CPU, PY, ROOT, interleaved, load_note, median, robosolve

PROBLEM = "bench/problems/task-2r-line.yaml"
REFERENCE = [PY, str(ROOT / "bench" / "task_rtb_reference.py")]


def same_answers(out) -> str:
    """Both sides' control answers (max |e|, final e), which must agree to 1e-6 m."""
    rs = json.loads((out / "results.json").read_text())["answers"]["work-space-pd"]["numeric"]
    ref = json.loads(subprocess.run(REFERENCE, capture_output=True, text=True, check=True, cwd=ROOT).stdout)
    ref = ref["work-space-pd"]
    rows = []
    for key in ("max_error", "final_error"):
        a, b = list(rs[key].values()), ref[key]
        if max(abs(x - y) for x, y in zip(a, b)) > 1e-6:
            raise SystemExit(f"{key} differs: robosolve {a}, reference {b}")
        rows.append(f"{key}: robosolve {[f'{x:.6g}' for x in a]}, reference {[f'{x:.6g}' for x in b]}")
    return "\n".join(rows)


def main():
    from pathlib import Path
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    out = Path(tempfile.mkdtemp(prefix="robosolve-bench-")) / "rs"
    commands = {"robosolve": robosolve("solve", PROBLEM, "--out", out), "reference": REFERENCE}
    before = load_note()
    times = interleaved(commands, n)
    after = load_note()
    rs, ref = median(times["robosolve"]), median(times["reference"])
    crs, cref = median(CPU["robosolve"]), median(CPU["reference"])
    print(f"# 2R line + work-space PD over 2 s vs Robotics Toolbox script, median of {n}")
    print(f"before: {before}\nafter:  {after}\n")
    print("| work | robosolve | reference in the same run | ratio | goal |")
    print("| --- | --- | --- | --- | --- |")
    print(f"| `{PROBLEM}` (line + `task_pd_gravity`, 2 s; report + 3 figures) | {rs:.2f} s | "
          f"RTB ctraj + ikine_LM ×200 + solve_ivp, no plots: {ref:.2f} s | {rs / ref:.2f} | ≤ 0.5 |")
    print(f"| same, CPU time (user + sys) | {crs:.2f} s | {cref:.2f} s | {crs / cref:.2f} | ≤ 0.5 |")
    print("\nall runs (wall):", {k: [round(x, 2) for x in v] for k, v in times.items()})
    print("all runs (CPU):", {k: [round(x, 2) for x in v] for k, v in CPU.items()})
    print("\nsame answers (to 1e-6 m):\n" + same_answers(out))


if __name__ == "__main__":
    main()
