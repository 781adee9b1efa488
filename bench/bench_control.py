"""Benchmark: a p_control question on a 2R arm, Kp = 5000, 2 s profile (target: < 1 s).

Run from the repository root:  python bench/bench_control.py
Prints a Markdown table (copied into bench/RESULTS-control.md).
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
PROBLEM = HERE / "control-2r.yaml"
RUNS = 5


def in_process():
    from robosolve.load.loader import load_problem
    from robosolve.model import RobotModel
    from robosolve.dynamics.numeric import NumericDynamics
    from robosolve.simulation.joint_control import simulate
    from robosolve.solvers import motion_profile, p_control
    from robosolve.run.pipeline import solve_context

    problem = load_problem(PROBLEM)
    qp, qc = problem.questions
    rows = {"derive the equations of motion (symbolic)": [], "lambdify M, c, g (cse) + closed loop": [],
            "simulate (LSODA, error coordinates)": [], "p_control question, whole (cold)": [],
            "p_control question, dynamics cached": []}
    for _ in range(RUNS):
        ctx = solve_context(problem, RobotModel(problem))
        motion_profile.solve(qp, ctx)
        t0 = time.perf_counter()
        ans = p_control.solve(qc, ctx)
        rows["p_control question, whole (cold)"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        p_control.solve(qc, ctx)
        rows["p_control question, dynamics cached"].append(time.perf_counter() - t0)
        # breakdown
        ctx = solve_context(problem, RobotModel(problem))
        motion_profile.solve(qp, ctx)
        prof = ctx.profile(qp.id)
        t0 = time.perf_counter()
        dyn = ctx.dynamics()
        t1 = time.perf_counter()
        fast = NumericDynamics.from_dynamics(dyn, ctx.substitutions({}))
        fast.closed_loop("p", [5000, 5000], [0, 0])
        t2 = time.perf_counter()
        res = simulate(fast, prof.numeric_plan(), "p", [5000, 5000])
        t3 = time.perf_counter()
        rows["derive the equations of motion (symbolic)"].append(t1 - t0)
        rows["lambdify M, c, g (cse) + closed loop"].append(t2 - t1)
        rows["simulate (LSODA, error coordinates)"].append(t3 - t2)
    return rows, ans, res


def whole_process():
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(3):
            t0 = time.perf_counter()
            subprocess.run([sys.executable, "-m", "robosolve", "solve", str(PROBLEM), "--out", f"{tmp}/out"],
                           check=True, capture_output=True)
            times.append(time.perf_counter() - t0)
    return times


def main():
    sys.path.insert(0, str(HERE.parent))
    rows, ans, res = in_process()
    print("| step | median (s) | min (s) |")
    print("| --- | --- | --- |")
    for k, v in rows.items():
        print(f"| {k} | {statistics.median(v):.3f} | {min(v):.3f} |")
    w = whole_process()
    print(f"| `robosolve solve` whole process (imports, 2 questions, 3 PNG figures) | {statistics.median(w):.3f} | {min(w):.3f} |")
    print()
    print(f"max_error = {ans.numeric['max_error']}, final_error = {ans.numeric['final_error']}, "
          f"right-hand-side evaluations = {res.nfev}")


if __name__ == "__main__":
    main()
