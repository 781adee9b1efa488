"""paper.md: the question sheet of one student (papers.md "The paper").

Header, conventions, the drawing, the data tables of the report (everything given, nothing
computed), then every question: its statement (the question's `text`, else the statement its
type writes, `QuestionType.statement`) and what to give for each graded key. Nothing here
reads a solution: a paper is the same bytes whether or not the problem was solved.
"""

from __future__ import annotations

import re

import sympy as sp

from robosolve.core.prose import name_md
from robosolve.load.paper import PLACEHOLDER
from robosolve.papers.keys import graded_keys
from robosolve.papers.template import form_text, key_unit, layout_text, marks_text
from robosolve.questions.registry import question_type, title as question_title
from robosolve.render.chain_names import symbol_latex
from robosolve.render.configuration import _known_values, _value, split_at
from robosolve.render.markdown import Tex, render_data

FIGURE = "figures/robot.png"


class Say:
    """What a type's `statement(question, say)` writes with: the problem's notation, values
    exact and in decimals, configurations, coordinates, references to other questions."""

    def __init__(self, problem, tex: Tex):
        self.problem = problem
        self.tex = tex
        self.numbers = {q.id: i for i, q in enumerate(problem.questions, 1)}
        # a value written with parameters (`at: {theta1: q1a}`, as variants vary a configuration)
        # is told with the exact value they give, as in the report: q1a = π/6 ≈ 0.523599
        self.known = {s: e for s, e in problem.parameters.items() if e is not None}

    def math(self, v) -> str:
        """`$…$` of an expression, a list (a vector) or a matrix."""
        if isinstance(v, sp.MatrixBase):
            v = v.tolist() if v.cols > 1 else list(v)
        return f"${self.tex(v)}$"

    def value(self, v) -> str:
        """An exact value with its decimals when it is not already a decimal: $π/6 ≈ 0.5236$."""
        return f"${_value(v, self.tex, self.known)}$"

    def equals(self, lhs, rhs, rate: bool = False) -> str:
        """'$E_{x} = \\frac{\\pi}{6} \\approx 0.5236$': a left side (its rate, with a dot) and its exact
        value with decimals."""
        left = f"\\dot{{{self.tex(lhs)}}}" if rate else self.tex(lhs)
        return f"${left} = {_value(rhs, self.tex, self.known)}$"

    def joint_values(self, mapping: dict) -> str:
        """{joint name: value} -> '$θ₁ = π/6 ≈ 0.523599$, $θ₂ = 0$'."""
        by_name = {j.name: j for j in self.problem.joints}
        names = {j.name: j.symbol for j in self.problem.joints}
        names.update({j.dot.name: j.dot for j in self.problem.joints})
        names.update({str(j.actuator): j.actuator for j in self.problem.joints})
        out = []
        for name, v in mapping.items():
            sym = names.get(name) or (by_name[name].symbol if name in by_name else sp.Symbol(name))
            out.append(f"${self.tex(sym)} = {_value(v, self.tex, self.known)}$")
        return ", ".join(out)

    def per_joint(self, mapping: dict, unit: str = "") -> str:
        """{joint name: value} of a limit or a gain -> '$θ₁$: $2$ rad/s², $θ₂$: $3$ rad/s²';
        `unit` "joint/s²" etc. is told by each joint's kind (rad or m)."""
        by_name = {j.name: j for j in self.problem.joints}
        out = []
        for name, v in mapping.items():
            j = by_name.get(name)
            sym = j.symbol if j is not None else sp.Symbol(name)
            u = unit
            if unit.startswith("joint"):
                u = ("rad" if j is None or j.is_revolute else "m") + unit[len("joint"):]
            out.append(f"${self.tex(sym)}$: ${_value(v, self.tex, self.known)}$" + (f" {u}" if u else ""))
        return ", ".join(out)

    def at(self, question) -> str:
        """'at θ₁ = …, θ₂ = … (rates …; accelerations …), with L₁ = … instead of the data's …'
        ('' without `at`)."""
        q, qd, qdd, params = split_at(question, self.problem)
        known = _known_values(question, self.problem)

        def listing(pairs):
            return ", ".join(f"${self.tex(s)} = {_value(v, self.tex, known)}$" for s, v in pairs)

        parts = []
        if q:
            parts.append("at " + listing(q))
        if qd:
            parts.append("with the rates " + listing(qd))
        if qdd:
            parts.append("the accelerations " + listing(qdd))
        if params:
            parts.append("with " + listing(params) + " instead of the data's value"
                         + ("s" if len(params) > 1 else ""))
        return ", ".join(parts)

    def coordinates(self, coords) -> str:
        return "(" + ", ".join(self.math(c) for c in coords) + ")"

    def question_number(self, qid: str) -> str:
        return f"question {self.numbers.get(qid, qid)}"

    def point(self, question) -> str:
        return f"point {question.point}"

    def frame(self, question) -> str:
        return f"frame {name_md(question.frame)}"

    def joints(self, joints=None) -> str:
        """The joints' symbols (`joints`: some of them, default every one)."""
        return ", ".join(f"${self.tex(j.symbol)}$" for j in (self.problem.joints if joints is None else joints))

    def asked(self, question) -> list[str]:
        """The graded keys of `question` (dotted paths, in grading order): what its statement
        asks for (questions/wording.py)."""
        return [gk.key for gk in graded_keys(question, self.problem)]


def teacher_text(question, say: Say) -> str:
    """A question's `text` with `{name}` the parameter's value (as in the data table), `{at}`
    its configuration, `{{`/`}}` braces."""
    params = {s.name: (s, v) for s, v in say.problem.parameters.items()}

    def sub(m):
        token = m.group(0)
        if token in ("{{", "}}"):
            return token[0]
        name = (m.group(1) or "").strip()
        if name == "at":
            # '{at}' reads 'at θ₁ = …'; a teacher who wrote 'at {at}' gets one 'at', and a
            # question without a configuration is about any (its answers symbolic in the joints)
            words = say.at(question) or "at any configuration (the joint variables as symbols)"
            before = m.string[:m.start()]
            if words.startswith("at ") and re.search(r"\bat\s*$", before):
                words = words[3:]
            return words
        s, v = params[name]
        return "null (symbolic)" if v is None else f"${say.tex(v)}$"

    return PLACEHOLDER.sub(sub, question.text)


def statement(question, say: Say) -> str:
    if question.text:
        return teacher_text(question, say)
    qt = question_type(question.type)
    if qt.statement is not None:
        return qt.statement(question, say)
    return f"{qt.title}{' ' + say.at(question) if say.at(question) else ''}."


def box_marker(question_index: int, key_index: int) -> str:
    """Where paper.html puts the answer box of a key (papers/html.py replaces it)."""
    return f"RSBOX{question_index}N{key_index}X"


def what_to_give(question, problem, boxes: bool = False) -> list[str]:
    out = []
    for k, gk in enumerate(graded_keys(question, problem)):
        ak = gk.answer_key
        unit = key_unit(ak, question, problem, gk.parent)
        out.append(f"- `{gk.key}`: {gk.doc}; {layout_text(ak, question, problem)}; {form_text(ak)}"
                   + (f"; {unit}" if unit else "") + "."
                   + (" " + box_marker(question.index, k) if boxes else ""))
    return out


def total_marks(problem) -> str:
    total = sum((sp.sympify(q.marks) for q in problem.questions if graded_keys(q, problem)), sp.Integer(0))
    return marks_text(total)


def header(problem, student: str | None, variant: str | None) -> list[str]:
    out = [f"# {name_md(problem.title or problem.name)}"]
    who = f"**Student:** {name_md(student)}" if student else "**Name:** ________________  **ID:** ________"
    lines = [who]
    if variant:
        lines.append(f"**Variant:** `{variant}`")
    lines.append(f"**Total:** {total_marks(problem)}")
    out.append("  \n".join(lines))
    return out


def gravity_sentence(g) -> str:
    """'Gravity points along −z₀ (the data's gravity vector).' for an axis-aligned gravity."""
    parts = [(i, e) for i, e in enumerate(g) if e != 0]
    if len(parts) == 1:
        i, e = parts[0]
        sign = e.could_extract_minus_sign() if hasattr(e, "could_extract_minus_sign") else e < 0
        return f"Gravity points along {'−' if sign else '+'}{'xyz'[i]}₀ (the gravity of the data)."
    return "Gravity is the vector of the data, in frame 0."


def dh_sentence(problem) -> str:
    """What DH(…) and MDH(…) of the frames table mean, when the table uses them."""
    kinds = {f.kind for f in problem.frames.values()}
    out = []
    if "dh" in kinds:
        out.append("$DH(\\theta, d, a, \\alpha) = R_z(\\theta)\\,T_z(d)\\,T_x(a)\\,R_x(\\alpha)$ "
                   "(standard Denavit–Hartenberg)")
    if "mdh" in kinds:
        out.append("$MDH(\\alpha, a, \\theta, d) = R_x(\\alpha)\\,T_x(a)\\,R_z(\\theta)\\,T_z(d)$ "
                   "(modified Denavit–Hartenberg)")
    return (" In the frames table, " + " and ".join(out) + ".") if out else ""


def conventions(problem) -> str:
    gravity = ""
    if problem.gravity is not None and (problem.bodies or problem.gravity_given):
        gravity = " " + gravity_sentence(problem.gravity)
    return ("**Conventions.** ${}^{i}M_{j}$ is the pose of frame $j$ in frame $i$ (4×4); angles are in "
            "radians and every quantity in SI units (m, kg, s, N, N·m)." + dh_sentence(problem) + gravity
            + " Give each answer in the layout of the answers file (answers.yaml): matrices as lists "
            "of rows, one value per joint in joint order; a value is a number or an expression in "
            "the problem's names.")


def render_paper(problem, model, student: str | None = None, variant: str | None = None,
                 figure: bool = True, boxes: bool = False) -> str:
    """paper.md of `problem` (`model`: its RobotModel, for the frames table, or None);
    `boxes`: with the markers of paper.html's answer boxes."""
    names = symbol_latex(problem) if model is not None else {}
    tex = Tex(names)
    say = Say(problem, tex)
    out = header(problem, student, variant)
    if problem.description:
        out.append(problem.description.strip())
    out.append(conventions(problem))
    if figure:
        out.append(f"![The robot at its reference configuration]({FIGURE})")
    data = render_data(problem, model, tex, notes=False, paper=True)
    out += data if len(data) > 1 else []          # no empty Data heading (a problem without a robot)
    out.append("## Questions")
    for i, q in enumerate(problem.questions, 1):
        out.append(f"### {i}. {question_title(q.type)} ({marks_text(q.marks)})")
        out.append(statement(q, say))
        give = what_to_give(q, problem, boxes)
        if give:
            out.append("**What to give** (answers file, question `" + q.id + "`):\n\n" + "\n".join(give))
    return "\n\n".join(out) + "\n"
