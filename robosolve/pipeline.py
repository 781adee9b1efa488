"""load -> model -> solve -> render, as library functions (the CLI is a thin layer).

`solve_file` returns a `Report` and writes nothing; `write_outputs` is the only
writer, and it writes into a temporary folder that replaces the target at the
end, so a run never leaves half-written outputs.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from robosolve.errors import EXIT_ANSWER_ERROR, EXIT_OK, SolverError, SymbolicTimeout
from robosolve.load.loader import load_problem
from robosolve.load.problem import Problem


@dataclass
class Report:
    problem: Problem
    model: object
    answers: list = field(default_factory=list)

    @property
    def exit_status(self) -> int:
        return EXIT_ANSWER_ERROR if any(a.error is not None for a in self.answers) else EXIT_OK


def solve_problem(problem: Problem) -> Report:
    from robosolve.model import RobotModel
    from robosolve.solvers import solver_for
    from robosolve.solvers.base import Answer, SolveContext

    model = RobotModel(problem) if problem.has_robot else None
    ctx = SolveContext(problem, model)
    report = Report(problem, model)
    for q in problem.questions:
        solve = solver_for(q.type)
        if solve is None:
            answer = Answer(q.type, q.id, error=f"question type '{q.type}' is not supported yet")
        else:
            try:
                answer = solve(q, ctx)
            except SolverError as exc:
                answer = Answer(q.type, q.id, error=str(exc))
            except SymbolicTimeout as exc:
                answer = Answer(q.type, q.id, error=f"a symbolic step took too long ({exc})")
            except RecursionError:
                answer = Answer(q.type, q.id, error="the expressions are too deeply nested to handle")
            except Exception as exc:  # a bug must not hide the other answers
                answer = Answer(q.type, q.id, error=f"internal error ({type(exc).__name__}: {exc})")
        ctx.answers[q.id] = answer
        report.answers.append(answer)
    return report


def solve_file(path) -> Report:
    return solve_problem(load_problem(path))


def render_outputs(report: Report, folder: Path, formats=("md",)) -> None:
    """Write results.json, figures/ and the reports of `formats` (robosolve.render.formats:
    md, html, ipynb) into an existing empty folder."""
    from robosolve.render.formats import FORMATS
    from robosolve.render.markdown import render_report
    from robosolve.render.results_json import render_results_json

    figure_paths: dict[str, list[str]] = {}
    for answer in report.answers:
        for spec in answer.figures:
            rel = f"figures/{answer.id}-{spec.name}.png"
            (folder / "figures").mkdir(exist_ok=True)
            try:
                from robosolve.render.plots import draw

                draw(spec, folder / rel)
            except Exception as exc:  # a figure that fails must not lose the answers
                answer.note(f"figure {spec.name} could not be drawn ({type(exc).__name__}: {exc})")
                continue
            figure_paths.setdefault(answer.id, []).append(rel)
    (folder / "results.json").write_text(render_results_json(report, figure_paths), encoding="utf-8")
    markdown = render_report(report, figure_paths)
    for name in formats:
        fmt = FORMATS[name]
        (folder / fmt.filename).write_text(fmt.render(report, markdown, figure_paths, folder),
                                           encoding="utf-8")


def write_outputs(report: Report, out_dir, formats=("md",)) -> Path:
    """Render into a temporary sibling folder, then replace `out_dir` with it."""
    out_dir = Path(out_dir)
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.", dir=out_dir.parent))
    try:
        render_outputs(report, tmp, formats)
        if out_dir.exists():
            old = out_dir.with_name(f".{out_dir.name}.old-{os.getpid()}")
            out_dir.rename(old)
            tmp.rename(out_dir)
            shutil.rmtree(old, ignore_errors=True)
        else:
            tmp.rename(out_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return out_dir
