"""Benchmark: forward dynamics — the four pendulum runs of problems/pendulum-runs.yaml and a
3-second run of a planar 2R arm — robosolve next to pinocchio ``aba`` + ``solve_ivp``.

Both sides integrate the same equations with the same method and tolerances (DOP853, rtol
1e-10, atol 1e-12), so the difference is the cost of one right-hand side (robosolve: one
lambdified scalar function of the problem's own equations, M solved symbolically; pinocchio:
the articulated-body algorithm in C++, called from Python) plus robosolve's extras (extremes
on the dense output, energy, work).

Run from the repository root:  python bench/bench_forward.py
Prints a Markdown table (copied into docs/questions/forward_dynamics.md).
"""

from __future__ import annotations

import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
RUNS = 5

TWO_R = """
robosolve: 1
name: two-r
parameters: {L1: 0.5, L2: 0.4, m1: 3, m2: 2, I1: 0.06, I2: 0.03, g: 9.81}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, com: [-0.25, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I1]]}
  - {name: b2, frame: "2", mass: m2, com: [-0.2, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I2]]}
questions:
  - {id: run, type: forward_dynamics, start: {q1: 0.3, q2: -0.2, q2_dot: 0.5},
     actuators: {C1: 15*cos(2*t), C2: 2*sin(3*t)}, duration: 3}
"""


def pin_one_link(F):
    import pinocchio as pin

    L, m1, m2, g = 1.0, 2.0, 1.0, 9.81
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelRX(), pin.SE3.Identity(), "theta")
    model.appendBodyToJoint(j, pin.Inertia(m1, np.array([0, L / 2, 0]), np.diag([m1 * L ** 2 / 12, 0, m1 * L ** 2 / 12])),
                            pin.SE3.Identity())
    model.appendBodyToJoint(j, pin.Inertia(m2, np.array([0, L, 0]), np.zeros((3, 3))), pin.SE3.Identity())
    model.gravity.linear = np.array([0, 0, -g])
    p, f = np.array([0, 2 * L / 3, 0]), np.array([0, 0, -F])
    return model, [pin.Force.Zero(), pin.Force(f, np.cross(p, f))]


def pin_two_r():
    import pinocchio as pin

    model = pin.Model()
    j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "q1")
    model.appendBodyToJoint(j1, pin.Inertia(3.0, np.array([0.25, 0, 0]), np.diag([0, 0, 0.06])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([0.5, 0, 0])), "q2")
    model.appendBodyToJoint(j2, pin.Inertia(2.0, np.array([0.2, 0, 0]), np.diag([0, 0, 0.03])), pin.SE3.Identity())
    model.gravity.linear = np.array([0, -9.81, 0])
    return model, None


def pin_run(model_fext, law, q0, qd0, duration):
    import pinocchio as pin
    from scipy.integrate import solve_ivp

    model, fext = model_fext
    data = model.createData()
    n = model.nq

    def f(t, y):
        q, v = y[:n], y[n:]
        tau = np.asarray(law(t, q, v), dtype=float)
        a = pin.aba(model, data, q, v, tau) if fext is None else pin.aba(model, data, q, v, tau, fext)
        return np.concatenate([v, a])

    sol = solve_ivp(f, (0, duration), np.concatenate([q0, qd0]), method="DOP853", rtol=1e-10, atol=1e-12,
                    dense_output=True)
    return sol


PENDULUM_LAWS = [("free-swing", 0.0, lambda t, q, v: [0.0], 5.0),
                 ("weak-motor", 0.0, lambda t, q, v: [12.0], 5.0),
                 ("strong-motor", 0.0, lambda t, q, v: [40.0], 4.0),
                 ("sine-motor", 3.0, lambda t, q, v: [70 * math.sin(t)], 10.0)]


def robosolve_times(text_or_path):
    """(whole problem cold: load + equations of motion + all runs, runs only with the dynamics cached)."""
    from robosolve.load.loader import load_problem, load_problem_text
    from robosolve.model import RobotModel
    from robosolve.solvers import forward_dynamics
    from robosolve.run.pipeline import solve_context

    whole, runs = [], []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        problem = load_problem(text_or_path) if isinstance(text_or_path, Path) else load_problem_text(text_or_path)
        ctx = solve_context(problem, RobotModel(problem))
        for q in problem.questions:
            forward_dynamics.solve(q, ctx)
        whole.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        for q in problem.questions:
            forward_dynamics.solve(q, ctx)
        runs.append(time.perf_counter() - t0)
    return statistics.median(whole), statistics.median(runs)


def engine_time(text_or_path):
    """The integration alone (compile_plant + integrate), from robosolve's own equations."""
    import sympy as sp

    from robosolve.load.loader import load_problem, load_problem_text
    from robosolve.model import RobotModel
    from robosolve.simulation.forward import compile_plant, integrate
    from robosolve.solvers import forward_dynamics as fd
    from robosolve.run.pipeline import solve_context

    problem = load_problem(text_or_path) if isinstance(text_or_path, Path) else load_problem_text(text_or_path)
    ctx = solve_context(problem, RobotModel(problem))
    dyn = ctx.dynamics()
    prepared = []
    for q in problem.questions:
        st = fd.setup(q, ctx, dyn)
        values, _ = fd._numbers(q, ctx, dyn, st)
        prepared.append((st, values))
    times, steps = [], 0
    for _ in range(RUNS):
        t0 = time.perf_counter()
        steps = 0
        for st, (params, q0, qd0, duration) in prepared:
            rep = lambda e: sp.sympify(e).xreplace(params)   # noqa: E731
            plant = compile_plant(dyn.mass_matrix.xreplace(params), dyn.velocity_terms.xreplace(params),
                                  dyn.gravity_terms.xreplace(params), [rep(f) for f in st.forces], dyn.q,
                                  dyn.qd, fd.T, kinetic=rep(st.kinetic), potential=rep(st.potential))
            run = integrate(plant, q0, qd0, duration, samples=fd.FIGURE_SAMPLES)
            steps += run.steps
        times.append(time.perf_counter() - t0)
    return statistics.median(times), steps


def pin_times(cases):
    times, steps = [], 0
    for _ in range(RUNS):
        t0 = time.perf_counter()
        steps = 0
        for model_fext, law, q0, qd0, duration in cases:
            sol = pin_run(model_fext, law, q0, qd0, duration)
            steps += len(sol.t) - 1
        times.append(time.perf_counter() - t0)
    return statistics.median(times), steps


def main():
    pendulum = ROOT / "problems" / "pendulum-runs.yaml"
    pend_cases = [(pin_one_link(F), law, np.zeros(1), np.zeros(1), d) for _, F, law, d in PENDULUM_LAWS]
    two_r_case = [(pin_two_r(), lambda t, q, v: [15 * math.cos(2 * t), 2 * math.sin(3 * t)],
                   np.array([0.3, -0.2]), np.array([0.0, 0.5]), 3.0)]
    rows = []
    for label, src, cases in (("pendulum, four runs (5 + 5 + 4 + 10 s)", pendulum, pend_cases),
                              ("2R arm, one 3 s run", TWO_R, two_r_case)):
        whole, runs = robosolve_times(src)
        eng, steps = engine_time(src)
        pin_t, pin_steps = pin_times(cases)
        rows.append((label, whole, runs, eng, steps, pin_t, pin_steps))
    print("| runs | robosolve, questions cold (load + equations of motion + runs) | robosolve, questions "
          "(equations cached) | robosolve, integration only (compile + DOP853) | steps | pinocchio aba + "
          "solve_ivp DOP853 | steps |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for label, whole, runs, eng, steps, pin_t, pin_steps in rows:
        print(f"| {label} | {whole:.2f} s | {runs:.2f} s | {eng:.3f} s | {steps} | {pin_t:.3f} s | {pin_steps} |")
    print(f"\n(median of {RUNS}; {sys.platform}, Python {sys.version.split()[0]})")


if __name__ == "__main__":
    main()
