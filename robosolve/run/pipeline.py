"""load -> model -> solve -> render, as library functions (the CLI is a thin layer).

`solve_file` returns a `Report` and writes nothing; `render_files` turns it into
bytes (relative path -> content) and `write_outputs` hands them to
`robosolve.run.outputs.write_output_folder`, the only writer of output folders (ownership
mark, atomic swap, umask, interrupts held back while it writes).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from robosolve.errors import ExitStatus, SolverError, SymbolicTimeout
from robosolve.load.loader import load_problem
from robosolve.load.problem import Problem


@dataclass
class Report:
    problem: Problem
    model: object
    answers: list = field(default_factory=list)
    # render.markdown.MarkdownPrinter holding answers' blocks printed during the solve, or None
    printer: object = field(default=None, repr=False, compare=False)

    @property
    def exit_status(self) -> int:
        return ExitStatus.ANSWER_ERROR if any(a.error is not None for a in self.answers) else ExitStatus.OK


def solve_context(problem: Problem, model=None, budgets=None):
    """The SolveContext of a problem's solve: its model, budgets and the LaTeX names of its
    symbols and poses (render.chain_names: the solvers write them, the model has none)."""
    from robosolve.render.chain_names import ChainNames
    from robosolve.solvers.base import SolveContext

    return SolveContext(problem, model, budgets, names=ChainNames(problem))


def check_inputs(problem: Problem) -> Problem:
    """The input mistakes only the robot's model shows (the types with `model_checked`: their
    solver's `check_input`), raised as an InputError (FILE:LINE, exit 2); the problem otherwise."""
    import importlib

    from robosolve.errors import InputError, InputIssue
    from robosolve.load.loader import path_str
    from robosolve.questions.registry import QUESTION_TYPES

    checked = [q for q in problem.questions if QUESTION_TYPES[q.type].model_checked]
    if not checked or not problem.has_robot:
        return problem
    from robosolve.model import RobotModel

    ctx = solve_context(problem, RobotModel(problem))
    issues = []
    for q in checked:
        module = importlib.import_module(QUESTION_TYPES[q.type].solver_module)
        for key, message in module.check_input(q, ctx):
            issues.append(InputIssue(problem.file, q.lines.get(key, q.line),
                                     path_str(("questions", q.index, key)), message))
    if issues:
        raise InputError(issues)
    return problem


def solve_problem(problem: Problem, budgets=None, figures=None, split: bool = False) -> Report:
    """Answer every question; `budgets` (solvers.base.Budgets) bounds the symbolic work, each
    question (`question_seconds`) and the whole file (`file_seconds`). Each answer's figures
    are handed to `figures` (robosolve.render.drawing) as soon as it is known. With `split`
    (the `solve` command, two cores or more), a forked helper solves some of the questions
    meanwhile (robosolve.run.split_solve): the same answers."""
    from robosolve.model import RobotModel
    from robosolve.solvers.base import Answer, Budgets

    budgets = budgets or Budgets()
    clock = _FileClock()
    model = RobotModel(problem) if problem.has_robot else None
    ctx = solve_context(problem, model, budgets)
    questions = problem.questions

    def answer_for(i: int):
        q = questions[i]
        left = budgets.file_seconds - clock.spent()
        if left <= 0:
            answer = Answer(q.type, q.id, error=f"not attempted: the file's budget of {budgets.file_seconds:g} s "
                                               "of CPU time is spent (a safety net)")
        else:
            answer = _solve_question(q, ctx, min(budgets.question_seconds, left))
        ctx.answers[q.id] = answer
        return answer

    if figures is not None and _may_draw(questions):
        figures.expect()
    answers: dict = {}
    printer = _EarlyMarkdown(problem, model, answers) if split else None
    helper = _question_helper(problem, model, answer_for, clock, split,
                              printer.print_in_helper if printer is not None else None)
    if not helper.indices:
        printer = None

    def add(i: int, answer) -> None:
        answers[i] = ctx.answers[questions[i].id] = answer
        if printer is not None:
            printer.adopt(i, answer)
        if figures is not None:
            figures.submit(answer.figures)

    try:
        for i in range(len(questions)):
            if i not in helper.indices:
                add(i, answer_for(i))
            for j, answer in helper.arrived().items():
                add(j, answer)
        # while the helper still solves: the Markdown of the answers known, one at a time, else
        # the next message waited for
        while helper.pending:
            idle = printer is None or not printer.print_one()
            for j, answer in helper.arrived(one=idle).items():
                add(j, answer)
    finally:
        helper.close()
    if len(answers) < len(questions):    # the helper did not send some back: solved here
        from robosolve.run.split_solve import to_solve_again

        for i in to_solve_again(questions, answers):
            add(i, answer_for(i))
    report = Report(problem, model)
    report.answers = [answers[i] for i in range(len(questions))]
    report.printer = printer.printer if printer is not None else None
    return report


class _EarlyMarkdown:
    """The Markdown blocks of the answers known so far, printed one by one while the parent
    waits for its question helper (render.markdown.MarkdownPrinter: the blocks the report then
    uses, with the figures' planned paths — printed again only for an answer whose figure
    fails)."""

    def __init__(self, problem, model, answers: dict):
        from robosolve.render.markdown import MarkdownPrinter

        self.printer = MarkdownPrinter(problem, model)
        self._answers = answers
        self._done: set = set()

    def print_in_helper(self, i: int, answer):
        """In the question helper: the answer's blocks, printed by the helper's copy of the
        printer, as `adopt` takes them."""
        from robosolve.render.results_json import planned_figures

        paths = planned_figures(answer)
        blocks = self.printer.answer_blocks(i + 1, answer, paths)
        compact = self.printer.tex.compact
        return paths, blocks, dict(compact.names), dict(compact.meaning)

    def adopt(self, i: int, answer) -> None:
        """An answer from the helper with its blocks printed there: kept as printed here."""
        printed = getattr(answer, "printed_markdown", None)
        if printed is not None:
            paths, blocks, names, meaning = printed
            self.printer.adopt(i + 1, answer, paths, blocks, names, meaning)
            self._done.add(i)

    def print_one(self) -> bool:
        """Print one answer not printed yet (question order); False when there is none."""
        from robosolve.render.results_json import planned_figures

        for i in sorted(self._answers):
            if i not in self._done:
                self._done.add(i)
                answer = self._answers[i]
                try:
                    self.printer.answer_blocks(i + 1, answer, planned_figures(answer))
                except Exception:       # printed again, with its error, when the report is
                    pass
                return True
        return False


def may_draw(problem: Problem) -> bool:
    """Whether some question of the problem may draw a figure (a drawer gets ready early)."""
    return _may_draw(problem.questions)


def _may_draw(questions) -> bool:
    from robosolve.questions.registry import QUESTION_TYPES

    return any(QUESTION_TYPES[q.type].figures for q in questions if q.type in QUESTION_TYPES)


class _FileClock:
    """CPU time spent on the file: this process's since the start, or, in a question helper
    (whose own clock starts at 0 when it is forked), the parent's until the fork plus its own."""

    def __init__(self):
        import os
        import time

        self._pid, self._start, self._before_fork = os.getpid(), time.process_time(), 0.0

    def spent(self) -> float:
        import os
        import time

        if os.getpid() == self._pid:
            return time.process_time() - self._start
        return self._before_fork + time.process_time()

    def mark_fork(self) -> None:
        self._before_fork = self.spent()


def _question_helper(problem, model, answer_for, clock, split: bool, print_markdown=None):
    """A QuestionHelper for the questions `split_solve.plan` gives it (with `split`, on two cores
    or more), else one that owns no question."""
    from robosolve.core.processes import usable_cores
    from robosolve.run.split_solve import QuestionHelper, plan

    indices = plan(problem.questions, len(problem.joints)) if split and usable_cores() >= 2 else None
    if not indices:
        return QuestionHelper()
    if model is not None:
        for frame in model.frames:      # computed once, before the fork: both processes use them
            model.M0(frame)
    clock.mark_fork()
    return QuestionHelper(indices, answer_for, print_markdown)


def _solve_question(q, ctx, seconds: float):
    """One answer, whatever happens: a SolverError, a budget past, or a bug become its error."""
    from robosolve.core.timing import time_limit
    from robosolve.solvers import solver_for
    from robosolve.solvers.base import Answer

    solve = solver_for(q.type)
    if solve is None:
        return Answer(q.type, q.id, error=f"question type '{q.type}' is not supported yet")
    try:
        with time_limit(seconds, repeat=True, what="the question") as token:
            return solve(q, ctx)
    except SolverError as exc:
        return Answer(q.type, q.id, error=str(exc))
    except SymbolicTimeout as exc:
        if exc.token is token:
            return Answer(q.type, q.id, error=f"the question exceeded its budget of {seconds:g} s of CPU "
                                              "time (a safety net; the symbolic steps have counted budgets)")
        return Answer(q.type, q.id, error=f"a symbolic step took too long ({exc})")
    except RecursionError:
        return Answer(q.type, q.id, error="the expressions are too deeply nested to handle")
    except MemoryError:
        return Answer(q.type, q.id, error="the question needs more memory than the machine has")
    except Exception as exc:  # a bug must not hide the other answers
        return Answer(q.type, q.id, error=f"internal error ({type(exc).__name__}: {exc})")


def solve_file(path) -> Report:
    return solve_problem(load_problem(path))


def render_files(report: Report, formats=("md",), figures=None, parallel: bool = False) -> dict[str, bytes]:
    """results.json, figures/*.png and the reports of `formats` (robosolve.render.formats:
    md -> report.md, html -> report.html, ipynb -> report.ipynb) as relative path -> bytes.
    The PNGs come from `figures` (robosolve.render.drawing; drawn here when None).

    results.json and the Markdown are printed before the PNGs are collected, for figures drawn
    in the background are still being drawn meanwhile; they name every figure, so they are
    printed again in the rare case one could not be drawn (its answer then carries a note).
    With `parallel` (the `solve` command on two cores or more) a forked helper prints
    results.json while this process prints the Markdown: the same texts."""
    from robosolve.render.drawing import FigureFailed, InlineFigures
    from robosolve.render.formats import FORMATS
    from robosolve.render.results_json import planned_figures

    figures = figures or InlineFigures()
    planned = {answer.id: planned_figures(answer) for answer in report.answers if answer.figures}
    texts = _texts(report, planned, parallel)
    files: dict[str, bytes] = {}
    figure_paths: dict[str, list[str]] = {}
    for answer in report.answers:
        for spec, rel in zip(answer.figures, planned.get(answer.id, [])):
            try:
                files[rel] = figures.png(spec)
            except FigureFailed as exc:  # a figure that fails must not lose the answers
                answer.note(f"figure {spec.name} could not be drawn ({exc})")
                continue
            figure_paths.setdefault(answer.id, []).append(rel)
    if figure_paths != planned:
        texts = _texts(report, figure_paths)
    results, markdown = texts
    files["results.json"] = results.encode("utf-8")
    for name in formats:
        fmt = FORMATS[name]
        files[fmt.filename] = fmt.render(report, markdown, figure_paths, files).encode("utf-8")
    return files


def _texts(report: Report, figure_paths: dict, parallel: bool = False) -> tuple[str, str]:
    """(results.json, report.md) of the report with these figures; with `parallel`, results.json
    printed by a forked helper meanwhile (robosolve.run.split_solve.TextHelper; printed here
    when no helper can be forked or it fails)."""
    from robosolve.render.markdown import render_report
    from robosolve.render.results_json import render_results_json

    if parallel and report.printer is None:     # after a split, the helper's answers come printed
        from robosolve.core.processes import usable_cores
        from robosolve.run.split_solve import TextHelper

        helper = TextHelper(lambda: render_results_json(report, figure_paths)) if usable_cores() >= 2 else None
        markdown = render_report(report, figure_paths, report.printer)
        results = helper.text() if helper is not None else None
        if results is None:
            results = render_results_json(report, figure_paths)
        return results, markdown
    return render_results_json(report, figure_paths), render_report(report, figure_paths, report.printer)


def write_outputs(report: Report, out_dir, formats=("md",), inputs=(), figures=None) -> Path:
    """Write the report as the output folder `out_dir` in the `formats` asked for (`--format`;
    robosolve.run.outputs: ownership, atomic swap).

    Raises robosolve.run.outputs.OutputFolderError, with nothing touched, when the folder is not
    robosolve's; `inputs` are the problem files read (a replaced folder must not hold them).
    """
    from robosolve.run.outputs import write_output_folder

    return write_output_folder(out_dir, render_files(report, formats, figures), inputs=inputs)


@dataclass
class FileResult:
    """One problem file solved (or only loaded): what every command reports about it, and its
    output files as bytes (relative path -> bytes; the caller writes them)."""

    file: str
    name: str | None = None
    status: int = ExitStatus.OK
    answered: int = 0
    total: int = 0
    messages: list = field(default_factory=list)
    files: dict = field(default_factory=dict)
    version: str | None = None
    warnings: list = field(default_factory=list)    # the problem's warnings, as lines (Problem.warnings)

    @classmethod
    def unreadable(cls, file, message: str) -> "FileResult":
        return cls(str(file), status=ExitStatus.INPUT, messages=[message])


def solve_loaded(problem: Problem, formats=("md",), figures=None, split: bool = False) -> FileResult:
    """The one "solve one file": solve a loaded problem, render its files, count its answers."""
    import robosolve

    report = solve_problem(problem, figures=figures, split=split)
    failed = [f"{problem.file}: {a.id}: {a.error}" for a in report.answers if a.error is not None]
    return FileResult(str(problem.file), problem.name, report.exit_status, len(report.answers) - len(failed),
                      len(report.answers), failed, render_files(report, tuple(formats), figures, parallel=split),
                      robosolve.__version__, [str(w) for w in problem.warnings])
