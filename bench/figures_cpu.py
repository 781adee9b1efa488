"""CPU time of drawing a problem's figures, in-process (issue 15).

    python bench/figures_cpu.py [problems/exam-2r-full.yaml] [rounds]

Solves the problem once (not timed), then draws every figure spec into memory: the first
round includes importing matplotlib, the next rounds show the drawing alone. Prints the CPU
time (time.process_time) of each figure and of each round, so that a tree can be compared
with another (PYTHONPATH=<tree> python bench/figures_cpu.py; PYTHONPATH=. for this one) whatever the machine's load.
"""

from __future__ import annotations

import io
import sys
import time


def main(path="problems/exam-2r-full.yaml", rounds=3):
    from robosolve.run.pipeline import solve_file
    from robosolve.render.plots import draw

    report = solve_file(path)
    specs = [(a.id, s) for a in report.answers for s in a.figures]
    for r in range(int(rounds)):
        total, sizes = 0.0, 0
        parts = []
        for qid, spec in specs:
            buffer = io.BytesIO()
            t0 = time.process_time()
            draw(spec, buffer)
            dt = time.process_time() - t0
            total += dt
            sizes += len(buffer.getvalue())
            parts.append(f"{qid}-{spec.name} {dt:.2f}")
        print(f"round {r + 1}: {len(specs)} figures {total:.2f} s CPU, {sizes / 1024:.0f} KiB"
              f" ({', '.join(parts)})")


if __name__ == "__main__":
    main(*sys.argv[1:])
