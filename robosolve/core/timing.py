"""Time limits for symbolic steps.

sympy is pure Python, so a SIGALRM raised between bytecodes stops a runaway
`solve`/`simplify` cleanly. Only the main thread can receive signals; elsewhere
the limit is not enforced (documented, and the batch runner uses processes).
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time

from robosolve.errors import SymbolicTimeout


@contextlib.contextmanager
def time_limit(seconds: float):
    """Raise SymbolicTimeout if the block runs longer than `seconds`.

    Yields a token: `exc.token is token` tells whether this block expired (and
    not an enclosing one, whose expiry must propagate).
    """
    token = object()
    usable = (seconds and seconds > 0 and hasattr(signal, "setitimer")
              and threading.current_thread() is threading.main_thread())
    if not usable:
        yield token
        return

    def on_alarm(signum, frame):
        raise SymbolicTimeout(f"symbolic step exceeded {seconds:g} s", token)

    previous = signal.signal(signal.SIGALRM, on_alarm)
    remaining, _ = signal.getitimer(signal.ITIMER_REAL)
    if remaining and remaining < seconds:
        # an outer limit is shorter: keep it
        signal.signal(signal.SIGALRM, previous)
        yield token
        return
    start = time.monotonic()
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield token
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
        if remaining:
            # restore the outer timer, minus the time spent here
            elapsed = time.monotonic() - start
            signal.setitimer(signal.ITIMER_REAL, max(remaining - elapsed, 1e-3))
