"""load -> model -> solve -> render, as library functions (the CLI is a thin layer).

`solve_file` returns a `Report` and writes nothing; `render_files` turns it into
bytes (relative path -> content) and `write_outputs` hands them to
`robosolve.outputs.write_output_folder`, the only writer of output folders (ownership
mark, atomic swap, umask, interrupts held back while it writes).
"""

from __future__ import annotations

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


def solve_problem(problem: Problem, budgets=None) -> Report:
    """Answer every question; `budgets` (solvers.base.Budgets) bounds the symbolic work."""
    from robosolve.model import RobotModel
    from robosolve.solvers import solver_for
    from robosolve.solvers.base import Answer, SolveContext

    model = RobotModel(problem) if problem.has_robot else None
    ctx = SolveContext(problem, model, budgets)
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


def render_files(report: Report) -> dict[str, bytes]:
    """report.md, results.json and figures/*.png as a mapping relative path -> bytes."""
    import io

    from robosolve.render.markdown import render_report
    from robosolve.render.results_json import render_results_json

    files: dict[str, bytes] = {}
    figure_paths: dict[str, list[str]] = {}
    for answer in report.answers:
        for spec in answer.figures:
            rel = f"figures/{answer.id}-{spec.name}.png"
            try:
                from robosolve.render.plots import draw

                buffer = io.BytesIO()
                draw(spec, buffer)
            except Exception as exc:  # a figure that fails must not lose the answers
                answer.note(f"figure {spec.name} could not be drawn ({type(exc).__name__}: {exc})")
                continue
            files[rel] = buffer.getvalue()
            figure_paths.setdefault(answer.id, []).append(rel)
    files["results.json"] = render_results_json(report, figure_paths).encode("utf-8")
    files["report.md"] = render_report(report, figure_paths).encode("utf-8")
    return files


def write_outputs(report: Report, out_dir, inputs=()) -> Path:
    """Write the report as the output folder `out_dir` (robosolve.outputs: ownership, atomic swap).

    Raises robosolve.outputs.OutputFolderError, with nothing touched, when the folder is not
    robosolve's; `inputs` are the problem files read (a replaced folder must not hold them).
    """
    from robosolve.outputs import write_output_folder

    return write_output_folder(out_dir, render_files(report), inputs=inputs)
