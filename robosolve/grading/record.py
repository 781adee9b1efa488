"""The result record (grading.md), the feedback Markdown and the CSV rows, deterministically.

Scores are exact fractions until written; then "the shortest decimal of the value
rounded to 4 places" (0.5, 1, 0.6667), and percent with one decimal.
"""

from __future__ import annotations

import json
from decimal import ROUND_HALF_UP, Decimal
from fractions import Fraction

from robosolve.grading.grader import NO_REFERENCE, SubmissionResult

GRADES_COLUMNS = ("student", "question", "key", "verdict", "diagnosis", "score", "out_of")
SUMMARY_COLUMNS = ("student", "score", "max_score", "percent")


def rounded(value: Fraction, places: int = 4) -> Decimal:
    d = Decimal(value.numerator) / Decimal(value.denominator) if value.denominator != 1 \
        else Decimal(value.numerator)
    return d.quantize(Decimal(1).scaleb(-places), rounding=ROUND_HALF_UP)


def number_text(value: Fraction) -> str:
    """Shortest decimal of the value rounded to 4 places: 0.5, 1, 0.6667."""
    d = rounded(Fraction(value))
    text = format(d, "f")
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def json_number(value: Fraction):
    text = number_text(value)
    return int(text) if "." not in text else float(text)


def percent_text(score: Fraction, max_score: Fraction) -> str:
    if max_score == 0:
        return "0.0"
    return format(rounded(Fraction(score) * 100 / Fraction(max_score), 1), "f")


def record(result: SubmissionResult) -> dict:
    out = {"format": 1, "problem": result.problem, "student": result.student,
           "score": json_number(result.score), "max_score": json_number(result.max_score)}
    if result.error:
        out["error"] = result.error
    if result.notes:
        out["notes"] = list(result.notes)
    if result.note:
        out["note"] = result.note
    out["questions"] = {
        q.id: {"marks": json_number(q.marks), "score": json_number(q.score),
               "keys": {k: r.as_dict() for k, r in q.keys.items()}}
        for q in result.questions}
    return out


def record_json(result: SubmissionResult) -> str:
    return json.dumps(record(result), indent=2, ensure_ascii=False) + "\n"


def grade_rows(result: SubmissionResult) -> list[tuple]:
    """grades.csv rows: graded keys only, in question then graded-key order."""
    rows = []
    for q in result.questions:
        for key in q.graded:
            r = q.keys[key]
            out_of = Fraction(0) if r.verdict == NO_REFERENCE else q.share
            score = out_of * r.earned
            rows.append((result.student, q.id, key, r.verdict, r.diagnosis,
                         number_text(score), number_text(out_of)))
    if not result.questions:      # not even the problem is known: one row says so
        rows.append((result.student, "", "", "invalid", "", "0", "0"))
    return rows


def summary_row(result: SubmissionResult) -> tuple:
    return (result.student, number_text(result.score), number_text(result.max_score),
            percent_text(result.score, result.max_score))
