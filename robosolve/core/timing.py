"""Time limits for symbolic steps.

sympy is pure Python, so a signal raised between bytecodes stops a runaway
`solve`/`simplify` cleanly. Only the main thread can receive signals; elsewhere
the limit is not enforced (documented, and the batch runner uses processes).

The limits count the process's CPU time (ITIMER_PROF: user + system), not the wall
clock: on a machine shared with other jobs a wall-clock limit expires early and the
same problem gets a different (numeric-only) answer; CPU time is what the step costs,
whatever else runs, so the outputs stay the same.

Every limited block also starts from the same state of sympy's pseudo-random generator
(sympy seeds it from the operating system when it is imported; its multivariate factorisation,
Wang's algorithm, draws evaluation points from it): the work a step does, and so whether its
limit fires, then depends on the step alone, not on the process or on what it solved before.
"""

from __future__ import annotations

import contextlib
import signal
import threading
import time

from robosolve.errors import SymbolicTimeout

_TIMER = getattr(signal, "ITIMER_PROF", None)
_SIGNAL = getattr(signal, "SIGPROF", None)
# CPU seconds after which an expiry that was swallowed is raised again
_AGAIN = 0.05
# the seed of sympy's pseudo-random generator at the start of every limited block
SYMPY_SEED = 0


def _reseed_sympy() -> None:
    """sympy's generator (and its assumptions' shuffler) in their fixed starting state."""
    from sympy.core.random import seed

    seed(SYMPY_SEED)


@contextlib.contextmanager
def time_limit(seconds: float, repeat: bool = False, what: str = "symbolic step"):
    """Raise SymbolicTimeout if the block runs longer than `seconds`.

    Yields a token: `exc.token is token` tells whether this block expired (and
    not an enclosing one, whose expiry must propagate). With `repeat`, the expiry is raised
    again every second until the block ends, so that code catching SymbolicTimeout without
    checking its token cannot swallow an outer budget (the pipeline's per-question net).
    Without it the expiry is raised again after a short while too (`_AGAIN`), until the block
    ends: the signal can land where Python ignores the exception (a weakref finaliser run
    by the garbage collector, a sympy `except Exception`), and one such landing must not
    let the block run on as if it had no limit.
    """
    token = object()
    _reseed_sympy()
    usable = (seconds and seconds > 0 and hasattr(signal, "setitimer") and _TIMER is not None
              and threading.current_thread() is threading.main_thread())
    if not usable:
        yield token
        return

    def on_alarm(signum, frame):
        signal.setitimer(_TIMER, 1.0 if repeat else min(max(seconds, 1e-3), _AGAIN))
        raise SymbolicTimeout(f"{what} exceeded {seconds:g} s", token)

    previous = signal.signal(_SIGNAL, on_alarm)
    remaining, _ = signal.getitimer(_TIMER)
    if remaining and remaining < seconds:
        # an outer limit is shorter: keep it
        signal.signal(_SIGNAL, previous)
        yield token
        return
    start = time.process_time()
    signal.setitimer(_TIMER, seconds)
    try:
        yield token
    finally:
        signal.setitimer(_TIMER, 0)
        signal.signal(_SIGNAL, previous)
        if remaining:
            # restore the outer timer, minus the time spent here
            elapsed = time.process_time() - start
            signal.setitimer(_TIMER, max(remaining - elapsed, 1e-3))
