"""What every command shares: the typer app, the options, printing, progress bars, the exit.

Heavy modules (sympy, numpy, matplotlib) are imported inside the commands so that
`robosolve --help` answers at once: at import, only typer (and so click) and this package.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
from typing import Optional

import typer

from robosolve.errors import ExitStatus

app = typer.Typer(
    add_completion=False,
    pretty_exceptions_enable=False,
    no_args_is_help=True,
    help="Solve industrial-robotics exam problems written as YAML files, step by step.\n\n"
         "A problem file describes the robot (joints, frames, masses, forces) and the questions; "
         "robosolve writes report.md (the worked solution), results.json and figures/*.png.",
)

FORMAT_HELP = ("Reports to write, comma-separated: md (report.md), html (report.html, one "
               "self-contained page), ipynb (report.ipynb, a notebook that recomputes the answers). "
               "Default: md. results.json and figures/ are always written.")

SCHEDULER_HELP = ("Solve on Dask: 'local' (a LocalCluster on this machine) or tcp://HOST:PORT (a "
                  "scheduler whose workers have robosolve installed; pip install \"robosolve[dask]\").")


# Options several commands share, defined once so that their names, bounds and help agree.
def format_option():
    return typer.Option(None, "--format", "-f", help=FORMAT_HELP)


def jobs_option():
    return typer.Option(0, "--jobs", "-j", min=0, help="Parallel processes (default: number of cores).")


def scheduler_option():
    return typer.Option(None, "--scheduler", help=SCHEDULER_HELP)


def problem_option(help_text: str):
    return typer.Option(None, "--problem", "-p", help=help_text, callback=usable_paths)


def tolerance_option(flag: str, kind: str, default: str):
    return typer.Option(None, flag, callback=_tolerance,
                        help=f"{kind} tolerance (default {default}, or the problem's grading:).")


def _tolerance(value: Optional[float]) -> Optional[float]:
    """--rtol / --atol: a finite number >= 0, as the problem file's `grading:` requires."""
    import math

    if value is not None and not (math.isfinite(value) and value >= 0):
        raise typer.BadParameter(f"expected a number >= 0, got {value:g}")
    return value


def usable_paths(value):
    """Callback of every path argument and option: a path the system cannot even look up (a
    name longer than it allows, a loop of symbolic links, no permission) is a usage error
    said in words, before anything is read or written. A path that does not exist yet
    passes (an output, or a missing input the command names itself)."""
    for item in value if isinstance(value, (list, tuple)) else [value]:
        if item is None or str(item) == "-":
            continue
        from robosolve.load.yamlsource import path_problem

        problem = path_problem(str(item))
        if problem:
            raise typer.BadParameter(problem)
    return value


# ---------------------------------------------------------------- printing

def err(text: str) -> None:
    """A plain line on standard error (an editor can jump to FILE:LINE; rich would wrap it)."""
    sys.stderr.write(text + "\n")


def counted(n: int, word: str) -> str:
    """'1 question', '3 questions': a count and its noun, singular for one."""
    return f"{n} {word}" + ("" if n == 1 else "s")


def warnings_of(problem) -> None:
    """The problem's accepted-but-suspicious data (`FILE:LINE: where: warning: what`) on standard
    error; the report says them too."""
    for w in getattr(problem, "warnings", ()):
        err(str(w))


def out(text: str) -> None:
    """A plain line on standard output."""
    typer.echo(text)


def write_stdout(text: str) -> None:
    """Text on standard output as is (a JSON record)."""
    sys.stdout.write(text)


def console(stderr: bool = True):
    """A rich console (tables, progress bars): on standard error unless asked otherwise."""
    from rich.console import Console

    return Console(stderr=stderr)


def progress_bars(description: str, con=None):
    """A factory `bar(total)` -> context manager yielding `advance(n=1)`: one transient bar."""
    @contextlib.contextmanager
    def bar(total):
        from rich.progress import Progress

        with Progress(console=con or console(), transient=True) as progress:
            task = progress.add_task(description, total=total)
            yield lambda n=1: progress.advance(task, n)
    return bar


class Steps:
    """Several progress bars in one display: `task(description, total)` returns an advance()."""

    def __init__(self, progress):
        self.progress = progress

    def task(self, description, total):
        tid = self.progress.add_task(description, total=total or None)
        return lambda: self.progress.advance(tid)


STATUS_LABEL = {ExitStatus.OK: "ok", ExitStatus.ANSWER_ERROR: "errors", ExitStatus.INPUT: "invalid"}


# ---------------------------------------------------------------- shared checks

def formats(text: Optional[str]) -> tuple:
    from robosolve.render.formats import parse_formats

    try:
        return parse_formats(text)
    except ValueError as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)


def check_scheduler(scheduler: Optional[str]) -> None:
    """--scheduler usage checks (Dask installed, address well formed), before any work."""
    from robosolve.run.execution import SchedulerError, check_scheduler as check

    try:
        check(scheduler)
    except SchedulerError as exc:
        err(str(exc))
        raise typer.Exit(ExitStatus.INPUT)


# ---------------------------------------------------------------- the exit

def main() -> None:
    from robosolve.run import interrupts

    interrupts.install()
    try:
        app()
        status = ExitStatus.OK
    except KeyboardInterrupt:
        status = ExitStatus.SIGINT
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except Exception as exc:          # a defect of robosolve: one line that says where, no traceback
        err(internal_error(exc))
        status = ExitStatus.ANSWER_ERROR
    # click turns KeyboardInterrupt into "Aborted!" and exit 1, and a library may swallow it:
    # a signal received at any point decides the status (spec §4: SIGINT exits 130).
    owed = interrupts.received()
    if owed is not None:
        err("interrupted")
        # os._exit: the interpreter's own exit path turns a KeyboardInterrupt seen anywhere
        # into death by SIGINT (status -2), whatever was caught; the clean-up ran in finally
        # blocks already
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(owed)
    # The work is done and its outputs written: a signal from here on must not turn a finished
    # run into death by SIGINT (-2) during the interpreter's exit. One that came between the
    # check above and this line raises here, and robosolve.__main__ exits 130 for it.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _exit(int(status))


def internal_error(exc: BaseException) -> str:
    """The one line a defect of robosolve gets: what was raised, and where in robosolve."""
    import traceback

    where = ""
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        parts = frame.filename.replace(os.sep, "/").split("/robosolve/")
        if len(parts) > 1:
            where = f", at robosolve/{parts[-1]}:{frame.lineno}"
            break
    return (f"internal error ({type(exc).__name__}: {exc}{where}): this is a bug in robosolve; please "
            "report it with the input files")


def _exit(status: int) -> None:
    """Exit without the interpreter's tear-down when nothing needs it.

    After a solve the heap holds the whole run's sympy expressions, and the interpreter's exit
    (a last garbage collection over them, then every module's objects freed one by one) took
    half a second of a 3R report's five (measured, bench/RESULTS-perf.md). When no other thread
    and no child process is left (robosolve's helpers are stopped and waited for by then; a Dask
    client or cluster keeps threads), there is nothing to wait for: the streams are flushed and
    the process ends. Otherwise, the ordinary exit."""
    import threading

    children = sys.modules.get("multiprocessing")
    if threading.active_count() == 1 and not (children and children.active_children()):
        if "logging" in sys.modules:
            sys.modules["logging"].shutdown()
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except (OSError, ValueError):   # a closed pipe or stream: nothing more to say
                pass
        os._exit(status)
    sys.exit(status)
