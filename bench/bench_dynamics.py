"""Benchmark: equations of motion with robosolve vs sympy.physics.mechanics, same run.

    python bench/bench_dynamics.py [--write] [--timeout 300] [--robots 2r,scara,3r,puma]

For each robot (fully symbolic parameters unless said): time to form the equations and
`count_ops` of the mass matrix M(q) with
  * robosolve (`derive_dynamics`: M, c, g, external forces, energies, all compacted),
  * sympy.physics.mechanics KanesMethod, then `trigsimp` of its M (time added),
  * sympy.physics.mechanics LagrangesMethod.
Then, for the PUMA 560, the numeric evaluation of the actuators from the derived equations
(lambdify with cse), per call. Each measurement runs in a fresh forked process (no shared
sympy cache) with a time limit. `--write` stores the table in bench/RESULTS-dynamics.md.
"""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import platform
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def _robot(key):
    from tests.support import robots as ex

    return {
        "2r": ex.planar_2r,
        "scara": ex.scara,
        "3r": ex.anthropomorphic_3r,
        "puma": ex.puma560,
        "puma-sym": lambda: ex.puma560(symbolic_parameters=True),
    }[key]()


def task_robosolve(key):
    import sympy as sp

    from robosolve.dynamics import derive_dynamics

    r = _robot(key)
    t = time.perf_counter()
    d = derive_dynamics(**r.engine_inputs())
    dt = time.perf_counter() - t
    return dt, sp.count_ops(d.mass_matrix)


def task_kane(key, simplify=False):
    import sympy as sp

    from tests.support import mechanics as ref

    r = _robot(key)
    t = time.perf_counter()
    model = ref.build(r)
    m, _forcing = ref.kane(model)
    dt = time.perf_counter() - t
    ops = sp.count_ops(m)
    if not simplify:
        return dt, ops
    t = time.perf_counter()
    ms = sp.trigsimp(m)
    return dt + (time.perf_counter() - t), sp.count_ops(ms)


def task_kane_trigsimp(key):
    return task_kane(key, simplify=True)


def task_lagrange(key):
    import sympy as sp

    from tests.support import mechanics as ref

    r = _robot(key)
    t = time.perf_counter()
    model = ref.build(r)
    m, _forcing = ref.lagrange(model)
    return time.perf_counter() - t, sp.count_ops(m)


def task_numeric(key):
    import timeit

    import numpy as np

    from robosolve.dynamics import derive_dynamics

    r = _robot(key)
    d = derive_dynamics(**r.engine_inputs())
    t = time.perf_counter()
    nd = d.numeric(r.values)
    build = time.perf_counter() - t
    rng = np.random.default_rng(0)
    q, qd, qdd = rng.uniform(-1, 1, (3, len(d.q)))
    nd.actuators(q, qd, qdd)
    n = 2000
    per_call = min(timeit.repeat(lambda: nd.actuators(q, qd, qdd), number=n, repeat=5)) / n
    return build, per_call * 1e6


def _worker(fn, key, conn):
    try:
        conn.send(("ok", globals()[fn](key)))
    except Exception as exc:  # report, do not crash the benchmark
        conn.send(("error", repr(exc)))


def run(fn, key, timeout):
    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    p = ctx.Process(target=_worker, args=(fn, key, child))
    p.start()
    if parent.poll(timeout):
        status, value = parent.recv()
        p.join()
        return value if status == "ok" else None
    p.terminate()
    p.join()
    return "timeout"


def fmt(res, timeout):
    if res == "timeout":
        return f"> {timeout:.0f} s", "—"
    if res is None:
        return "error", "—"
    return f"{res[0]:.2f} s", f"{res[1]:,}"


NAMES = {"2r": "planar 2R", "scara": "SCARA RRP + payload", "3r": "anthropomorphic 3R",
         "puma": "PUMA 560, numeric parameters", "puma-sym": "PUMA 560, 51 symbolic parameters"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--write", action="store_true")
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--robots", default="2r,scara,3r,puma,puma-sym")
    ap.add_argument("--skip-slow", action="store_true",
                    help="no Lagrange / trigsimp for the PUMA (minutes each)")
    args = ap.parse_args()
    keys = args.robots.split(",")
    rows = []
    for key in keys:
        big = key.startswith("puma")
        res = {"robosolve": run("task_robosolve", key, args.timeout),
               "kane": run("task_kane", key, args.timeout)}
        skip = big and args.skip_slow
        res["kane_ts"] = "skipped" if skip else run("task_kane_trigsimp", key, args.timeout)
        res["lagrange"] = "skipped" if skip else run("task_lagrange", key, args.timeout)
        cells = []
        for k in ("robosolve", "kane", "kane_ts", "lagrange"):
            cells += ["skipped", "—"] if res[k] == "skipped" else list(fmt(res[k], args.timeout))
        rows.append([NAMES[key], *cells])
        print(" | ".join(rows[-1]), flush=True)
    num = run("task_numeric", "puma", args.timeout) if "puma" in keys else None
    header = ("| robot | robosolve time | robosolve M ops | Kane time | Kane M ops | "
              "Kane + trigsimp(M) time | M ops after trigsimp | Lagrange time | Lagrange M ops |")
    lines = [
        "# Equations of motion: robosolve vs sympy.physics.mechanics",
        "",
        f"Measured in one run by `python bench/bench_dynamics.py` on {platform.machine()}, "
        f"Python {platform.python_version()}, {os.cpu_count()} CPUs; each cell is a fresh "
        f"forked process (time limit {args.timeout:.0f} s). Times include forming M, c, g "
        "(robosolve also the external forces and the energies, compacted); `count_ops` is "
        "that of the mass matrix M(q). Compare ratios within the table only.",
        "",
        header,
        "|" + " --- |" * 9,
    ]
    lines += ["| " + " | ".join(r) + " |" for r in rows]
    if isinstance(num, tuple):
        lines += ["", "Numeric inverse dynamics of the PUMA 560 from the derived equations "
                  "(`Dynamics.numeric`, lambdify with cse, math module):", "",
                  "| lambdify (build) | one call `actuators(q, q', q'')` |", "| --- | --- |",
                  f"| {num[0]:.2f} s | {num[1]:.0f} µs |"]
    text = "\n".join(lines) + "\n"
    print(text)
    if args.write:
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "RESULTS-dynamics.md")
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)


if __name__ == "__main__":
    main()
