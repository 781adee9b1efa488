"""Where the solves run: in this process, in a warm local process pool, or on Dask.

One interface for `batch` and `variants`: ``run_tasks(tasks, jobs, scheduler)`` yields
``(index, result)`` as each task finishes. A task is a plain dict (the problem's YAML text
and what to produce), so it travels to a process or a remote Dask worker as is; a result
(a `FileResult`) carries the output files as bytes (relative path -> bytes) and the client writes them, so
the files are the same bytes whichever back-end solved them.

- local pool: workers import robosolve once (the initializer), tasks are submitted longest
  first by a cheap estimate (questions x joints), results are streamed as they finish;
- Dask: ``scheduler="local"`` starts a LocalCluster (processes, one thread each),
  ``"tcp://HOST:PORT"`` uses a running scheduler whose workers have robosolve installed.

Callers sort the results themselves (by task order), so the output order never depends on
which task finished first.
"""

from __future__ import annotations

import os
import re

from robosolve.errors import ExitStatus, InputError

DASK_HINT = 'Dask is not installed: pip install "robosolve[dask]"'
SCHEDULER_RE = re.compile(r"^(local|(tcp|tls|ws|wss|inproc)://\S+)$")


class SchedulerError(Exception):
    """--scheduler cannot be used (Dask missing, bad address, scheduler unreachable)."""


# ---------------------------------------------------------------------------
# the task (runs in a worker)

def make_task(text: str, file: str, formats=("md",), solve: bool = True, paper: dict | None = None) -> dict:
    """`paper`: {"student", "variant"} to add the student's paper and answers template
    (papers.md) to the files, solved or not."""
    return {"text": text, "file": file, "formats": tuple(formats), "solve": solve, "paper": paper}


def _paper(task: dict, problem) -> dict:
    if not task.get("paper"):
        return {}
    from robosolve.papers.workflow import paper_files

    formats = tuple(f for f in task.get("formats", ("md",)) if f == "html")
    return paper_files(problem, "problem.yaml", task["paper"].get("student", ""),
                       task["paper"].get("variant"), ("md",) + formats)


def solve_task(task: dict):
    """Load (and solve and render) one problem from its YAML text: a `FileResult`; never raises
    on bad input. Writes nothing: the files come back as bytes."""
    import robosolve
    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import FileResult, solve_loaded

    file = task["file"]
    try:
        problem = load_problem_text(task["text"], file)
    except InputError as exc:
        return FileResult(file, status=ExitStatus.INPUT, messages=[str(i) for i in exc.issues],
                          version=robosolve.__version__)
    if not task.get("solve", True):
        return FileResult(file, problem.name, total=len(problem.questions), version=robosolve.__version__,
                          files=_paper(task, problem))
    result = solve_loaded(problem, tuple(task.get("formats", ("md",))))
    result.files.update(_paper(task, problem))
    return result


def read_error(path, exc: BaseException):
    """The summary of a problem file that cannot be read."""
    from robosolve.run.pipeline import FileResult

    why = ("the file is not UTF-8 text" if isinstance(exc, UnicodeDecodeError)
           else f"cannot read the file: {getattr(exc, 'strerror', None) or exc}")
    return FileResult.unreadable(path, f"{path}:1: {why}")


def warm_worker() -> None:
    """Pool initializer: the parent handles SIGINT (robosolve.run.interrupts), and the imports are
    paid once per worker, not once per task."""
    from robosolve.core.processes import worker_init

    worker_init()
    import matplotlib

    matplotlib.use("Agg")
    import robosolve.run.pipeline  # noqa: F401
    import robosolve.solvers  # noqa: F401


def estimate(task: dict) -> int:
    """A cheap guess of a task's cost, to start the longest ones first."""
    from robosolve.questions.registry import types_where

    text = task["text"]
    joints = len(re.findall(r"\btype:\s*(revolute|prismatic)\b", text)) + text.count("theta:")
    questions = max(1, len(re.findall(r"\btype:\s*[a-z_]+", text)) - joints)
    words = ["bodies"] + [t.name for t in types_where("needs_dynamics")]
    dynamic = 2 if re.search(r"\b(" + "|".join(words) + r")\b", text) else 1
    return questions * (1 + joints) ** 2 * dynamic


def crash_result(task: dict, exc: BaseException):
    from robosolve.run.pipeline import FileResult

    return FileResult(task["file"], status=ExitStatus.ANSWER_ERROR,
                      messages=[f"{task['file']}: the worker failed ({type(exc).__name__}: {exc})"])


# ---------------------------------------------------------------------------
# back-ends

def check_scheduler(scheduler: str | None) -> None:
    """Usage checks before any work: Dask importable, address well formed."""
    if scheduler is None:
        return
    if not SCHEDULER_RE.match(scheduler):
        raise SchedulerError(f"--scheduler {scheduler!r}: expected 'local' or an address such as "
                             "tcp://HOST:8786")
    import importlib.util

    try:
        found = importlib.util.find_spec("distributed") is not None
    except (ImportError, ValueError):
        found = False
    if not found:
        raise SchedulerError(DASK_HINT)


def run_tasks(tasks: list, jobs: int = 0, scheduler: str | None = None):
    """Yield (index, result) for every task, as they finish."""
    order = sorted(range(len(tasks)), key=lambda i: (-estimate(tasks[i]), i))
    if scheduler is not None:
        yield from _run_dask(tasks, order, jobs, scheduler)
        return
    jobs = jobs or os.cpu_count() or 1
    if jobs == 1 or len(tasks) <= 1:
        for i in range(len(tasks)):
            yield i, solve_task(tasks[i])
        return
    yield from _run_pool(tasks, order, jobs)


def _run_pool(tasks, order, jobs):
    from concurrent.futures import as_completed

    from robosolve.run.interrupts import process_pool

    with process_pool(max_workers=min(jobs, len(tasks)), initializer=warm_worker) as pool:
        futures = {pool.submit(solve_task, tasks[i]): i for i in order}
        for fut in as_completed(futures):
            i = futures[fut]
            try:
                yield i, fut.result()
            except Exception as exc:  # a crashed worker is a row of the summary, not a traceback
                yield i, crash_result(tasks[i], exc)


def start_local_cluster(jobs: int = 0):
    """A LocalCluster of `jobs` worker processes (default: the cores), one thread each."""
    import logging

    from dask.distributed import LocalCluster

    n = jobs or os.cpu_count() or 1
    return LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None,
                        silence_logs=logging.ERROR)


# How long `--scheduler tcp://…` waits for the scheduler before it is a usage error.
CONNECT_TIMEOUT = "10s"


def _connect(scheduler, jobs):
    from dask.distributed import Client

    if scheduler == "local":
        cluster = start_local_cluster(jobs)
        return Client(cluster), cluster
    try:
        return Client(scheduler, timeout=CONNECT_TIMEOUT), None
    except (OSError, TimeoutError) as exc:
        raise SchedulerError(f"cannot reach the Dask scheduler at {scheduler}: {exc}") from None


def _run_dask(tasks, order, jobs, scheduler):
    from dask.distributed import as_completed

    client, cluster = _connect(scheduler, jobs)
    futures = []
    try:
        keys = {}
        for rank, i in enumerate(order):
            # higher priority runs first: the longest tasks start first, as in the pool
            fut = client.submit(solve_task, tasks[i], key=f"robosolve-task-{i}-{os.getpid()}",
                                pure=False, priority=len(order) - rank)
            keys[fut.key] = i
            futures.append(fut)
        for fut in as_completed(futures):
            i = keys[fut.key]
            try:
                yield i, fut.result()
            except Exception as exc:
                yield i, crash_result(tasks[i], exc)
            fut.release()
    finally:
        for fut in futures:
            fut.cancel()
        client.close()
        if cluster is not None:
            cluster.close()
