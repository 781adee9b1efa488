"""Where the figures' PNGs are drawn: in this process, or beside the solve in a helper process.

A figure is known as soon as its question is answered (`Answer.figures`), but it is needed only
when the output folder is written. `solve_problem` hands each answer's figures to a drawer
(`submit`) and `render_files` asks it for the bytes (`png`):

* `InlineFigures` draws when asked, in this process: what `batch`, `variants` and `grade` use,
  whose worker processes already keep every core busy;
* `BackgroundFigures` (the `solve` command, on a machine with two cores or more) forks one
  helper process when the first figure is known. The helper imports matplotlib and draws each
  figure while the next question is being solved, so a report's wall time loses the figures'
  second or so. The helper is forked from this process, so it draws with the same code,
  settings and data, and its PNGs are byte-identical to the inline ones (tested). If it cannot
  be started, or dies, the figures it owes are drawn inline; it never writes a file.
"""

from __future__ import annotations

import io


class FigureFailed(Exception):
    """A figure could not be drawn; the message is `<exception type>: <message>`."""


def _draw_png(spec) -> bytes:
    buffer = io.BytesIO()
    try:
        from robosolve.render.plots import draw

        draw(spec, buffer)
    except Exception as exc:  # a figure that fails must not lose the answers
        raise FigureFailed(f"{type(exc).__name__}: {exc}") from exc
    return buffer.getvalue()


class InlineFigures:
    """Draws each figure when its PNG is asked for."""

    def expect(self) -> None:
        """Figures will come: a background drawer gets ready (forks, imports matplotlib)."""

    def submit(self, specs) -> None:
        pass

    def png(self, spec) -> bytes:
        return _draw_png(spec)

    def close(self) -> None:
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def _serve(requests, results, parent_ends) -> None:
    """The helper's loop: draw each (ticket, spec) received, send back (ticket, ok, bytes or reason),
    until the parent's end of `requests` is closed (robosolve.core.processes: the helpers' rules).
    A thread sends the PNGs, so the next figure is drawn meanwhile."""
    import gc
    import queue
    import threading

    from robosolve.core.processes import child_setup

    child_setup(parent_ends)
    gc.disable()        # a short-lived process: no collections of the heap it shares with the parent
    outbox: queue.SimpleQueue = queue.SimpleQueue()

    def send():
        try:
            while True:
                results.send(outbox.get())
        except OSError:     # the parent is gone
            return

    threading.Thread(target=send, daemon=True).start()
    import robosolve.render.plots as plots

    plots.setup()       # matplotlib's import, paid while the parent solves the next question
    while True:
        try:
            ticket, spec = requests.recv()
        except (EOFError, OSError):
            return
        try:
            outbox.put((ticket, True, _draw_png(spec)))
        except FigureFailed as exc:
            outbox.put((ticket, False, str(exc)))


class BackgroundFigures(InlineFigures):
    """Draws the figures in a helper process, forked when figures are expected (see the module's
    docstring): a problem without figures costs nothing. A figure's ticket is id(spec): its
    spec stays alive in its answer until the PNG is asked for."""

    def __init__(self):
        self._process = None
        self._sent: set[int] = set()               # tickets sent to the helper
        self._done: dict[int, tuple] = {}          # ticket -> (ok, bytes or reason)
        self._lost = False                         # no helper: everything is drawn inline

    def _start(self) -> None:
        from robosolve.core.processes import fork_helper, pipe

        requests, self._requests = pipe()
        self._results, results = pipe()
        self._process = fork_helper(_serve, (requests, results, (self._requests, self._results)))
        requests.close()
        results.close()
        if self._process is None:
            self._lost = True
            self._requests.close()
            self._results.close()

    def expect(self) -> None:
        if self._process is None and not self._lost:
            self._start()

    def submit(self, specs) -> None:
        for spec in specs:
            self.expect()
            if self._lost or id(spec) in self._sent:
                continue
            try:
                self._requests.send((id(spec), spec))
            except Exception:   # a spec that cannot be sent (or a helper gone) is drawn inline
                continue
            self._sent.add(id(spec))

    def png(self, spec) -> bytes:
        ticket = id(spec)
        if ticket not in self._sent or not self._wait_for(ticket):
            return _draw_png(spec)
        ok, payload = self._done.pop(ticket)
        if not ok:
            raise FigureFailed(payload)
        return payload

    def _wait_for(self, ticket: int) -> bool:
        while ticket not in self._done and not self._lost:
            try:
                got, ok, payload = self._results.recv()
            except (EOFError, OSError):     # the helper died: what it owes is drawn inline
                self._lost = True
                break
            self._done[got] = (ok, payload)
        return ticket in self._done

    def close(self) -> None:
        if self._process is None:
            return
        from robosolve.core.processes import stop

        self._requests.close()
        stop(self._process)
        self._results.close()
        self._process = None


def figure_drawer(background: bool = False):
    """A drawer for one command run, to use as a context manager: in a helper process when
    `background` is asked for and useful (two cores or more), inline otherwise."""
    from robosolve.core.processes import usable_cores

    return BackgroundFigures() if background and usable_cores() >= 2 else InlineFigures()
