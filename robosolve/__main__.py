"""`python -m robosolve` and the `robosolve` script: signal handlers first, then the CLI.

The handlers go in before typer and the rest are imported, so an interrupt at any point of
start-up also ends with exit status 130 (spec §4) instead of a traceback.
"""

import sys

from robosolve import interrupts


def main() -> None:
    interrupts.install()
    try:
        from robosolve.cli import main as cli_main
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        sys.exit(interrupts.EXIT_SIGINT)
    cli_main()


if __name__ == "__main__":
    main()
