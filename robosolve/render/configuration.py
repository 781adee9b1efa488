"""The data every numeric answer comes from: a question's `at`, in the course's notation.

Done once here from the question rather than in every solver: the joint values
(q), rates (q̇) and accelerations (q̈) of the configuration, and the parameter
overrides next to the values of the data section.
"""

from __future__ import annotations

import sympy as sp

from robosolve.render.numbers import report_number


def _value(v, tex) -> str:
    """Exact value, followed by its decimal when the exact form is not already a decimal."""
    v = sp.sympify(v)
    exact = tex(v)
    if v.is_Integer or v.is_Float or not v.is_number:
        return exact
    try:
        return f"{exact} \\approx {report_number(float(v))}"
    except TypeError:       # complex or not evaluable: the exact form alone
        return exact


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

    def listing(pairs):
        return ", ".join(f"${tex(s)} = {_value(v, tex)}$" for s, v in pairs)

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


def overrides_by_parameter(problem, tex) -> dict:
    """Parameter symbol -> "value in `id`" strings of the questions that override it."""
    out: dict = {}
    for question in problem.questions:
        for s, v in split_at(question, problem)[3]:
            out.setdefault(s, []).append(f"${_value(v, tex)}$ in `{question.id}`")
    return out
