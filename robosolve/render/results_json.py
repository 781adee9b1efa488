"""results.json exactly as the spec's §2 lays it out."""

from __future__ import annotations

import json

import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.questions.registry import QUESTION_TYPES
from robosolve.render.numbers import json_angle, json_number, text
from robosolve.render.printers import SharedStrPrinter


def symbolic_value(v, printer: SharedStrPrinter | None = None):
    """sympy objects -> str() strings (lists of rows for matrices), recursively."""
    printer = printer or SharedStrPrinter()
    if isinstance(v, sp.MatrixBase):
        return [[printer.doprint(e) for e in v.row(i)] for i in range(v.rows)]
    if isinstance(v, dict):
        return {str(k): symbolic_value(x, printer) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [symbolic_value(x, printer) for x in v]
    if v is None or isinstance(v, bool):
        return v
    if isinstance(v, str):
        return v
    return printer.doprint(sp.sympify(v))


def numeric_value(v, key=None):
    """Plain JSON numbers; `key` (the registry's AnswerKey) may ask for fewer digits."""
    if isinstance(v, dict):
        return {str(k): numeric_value(x, _child(key, k)) for k, x in v.items()}
    if isinstance(v, (list, tuple)) and not isinstance(v, Text):
        return [numeric_value(x, key) for x in v]
    if isinstance(v, str):
        return v
    if isinstance(v, (Num, Text)):
        return text(v)
    if key is not None and key.angle:
        return json_angle(v, key.digits)
    return json_number(v, key.digits if key is not None else None)


def _child(key, name):
    """The AnswerKey of a record's field, else the key itself (per-joint maps, sets)."""
    if key is None:
        return None
    return key.field(str(name)) or key


def _numeric_answers(answer) -> dict:
    qt = QUESTION_TYPES.get(answer.type)
    return {str(k): numeric_value(v, qt.key(str(k)) if qt is not None else None)
            for k, v in answer.numeric.items()}


def answer_record(answer, figure_paths: list[str], printer: SharedStrPrinter | None = None) -> dict:
    printer = printer or SharedStrPrinter()
    rec: dict = {"type": answer.type}
    for k, v in answer.extra.items():
        rec[k] = numeric_value(v) if not isinstance(v, (sp.Basic, sp.MatrixBase)) else symbolic_value(v, printer)
    if answer.error is not None:
        rec["error"] = answer.error
    rec["symbolic"] = symbolic_value(answer.symbolic, printer)
    rec["numeric"] = _numeric_answers(answer)
    rec["figures"] = list(figure_paths)
    rec["notes"] = [text(n) for n in answer.notes]
    return rec


def planned_figures(answer) -> list[str]:
    """The paths of the answer's figures in the output folder (when every one is drawn)."""
    return [f"figures/{answer.id}-{spec.name}.png" for spec in answer.figures]


def results_document(report, figure_paths: dict) -> dict:
    printer = SharedStrPrinter()
    return {
        "format": 1,
        "problem": report.problem.name,
        "answers": {a.id: _record(a, figure_paths.get(a.id, []), printer) for a in report.answers},
    }


def _record(answer, paths: list[str], printer) -> dict:
    """The answer's record; one a question helper printed already (run/split_solve) when it was
    printed with these figure paths (a figure that could not be drawn adds a note: printed again)."""
    printed = getattr(answer, "printed_record", None)
    if printed is not None and printed[0] == paths:
        return printed[1]
    return answer_record(answer, paths, printer)


def dumps(value, indent: int = 0) -> str:
    """JSON with 2-space indentation, but lists of scalars (vectors, matrix rows) on one line."""
    pad, inner = "  " * indent, "  " * (indent + 1)
    if isinstance(value, dict):
        if not value:
            return "{}"
        items = [f"{inner}{json.dumps(str(k), ensure_ascii=False)}: {dumps(v, indent + 1)}"
                 for k, v in value.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(value, list):
        if all(not isinstance(v, (list, dict)) for v in value):
            return "[" + ", ".join(json.dumps(v, ensure_ascii=False) for v in value) + "]"
        items = [inner + dumps(v, indent + 1) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(value, ensure_ascii=False)


def render_results_json(report, figure_paths: dict) -> str:
    return dumps(results_document(report, figure_paths)) + "\n"
