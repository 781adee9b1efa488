"""`python -m robosolve` and the `robosolve` script: signal handlers first, then the CLI.

The handlers go in before typer and the rest are imported, so an interrupt at any point of
start-up also ends with exit status 130 (spec §4) instead of a traceback.
"""

import os
import sys

from robosolve.errors import ExitStatus
from robosolve.run import interrupts


def main() -> None:
    interrupts.install()
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
