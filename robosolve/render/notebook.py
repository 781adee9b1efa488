"""report.ipynb: the report as a Jupyter notebook that recomputes its answers.

* Markdown cells: report.md's parts (render/markdown.py `report_sections`): the head, then each
  answer's section, then the course notes; figures stay relative links to figures/.
* Code cells, importing only sympy, numpy and matplotlib (so the notebook runs in a fresh kernel
  from any working directory): first the runtime, the source of
  robosolve/render/notebook_runtime.py copied in (`inspect.getsource`); then the data cell,
  `robot = Robot(...)` with the problem's values as text, so that a reader can change a number
  and re-run; then after each answer's section the cell of its type (its type module's `notebook_cells`, questions/<type>.py),
  which recomputes the answer from the data and prints it beside robosolve's numbers (held in the
  cell as literals: no cell reads a file). A type or option layout without a builder gets a cell
  that prints robosolve's numbers and says so.
* Every string of the problem file reaches the code as a Python literal (repr), never as code.
* Cell ids are deterministic (`md-003`, `code-004`): the same problem gives the same bytes.
"""

from __future__ import annotations

import inspect

import sympy as sp

from robosolve.core.chain import forward, numpy_algebra
from robosolve.questions.notebook_code import literal, text
from robosolve.questions.registry import QUESTION_TYPES
from robosolve.render import notebook_runtime


def runtime_source() -> str:
    """The runtime cell: robosolve's numeric chain computation (core/chain/forward.py and
    core/chain/numpy_algebra.py: numpy only), then notebook_runtime.py without its two imports of them."""
    runtime = "".join(line for line in inspect.getsource(notebook_runtime).splitlines(keepends=True)
                      if not line.startswith("from robosolve."))
    parts = [inspect.getsource(forward).rstrip("\n"), inspect.getsource(numpy_algebra).rstrip("\n"),
             runtime.rstrip("\n")]
    return ("# The notebook's runtime (robosolve/render/notebook_runtime.py, after robosolve's chain\n"
            "# computation core/chain/forward.py and core/chain/numpy_algebra.py, copied in): sympy, numpy and\n"
            "# matplotlib only.\n" + "\n\n\n".join(parts))


def _pose(frame) -> list | tuple:
    if frame.kind == "pose":
        return [[op, text(arg)] for op, arg in frame.factors]
    if frame.kind in ("dh", "mdh"):
        return (frame.kind, [text(x) for x in frame.factors])
    return ("matrix", sp.Matrix(frame.matrix))


def _pseudo_inertia(body) -> sp.Matrix:
    """The body's pseudo-inertia J in its own frame (the course's 4x4 matrix of moments)."""
    from robosolve.core import matrices as mx

    d = body.data
    if body.kind == "point":
        return sp.Matrix(mx.pseudo_inertia_point(body.mass, d["at"]))
    if body.kind == "rod":
        return sp.Matrix(mx.pseudo_inertia_rod(body.mass, d["from"], d["to"]))
    if body.kind == "com":
        return sp.Matrix(mx.pseudo_inertia_from_com(body.mass, d["com"], d["inertia"]))
    return sp.Matrix(d["J"])


def _vector(v) -> list | None:
    return None if v is None else [text(x) for x in v]


def data_cell(problem) -> str:
    """`robot = Robot(...)`: the problem's data, every value a text expression."""
    parameters = {s.name: (None if v is None else text(v)) for s, v in problem.parameters.items()}
    joints = [[j.name, j.kind, str(j.actuator)] for j in problem.joints]
    items = [
        ("parameters", "{name: value; None: not given}", parameters),
        ("joints", "[name, kind, actuator]", joints),
        ("frames", "{frame: (parent, pose in the parent)}",
         {f.name: (f.parent, _pose(f)) for f in problem.frames.values()}),
        ("points", "{point: (frame, coordinates in that frame)}",
         {p.name: (p.frame, _vector(p.at)) for p in problem.points.values()} if problem.frames else {}),
        ("gravity", "in frame 0", _vector(problem.gravity)),
        ("bodies", "{body: (frame, pseudo-inertia J in that frame)}",
         {b.name: (b.frame, _pseudo_inertia(b)) for b in problem.bodies}),
        ("forces", "{force: (frame, point, force, torque, frame of the components)}",
         {f.name: (f.frame, _vector(f.at), _vector(f.force), _vector(f.torque), f.in_frame)
          for f in getattr(problem, "forces", None) or []}),
    ]
    lines = ["# The problem's data: change a value and re-run the notebook (robosolve's numbers,",
             "# printed beside the recomputed ones, hold for the data as given).",
             "robot = Robot("]
    for key, comment, value in items:
        lines.append(f"    # {key}: {comment}")
        lines.append(f"    {key}={_wrapped(value)},")
    lines.append(")")
    return "\n".join(lines)


def _wrapped(value) -> str:
    """A mapping or list literal with one entry a line when it is long."""
    flat = literal(value)
    if len(flat) <= 90 or not isinstance(value, (dict, list)) or not value:
        return flat
    if isinstance(value, dict):
        entries = [f"{literal(k)}: {literal(v)}" for k, v in value.items()]
        return "{\n" + "".join(f"        {e},\n" for e in entries) + "    }"
    return "[\n" + "".join(f"        {literal(v)},\n" for v in value) + "    ]"


def fallback_cell(answer) -> str:
    """robosolve's numbers of an answer the notebook does not recompute."""
    if answer.error is not None:                 # nothing to recompute: why, in robosolve's words
        return "\n".join([f"# `{answer.id}` is not answered", f"print({literal('robosolve: ' + answer.error)})"])
    return "\n".join([
        f"# `{answer.id}` is not recomputed by this notebook: robosolve's numbers (they hold for the data as given)",
        "robosolve = " + literal(answer.numeric),
        "print(robosolve)",
    ])


def question_cell(question, answer, problem) -> str:
    """The code cell after an answer's section: its type's builder, or robosolve's numbers."""
    qt = QUESTION_TYPES.get(answer.type)
    make = qt.notebook_cells if qt is not None else None
    code = None
    if answer.error is None and question is not None and make is not None:
        try:
            code = make(question, answer, problem)
        except (KeyError, TypeError, ValueError, AttributeError):
            code = None      # an option layout the builder cannot rebuild (tests: every bundled
            #                 question gets its recomputing cell)
    return code if code is not None else fallback_cell(answer)


def code_cells(problem, answers) -> list[str]:
    """The notebook's code cells: the runtime, the data, then one per answer (in report order)."""
    questions = {q.id: q for q in problem.questions}
    return [runtime_source(), data_cell(problem)] + [question_cell(questions.get(a.id), a, problem)
                                                     for a in answers]


def build_notebook(report, figure_paths=None):
    import nbformat
    from nbformat import v4

    from robosolve.render.markdown import report_sections

    problem = report.problem
    cells = []

    def add(kind: str, source: str):
        cell = v4.new_markdown_cell(source) if kind == "md" else v4.new_code_cell(source)
        cell["id"] = f"{kind}-{len(cells) + 1:03d}"
        cells.append(cell)

    sections = report_sections(report, figure_paths or {})
    runtime, data, *per_answer = code_cells(problem, report.answers)
    add("md", "\n\n".join(sections.head))
    add("code", runtime)
    add("code", data)
    for (_, blocks), code in zip(sections.answers, per_answer):
        add("md", "\n\n".join(blocks))
        add("code", code)
    if sections.notes:
        add("md", "\n\n".join(sections.notes))
    nb = v4.new_notebook(cells=cells, metadata={
        "kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"},
        "language_info": {"name": "python"},
        "robosolve": {"problem": problem.name}})
    nb.nbformat, nb.nbformat_minor = 4, 5
    nbformat.validate(nb)
    return nb


def render_notebook_file(report, markdown: str, figure_paths, files) -> str:
    """The `ipynb` format (robosolve.render.formats)."""
    import nbformat

    return nbformat.writes(build_notebook(report, figure_paths)) + "\n"
