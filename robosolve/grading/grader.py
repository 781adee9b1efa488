"""Grade one submission against a Reference: key verdicts, diagnoses, feedback, scores.

For each key: read the given value by the key's kind (registry schema); a value with no
free symbol is compared with the numeric answer (at the question's `at`), one with free
symbols with the symbolic answer, at seeded sample points (keys marked `by_value`, the
singularities, are compared as numbers whatever their form); then, when wrong, the
diagnoses of `diagnose.py`. Scores are exact fractions of the marks.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from fractions import Fraction

import numpy as np
import sympy as sp

from robosolve.core.plain import plain
from robosolve.core.simplify import is_zero
from robosolve.grading import diagnose as D
from robosolve.grading.compare import Rules, compare, equivalents
from robosolve.grading.conditions import expand, factor_conditions, one_joint_conditions
from robosolve.grading.pieces import has_piecewise, split_pieces, wrong_intervals
from robosolve.grading.points import evaluate, sample, single_point
from robosolve.grading.reach import set_reaches
from robosolve.grading.reference import Reference, lookup
from robosolve.grading.values import (ORDERED_MAP_KINDS, Equation, Pieces, Reader, ValueProblem, as_bool, blanks,
                                      entry_names, free_symbols, substitute)
from robosolve.questions import registry as R
from robosolve.questions.registry import question_type

CORRECT, INCORRECT, MISSING, INVALID, NO_REFERENCE = (
    "correct", "incorrect", "missing", "invalid", "no_reference")
MIN_POINTS = 6
PROVE_NODES = 2000                # above (expression nodes of the pairs): sympy is not asked to prove equality
PROVE_SECONDS = 30.0              # safety net of CPU time around a proof within PROVE_NODES
SUBSCRIPTS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")
MAX_SHOWN = 600                   # characters of an expected value quoted in feedback


@dataclass
class KeyResult:
    verdict: str
    compared: str = ""
    diagnosis: str = ""
    feedback: str = ""
    hidden: str | None = None      # the feedback without the expected value (None: feedback shows none)
    given: str = ""                # what the submission gave, as read
    expected: str = ""             # the expected value, as shown in the feedback
    credit: Fraction = Fraction(0)   # share of the key's marks earned when not correct (partial credit)

    @property
    def earned(self) -> Fraction:
        """The fraction of the key's share this verdict earns."""
        return Fraction(1) if self.verdict == CORRECT else self.credit

    def without_expected(self) -> "KeyResult":
        return replace(self, feedback=self.feedback if self.hidden is None else self.hidden,
                       hidden=None, expected="")

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
        return sum((self.share * self.keys[k].earned for k in self.graded), Fraction(0))

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
    note: str = ""                                # --variants: it answered another student's variant

    @property
    def score(self) -> Fraction:
        return sum((q.score for q in self.questions), Fraction(0))

    @property
    def max_score(self) -> Fraction:
        return sum((q.max_score for q in self.questions), Fraction(0))

    def without_expected(self) -> "SubmissionResult":
        """The same result with no expected value in any feedback (`--no-expected`)."""
        questions = [replace(q, keys={k: r.without_expected() for k, r in q.keys.items()})
                     for q in self.questions]
        return replace(self, questions=questions)

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
    if isinstance(tree, sp.MatrixBase):     # a reference's matrix (a key not given): as rows
        return _show(tree.tolist())
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
    if isinstance(tree, sp.Basic) and tree.is_number and tree.free_symbols == set():
        text = plain(tree)       # 1/3 and pi/6 as written; a 400-digit integer as 7.778e+399
        return text if len(text) <= 12 else _approximately(tree)
    return plain(tree) if isinstance(tree, sp.Basic) else str(tree)


def _approximately(number) -> str:
    """A long exact number in 4 significant digits (beyond floats' range too: 10**400)."""
    value = float(sp.N(number))
    if math.isfinite(value):
        return f"{value:.4g}"
    return str(sp.N(number, 4))


def as_written(value) -> str:
    """A value of an answers file as it was read (plain YAML data), in flow style."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {as_written(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(as_written(v) for v in value) + "]"
    if value is None:
        return "null"
    if isinstance(value, bool):
        return str(value).lower()
    return str(value)


def _wrong_given(outcome, g) -> str:
    """What is wrong, with what was given there but not the expected value (`--no-expected`)."""
    if outcome.where:
        parts = [f"{label} is {show(_at(g, p))}" for label, p in zip(outcome.wrong, outcome.where)][:3]
        parts += outcome.wrong[len(outcome.where):]          # entries not given ("no value for q2")
        more = len(outcome.where) - min(len(outcome.where), 3)
        return "wrong: " + "; ".join(parts) + (f" (and {more} more)" if more > 0 else "")
    if outcome.wrong and outcome.wrong != ["the value"]:
        return "wrong: " + ", ".join(outcome.wrong)
    return "this is not the expected value"


def _entry_count(ak, e) -> int:
    """The entries of a vector, matrix or per-joint mapping (per joint, actuator or task
    coordinate: a control question's errors) (0 for other kinds)."""
    if ak.kind == R.MATRIX and isinstance(e, list) and e and isinstance(e[0], list):
        return sum(len(row) for row in e)
    if ak.kind == R.VECTOR and isinstance(e, list):
        return len(e)
    if ak.kind in ORDERED_MAP_KINDS and isinstance(e, dict):
        return len(e)
    return 0


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
        self.reader = Reader(self.ns, joints=[(j.name, j.symbol) for j in reference.problem.joints],
                             actuators=[str(j.actuator) for j in reference.problem.joints])
        self.expected_reader = Reader(self.ns, expected=True)
        self.revolute = reference.revolute
        self.joint_names = {j.symbol: j.name for j in reference.problem.joints}
        self.parameters = set(reference.problem.parameters)
        grading = reference.problem.grading or {}
        self.partial = dict(grading.get("partial") or {})
        self.proportional = grading.get("entries") == "proportional"

    # -- one key ------------------------------------------------------------
    def symbol(self, qref, ak) -> str:
        frame = qref.frame
        sub = frame.translate(SUBSCRIPTS) if frame.isdigit() else f"[{frame}]"
        return ak.symbol.format(sub=sub, frame=frame)

    def grade_key(self, qref, key: str, given) -> KeyResult:
        result = self._grade_key(qref, key, given)
        return result if self.reveal else result.without_expected()

    def _grade_key(self, qref, key: str, given) -> KeyResult:
        if given is not None and given.problem:
            return KeyResult(INVALID, feedback=given.problem, given=as_written(given.value))
        qt = question_type(qref.type)
        ak = qt.key(key)
        if qref.error is not None:
            return KeyResult(NO_REFERENCE, feedback=f"robosolve could not answer this question ({qref.error}); "
                                                    "it is not graded")
        sym, num = self._reference(qref, ak, key)
        if sym is None and num is None:
            return KeyResult(NO_REFERENCE, feedback=f"the reference answer has no {key}")
        if given is None:
            expected = num if num is not None else sym
            shown = f"{self.symbol(qref, ak)} = {show(expected)}"
            return KeyResult(MISSING, feedback=f"not given; expected {shown}", hidden="not given",
                             expected=shown)
        holes = blanks(given.value, num if num is not None else sym)
        if holes:                 # a template's `~` left: not given yet (papers.md)
            listed = ", ".join(holes[:6]) + (f" (and {len(holes) - 6} more)" if len(holes) > 6 else "")
            what = "not filled in (still ~)" if _all_blank(given.value) else f"not filled in: {listed} still ~"
            expected = num if num is not None else sym
            shown = f"{self.symbol(qref, ak)} = {show(expected)}"
            return KeyResult(MISSING, feedback=f"{what}; expected {shown}", hidden=what, expected=shown,
                             given=as_written(given.value))
        result = self._read_and_compare(qref, ak, key, given, sym, num)
        result.given = as_written(given.value)
        return result

    def _read_and_compare(self, qref, ak, key, given, sym, num) -> KeyResult:
        try:
            g = self.reader.read(ak, given.value, entries=entry_names(self.ref.problem, qref.id, key))
            return self._compare(qref, ak, key, g, sym, num)
        except ValueProblem as exc:
            # a shape refused as it is read (three values for two joints) is the same mistake as
            # one found comparing (a 2x3 matrix for a 2x2): the same diagnosis, the same share
            diagnosis = "wrong_shape" if exc.wrong_shape else ""
            return KeyResult(INVALID, diagnosis=diagnosis, feedback=str(exc),
                             credit=self.partial.get(diagnosis, Fraction(0)) if diagnosis else Fraction(0))

    def _reference(self, qref, ak, key):
        if ak.top:
            return None, qref.extra.get(key)
        return lookup(qref.symbolic, key), lookup(qref.numeric, key)

    def _names(self, symbols) -> str:
        return ", ".join(sorted(s.name for s in symbols))

    def _compare(self, qref, ak, key, g, sym, num) -> KeyResult:
        subs = qref.subs
        conditions = []
        if ak.by_value and isinstance(g, list):     # `sin(theta2) = 0`: the values it stands for
            reference = self._expected(qref, ak, key, "symbolic", sym) if sym is not None else []
            g = factor_conditions(g, self.joint_names, self.revolute)
            g, conditions = one_joint_conditions(g, self.joint_names, self.revolute, reference)
        free = free_symbols(g) | free_symbols([el for el, _ in conditions])
        if ak.by_value:
            # singular conditions: compared as numbers when the reference has them as numbers;
            # else at sample points (its equations, up to a constant factor), their values
            # still compared at the problem's values only (compare.py)
            symbolic = sym is not None and num is None
        else:
            symbolic = bool(free) and sym is not None
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
                if left and not ak.by_value:    # (a condition in joints matches no value: wrong)
                    raise ValueProblem(f"{self._names(left)} {'has' if len(left) == 1 else 'have'} no value "
                                       "here: give numbers (or expressions of the parameters)")
            if num is not None:
                e = self._expected(qref, ak, key, "numeric", num)
            else:
                e = substitute(self._expected(qref, ak, key, "symbolic", sym), subs)
                left = free_symbols(e)
                if left:
                    which = "which has no value" if len(left) == 1 else "which have no values"
                    raise ValueProblem(f"the answer depends on {self._names(left)}, {which}: "
                                       "give it as an expression")
        return self._judge(qref, ak, key, g, e, symbolic, conditions)

    def _judge(self, qref, ak, key, g, e, symbolic: bool, conditions=()) -> KeyResult:
        """The verdict on the given tree `g` against the expected `e` (sympy trees), compared at
        sample points (`symbolic`) or at the question's values; `conditions`: singular conditions
        of one joint per equation, taken out of g (conditions.py)."""
        compared = "symbolic" if symbolic else "numeric"
        written = (g + [el for el, _ in conditions] if conditions else g), e    # for the feedback
        pieced = symbolic and (has_piecewise(g) or has_piecewise(e))
        if pieced:                     # profiles: compared piece by piece on [0, T] (pieces.py)
            roles = qref.roles
            g, e = split_pieces(g, e, roles.t_symbol, qref.subs, roles.t_range, self.tol)
        free = free_symbols(g) | free_symbols([el for el, _ in conditions])
        points = (sample(free | free_symbols(e), qref.roles, f"{self.ref.name}/{qref.id}/{key}")
                  if symbolic else single_point())
        ge = evaluate(g, points)
        ee = evaluate(e, points) if pieced else self._evaluated(qref, key, compared, e, points)
        mask = _finite_mask(ee, points.size)
        if symbolic and mask.sum() < MIN_POINTS:
            return self._prove(qref, ak, key, g, e)
        rules = Rules(self.tol, mask, self.revolute, fixed=points.fixed if symbolic else None)
        if conditions:
            ge = ge + self._condition_values(qref, conditions, ee, points, rules)
        outcome = compare(ak, ge, ee, rules)
        if not outcome.ok and any(compare(ak, ge, other, rules).ok for other in equivalents(ak, ge, ee, rules)):
            return KeyResult(CORRECT, compared)
        if outcome.ok or (ak.reaches and not symbolic and qref.reach
                          and set_reaches(qref.reach, ge, outcome.n_expected, self.revolute, self.tol)):
            return KeyResult(CORRECT, compared)
        if outcome.unknown:
            return KeyResult(INVALID, compared, feedback=outcome.unknown)
        if pieced:
            outcome.wrong = _named_intervals(outcome, ge, ee, ak, rules)
        g, e = written
        substituted = (free_symbols(e) & self.parameters) - free   # parameters the answer lacks
        alts = self._alternatives(qref, ak, key, compared, points)
        diagnosis = D.diagnose(ak, ge, ee, rules, outcome, symbolic and bool(substituted), alts)
        symbol = self.symbol(qref, ak)
        shown = f"{symbol} = {show(e)}"
        expected_text = f"expected {shown}"
        credit = self._credit(ak, diagnosis, outcome, e)
        if diagnosis:
            params = self._names(substituted)
            text = D.sentence(diagnosis, ak, symbol=symbol, frame=qref.frame, outcome=outcome, params=params)
            verdict = INVALID if diagnosis == "wrong_shape" else INCORRECT
            return KeyResult(verdict, compared, diagnosis, f"{text}; {expected_text}", hidden=text,
                             expected=shown, credit=credit)
        return KeyResult(INCORRECT, compared, "", self._wrong_entries(outcome, g, e) + expected_text,
                         hidden=_wrong_given(outcome, g), expected=shown, credit=credit)

    def _condition_values(self, qref, conditions, ee, points, rules) -> list:
        """The evaluated elements the singular conditions of one joint per equation stand for
        (conditions.py), compared with the reference's values as compare.py compares them;
        a condition that stands for no roots stays the equation it is."""
        from robosolve.grading.compare import leaf_ok, value_rules

        by_value = value_rules(rules)
        if points.symbols:
            columns = points.columns
        else:
            columns = {s: np.array([_number(v)]) for s, v in qref.subs.items() if s not in self.joint_names}
        out = []
        for el, parts in conditions:
            values = expand(parts, ee, columns, points.size,
                            lambda a, b, name: leaf_ok(a, b, name in self.revolute, by_value))
            out += values if values is not None else [evaluate(el if points.symbols else substitute(el, qref.subs),
                                                               points)]
        return out

    def _credit(self, ak, diagnosis: str, outcome, e) -> Fraction:
        """Partial credit (grading.md): the diagnosis's share, or the share of entries right."""
        credit = self.partial.get(diagnosis, Fraction(0)) if diagnosis else Fraction(0)
        if self.proportional and not outcome.shape and not outcome.unknown:
            total = _entry_count(ak, e)
            if total:
                credit = max(credit, Fraction(max(total - len(outcome.wrong), 0), total))
        return credit

    def _alternatives(self, qref, ak, key, mode, points) -> dict:
        """diagnosis -> the evaluated value that mistake gives (grading/alternatives.py)."""
        out = {}
        for diagnosis, value in qref.alternatives.get(key, {}).items():
            try:
                tree = self._expected(qref, ak, key, f"alt:{diagnosis}", value)
                if mode == "numeric":
                    tree = substitute(tree, qref.subs)
                    if free_symbols(tree):
                        continue
                    out[diagnosis] = evaluate(tree, points)
                elif free_symbols(tree) <= set(points.symbols):
                    out[diagnosis] = evaluate(tree, points)
            except (ValueProblem, TypeError, ValueError, ZeroDivisionError):
                continue
        return out

    def _wrong_entries(self, outcome, g, e) -> str:
        if outcome.where:
            parts = [f"{label} is {show(_at(g, p))}; expected {show(_at(e, p))}"
                     for label, p in zip(outcome.wrong, outcome.where)][:3]
            parts += outcome.wrong[len(outcome.where):]      # entries not given ("no value for q2")
            more = len(outcome.where) - min(len(outcome.where), 3)
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
        shown = f"{self.symbol(qref, ak)} = {show(e)}"
        if pairs is None:
            return KeyResult(INCORRECT, "symbolic", "", f"expected {shown}",
                             hidden="this is not the expected value", expected=shown)
        from robosolve.core.simplify import expression_nodes

        # whether sympy is asked is a count (the same verdict on every machine); the time limit
        # is a safety net above it. The same expression written back (a closed form copied from
        # the report, in r11…r33 and px, py, pz, whose random samples leave acos undefined) is
        # equal whatever its size.
        try:
            with time_limit(PROVE_SECONDS):
                copied = all(_written_alike(a, b) for a, b in pairs)
        except SymbolicTimeout:
            copied = False
        if copied:
            same = True
        elif expression_nodes(list(pairs)) > PROVE_NODES:
            same = False
        else:
            try:
                with time_limit(PROVE_SECONDS):
                    same = all(is_zero(a - b) for a, b in pairs)
            except SymbolicTimeout:
                same = False
        if same:
            return KeyResult(CORRECT, "symbolic")
        return KeyResult(INCORRECT, "symbolic", "", f"could not be confirmed equal; expected {shown}",
                         hidden="could not be confirmed equal", expected=shown)

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


def invalid_result(reference: Reference | None, student: str, error: str, reason: str = "",
                   known: bool = True) -> SubmissionResult:
    """A submission that could not be graded: every graded key `invalid` (its feedback the
    reason: by default, that the file could not be read), score 0. `known`: the reference is
    the submission's own problem (else it only gives the questions, e.g. of any variant)."""
    reason = reason or "the answers file could not be read"
    questions = []
    for qref in (reference.questions if reference else []):
        graded = qref.graded_keys()
        qr = QuestionResult(qref.id, fraction(qref.marks), graded, no_reference=qref.error is not None)
        for key in graded:
            qr.keys[key] = KeyResult(INVALID, feedback=reason)
        questions.append(qr)
    return SubmissionResult(reference.name if reference and known else "", student, questions, error=error)


def _gather(qt, key, given: dict):
    """The Given for a graded key; a record key may be given field by field (dotted)."""
    from robosolve.grading.answers import Given

    if key in given:
        return given[key]
    ak = qt.key(key)
    said = given.get("unreachable")
    if (said is not None and as_bool(said.value) is True and qt.key("unreachable") is not None
            and ak is not None and ak.kind == R.JOINT_MAP_SET):
        # `unreachable: true` alone says the set of solutions is empty, as the reference writes
        # it (`solutions: []` beside it): graded as that empty set, right or wrong
        return Given(key, [], said.path[:-1] + (key,), said.line)
    if ak is not None and ak.kind == R.RECORD:
        parts = {k[len(key) + 1:]: v for k, v in given.items() if k.startswith(key + ".")}
        if parts:
            first = next(iter(parts.values()))
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


def _named_intervals(outcome, ge, ee, ak, rules) -> list:
    """The labels of the wrong entries, a profile's with the intervals of t where it is wrong
    ("theta1 (wrong for t in [0.8862, 1.772])")."""
    from robosolve.grading.compare import leaf_ok

    labels = list(outcome.wrong)
    for i, path in enumerate(outcome.where):
        a, b = _at(ge, path), _at(ee, path)
        if i < len(labels) and isinstance(a, Pieces) and isinstance(b, Pieces):
            angle = ak.angle and path[-1] in rules.revolute
            spans = [f"[{x:.4g}, {y:.4g}]" for x, y in
                     wrong_intervals(a, b, lambda u, v: leaf_ok(u, v, angle, rules))]
            if spans:
                labels[i] += f" (wrong for t in {', '.join(spans)})"
    return labels


def _number(v) -> float:
    try:
        return float(sp.N(v))
    except (TypeError, ValueError):
        return float("nan")


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
        elif isinstance(t, Pieces):
            walk(t.parts)
        elif isinstance(t, np.ndarray):
            mask &= np.isfinite(t)

    walk(tree)
    return mask


def _decimals_rounded(e):
    """e with its decimals at 12 significant digits: the report prints 15, its own values hold more."""
    e = sp.sympify(e)
    floats = e.atoms(sp.Float)
    return e.xreplace({f: sp.Float(float(f"{float(f):.12g}"), 15) for f in floats}) if floats else e


def _written_alike(a, b) -> bool:
    """a and b the same expression up to the order of its terms, the signs factored out and the
    decimals' last digits (no simplification: expanded, both are the same sum)."""
    a, b = _decimals_rounded(a), _decimals_rounded(b)
    return a == b or sp.expand(a - b) == 0


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
    if isinstance(e, Pieces) and isinstance(g, Pieces):
        return _pairs(list(g.parts), list(e.parts))
    if isinstance(e, (Equation, Pieces)) or isinstance(g, (Equation, Pieces)):
        return None
    if isinstance(e, (sp.Basic, float, int)) and isinstance(g, (sp.Basic, float, int)):
        return [(sp.sympify(g), sp.sympify(e))]
    return None
