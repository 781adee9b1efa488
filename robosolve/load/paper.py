"""What a problem file says about its exam paper (papers.md): a question's `text` and the
top-level `paper: {at: …}`, the configuration of the drawing."""

from __future__ import annotations

import re

from robosolve.core.printing import sstr
from robosolve.load.expressions import Namespace, did_you_mean

PLACEHOLDER = re.compile(r"\{\{|\}\}|\{([^{}]*)\}|[{}]")


def text_names(text: str) -> list[tuple[str, int]]:
    """(name, offset) of each `{name}` of a text; `{{` and `}}` are literal braces. A lone
    brace is reported with the name '' (offset of the brace)."""
    out = []
    for m in PLACEHOLDER.finditer(text):
        if m.group(0) in ("{{", "}}"):
            continue
        out.append(((m.group(1) or "").strip() if m.group(1) is not None else "", m.start()))
    return out


def question_text(chk, path, value, parameters) -> str | None:
    """A question's `text`: a string whose `{name}` are parameters or `{at}`."""
    if not isinstance(value, str) or not value.strip():
        chk.error(path, "expected the question's wording (a non-empty string)")
        return None
    known = [s.name for s in parameters] + ["at"]
    ok = True
    for name, _ in text_names(value):
        if not name:
            chk.error(path, "a lone brace: write {{ or }} for a literal brace, {name} for a "
                      "parameter's value, {at} for the configuration")
            ok = False
        elif name not in known:
            chk.error(path, f"unknown name '{{{name}}}' in text" + did_you_mean(name, known)
                      + f" (known: {', '.join('{' + k + '}' for k in known)})")
            ok = False
    return value if ok else None


def load_paper(builder, value) -> dict:
    """`paper: {at: {joint: value}}` -> {joint symbol: exact value}, each within its limits."""
    chk = builder.chk
    if value is None or not chk.mapping(("paper",), value, ("at",)):
        return {}
    at = value.get("at")
    if at is None:
        return {}
    path = ("paper", "at")
    if not isinstance(at, dict):
        chk.error(path, f"expected a mapping joint -> value, got {type(at).__name__}")
        return {}
    joints = {j.name: j for j in builder.joints}
    ns = Namespace({s.name: s for s in builder.parameters}, what="parameter", unknown_ok=builder.parameters_refused)
    out = {}
    for name, v in at.items():
        if name not in joints:
            chk.error(path + (name,), f"unknown joint '{name}'" + did_you_mean(str(name), joints)
                      + (f" (joints: {', '.join(joints)})" if joints else ""))
            continue
        e = chk.expr(path + (name,), v, ns)
        if e is None:
            continue
        j = joints[name]
        if j.limits is not None and not _within(chk, e, j.limits):
            lo, hi = (sstr(x, full_prec=False) for x in j.limits)      # 0.5, not 0.500000000000000
            chk.error(path + (name,), f"{v!r} is outside the limits of {name} [{lo}, {hi}]")
            continue
        out[j.symbol] = e
    return out


def _within(chk, e, limits) -> bool:
    value, lo, hi = chk.number_value(e), chk.number_value(limits[0]), chk.number_value(limits[1])
    if value is None or lo is None or hi is None:
        return True
    return lo - 1e-12 <= value <= hi + 1e-12
