"""The data every numeric answer comes from: a question's `at`, in the course's notation.

Done once here from the question rather than in every solver: the joint values
(q), rates (q̇) and accelerations (q̈) of the configuration, and the parameter
overrides next to the values of the data section.
"""

from __future__ import annotations

import sympy as sp

from robosolve.render.numbers import report_number


def _value(v, tex, values=None) -> str:
    """Exact value, followed by its decimal when the exact form is not already a decimal; a
    value written with parameters (`q1a`, as variants.md varies a configuration) also shows
    the exact value they give (`q_{1a} = \\frac{\\pi}{2} \\approx 1.5708`)."""
    v = sp.sympify(v)
    exact = tex(v)
    if not v.is_number and values:
        resolved = resolve(v, values)
        if resolved.is_number and resolved != v:
            return f"{exact} = {_value(resolved, tex)}"
    if v.is_Integer or v.is_Float or not v.is_number:
        return exact
    try:
        return f"{exact} \\approx {report_number(float(v))}"
    except TypeError:       # complex or not evaluable: the exact form alone
        return exact


def resolve(v, values: dict):
    """`v` with the parameters' values (which may name other parameters) put in, exactly."""
    for _ in range(len(values) + 1):
        nxt = v.xreplace(values)
        if nxt == v:
            break
        v = nxt
    return v


def _known_values(question, problem) -> dict:
    """The parameters' values with the question's own overrides: symbol -> exact value."""
    at = question.at or {}
    out = {s: e for s, e in problem.parameters.items() if e is not None}
    out.update({s: at[s] for s in problem.parameters if s in at and at[s] is not None})
    return out


def split_at(question, problem) -> tuple[list, list, list, list]:
    """(joint values, rates, accelerations, parameter overrides) of `at`, in joint order."""
    at = question.at or {}
    q = [(j.symbol, at[j.symbol]) for j in problem.joints if j.symbol in at]
    qd = [(j.dot, at[j.dot]) for j in problem.joints if j.dot in at]
    qdd = [(j.ddot, at[j.ddot]) for j in problem.joints if j.ddot in at]
    params = [(s, at[s]) for s in problem.parameters if s in at]
    return q, qd, qdd, params


def configuration_text(question, problem, tex) -> str | None:
    """One paragraph stating the configuration and the overrides, or None without `at`."""
    q, qd, qdd, params = split_at(question, problem)
    if not (q or qd or qdd or params):
        return None
    known = _known_values(question, problem)

    def listing(pairs):
        return ", ".join(f"${tex(s)} = {_value(v, tex, known)}$" for s, v in pairs)

    parts = []
    if q:
        parts.append("joints " + listing(q))
    if qd:
        parts.append("rates " + listing(qd))
    if qdd:
        parts.append("accelerations " + listing(qdd))
    text = "**Configuration of the numbers.** " + ("; ".join(parts) + "." if parts else "")
    if params:
        base = problem.parameters
        over = ", ".join(
            f"${tex(s)} = {_value(v, tex)}$ (data: "
            + ("null" if base[s] is None else f"${tex(base[s])}$") + ")"
            for s, v in params)
        text += (" " if parts else "") + f"Parameters changed for this question: {over}; " \
                                         "the others as in the data section."
    elif parts:
        text += " Parameters as in the data section."
    return text


def overrides_by_parameter(problem, tex, numbered: bool = False) -> dict:
    """Parameter symbol -> "value in `id`" strings of the questions that override it ("value in
    question 3" when `numbered`: a paper, whose reader knows the questions by their numbers)."""
    out: dict = {}
    for k, question in enumerate(problem.questions, 1):
        where = f"question {k}" if numbered else f"`{question.id}`"
        for s, v in split_at(question, problem)[3]:
            out.setdefault(s, []).append(f"${_value(v, tex)}$ in {where}")
    return out
