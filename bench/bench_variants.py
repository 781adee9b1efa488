"""Variants at scale: the local process pool against a Dask LocalCluster, and Dask's overhead.

    python bench/bench_variants.py [--count 200] [--jobs 2] [--tiny 60]

1. `robosolve variants problems/exam-2r-full.yaml --count N --jobs J` (the warm process pool),
   wall time and time per variant;
2. the same with `--scheduler local` (a LocalCluster of J worker processes; its start-up is
   part of the time, as a user sees it);
3. per-task overhead: `--tiny` copies of a problem that takes milliseconds (a Grübler count)
   through `execution.run_tasks` on the pool and on an already running LocalCluster of J
   workers; the difference per task is what Dask adds (scheduling, pickling, transfer).

Prints the load average before and after: the machine may be shared.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TINY = """robosolve: 1
name: tiny-{i}
questions:
  - {{type: dof, bodies: {b}, joints_1dof: {j}, space: planar}}
"""


def run_variants(count, jobs, out, scheduler=None) -> float:
    cmd = [sys.executable, "-m", "robosolve", "variants", str(ROOT / "problems" / "exam-2r-full.yaml"),
           "--count", str(count), "--out", str(out), "--jobs", str(jobs)]
    if scheduler:
        cmd += ["--scheduler", scheduler]
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if res.returncode != 0:
        print(res.stderr[-2000:])
        raise SystemExit(f"variants failed ({res.returncode})")
    return dt


def overhead(n, jobs) -> tuple[float, float, float]:
    sys.path.insert(0, str(ROOT))
    from robosolve.run.execution import make_task, run_tasks, start_local_cluster

    tasks = [make_task(TINY.format(i=i, b=4 + i % 3, j=4 + i % 4), f"tiny-{i}.yaml") for i in range(n)]
    list(run_tasks(tasks[:jobs], jobs))                 # a first pool, so imports are cached on disk
    t0 = time.perf_counter()
    pool = [r for _, r in run_tasks(tasks, jobs)]
    t_pool = time.perf_counter() - t0
    t0 = time.perf_counter()
    cluster = start_local_cluster(jobs)
    t_start = time.perf_counter() - t0
    try:
        address = cluster.scheduler_address
        list(run_tasks(tasks[:jobs], jobs, address))     # warm the workers (imports)
        t0 = time.perf_counter()
        dask = [r for _, r in run_tasks(tasks, jobs, address)]
        t_dask = time.perf_counter() - t0
    finally:
        cluster.close()
    assert all(r.status == 0 for r in pool + dask)
    return t_pool, t_dask, t_start


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--tiny", type=int, default=60)
    ap.add_argument("--skip-exam", action="store_true")
    a = ap.parse_args()
    print(f"load average before: {os.getloadavg()}  cores: {os.cpu_count()}")
    if not a.skip_exam:
        tmp = Path(tempfile.mkdtemp(prefix="bench-variants-"))
        try:
            t = run_variants(a.count, a.jobs, tmp / "pool")
            print(f"pool, --jobs {a.jobs}: {a.count} variants in {t:.1f} s = {t / a.count:.2f} s per variant")
            t = run_variants(a.count, a.jobs, tmp / "dask", "local")
            print(f"LocalCluster of {a.jobs} workers: {a.count} variants in {t:.1f} s = "
                  f"{t / a.count:.2f} s per variant")
            same = subprocess.run(["diff", "-r", str(tmp / "pool"), str(tmp / "dask")]).returncode == 0
            print(f"identical outputs: {same}")
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
    t_pool, t_dask, t_start = overhead(a.tiny, a.jobs)
    print(f"{a.tiny} tiny tasks: pool {t_pool:.2f} s ({1000 * t_pool / a.tiny:.1f} ms/task), "
          f"Dask {t_dask:.2f} s ({1000 * t_dask / a.tiny:.1f} ms/task): Dask adds "
          f"{1000 * (t_dask - t_pool) / a.tiny:.1f} ms per task; LocalCluster start-up {t_start:.1f} s")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
