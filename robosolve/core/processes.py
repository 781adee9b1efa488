"""Helper processes forked by one command run (the `solve` command on two cores or more).

A helper is forked, not spawned: it starts with the parent's modules, problem, model and
caches, so it computes exactly what the parent would, and costs no imports. Both helpers
(render/drawing.py draws the figures, split_solve.py solves some of the questions) follow the
same rules, kept here:

* no fork while other threads run (a fork copies locks other threads may hold);
* the helper keeps only its own ends of the pipes (`child_setup`), so that it sees the end of
  its input, or fails to send, once the parent is gone, however the parent ended; on Linux it
  is also sent SIGTERM when the parent dies (PR_SET_PDEATHSIG), so it never outlives it;
* it ignores SIGINT (the parent handles Ctrl-C and stops it) and dies at once on SIGTERM;
* the parent stops it when the command ends (`stop`) and waits for it: no process is left.
"""

from __future__ import annotations

import os
import signal


def worker_init() -> None:
    """Worker processes ignore SIGINT (the parent stops them) and die at once on SIGTERM."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "SIGTERM"):
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def usable_cores() -> int:
    """The cores this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def fork_helper(target, args: tuple):
    """A started daemon Process running target(*args) in a fork of this process, or None when
    a fork is not possible here (other threads running, no fork, a daemon's own child)."""
    import multiprocessing
    import threading

    if threading.active_count() > 1:
        return None
    try:
        process = multiprocessing.get_context("fork").Process(target=target, args=args, daemon=True)
        process.start()
    except (OSError, ValueError, AssertionError):
        return None
    return process


def pipe():
    """(reader, writer): one-way connection ends."""
    import multiprocessing

    return multiprocessing.get_context("fork").Pipe(duplex=False)


def child_setup(parent_ends=()) -> None:
    """First thing in a helper: close the parent's pipe ends, set its signals."""
    for end in parent_ends:
        end.close()
    worker_init()
    _die_with_parent()


def _die_with_parent() -> None:
    """Linux: SIGTERM when the parent dies (the helper may be deep in a solve, not reading)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        pr_set_pdeathsig = 1
        libc.prctl(pr_set_pdeathsig, int(signal.SIGTERM), 0, 0, 0)
    except (OSError, AttributeError, TypeError):
        pass
    import multiprocessing

    parent = multiprocessing.parent_process()
    if parent is not None and os.getppid() != parent.pid:   # it died before the call above
        os._exit(0)


def stop(process) -> None:
    """Stop a helper now (whatever it still does was not asked for) and wait for it."""
    if process.is_alive():
        process.terminate()
    process.join()
