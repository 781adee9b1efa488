"""Shared helpers of the bench scripts: whole-process timings, interleaved so that the
rows of one run see the same machine load (the machine is shared: compare ratios)."""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PY = sys.executable
IMPORT_FLOOR = [PY, "-c", "import matplotlib; matplotlib.use('Agg'); "
                          "import sympy, numpy, scipy.integrate, matplotlib.pyplot"]


CPU: dict = {}      # label -> [user + sys seconds of the child], beside the wall times


def byte_compile() -> None:
    """Byte-compile robosolve as `pip install .` does. The references (Robotics Toolbox,
    sympy, numpy...) were compiled into site-packages when installed; a checkout run with
    PYTHONDONTWRITEBYTECODE=1 (as on the project's machine) would otherwise compile
    robosolve's sources again in every timed process (0.2-0.3 s each)."""
    subprocess.run([PY, "-m", "compileall", "-q", str(ROOT / "robosolve")], check=True)


byte_compile()


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_once(cmd, timeout=900, label=None) -> float:
    """Wall seconds of one whole process; its CPU seconds (user + sys) go to CPU[label]:
    on a loaded machine the wall time counts the other jobs too, the CPU time does not."""
    c0 = _children_cpu()
    t = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, cwd=ROOT, timeout=timeout, text=True)
    dt = time.perf_counter() - t
    if label is not None:
        CPU.setdefault(label, []).append(_children_cpu() - c0)
    if done.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(map(str, cmd))} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    return dt


def interleaved(commands: dict, n: int) -> dict:
    """{label: [seconds] * n}: round i runs every command once, in order."""
    times = {label: [] for label in commands}
    for _ in range(n):
        for label, cmd in commands.items():
            times[label].append(run_once(cmd, label=label))
    return times


def median(xs) -> float:
    return statistics.median(xs)


def load_note() -> str:
    one, five, fifteen = os.getloadavg()
    return (f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores "
            f"(shared machine: compare the ratios, not the seconds)")


def robosolve(*args) -> list:
    return [PY, "-m", "robosolve", *map(str, args)]
