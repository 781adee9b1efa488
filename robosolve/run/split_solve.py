"""One problem's questions on two cores: a forked helper process solves some of them.

`robosolve solve` on a machine with two cores or more (pipeline.solve_problem(split=True)):

* `plan` splits the questions in two sets of about the same cost (the registry's `cost` and
  `cost_growth`, the largest first); the questions of one `unit` (those that share the
  dynamics' derivation, or a motion profile and the torques along it) stay together. A problem
  whose smaller set costs too little to pay for a process is not split.
* The helper is forked after the model's frames are computed, so both processes start from
  them; it solves its questions in their order, with the same code, budgets and caches as the
  parent, and sends each answer back pickled.
* The parent solves the others meanwhile, then unpickles the helper's answers with sympy's
  evaluation off (`sympy.evaluate(False)`): each expression is rebuilt from its arguments as it
  was built, not simplified again, so the report is byte-identical to a solve in one process
  (tested on every bundled problem). An answer that cannot be pickled, or a helper that dies,
  only means that the parent solves that question itself afterwards.
* The helper also prints each of its answers' results.json record (with the figure paths
  planned) and sends it beside the answer: results.json uses it when the figures are the ones
  planned, so the helper's answers are not printed on the parent's time after the questions.
  The last answer leaves first and its record follows: the parent prints its Markdown meanwhile.
* The helper prints its answers' Markdown blocks too, but the last one's (its copy of the parent's
  render.markdown.MarkdownPrinter, forked with it) and sends them with the compact cᵢ, sᵢ names
  they use; a parent done with its own questions prints the Markdown of the answers it has while
  it waits (pipeline._EarlyMarkdown). The report uses those blocks.
* Once every question is answered, the parent prints what is left: itself after a split (the
  helper's answers come printed, and forking the grown process costs more than printing the
  records of the parent's own answers); else `TextHelper` prints results.json in a fork while the
  parent prints the Markdown report (pipeline.render_files(parallel=True)); a helper that fails
  only means that the parent prints it too.

The helper follows robosolve.core.processes' rules (never outlives the command, no files).
"""

from __future__ import annotations

import pickle

# The smaller set must cost at least this (the registry's cost unit, about a second of CPU on
# this project's machine): a helper costs a fork and the pickling of its answers.
MIN_SPLIT_COST = 0.25


def question_cost(question, joints: int) -> float:
    from robosolve.questions.registry import QUESTION_TYPES

    qt = QUESTION_TYPES.get(question.type)
    return 0.0 if qt is None else qt.split_cost(joints, question)


def units(questions) -> dict:
    """unit -> the indices of its questions: a registry `unit`, or a question on its own."""
    from robosolve.questions.registry import QUESTION_TYPES

    out: dict = {}
    for i, q in enumerate(questions):
        qt = QUESTION_TYPES.get(q.type)
        out.setdefault(qt.unit if qt is not None and qt.unit else ("question", i), []).append(i)
    return out


def to_solve_again(questions, received) -> list[int]:
    """The questions the parent solves after the helper: each one not received, with the rest of
    its unit (the torques along a profile need the profile solved in the same process)."""
    again: set = set()
    for members in units(questions).values():
        if any(i not in received for i in members):
            again.update(members)
    return sorted(again)


def plan(questions, joints: int) -> list[int] | None:
    """The indices of the questions for the helper (in question order), or None: no split."""
    grouped = units(questions)
    cost = {key: sum(question_cost(questions[i], joints) for i in members) for key, members in grouped.items()}
    sets: tuple[list, list] = ([], [])
    loads = [0.0, 0.0]
    for key in sorted(grouped, key=lambda k: (-cost[k], grouped[k][0])):    # largest first, then in order
        side = 0 if loads[0] <= loads[1] else 1
        sets[side].extend(grouped[key])
        loads[side] += cost[key]
    light = 0 if loads[0] < loads[1] else 1      # the helper's: its answers cost a pickling
    if loads[light] < MIN_SPLIT_COST:
        return None
    return sorted(sets[light])


def _serve(results, parent_ends, indices, solve_one, print_markdown=None) -> None:
    """The helper: solve each question of `indices`, send (index, pickled answer or None, its
    results.json record, its Markdown) — the last two printed here, or None. The last answer
    leaves at once, its Markdown left to the parent (idle by then, or it would not wait for it),
    and its record follows as (index, None, record, None)."""
    from robosolve.core.processes import child_setup

    child_setup(parent_ends)
    for i in indices:
        answer = solve_one(i)
        try:
            data = pickle.dumps(answer, protocol=pickle.HIGHEST_PROTOCOL)
        except Exception:       # not picklable: the parent solves it again
            data = None
        last = i == indices[-1]
        # printed here, where the answer's expressions are the ones just printed by its solver (the
        # memos hold them); the parent's copy, rebuilt from the pickle, is printed from scratch
        record = _printed_record(answer) if data is not None and not last else None
        markdown = None
        if data is not None and print_markdown is not None and not last:
            try:
                markdown = print_markdown(i, answer)
            except Exception:   # printed by the parent
                markdown = None
        try:
            results.send((i, data, record, markdown))
            if last:
                results.send((i, None, _printed_record(answer) if data is not None else None, None))
        except OSError:         # the parent is gone
            return


def _printed_record(answer):
    """(figure paths, the answer's results.json record printed with them), printed here while
    the parent still solves (the helper's answers would otherwise be printed after every
    question, on the parent's time); None when printing fails (the parent prints it)."""
    from robosolve.render.results_json import answer_record, planned_figures

    try:
        paths = planned_figures(answer)
        return paths, answer_record(answer, paths)
    except Exception:
        return None


def _unpickled(data):
    """The answer sent, rebuilt as it was built (no evaluation), or None."""
    from sympy.core.parameters import evaluate

    if data is None:
        return None
    try:
        with evaluate(False):
            return pickle.loads(data)
    except Exception:   # solved again by the parent
        return None


class QuestionHelper:
    """A forked helper solving the questions of `indices` with `solve_one(index) -> Answer`.
    Without indices, or when no fork is possible, it is no helper: it owns no question and
    sends nothing."""

    def __init__(self, indices=(), solve_one=None, print_markdown=None):
        from robosolve.core.processes import fork_helper, pipe

        self.indices = list(indices)
        self._process = None
        self._pending = len(self.indices) + 1       # the answers, and the last one's record
        self._received: dict = {}
        if not self.indices:
            return
        self._results, results = pipe()
        self._process = fork_helper(_serve, (results, (self._results,), self.indices, solve_one, print_markdown))
        results.close()
        if self._process is None:
            self._results.close()
            self.indices = []

    def arrived(self, wait: bool = False, one: bool = False) -> dict:
        """index -> Answer of the answers sent since the last call: those already there; with
        `one`, at least one message waited for first; with `wait`, all the others (the helper is
        then stopped). A record sent after its answer is put on the answer received before."""
        got: dict = {}
        while self._process is not None and (wait or one or self._results.poll()):
            one = False
            try:
                i, data, record, markdown = self._results.recv()
            except (EOFError, OSError):
                self.close()
                break
            self._pending -= 1
            if data is None and i in self._received:     # the last answer's record
                if record is not None:
                    self._received[i].printed_record = record
            else:
                answer = _unpickled(data)
                if answer is not None:
                    if record is not None:
                        answer.printed_record = record      # render/results_json uses it as it is
                    if markdown is not None:
                        answer.printed_markdown = markdown  # the report's printer adopts it
                    got[i] = self._received[i] = answer
            if not self._pending:
                self.close()
        return got

    @property
    def pending(self) -> bool:
        """Some answers are still to come."""
        return self._process is not None and self._pending > 0

    def close(self) -> None:
        if self._process is None:
            return
        from robosolve.core.processes import stop

        stop(self._process)
        self._results.close()
        self._process = None


def _serve_text(results, parent_ends, render) -> None:
    """The text helper: print one text, send it (None when printing failed)."""
    from robosolve.core.processes import child_setup

    child_setup(parent_ends)
    try:
        data = render().encode("utf-8")
    except Exception:   # printed again by the parent
        data = None
    try:
        results.send(data)
    except OSError:     # the parent is gone
        return


class TextHelper:
    """A forked helper printing one text with `render() -> str` (results.json, while the parent
    prints the Markdown report: both need every answer, so they start once the questions are
    answered). `text()` is the text, or None when no helper could be forked or it failed."""

    def __init__(self, render):
        from robosolve.core.processes import fork_helper, pipe

        self._results, results = pipe()
        self._process = fork_helper(_serve_text, (results, (self._results,), render))
        results.close()
        if self._process is None:
            self._results.close()

    def text(self) -> str | None:
        if self._process is None:
            return None
        try:
            data = self._results.recv()
        except (EOFError, OSError):
            data = None
        finally:
            self._results.close()
            self._process.join()
            self._process = None
        return None if data is None else data.decode("utf-8")
