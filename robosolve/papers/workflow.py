"""The files of a paper: paper.md, answers.yaml, figures/robot.png, paper.html (papers.md).

`paper_files` is what `robosolve paper` writes and what every variant's task adds to its
folder (execution.solve_task), with or without solving: nothing in it comes from a solution.
`papers_html` joins the variants' paper.html into one page per student for printing.
"""

from __future__ import annotations

import os
from pathlib import Path


PAPER_FORMATS = ("md", "html")


def paper_files(problem, problem_path: str, student: str = "", variant: str | None = None,
                formats=("md",)) -> dict[str, bytes]:
    """relative path -> bytes of the paper of `problem` (already loaded and valid)."""
    from robosolve.model.chain import RobotModel
    from robosolve.papers.drawing import paper_figure
    from robosolve.papers.paper import FIGURE, render_paper
    from robosolve.papers.template import render_template
    from robosolve.render.drawing import InlineFigures

    model = RobotModel(problem) if problem.has_robot else None
    files: dict[str, bytes] = {}
    spec = paper_figure(problem, model)
    if spec is not None:
        files[FIGURE] = InlineFigures().png(spec)
    markdown = render_paper(problem, model, student or None, variant, figure=spec is not None)
    files["paper.md"] = markdown.encode("utf-8")
    files["answers.yaml"] = render_template(problem, problem_path, student, variant).encode("utf-8")
    if "html" in formats:
        from robosolve.papers.html import render_paper_html

        boxed = render_paper(problem, model, student or None, variant, figure=spec is not None, boxes=True)
        files["paper.html"] = render_paper_html(boxed, problem, model, files).encode("utf-8")
    return files


def parse_paper_formats(text: str | None) -> tuple:
    """--format of `robosolve paper`: md (always written) and html."""
    if text is None:
        return ("md",)
    names = [t.strip().lower() for t in text.split(",") if t.strip()]
    for n in names:
        if n not in PAPER_FORMATS:
            from robosolve.load.expressions import did_you_mean

            raise ValueError(f"--format: unknown paper format '{n}'" + did_you_mean(n, PAPER_FORMATS)
                             + f"; choose from {', '.join(PAPER_FORMATS)}")
    if "html" in names:
        import importlib.util

        if importlib.util.find_spec("latex2mathml") is None:
            raise ValueError("--format html needs the optional package latex2mathml: "
                             "pip install 'robosolve[html]'")
    return tuple(dict.fromkeys(["md"] + names))


def default_folder(problem) -> Path:
    return Path("out") / f"{problem.name}-paper"


def write_paper(problem_file: Path, out: str | None, formats: tuple, student: str | None):
    """`robosolve paper`: load the problem, check DIR, write the paper's folder (atomic).
    Returns (problem, DIR); raises InputError or OutputFolderError (exit 2) with nothing written."""
    from robosolve.load.loader import load_problem
    from robosolve.run.outputs import check_output_folder, write_output_folder

    problem = load_problem(problem_file)
    target = Path(out) if out is not None else default_folder(problem)
    check_output_folder(target, inputs=[problem_file])
    rel = os.path.relpath(os.path.abspath(problem_file), os.path.abspath(target))
    files = paper_files(problem, Path(rel).as_posix(), student or "", None, formats)
    write_output_folder(target, dict(sorted(files.items())), inputs=[problem_file])
    return problem, target


def papers_html(pages: list[tuple[str, bytes]], title: str) -> bytes:
    """One printable page per paper: the bodies of the variants' paper.html, in order."""
    from robosolve.papers.html import join_papers

    return join_papers([(name, data.decode("utf-8")) for name, data in pages], title).encode("utf-8")
