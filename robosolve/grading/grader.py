"""Grade one submission against a Reference: key verdicts, diagnoses, feedback, scores.

For each key: read the given value by the key's kind (registry schema); a value with no
free symbol is compared with the numeric answer (at the question's `at`), one with free
symbols with the symbolic answer, at seeded sample points (keys marked `by_value`, the
singularities, are compared as numbers whatever their form); then, when wrong, the
diagnoses of `diagnose.py`. Scores are exact fractions of the marks.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np
import sympy as sp

from robosolve.core.simplify import is_zero
from robosolve.grading import diagnose as D
from robosolve.grading.compare import Rules, compare
from robosolve.grading.points import evaluate, sample, single_point
from robosolve.grading.reference import Reference, lookup
from robosolve.grading.values import Equation, Reader, ValueProblem, blanks, free_symbols, substitute
from robosolve.questions import registry as R
from robosolve.questions.registry import question_type

CORRECT, INCORRECT, MISSING, INVALID, NO_REFERENCE = (
    "correct", "incorrect", "missing", "invalid", "no_reference")
MIN_POINTS = 6
SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
MAX_SHOWN = 600                   # characters of an expected value quoted in feedback


@dataclass
class KeyResult:
    verdict: str
    compared: str = ""
    diagnosis: str = ""
    feedback: str = ""

    def as_dict(self) -> dict:
        return {"verdict": self.verdict, "compared": self.compared,
                "diagnosis": self.diagnosis, "feedback": self.feedback}


@dataclass
class QuestionResult:
    id: str
    marks: Fraction
    graded: tuple
    keys: dict = field(default_factory=dict)     # key -> KeyResult, graded keys first
    no_reference: bool = False

    @property
    def share(self) -> Fraction:
        return self.marks / len(self.graded) if self.graded and not self.no_reference else Fraction(0)

    @property
    def score(self) -> Fraction:
        return sum((self.share for k in self.graded if self.keys[k].verdict == CORRECT), Fraction(0))

    @property
    def max_score(self) -> Fraction:
        return Fraction(0) if self.no_reference else self.marks


@dataclass
class SubmissionResult:
    problem: str
    student: str
    questions: list                               # QuestionResult, in the problem's order
    error: str = ""                               # the submission could not be read
    notes: list = field(default_factory=list)     # answers that could not be placed (unknown question ids)

    @property
    def score(self) -> Fraction:
        return sum((q.score for q in self.questions), Fraction(0))

    @property
    def max_score(self) -> Fraction:
        return sum((q.max_score for q in self.questions), Fraction(0))

    @property
    def all_correct(self) -> bool:
        return all(q.keys[k].verdict == CORRECT for q in self.questions for k in q.graded
                   if not q.no_reference)


def fraction(marks) -> Fraction:
    if isinstance(marks, sp.Rational):
        return Fraction(int(marks.p), int(marks.q))
    if isinstance(marks, (int, Fraction)):
        return Fraction(marks)
    return Fraction(str(float(marks)))


# -- formatting values for feedback ---------------------------------------------
def show(tree) -> str:
    """A value as a student would write it (numbers to 4 significant digits), cut at MAX_SHOWN."""
    text = _show(tree)
    return text if len(text) <= MAX_SHOWN else text[:MAX_SHOWN].rstrip() + " … (see the report)"


def _show(tree) -> str:
    if isinstance(tree, dict):
        return "{" + ", ".join(f"{k}: {_show(v)}" for k, v in tree.items()) + "}"
    if isinstance(tree, (list, tuple)):
        return "[" + ", ".join(_show(v) for v in tree) + "]"
    if isinstance(tree, Equation):
        return tree.text or f"{tree.residual} = 0"
    if tree is None:
        return "null"
    if isinstance(tree, bool):
        return str(tree).lower()
    if isinstance(tree, float) or (isinstance(tree, sp.Basic) and tree.is_Float):
        return f"{float(tree):.4g}"
    if isinstance(tree, sp.Basic) and tree.is_number and not tree.is_Rational and tree.free_symbols == set():
        return str(tree) if len(str(tree)) <= 12 else f"{float(sp.N(tree)):.4g}"
    return str(tree)


def _at(tree, path):
    for p in path:
        try:
            tree = tree[p]
        except (KeyError, IndexError, TypeError):
            return None
    return tree


class Grader:
    """Grades submissions of one problem (caches the expected values it evaluates)."""

    def __init__(self, reference: Reference, tolerance=None, reveal: bool = True):
        self.ref = reference
        self.reveal = reveal      # False: no expected value in any feedback (--no-expected)
        self.tol = tolerance or reference.tolerance
        self.ns = reference.namespace
        self.reader = Reader(self.ns)
        self.expected_reader = Reader(self.ns, expected=True)
        self.revolute = reference.revolute
        self.parameters = set(reference.problem.parameters)

    # -- one key ------------------------------------------------------------
    def symbol(self, qref, ak) -> str:
        frame = qref.frame
        sub = frame.translate(SUBSCRIPTS) if frame.isdigit() else f"[{frame}]"
        return ak.symbol.format(sub=sub, frame=frame)

    def grade_key(self, qref, key: str, given) -> KeyResult:
        if given is not None and given.problem:
            return KeyResult(INVALID, feedback=given.problem)
        qt = question_type(qref.type)
        ak = qt.key(key)
        if qref.error is not None:
            return KeyResult(NO_REFERENCE, feedback=f"robosolve could not answer this question ({qref.error}); "
                                                    "it is not graded")
        sym, num = self._reference(qref, ak, key)
        if sym is None and num is None:
            return KeyResult(NO_REFERENCE, feedback=f"the reference answer has no {key}")

        def expected():
            return f"expected {self.symbol(qref, ak)} = {show(num if num is not None else sym)}"

        if given is None:
            return KeyResult(MISSING, feedback=self._reveal("not given", expected))
        holes = blanks(given.value, num if num is not None else sym)
        if holes:                 # a template's `~` left: not given yet (papers.md)
            shown = ", ".join(holes[:6]) + (f" (and {len(holes) - 6} more)" if len(holes) > 6 else "")
            what = "not filled in (still ~)" if _all_blank(given.value) else f"not filled in: {shown} still ~"
            return KeyResult(MISSING, feedback=self._reveal(what, expected))
        try:
            g = self.reader.read(ak, given.value)
        except ValueProblem as exc:
            return KeyResult(INVALID, diagnosis="wrong_shape" if exc.wrong_shape else "", feedback=str(exc))
        try:
            return self._compare(qref, ak, key, g, sym, num)
        except ValueProblem as exc:
            return KeyResult(INVALID, diagnosis="wrong_shape" if exc.wrong_shape else "", feedback=str(exc))

    def _reveal(self, text: str, expected: str) -> str:
        """Feedback with the expected value, unless the grader hides it (`--no-expected`)."""
        if not self.reveal:
            return text
        return f"{text}; {expected() if callable(expected) else expected}" if text else (
            expected() if callable(expected) else expected)

    def _reference(self, qref, ak, key):
        if ak.top:
            return None, qref.extra.get(key)
        return lookup(qref.symbolic, key), lookup(qref.numeric, key)

    def _names(self, symbols) -> str:
        return ", ".join(sorted(s.name for s in symbols))

    def _compare(self, qref, ak, key, g, sym, num) -> KeyResult:
        subs = qref.subs
        free = free_symbols(g)
        # by_value keys (singularities) are compared as numbers whenever the reference has them
        # as numbers; conditions written as equations stay symbolic (a single point cannot
        # tell an equation up to a constant factor)
        symbolic = bool(free) and sym is not None and not (ak.by_value and num is not None)
        if symbolic:
            e = self._expected(qref, ak, key, "symbolic", sym)
            if not free_symbols(e):
                # the reference is a number even in symbolic form (e.g. ellipse lengths at `at`):
                # the given expression is evaluated at the question's values instead
                symbolic = False
        if not symbolic:
            if free:
                g = substitute(g, subs)
                left = free_symbols(g)
                if left:
                    raise ValueProblem(f"{self._names(left)} {'has' if len(left) == 1 else 'have'} no value "
                                       "here: give numbers (or expressions of the parameters)")
            if num is not None:
                e = self._expected(qref, ak, key, "numeric", num)
            else:
                e = substitute(self._expected(qref, ak, key, "symbolic", sym), subs)
                left = free_symbols(e)
                if left:
                    raise ValueProblem(f"the answer depends on {self._names(left)}, which has no value: "
                                       "give it as an expression")
        compared = "symbolic" if symbolic else "numeric"
        points = (sample(free | free_symbols(e), qref.roles, f"{self.ref.name}/{qref.id}/{key}")
                  if symbolic else single_point())
        ge, ee = evaluate(g, points), self._evaluated(qref, key, compared, e, points)
        mask = _finite_mask(ee, points.size)
        if symbolic and mask.sum() < MIN_POINTS:
            return self._prove(qref, ak, key, g, e)
        rules = Rules(self.tol, mask, self.revolute, fixed=points.fixed if symbolic else None)
        outcome = compare(ak, ge, ee, rules)
        if outcome.ok:
            return KeyResult(CORRECT, compared)
        if outcome.unknown:
            return KeyResult(INVALID, compared, feedback=outcome.unknown)
        substituted = (free_symbols(e) & self.parameters) - free   # parameters the answer lacks
        diagnosis = D.diagnose(ak, ge, ee, rules, outcome, symbolic and bool(substituted))
        symbol = self.symbol(qref, ak)
        expected_text = f"expected {symbol} = {show(e)}"
        if diagnosis:
            params = self._names(substituted)
            text = D.sentence(diagnosis, ak, symbol=symbol, frame=qref.frame, outcome=outcome, params=params)
            verdict = INVALID if diagnosis == "wrong_shape" else INCORRECT
            return KeyResult(verdict, compared, diagnosis, self._reveal(text, expected_text))
        wrong = self._wrong_entries(outcome, g, e)
        if not self.reveal:
            return KeyResult(INCORRECT, compared, "", wrong.removesuffix(" In full: ").rstrip("; ") or "wrong")
        return KeyResult(INCORRECT, compared, "", wrong + expected_text)

    def _wrong_entries(self, outcome, g, e) -> str:
        if outcome.where:
            parts = [f"{label} is {show(_at(g, p))}" + (f"; expected {show(_at(e, p))}" if self.reveal else "")
                     for label, p in zip(outcome.wrong, outcome.where)][:3]
            more = len(outcome.where) - len(parts)
            return "; ".join(parts) + (f" (and {more} more)" if more > 0 else "") + ". In full: "
        if outcome.wrong and outcome.wrong != ["the value"]:
            return "wrong: " + ", ".join(outcome.wrong) + "; "
        if outcome.wrong == ["the value"]:
            return f"given {show(g)}; "
        return ""

    def _expected(self, qref, ak, key, mode, value):
        ck = ("tree", qref.id, key, mode)
        if ck not in self.ref.cache:
            self.ref.cache[ck] = self.expected_reader.read(ak, value)
        return self.ref.cache[ck]

    def _evaluated(self, qref, key, mode, e, points):
        if mode == "numeric":
            return evaluate(e, points)
        ck = ("values", qref.id, key, points.symbols)
        if ck not in self.ref.cache:
            self.ref.cache[ck] = evaluate(e, points)
        return self.ref.cache[ck]

    def _prove(self, qref, ak, key, g, e) -> KeyResult:
        """Too few points where the expected value is defined: ask sympy, briefly."""
        from robosolve.core.timing import time_limit
        from robosolve.errors import SymbolicTimeout

        pairs = _pairs(g, e)
        if pairs is None:
            return KeyResult(INCORRECT, "symbolic", "", self._reveal("", f"expected {self.symbol(qref, ak)} = {show(e)}")
                             or "not equal")
        try:
            with time_limit(2.0):
                same = all(is_zero(a - b) for a, b in pairs)
        except SymbolicTimeout:
            same = False
        if same:
            return KeyResult(CORRECT, "symbolic")
        return KeyResult(INCORRECT, "symbolic", "", self._reveal(
            "could not be confirmed equal", f"expected {self.symbol(qref, ak)} = {show(e)}"))

    # -- one submission -----------------------------------------------------
    def grade(self, student: str, answers: dict, notes=()) -> SubmissionResult:
        """`answers`: question id -> {dotted key: Given} (answers.resolve_answers)."""
        out = []
        for qref in self.ref.questions:
            given = answers.get(qref.id, {})
            graded = qref.graded_keys()
            qr = QuestionResult(qref.id, fraction(qref.marks), graded, no_reference=qref.error is not None)
            qt = question_type(qref.type)
            for key in graded:
                qr.keys[key] = self.grade_key(qref, key, _gather(qt, key, given))
            covered = set(graded)
            for key in _schema_order(qt, given):
                if key in covered or any(key.startswith(k + ".") for k in covered):
                    continue
                qr.keys[key] = self.grade_key(qref, key, given[key])
            out.append(qr)
        return SubmissionResult(self.ref.name, student, out, notes=list(notes))


def invalid_result(reference: Reference | None, student: str, error: str) -> SubmissionResult:
    """A submission that could not be read: every graded key `invalid`, score 0."""
    questions = []
    for qref in (reference.questions if reference else []):
        graded = qref.graded_keys()
        qr = QuestionResult(qref.id, fraction(qref.marks), graded, no_reference=qref.error is not None)
        for key in graded:
            qr.keys[key] = KeyResult(INVALID, feedback="the answers file could not be read")
        questions.append(qr)
    return SubmissionResult(reference.name if reference else "", student, questions, error=error)


def _gather(qt, key, given: dict):
    """The Given for a graded key; a record key may be given field by field (dotted)."""
    if key in given:
        return given[key]
    ak = qt.key(key)
    if ak is not None and ak.kind == R.RECORD:
        parts = {k[len(key) + 1:]: v for k, v in given.items() if k.startswith(key + ".")}
        if parts:
            first = next(iter(parts.values()))
            from robosolve.grading.answers import Given
            return Given(key, {k: v.value for k, v in parts.items()}, first.path[:-1], first.line)
    return None


def _all_blank(value) -> bool:
    """Every entry of a given value is still `~` (an untouched template key)."""
    if isinstance(value, dict):
        return all(_all_blank(v) for v in value.values())
    if isinstance(value, list):
        return all(_all_blank(v) for v in value)
    return value is None


def _schema_order(qt, given: dict) -> list:
    order = []
    for a in qt.answers:
        order.append(a.name)
        order += [f"{a.name}.{f.name}" for f in a.fields]
    return sorted(given, key=lambda k: order.index(k) if k in order else len(order))


def _finite_mask(tree, n: int) -> np.ndarray:
    mask = np.ones(n, dtype=bool)

    def walk(t):
        nonlocal mask
        if isinstance(t, dict):
            for v in t.values():
                walk(v)
        elif isinstance(t, (list, tuple)):
            for v in t:
                walk(v)
        elif isinstance(t, Equation):
            walk(t.residual)
        elif isinstance(t, np.ndarray):
            mask &= np.isfinite(t)

    walk(tree)
    return mask


def _pairs(g, e):
    """Aligned (given, expected) expression pairs of two trees of the same layout, or None."""
    if isinstance(e, dict):
        if not isinstance(g, dict) or set(g) != set(e):
            return None
        out = []
        for k in e:
            sub = _pairs(g[k], e[k])
            if sub is None:
                return None
            out += sub
        return out
    if isinstance(e, (list, tuple)):
        if not isinstance(g, (list, tuple)) or len(g) != len(e):
            return None
        out = []
        for a, b in zip(g, e):
            sub = _pairs(a, b)
            if sub is None:
                return None
            out += sub
        return out
    if isinstance(e, Equation) or isinstance(g, Equation):
        return None
    if isinstance(e, (sp.Basic, float, int)) and isinstance(g, (sp.Basic, float, int)):
        return [(sp.sympify(g), sp.sympify(e))]
    return None
