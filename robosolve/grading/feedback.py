"""The feedback page a student reads (grading.md "Grading a class": feedback pages).

DIR/feedback/<student>.md shows, for every key: the question's number and statement (the
type's `statement` when it has one, else its title and what it is asked about), the
verdict, what the student gave (as read), the diagnosis sentence, the expected value
(left out with `--no-expected`) and the marks earned; with `--variants`, a relative link to
the student's worked solution (`…/<variant>/report.md`).
"""

from __future__ import annotations

from robosolve.grading.record import number_text, percent_text

NOT_READ = "the answers file could not be read"


def statement_text(question, problem) -> str:
    """The question as the paper states it, or its title and options."""
    from robosolve.questions.registry import question_type

    qt = question_type(question.type)
    if problem is not None:
        text = _paper_statement(question, problem)
        if text:
            return text
    parts = [f"{_name(k)} = {_value(v)}" for k, v in question.options.items()]
    if question.at:
        parts.append("at " + ", ".join(f"{_name(k)} = {_value(v)}" for k, v in question.at.items()))
    return qt.title + (" (" + "; ".join(parts) + ")" if parts else "") + "."


def _paper_statement(question, problem) -> str:
    """The statement the paper prints (the teacher's `text`, else the type's own)."""
    from robosolve.papers.paper import Say, statement
    from robosolve.render.chain_names import symbol_latex
    from robosolve.render.markdown import Tex

    try:
        # the problem's LaTeX names, as the paper's: sympy's own print q1_dot as q_{1 dot}
        return statement(question, Say(problem, Tex(symbol_latex(problem))))
    except Exception:  # noqa: BLE001 - a statement bug must not lose the feedback page
        return ""


def _name(k) -> str:
    return getattr(k, "name", None) or str(k)


def _value(v) -> str:
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_name(k)}: {_value(x)}" for k, x in v.items()) + "}"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    return str(v)


def _code(text: str) -> str:
    """Inline code that survives backticks in the text."""
    fence = "``" if "`" in text else "`"
    return f"{fence}{text}{fence}" if text else "—"


def page(result, questions: dict, problem=None, link: str = "", reason: str = "",
         show_expected: bool = True) -> str:
    """Markdown of one submission; `questions`: id -> Question (None when unknown)."""
    lines = [f"# Feedback for {result.student}", ""]
    if result.problem:
        lines.append(f"Problem `{result.problem}`: **{number_text(result.score)} / "
                     f"{number_text(result.max_score)}** ({percent_text(result.score, result.max_score)} %)")
        lines.append("")
    if link:
        lines += [f"Your worked solution: [report.md]({link})", ""]
    if result.note:
        lines += [f"Note: this submission {result.note}.", ""]
    if result.error:
        if reason and reason != NOT_READ:
            lines += [f"No answer was graded: {reason}" + ("" if reason.endswith((".", "?")) else "."), ""]
        else:
            lines += ["The answers file could not be read, so no answer was graded:", "", "```",
                      result.error, "```", ""]
    if result.notes:
        lines += ["These answers could not be graded:", ""] + [f"- {n}" for n in result.notes] + [""]
    for number, q in enumerate(result.questions, start=1):
        lines += _question(number, q, questions.get(q.id), problem, show_expected, bool(result.error))
    return "\n".join(lines).rstrip("\n") + "\n"


def _question(number, q, question, problem, show_expected: bool, unread: bool) -> list:
    lines = [f"## {number}. {q.id}", ""]
    if question is not None:
        lines += [statement_text(question, problem), ""]
    if q.no_reference:
        lines += ["Not graded: robosolve could not answer this question.", ""]
    else:
        lines += [f"Score: {number_text(q.score)} / {number_text(q.max_score)}.", ""]
    if unread:
        return lines
    for key, r in q.keys.items():
        graded = key in q.graded
        verdict = r.verdict + (f" ({r.diagnosis})" if r.diagnosis else "")
        lines.append(f"### `{key}`: {verdict}" + ("" if graded else " (not graded)"))
        lines.append("")
        if r.given:
            lines.append(f"- You gave: {_code(r.given)}")
        what = r.hidden if r.hidden is not None else r.feedback      # never the expected value
        if what and r.verdict != "correct":
            lines.append(f"- What is wrong: {_escape(what)}")
        if r.expected and show_expected and r.verdict != "correct":
            lines.append(f"- Expected: {_code(r.expected)}")
        if graded and not q.no_reference:
            lines.append(f"- Marks: {number_text(q.share * r.earned)} of {number_text(q.share)}"
                         + (" (partial credit)" if r.verdict != "correct" and r.earned else ""))
        lines.append("")
    return lines


def _escape(text: str) -> str:
    """Markdown text: `*` and `_` escaped (L1*cos(theta1)*L2 must not turn italic)."""
    return text.replace("\\", "\\\\").replace("*", "\\*").replace("_", "\\_").replace("\n", " ")
