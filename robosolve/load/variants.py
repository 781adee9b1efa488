"""The `variants:` section of a problem file -> `VariantSpec` (spec variants.md).

Validated by the loader like every other key (`FILE:LINE: path: message`, did-you-mean),
after the questions, because `require` names question ids. `solve` then ignores it; only
`robosolve variants` draws from it.

Values are exact: YAML decimals become exact decimals (0.05 -> 1/20), so that
`range[0] + k*step` lands exactly on the values a teacher expects and the drawn values
can be written back as exact expression strings.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import sympy as sp

from robosolve.core.simplify import full, is_zero
from robosolve.load.expressions import ExpressionError, Namespace, did_you_mean, digits_issue
from robosolve.load.questions import may_be_refused
from robosolve.questions.registry import types_where

SECTION_KEYS = ("parameters", "require")
PARAMETER_KEYS = ("range", "step", "choices")
REQUIRE_KINDS = ("reachable", "nonsingular")
# the question types whose answer has a Jacobian J evaluated at the question's `at`
JACOBIAN_TYPES = tuple(t.name for t in types_where("has_jacobian"))
INEQUALITY_RE = re.compile(r"<=|>=|==|!=|<|>|=")
OPERATORS = ("<", "<=", ">", ">=")


@dataclass
class VariedParameter:
    """One varied parameter and its finite set of exact values, in order."""

    name: str
    symbol: sp.Symbol
    kind: str                       # "range" or "choices"
    line: int
    choices: tuple = ()             # kind == "choices"
    start: sp.Expr = None           # kind == "range": start + i*step, i < count
    step: sp.Expr = None
    count: int = 0
    written: str = ""               # the entry as written: `range [1, 100], step 1e-29` or `choices`

    @property
    def size(self) -> int:
        return len(self.choices) if self.kind == "choices" else self.count

    def value(self, i: int) -> sp.Expr:
        if self.kind == "choices":
            return self.choices[i]
        return self.start + i * self.step


@dataclass
class Requirement:
    """One `require` item: an inequality of parameters, or a question-based condition."""

    kind: str                       # "inequality", "reachable", "nonsingular"
    text: str                       # as written (for messages)
    line: int
    path: str
    question: str | None = None     # reachable / nonsingular: the question id
    lhs: sp.Expr | None = None      # inequality: lhs op rhs
    op: str | None = None
    rhs: sp.Expr | None = None


@dataclass
class VariantSpec:
    parameters: list                # VariedParameter, in file order
    require: list = field(default_factory=list)
    line: int = 1

    @property
    def grid_size(self) -> int:
        return math.prod(p.size for p in self.parameters)

    def parameter(self, name: str) -> VariedParameter | None:
        for p in self.parameters:
            if p.name == name:
                return p
        return None


def exact(e: sp.Expr) -> sp.Expr:
    """Decimal literals as exact decimals: Float(0.05) -> 1/20 (shortest repr of the float)."""
    floats = e.atoms(sp.Float)
    if not floats:
        return e
    return e.xreplace({f: sp.Rational(repr(float(f))) for f in floats})


def _real_number(chk, path, value, ns) -> sp.Expr | None:
    """An exact, finite, real constant (numbers, pi, sqrt, deg...: no parameters), of at most
    MAX_EXACT_DIGITS digits: a step of 1e-300 is 1/10**300, every value drawn from it as long."""
    if isinstance(value, float) and math.isfinite(value):
        return _short_enough(chk, path, repr(value), sp.Rational(repr(value)), value)
    e = chk.expr(path, value, ns)
    if e is None:
        return None
    e = exact(e)
    try:
        v = complex(sp.N(e))
    except (TypeError, ValueError):
        chk.error(path, f"expected a number, got {value!r}")
        return None
    if abs(v.imag) > 1e-12 or not math.isfinite(v.real):
        chk.error(path, f"{value!r} is not a finite real number")
        return None
    return _short_enough(chk, path, str(value), e, v.real)


def _short_enough(chk, path, text: str, e: sp.Expr, approx: float) -> sp.Expr | None:
    issue = digits_issue(text, e, approx, advice="a variant's values are exact (a decimal as written), "
                         "so give it fewer digits")
    if issue is not None:
        chk.error(path, issue)
        return None
    return e


def load_variants(builder, value) -> VariantSpec | None:
    """Validate `variants:` (None when absent). Issues go to the builder's checker."""
    if value is None:
        return None
    chk = builder.chk
    path = ("variants",)
    if not chk.mapping(path, value, SECTION_KEYS, required=("parameters",)):
        return None
    spec = VariantSpec([], [], line=chk.src.line(path))
    spec.parameters = _parameters(builder, value.get("parameters"))
    if "require" in value:
        # the names written under `parameters`, loaded or not: an entry with a mistake of its
        # own has had its message, a condition on it is no second one (None: no such mapping)
        written = value.get("parameters")
        varied = {str(k) for k in written} if isinstance(written, dict) and written else None
        spec.require = _require(builder, value["require"], varied)
    return spec


def _parameters(builder, value) -> list:
    chk = builder.chk
    path = ("variants", "parameters")
    if value is None:
        return []
    if not isinstance(value, dict) or not value:
        chk.error(path, "expected a mapping parameter: {range, step} or {choices} (at least one parameter)")
        return []
    declared = {s.name: s for s in builder.parameters}
    joints = {j.name for j in builder.joints}
    consts = Namespace({}, what="constant")
    out = []
    for name, item in value.items():
        ppath = path + (name,)
        if name not in declared:
            if name in joints:
                chk.error(ppath, f"'{name}' is a joint, not a parameter: vary a joint value through a "
                          "parameter used in `at`, a target or a profile")
            elif not builder.parameters_refused:     # (the section refused whole: said already)
                chk.error(ppath, f"undeclared parameter '{name}'" + did_you_mean(name, declared)
                          + " (a varied parameter must be declared in `parameters`, with its base value)")
            continue
        if not chk.mapping(ppath, item, PARAMETER_KEYS) or any(k not in PARAMETER_KEYS for k in item):
            continue                     # one mistake, one message
        given = [k for k in ("range", "choices") if k in item]
        if len(given) != 1:
            chk.error(ppath, "expected exactly one of range (with step) or choices"
                      + (f" (got {', '.join(given)})" if given else ""))
            continue
        line = chk.src.line(ppath)
        if given[0] == "choices":
            if "step" in item:
                chk.error(ppath + ("step",), "step goes with range, not with choices")
                continue
            p = _choices(chk, ppath + ("choices",), item["choices"], consts)
            if p is not None:
                out.append(VariedParameter(name, declared[name], "choices", line, choices=p,
                                           written="its choices"))
        else:
            if "step" not in item:
                chk.error(ppath, "a range needs a step (values range[0] + k*step within the range)")
                continue
            r = _range(chk, ppath, item["range"], item["step"], consts)
            if r is not None:
                start, step, count = r
                written = (f"range [{_as_written(item['range'][0])}, {_as_written(item['range'][1])}], "
                           f"step {_as_written(item['step'])}")
                out.append(VariedParameter(name, declared[name], "range", line,
                                           start=start, step=step, count=count, written=written))
    return out


def _as_written(value) -> str:
    """A number of the section as the teacher wrote it (YAML read 1e-29 as a float)."""
    return repr(value) if isinstance(value, float) else str(value)


def _choices(chk, path, value, ns):
    if not isinstance(value, list) or not value:
        chk.error(path, "expected a non-empty list of values")
        return None
    values = [_real_number(chk, path + (i,), v, ns) for i, v in enumerate(value)]
    if any(v is None for v in values):
        return None
    floats = [float(sp.N(v, 30)) for v in values]
    for i in range(len(values)):
        for j in range(i):
            if abs(floats[i] - floats[j]) <= 1e-12 * max(1.0, abs(floats[j])) \
                    and is_zero(values[i] - values[j]):
                chk.error(path + (i,), f"choices must be distinct: {value[i]!r} equals {value[j]!r}")
                return None
    return tuple(values)


def _range(chk, path, rng, step_value, ns):
    if not isinstance(rng, list) or len(rng) != 2:
        chk.error(path + ("range",), "expected [low, high] (two numbers)")
        return None
    lo = _real_number(chk, path + ("range", 0), rng[0], ns)
    hi = _real_number(chk, path + ("range", 1), rng[1], ns)
    step = _real_number(chk, path + ("step",), step_value, ns)
    if lo is None or hi is None or step is None:
        return None
    if not float(sp.N(step, 30)) > 0:
        chk.error(path + ("step",), f"the step must be positive, got {step_value!r}")
        return None
    if float(sp.N(hi - lo, 30)) < 0 and not is_zero(hi - lo):
        chk.error(path + ("range",), f"empty range [{rng[0]}, {rng[1]}]: the low end is above the high end")
        return None
    ratio = full((hi - lo) / step)
    k = sp.floor(ratio)
    if not isinstance(k, sp.Integer):
        k = math.floor(float(sp.N(ratio, 30)) + 1e-12)
    count = int(k) + 1
    if count < 1:
        chk.error(path + ("range",), "the range holds no value")
        return None
    return lo, step, count


def _require(builder, value, varied: set | None) -> list:
    chk = builder.chk
    path = ("variants", "require")
    if not isinstance(value, list) or not value:
        chk.error(path, "expected a non-empty list of conditions (\"L1 > L2\", {reachable: <question id>}, "
                  "{nonsingular: <question id>})")
        return []
    questions = {q.id: q for q in builder.problem.questions}
    params = Namespace({s.name: s for s in builder.parameters}, what="parameter",
                       unknown_ok=builder.parameters_refused)
    out = []
    for i, item in enumerate(value):
        ipath = path + (i,)
        line = chk.src.line(ipath)
        where = f"variants.require[{i}]"
        if isinstance(item, str):
            r = _inequality(chk, ipath, item, params, varied, builder.parameters)
            if r is not None:
                lhs, op, rhs = r
                out.append(Requirement("inequality", item, line, where, lhs=lhs, op=op, rhs=rhs))
            continue
        if not isinstance(item, dict):
            chk.error(ipath, "expected an inequality string such as \"L1 > L2\", or {reachable: <question id>} "
                      "or {nonsingular: <question id>}")
            continue
        if not chk.mapping(ipath, item, REQUIRE_KINDS) or any(k not in REQUIRE_KINDS for k in item):
            continue
        if len(item) != 1:
            chk.error(ipath, "expected one condition per item (reachable or nonsingular)")
            continue
        kind, qid = next(iter(item.items()))
        q = _question_ref(chk, builder, ipath + (kind,), kind, qid, questions)
        if q is not None:
            out.append(Requirement(kind, f"{kind}: {qid}", line, where, question=q.id))
    return out


def _question_ref(chk, builder, path, kind, qid, questions):
    if not questions:
        return None         # no question at all (the file's own message says so)
    if isinstance(qid, str) and qid not in questions and may_be_refused(builder.refused_question_ids, qid):
        return None         # a question refused whole (said already): one mistake, one message
    if not isinstance(qid, str) or qid not in questions:
        known = ", ".join(questions) or "none"
        chk.error(path, f"unknown question id {qid!r}"
                  + (did_you_mean(qid, questions) if isinstance(qid, str) else "")
                  + f" (known: {known})")
        return None
    q = questions[qid]
    reaching = [t.name for t in types_where("reaches")]
    if kind == "reachable" and q.type not in reaching:
        chk.error(path, f"question '{qid}' is a {q.type} question: reachable needs an "
                  f"{' or '.join(reaching)} question")
        return None
    if kind == "nonsingular":
        if q.type not in JACOBIAN_TYPES:
            chk.error(path, f"question '{qid}' is a {q.type} question: nonsingular needs a question "
                      f"with a Jacobian ({', '.join(JACOBIAN_TYPES)})")
            return None
        missing = [j.name for j in builder.joints if j.symbol not in q.at]
        if missing and "at" not in q.rejected:      # (a refused `at` value is said already)
            chk.error(path, f"question '{qid}' has no `at` value for {', '.join(missing)}: nonsingular "
                      "checks J at the question's `at`, which must give every joint")
            return None
    return q


def _depends_on(e, varied: set, parameters: dict) -> bool:
    """Whether `e` depends on a varied parameter, directly or through the parameters defined
    from it (`Lc: L1/2` follows a drawn L1)."""
    seen, todo = set(), list(e.free_symbols)
    while todo:
        s = todo.pop()
        if s in seen:
            continue
        seen.add(s)
        if s.name in varied:
            return True
        value = parameters.get(s)
        if value is not None:
            todo.extend(sp.sympify(value).free_symbols)
    return False


def _inequality(chk, path, text, ns, varied, parameters):
    ops = INEQUALITY_RE.findall(text)
    if len(ops) != 1 or ops[0] not in OPERATORS:
        chk.error(path, f"expected one inequality such as \"L1 > L2\" (operators < <= > >=), got {text!r}")
        return None
    left, right = INEQUALITY_RE.split(text)
    try:
        lhs, rhs = exact(ns.parse_text(left)), exact(ns.parse_text(right))
    except ExpressionError as exc:
        chk.error(path, str(exc))
        return None
    if varied is not None and not _depends_on(lhs - rhs, varied, parameters):
        chk.error(path, f"{text!r} involves no varied parameter: it would hold for every variant or for none")
        return None
    return lhs, ops[0], rhs
