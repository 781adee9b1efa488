"""Papers at scale (issue 23): `variants --count N --no-solve` with every variant's paper,
answers template and drawing, against the import floor timed in the same run.

    python bench/bench_papers.py [--count 200] [--jobs 2] [--format md]

The floor is `python -c "import sympy, numpy, matplotlib.pyplot"`; the target is at most 40
floors for 200 variants on 2 cores. Prints the load average before and after (the machine
may be shared).
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def timed(cmd) -> float:
    t0 = time.perf_counter()
    res = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if res.returncode != 0:
        print(res.stderr[-2000:])
        raise SystemExit(f"{cmd[2:4]} failed ({res.returncode})")
    return dt


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--format", default="md")
    args = ap.parse_args()
    print(f"load average before: {os.getloadavg()}")
    floor = min(timed([sys.executable, "-c", "import sympy, numpy, matplotlib.pyplot"]) for _ in range(3))
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "exams"
        dt = timed([sys.executable, "-m", "robosolve", "variants", "problems/exam-2r-full.yaml",
                    "--count", str(args.count), "--out", str(out), "--no-solve", "--jobs", str(args.jobs),
                    "--format", args.format])
        papers = len(list(out.glob("*/paper.md")))
    print(f"import floor {floor:.2f} s; variants --count {args.count} --no-solve with {papers} papers: "
          f"{dt:.1f} s = {dt / floor:.1f} floors ({dt / max(papers, 1) * 1000:.0f} ms per paper; target <= 40 floors)")
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
