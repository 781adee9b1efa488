"""Gradescope's autograder `results.json` (grading.md "Grading a class": Gradescope).

`check ANSWERS --json FILE --json-format gradescope` writes the record in Gradescope's
layout: the total, one test per graded key (`<question>.<key>`, in grading order) with its
share of the marks and `<verdict>: <feedback>` as its output, and the one-line summary.
"""

from __future__ import annotations

import json

from robosolve.grading.gradebook import summary_line
from robosolve.grading.record import json_number

FORMATS = ("record", "gradescope")


def format_issue(json_out: str | None, json_format: str) -> str:
    """Why the --json / --json-format pair is a usage error, or ''."""
    from robosolve.load.expressions import did_you_mean

    if json_format not in FORMATS:
        return (f"--json-format: unknown format '{json_format}'" + did_you_mean(json_format, FORMATS)
                + f" (expected one of: {', '.join(FORMATS)})")
    if json_format != "record" and not json_out:
        return "--json-format goes with --json FILE"
    return ""


def gradescope(result) -> dict:
    tests = []
    for q in result.questions:
        for key in q.graded:
            r = q.keys[key]
            tests.append({"name": f"{q.id}.{key}", "score": json_number(q.share * r.earned),
                          "max_score": json_number(q.share), "output": f"{r.verdict}: {r.feedback}"})
    return {"score": json_number(result.score), "max_score": json_number(result.max_score),
            "tests": tests, "output": summary_line(result)}


def gradescope_json(result) -> str:
    return json.dumps(gradescope(result), indent=2, ensure_ascii=False) + "\n"
