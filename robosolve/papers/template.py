"""answers.yaml: the answers template of a paper (papers.md "The answers template").

Every graded key of every question, in the paper's order, each under a comment saying what
it is, its layout, whether it may be symbolic, and its unit; `~` (null) in the answer's
shape. Nothing in it comes from the solution: it is the same bytes with or without solving.
"""

from __future__ import annotations

import json
import re

from robosolve.papers.keys import decided, graded_keys, placeholder, shape
from robosolve.questions import registry as R
from robosolve.questions.registry import title as question_title
from robosolve.render.numbers import marks_number

PLAIN_KEY = re.compile(r"^[A-Za-z_][A-Za-z0-9_.]*$")


# What a YAML double-quoted scalar may not hold as it is (YAML 1.1 / 1.2 "printable", §5.1):
# the C0 controls (a line break inside quotes is read as a space, a tab may be trimmed), DEL and
# the C1 controls, surrogates, U+FFFE / U+FFFF; and what a YAML reader takes for a line break
# (NEL, U+2028 / U+2029) or strips (BOM U+FEFF).
NOT_AS_IS = re.compile("[\x00-\x1f\x7f-\x9f\u2028\u2029\ud800-\udfff\ufeff\ufffe\uffff]")


def quoted(text: str) -> str:
    """A YAML double-quoted string: UTF-8 as it is (`"José Álvarez"`, students read the file),
    only a quote, a backslash and the characters YAML cannot hold written as escapes."""
    inner = text.replace("\\", "\\\\").replace('"', '\\"')
    return '"' + NOT_AS_IS.sub(lambda m: f"\\u{ord(m.group()):04x}", inner) + '"'


def flow(value) -> str:
    """A placeholder tree in YAML flow style: ~, [~, ~], {theta1: ~}."""
    if value is None:
        return "~"
    if isinstance(value, list):
        return "[" + ", ".join(flow(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{yaml_key(k)}: {flow(v)}" for k, v in value.items()) + "}"
    return quoted(value) if isinstance(value, str) else json.dumps(value)


def yaml_key(key: str) -> str:
    return key if PLAIN_KEY.fullmatch(key) and key not in ("y", "n", "yes", "no", "on", "off",
                                                            "true", "false", "null") else quoted(key)


def marks_text(marks) -> str:
    text = marks_number(marks)
    return f"{text} mark" + ("" if text == "1" else "s")


def unit_text(unit: str, problem) -> str:
    """The unit of a key, the joint-dependent ones ("joint", "effort") told by the joints' kinds."""
    kinds = {j.kind for j in problem.joints}
    if unit.startswith("joint"):
        rest = unit[len("joint"):]
        names = {"revolute": "rad" + rest, "prismatic": "m" + rest}
    elif unit == "effort":
        names = {"revolute": "N·m", "prismatic": "N"}
    else:
        return unit
    if len(kinds) == 1:
        return names[next(iter(kinds))]
    return f"{names['revolute']} (revolute joints) or {names['prismatic']} (prismatic)"


def key_unit(ak, question, problem, parent=None) -> str:
    """The unit of a key in this question: the one the question decides, else the schema's (a
    field's, else its record's: `parent`)."""
    unit = decided(ak, question, problem)[1]
    if unit is None:
        unit = ak.unit or (parent.unit if parent is not None else "")
    return unit_text(unit, problem)


def layout_text(ak, question, problem) -> str:
    """How the answer is laid out, in words."""
    kind = ak.kind
    dims = shape(ak, question, problem)
    joints = ", ".join(j.name for j in problem.joints)
    entries = decided(ak, question, problem)[0]
    bodies = ", ".join(b.name for b in problem.bodies)
    if kind == R.MATRIX_LIST and entries is not None:
        return (f"a list of {len(entries)} 4×4 matri{'x' if len(entries) == 1 else 'ces'} (frame "
                + ", ".join(entries) + " in its parent), each a list of rows")
    if kind == R.BODY_MAP:
        return f"one value per body ({bodies}) and their total (total)"
    if kind == R.MATRIX_MAP and len(dims) == 2:
        return f"one {dims[0]}×{dims[1]} matrix per body ({bodies}), each a list of rows"
    if kind == R.EQUATIONS:
        return (f"a list of {len(problem.joints)} equations, one per joint in joint order ({joints}), "
                "each a string \"left side = right side\"")
    if kind == R.JOINT_MAP_SET:      # a pose target's solutions: the joints that move its frame
        element = "{" + ", ".join(f"{name}: …" for name in (entries or [j.name for j in problem.joints])) + "}"
        return f"a set, a list of {element} in any order ([] when there is none)"
    if entries is not None:
        names = [j.name for j in problem.joints]
        return (f"one value per joint ({', '.join(entries)})" if set(entries) <= set(names) else
                f"one value per coordinate ({', '.join(entries)})")
    if kind == R.MATRIX and len(dims) == 2:
        return f"{dims[0]}×{dims[1]} matrix, a list of rows"
    if kind == R.VECTOR and len(dims) == 1:
        return f"a list of {dims[0]} values"
    if kind == R.JOINT_MAP:
        return f"one value per joint ({joints})"
    if kind == R.ACTUATOR_MAP:
        return "one value per actuator (" + ", ".join(str(j.actuator) for j in problem.joints) + ")"
    if kind == R.ACTUATOR_RECORDS:
        return ("per actuator (" + ", ".join(str(j.actuator) for j in problem.joints) + "): "
                + ", ".join(f"{f.name} ({f.doc}" + (f"; {u}" if (u := key_unit(f, question, problem)) else "") + ")"
                            for f in ak.fields))
    if kind == R.VECTOR_SET:
        n = dims[0] if dims else 3
        return f"a set, a list of [{', '.join(['…'] * n)}] in any order ([] when there is none)"
    if kind == R.RECORD:
        return "fields " + "; ".join(f"{f.name}: {f.doc} ({layout_text(f, question, problem)})"
                                     for f in ak.fields)
    if kind == R.BOOL:
        return "true or false"
    if kind == R.AXES:
        return "a list of vectors, longest first"
    return "a number or an expression"


def form_text(ak) -> str:
    if ak.symbolic and ak.numeric:
        return "symbolic or numeric"
    return "numeric" if ak.numeric else "symbolic"


def key_comment(gk, question, problem) -> str:
    ak = gk.answer_key
    parts = [gk.doc, layout_text(ak, question, problem), form_text(ak)]
    unit = key_unit(ak, question, problem, gk.parent)
    if unit:
        parts.append(unit)
    return "; ".join(p for p in parts if p)


def render_template(problem, problem_path: str, student: str = "", name: str | None = None) -> str:
    """answers.yaml of `problem`; `problem_path`: the problem file relative to the template."""
    lines = [f"# Answers for {name or problem.name} — fill in every ~ (null); keep the layout.",
             "# A value is a number or an expression in the problem's names, e.g. \"L1*cos(theta1)\";",
             "# a matrix may also be one string such as \"[1 0; 0 1]\", and ^ means a power.",
             "robosolve-answers: 1",
             f"problem: {quoted(problem_path)}",
             f"student: {quoted(student)}",
             "answers:"]
    for i, q in enumerate(problem.questions, 1):
        keys = graded_keys(q, problem)
        if not keys:
            continue
        lines.append(f"  {yaml_key(q.id)}:  # {i}. {question_title(q.type)}, {marks_text(q.marks)}")
        for gk in keys:
            lines.append(f"    # {gk.key} — {key_comment(gk, q, problem)}")
            lines.append(f"    {yaml_key(gk.key)}: {flow(placeholder(gk.answer_key, q, problem))}")
    return "\n".join(lines) + "\n"
