"""report.md: the problem's data, then each question worked out step by step.

LaTeX uses only what GitHub's math renderer supports: `$...$` inline and
`$$...$$` display blocks on their own lines, `\\left[\\begin{matrix}` matrices.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from robosolve.questions.registry import title as question_title
from robosolve.core.prose import Num, Text, name_md
from robosolve.render.chain_names import ChainNames, symbol_latex
from robosolve.render.compact import CompactTrig, display_lines
from robosolve.render.configuration import configuration_text, overrides_by_parameter
from robosolve.render.numbers import report_number, text
from robosolve.render.printers import SharedLatexPrinter



class Tex:
    """LaTeX of sympy objects and plain numbers with the problem's symbol names."""

    def __init__(self, symbol_names: dict, compact=None):
        self.names = symbol_names
        self.compact = compact          # CompactTrig: c_{1}, s_{23} for cos/sin of joints
        # LaTeX of each sympy expression once: a big entry is printed again to measure the
        # width of its matrix and to break its sum into lines (a third of a report's time)
        self._latex: dict = {}
        # the printer's names: the problem's, and the compact symbols' as they appear (the
        # printer reads this dict when it prints a symbol)
        self._printer_names = dict(symbol_names)
        self._printer = SharedLatexPrinter(self._printer_names)

    def __call__(self, v) -> str:
        if isinstance(v, sp.Basic):
            out = self._latex.get(v)
            if out is None:
                out = self._latex[v] = self._sympy(v)
            return out
        return self._sympy(v)

    def _sympy(self, v) -> str:
        if isinstance(v, str):
            return v
        if isinstance(v, (Num, Text)):
            return text(v, math=True)
        if isinstance(v, bool):
            return "\\text{true}" if v else "\\text{false}"
        if v is None:
            return "\\text{—}"
        if isinstance(v, (int, float)):
            return report_number(v)
        if isinstance(v, (list, tuple)):
            if v and all(isinstance(r, (list, tuple)) for r in v):
                rows = [" & ".join(self(x) for x in r) for r in v]
            else:
                rows = [self(x) for x in v]
            return "\\left[\\begin{matrix}" + " \\\\ ".join(rows) + "\\end{matrix}\\right]"
        if isinstance(v, dict):
            return ",\\quad ".join(f"{self(k) if not isinstance(k, str) else _text(k)} = {self(x)}"
                                   for k, x in v.items())
        if self.compact is not None:
            v = self.compact(v)
            self._printer_names.update(self.compact.names)
        return self._printer.doprint(v)


def _text(s: str) -> str:
    return "\\text{" + s.replace("_", "\\_") + "}"


def display(tex: str) -> str:
    return f"$$\n{tex}\n$$"


def render_table(header, rows) -> str:
    def cell(x):
        return text(x).replace("|", "\\|").replace("\n", " ")
    out = ["| " + " | ".join(cell(h) for h in header) + " |",
           "| " + " | ".join("---" for _ in header) + " |"]
    out += ["| " + " | ".join(cell(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def render_data(problem, model, tex: Tex, notes: bool = True, paper: bool = False) -> list[str]:
    """The data section; `notes`: with the loader's warnings under the data (not on a paper);
    `paper`: for a student, who knows the questions by their numbers and not the file's keys."""
    out = ["## Data"]
    if problem.parameters:
        rows = [(f"${tex(s)}$", "null (symbolic)" if v is None else f"${tex(v)}$")
                for s, v in problem.parameters.items()]
        header = ("symbol", "value")
        overrides = overrides_by_parameter(problem, tex, numbered=paper)
        if overrides:       # the values some questions use instead, next to the base value
            header += ("changed by a question" if paper else "changed by a question's `at`",)
            rows = [r + ("; ".join(overrides.get(s, [])) or "—",)
                    for r, s in zip(rows, problem.parameters)]
        out += ["### Parameters", render_table(header, rows)]
    if problem.joints:
        rows = []
        for j in problem.joints:
            lim = "—" if j.limits is None else f"$[{tex(j.limits[0])}, {tex(j.limits[1])}]$"
            rows.append((j.index + 1, f"${tex(j.symbol)}$", j.kind, lim, f"${tex(j.actuator)}$"))
        out += ["### Joints", render_table(("#", "variable", "type", "limits", "actuator"), rows)]
    if problem.frames and model is not None:
        rows = []
        names = ChainNames(problem)
        for name, f in problem.frames.items():
            factors = names.factors(name)
            pose = " ".join(factors) if f.kind == "pose" else (
                f"${tex(f.matrix)}$ (matrix)" if f.kind == "matrix" else f"${factors[0]}$ ({f.kind})")
            if f.kind == "pose":
                pose = f"${pose}$"
            rows.append((name_md(name), name_md(f.parent), pose))
        out += ["### Frames", "Each pose is applied in the current (moving) frame, left to right.",
                render_table(("frame", "parent", "pose in parent"), rows)]
    if problem.points and problem.has_robot:       # a problem without a robot has no point E
        rows = [(p.name, name_md(p.frame), f"${tex(list(p.at))}$" + (" (default: origin of the last frame)"
                                                              if p.implicit else ""))
                for p in problem.points.values()]
        out += ["### Points", render_table(("point", "frame", "coordinates in its frame"), rows)]
    if problem.gravity is not None and (problem.bodies or problem.gravity_given):
        out += [f"Gravity in frame 0: ${tex(list(problem.gravity))}$."]
    if problem.bodies:
        rows = []
        for b in problem.bodies:
            d = b.data
            if b.kind == "point":
                dist = f"point mass at ${tex(list(d['at']))}$"
            elif b.kind == "rod":
                dist = f"uniform rod from ${tex(list(d['from']))}$ to ${tex(list(d['to']))}$"
            elif b.kind == "com":
                dist = f"centre of mass ${tex(list(d['com']))}$, inertia ${tex(d['inertia'])}$"
            else:
                dist = f"pseudo-inertia ${tex(d['J'])}$"
            rows.append((name_md(b.name), name_md(b.frame), f"${tex(b.mass)}$", dist))
        out += ["### Bodies", render_table(("body", "frame", "mass", "distribution"), rows)]
    out += [data_note(w) for w in problem.warnings] if notes else []
    if problem.forces:
        rows = []
        for f in problem.forces:
            rows.append((name_md(f.name), name_md(f.frame), f"${tex(list(f.at))}$",
                         f"${tex(list(f.force))}$" if f.force is not None else "—",
                         f"${tex(list(f.torque))}$" if f.torque is not None else "—", name_md(f.in_frame)))
        out += ["### External forces",
                render_table(("name", "acts on frame", "at (in its frame)", "force", "torque",
                              "components in frame"), rows)]
    return out


def data_note(warning) -> str:
    """A warning of the loader (errors.InputWarning: accepted data that may be a mistake) as a
    note under the data it is about."""
    about = f"{warning.subject[0].capitalize()} {name_md(warning.subject[1])}: " if warning.subject else ""
    return f"**Note on the data** (line {warning.line} of the problem file). {about}{warning.message}."


def decimal_companion(value, tex: Tex) -> str | None:
    """Decimals of an exact numeric value that is not already a plain number (√3/2, π/6,
    atan2(…)), so that exact and numeric forms are shown together; None otherwise."""
    def numeric_leaves(v):
        if isinstance(v, sp.MatrixBase):
            return list(v)
        if isinstance(v, (list, tuple)):
            return [x for item in v for x in numeric_leaves(item)]
        return [v]

    leaves = numeric_leaves(value)
    if not leaves or not all(isinstance(x, sp.Basic) and x.is_number for x in leaves):
        return None
    if all(x.is_Rational or x.is_Float for x in leaves):
        return None

    def decimals(v):
        if isinstance(v, sp.MatrixBase):
            return [[decimals(x) for x in v.row(i)] for i in range(v.rows)] if v.cols > 1 else \
                [decimals(x) for x in v]
        if isinstance(v, (list, tuple)):
            return [decimals(x) for x in v]
        return float(sp.N(v, 17))

    try:
        return tex(decimals(value))
    except (TypeError, ValueError):         # complex or infinite: the exact form alone
        return None


def render_step(step, tex: Tex) -> list[str]:
    out = [f"#### {step.title}"]
    if step.text:
        out.append(text(step.text))
    for lhs, value in step.equations:
        intro, lines = display_lines(lhs, value, tex)
        approx = decimal_companion(value, tex)
        if intro:
            out.append(intro)
        elif approx is not None and len(lines) == 1:
            lines = [f"{lines[0]} \\approx {approx}"]
        out += [display(line) for line in lines]
    if step.table:
        header, rows = step.table
        out.append(render_table(header, rows))
    return out


def _numbers_start(steps) -> int:
    """Index of the first step that shows numbers of the question's configuration."""
    for k, step in enumerate(steps):
        title = step.title if isinstance(step.title, str) else step.title.words()
        if title.startswith("Numeric") or "configuration of the question" in (step.text or ""):
            return k
    return 0


def render_answer(index: int, answer, figure_paths: list[str], tex: Tex,
                  configuration: str | None = None) -> list[str]:
    title = question_title(answer.type)
    out = [f"## {index}. {title} — `{answer.id}`"]
    if answer.error is not None:
        out.append(f"**Not answered:** {answer.error}")
        return out
    start = _numbers_start(answer.steps) if configuration else -1
    for k, step in enumerate(answer.steps):
        if k == start:
            out.append(configuration)
        out += render_step(step, tex)
    for path in figure_paths:
        out.append(f"![{answer.id}]({path})")
    if answer.notes:
        out.append("**Notes**")
        out += [f"- {text(n)}" for n in answer.notes]
    return out


@dataclass(frozen=True)
class ReportSections:
    """report.md in its parts: the head (title, description, conventions, notation, data), each
    answer's blocks (by answer id, in report order) and the course notes; report.md is their
    blocks joined by blank lines (the notebook interleaves its code cells between them)."""

    head: list
    answers: list            # [(answer id, [block, ...])]
    notes: list

    def blocks(self) -> list:
        return self.head + [b for _, blocks in self.answers for b in blocks] + self.notes


class MarkdownPrinter:
    """The Markdown of one problem's report, answer by answer. An answer's blocks depend only on
    the answer, its section number, its figures' paths and the problem (the LaTeX printer's memo
    and the compact cᵢ, sᵢ names it records only grow, and the notation is read off the finished
    text), so they can be printed as soon as the answer is known: the split solve prints them
    while it waits for its helper (pipeline.solve_problem), and `report_sections` uses the blocks
    printed for the same answer object with the same paths."""

    def __init__(self, problem, model):
        self.problem = problem
        self.names = symbol_latex(problem) if model is not None else {}
        self.tex = Tex(self.names, CompactTrig(problem))
        self._questions = {q.id: q for q in problem.questions}
        self._printed: dict = {}         # (section, answer id, paths) -> (answer, blocks)

    def answer_blocks(self, index: int, answer, paths) -> list[str]:
        key = (index, answer.id, tuple(paths))
        hit = self._printed.get(key)
        if hit is not None and hit[0] is answer:
            return hit[1]
        q = self._questions.get(answer.id)
        config = configuration_text(q, self.problem, self.tex) if q is not None else None
        blocks = render_answer(index, answer, list(paths), self.tex, config)
        self._printed[key] = (answer, blocks)
        return blocks

    def adopt(self, index: int, answer, paths, blocks, names: dict, meaning: dict) -> None:
        """Blocks printed by another copy of this printer (a question helper's, forked from it),
        with the compact symbols that copy met: the notation then defines those it uses."""
        self._printed[(index, answer.id, tuple(paths))] = (answer, list(blocks))
        compact = self.tex.compact
        for sym, name in names.items():
            if sym not in compact.names:
                compact.names[sym] = name
                compact.meaning[sym] = meaning[sym]


def report_sections(report, figure_paths: dict, printer: MarkdownPrinter | None = None) -> ReportSections:
    """The report's parts; `printer`: one that may hold answers' blocks printed already (for the
    same problem), else a new one."""
    problem, model = report.problem, report.model
    printer = printer if printer is not None and printer.problem is problem else MarkdownPrinter(problem, model)
    names, tex = printer.names, printer.tex
    head = [f"# {name_md(problem.title or problem.name)}"]
    if problem.description:
        head.append(problem.description.strip())
    head.append(f"Problem `{problem.name}`, solved by robosolve. Conventions: ${{}}^{{i}}M_{{j}}$ is the pose "
                "of frame $j$ in frame $i$; $W$ and $H$ are expressed in frame 0; angles in radians, SI units.")
    notation_at = len(head)
    head += render_data(problem, model, tex)
    answers = []
    for i, answer in enumerate(report.answers, 1):
        answers.append((answer.id, printer.answer_blocks(i, answer, figure_paths.get(answer.id, []))))
    body = head + [b for _, blocks in answers for b in blocks]
    notes = render_course_notes(body)
    notation = tex.compact.definitions("\n".join(body + notes), names)
    if notation:                # defined once, before the data and answers that use it
        head.insert(notation_at, notation)
    return ReportSections(head, answers, notes)


def render_report(report, figure_paths: dict, printer: MarkdownPrinter | None = None) -> str:
    return "\n\n".join(report_sections(report, figure_paths, printer).blocks()) + "\n"


def render_course_notes(blocks: list[str]) -> list[str]:
    """The course notes the report links to, copied in so that the links work anywhere."""
    from robosolve.core.course_notes import NOTES, cited, note_block

    anchors = cited(blocks)
    if not anchors:
        return []
    return (["## Notes on the course summary",
             "Where the course summary is wrong or ambiguous, what this report does instead "
             "(all the notes: robosolve's docs/course-notes.md)."]
            + [note_block(NOTES[a], "####") for a in anchors])


def render_markdown_file(report, markdown: str, figure_paths, files) -> str:
    """The `md` format (robosolve.render.formats): report.md as rendered."""
    return markdown
