"""Start-up and whole-run timings of the CLI (a benchmark, not a test).

Compares, in the same run: `robosolve --help`, `robosolve solve problems/scara-rrp.yaml`,
and the bare import of the heavy stack (`import sympy, numpy, scipy.integrate,
matplotlib.pyplot`) that any Python exam solution pays. Median of N runs.

    python bench/startup.py [N]
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def timed(cmd, n):
    times = []
    for _ in range(n):
        t = time.perf_counter()
        subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    out = tempfile.mkdtemp()
    rows = [
        ("robosolve --help", [sys.executable, "-m", "robosolve", "--help"]),
        ("import sympy, numpy, scipy.integrate, matplotlib.pyplot",
         [sys.executable, "-c", "import matplotlib; matplotlib.use('Agg'); "
                                "import sympy, numpy, scipy.integrate, matplotlib.pyplot"]),
        ("robosolve solve problems/scara-rrp.yaml",
         [sys.executable, "-m", "robosolve", "solve", "problems/scara-rrp.yaml", "--out", out]),
    ]
    print(f"| command | median of {n} |")
    print("| --- | --- |")
    for label, cmd in rows:
        print(f"| `{label}` | {timed(cmd, n):.2f} s |")


if __name__ == "__main__":
    main()
