"""SIGINT and SIGTERM: stop any command cleanly, with exit status 130 (143 for SIGTERM).

`install()` (called by the CLI's entry point) makes SIGINT raise KeyboardInterrupt and SIGTERM
raise SystemExit, so every `finally` runs and no temporary folder is left; it also records
that the signal came, so an interrupt swallowed by a library's `except:` still ends the run
with 130 and nothing is written after it (`robosolve.run.outputs` calls `raise_if_interrupted`).
"""

from __future__ import annotations

import signal
import sys
from contextlib import contextmanager

from robosolve.errors import ExitStatus

_received: list[int] = []


def _on_sigint(signum, frame):
    _received.append(signum)
    raise KeyboardInterrupt


def _on_sigterm(signum, frame):
    _received.append(signum)
    raise SystemExit(ExitStatus.SIGTERM)


def _on_unraisable(unraisable) -> None:
    """A KeyboardInterrupt raised inside a callback Python cannot propagate from (a weakref or
    import-lock callback, a finaliser) is recorded, not printed as "Exception ignored ... Traceback":
    the run then stops at its next check (`raise_if_interrupted`) with 130."""
    if isinstance(unraisable.exc_value, KeyboardInterrupt):
        _received.append(signal.SIGINT)
        return
    sys.__unraisablehook__(unraisable)


def install() -> None:
    signal.signal(signal.SIGINT, _on_sigint)
    sys.unraisablehook = _on_unraisable
    if hasattr(signal, "SIGTERM"):
        signal.signal(signal.SIGTERM, _on_sigterm)


def received() -> int | None:
    """The exit status owed to a signal received so far (130 or 143), or None."""
    if not _received:
        return None
    return ExitStatus.SIGINT if signal.SIGINT in _received else ExitStatus.SIGTERM


def raise_if_interrupted() -> None:
    """Re-raise an interrupt that some library code caught and ignored."""
    status = received()
    if status == ExitStatus.SIGINT:
        raise KeyboardInterrupt
    if status is not None:
        raise SystemExit(status)


@contextmanager
def process_pool(**options):
    """A ProcessPoolExecutor(**options) that is shut down when the block ends.

    A block that ends normally waits for the workers; an interrupted one (an exception,
    KeyboardInterrupt, a closed generator) terminates them, since a waiting shutdown could
    hang on a busy worker.
    """
    from concurrent.futures import ProcessPoolExecutor

    pool = ProcessPoolExecutor(**options)
    clean = False
    try:
        yield pool
        clean = True
    finally:
        if clean:
            pool.shutdown(wait=True)
        else:
            for proc in list((getattr(pool, "_processes", None) or {}).values()):
                proc.terminate()
            pool.shutdown(wait=False, cancel_futures=True)
