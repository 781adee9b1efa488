"""`python -m robosolve` and the `robosolve` script: signal handlers first, then the CLI.

The handlers go in before typer and the rest are imported, so an interrupt at any point of
start-up also ends with exit status 130 (spec §4) instead of a traceback.
"""

import os
import sys

from robosolve.errors import ExitStatus
from robosolve.run import interrupts


# The cyclic garbage collector's first generation is scanned every 700 allocations by default;
# symbolic work allocates millions of short-lived, acyclic expression nodes, and the scans cost
# a few percent of a solve for nothing (the memory held is the same: reference counting frees
# them). A command runs for seconds: scan every 100,000 (the helpers forked from it inherit it).
GC_THRESHOLDS = (100_000, 50, 100)


def main() -> None:
    interrupts.install()
    import gc

    gc.set_threshold(*GC_THRESHOLDS)
    try:
        from robosolve.cli import main as cli_main
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.stderr.flush()
        os._exit(ExitStatus.SIGINT)  # (see cli.main: not the interpreter's SIGINT exit)
    try:
        cli_main()
    except KeyboardInterrupt:   # one that arrives after the CLI's own handling (at exit)
        sys.stderr.write("interrupted\n")
        sys.stderr.flush()
        os._exit(ExitStatus.SIGINT)


if __name__ == "__main__":
    main()
