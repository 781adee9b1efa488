"""The reference answers of one problem, solved once, in a form worker processes can share.

`Reference.from_report` keeps what grading needs from the pipeline's `Report`: the
Problem (its names, so that a student's expression parses exactly like the problem's),
and for each question its Answer values (sympy in `symbolic`, floats in `numeric`), its
substitutions (parameters and `at`), marks and graded keys, and the roles of the
symbols for sampling. It pickles (no model, no steps, no figures), so `grade` solves in
the parent and sends it to the workers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import sympy as sp

from robosolve.grading.compare import Tolerance
from robosolve.grading.points import SymbolRoles
from robosolve.load.expressions import Namespace
from robosolve.questions.registry import question_type

DEFAULT_TOLERANCE = Tolerance(0.005, 1e-6)


def lookup(values: dict, key: str):
    """values['force']['lengths'] for 'force.lengths' (None when absent)."""
    cur = values
    for part in key.split("."):
        if not isinstance(cur, dict) or part not in cur:
            return None
        cur = cur[part]
    return cur


@dataclass
class QuestionRef:
    id: str
    type: str
    marks: object                  # sympy number
    grade: tuple                   # the question's `grade` list, or ()
    error: str | None
    symbolic: dict
    numeric: dict
    extra: dict
    subs: dict                     # Symbol -> exact value (parameters and `at`)
    roles: SymbolRoles
    frame: str
    form: tuple = ()               # the question's option keys (principal keys may depend on its form)
    alternatives: dict = field(default_factory=dict)   # key -> diagnosis -> value (alternatives.py)
    reach: tuple = ()              # IK: (residual expressions of the target, joint limits) (reach.py)

    def has(self, key: str) -> bool:
        qt = question_type(self.type)
        ak = qt.key(key)
        if ak is not None and ak.top:
            return key in self.extra
        return lookup(self.symbolic, key) is not None or lookup(self.numeric, key) is not None

    def graded_keys(self) -> tuple:
        if self.grade:
            return tuple(self.grade)
        principal = question_type(self.type).principal_keys_for(dict.fromkeys(self.form))
        if self.error is not None:
            return principal
        return tuple(k for k in principal if self.has(k))


@dataclass
class Reference:
    problem: object                # robosolve.load.problem.Problem
    questions: list                # QuestionRef, in the problem's order
    tolerance: Tolerance = DEFAULT_TOLERANCE
    cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def name(self) -> str:
        return self.problem.name

    def question(self, qid: str) -> QuestionRef | None:
        return next((q for q in self.questions if q.id == qid), None)

    @property
    def namespace(self) -> Namespace:
        from robosolve.grading.values import answers_namespace

        return answers_namespace(self.problem)

    @property
    def revolute(self) -> frozenset:
        return frozenset(j.name for j in self.problem.joints if j.is_revolute)

    def __getstate__(self):
        state = dict(self.__dict__)
        state["cache"] = {}
        return state

    @classmethod
    def from_report(cls, report, rtol=None, atol=None) -> "Reference":
        from robosolve.grading.alternatives import alternatives
        from robosolve.grading.reach import reach_data
        from robosolve.solvers.base import SolveContext

        problem = report.problem
        ctx = SolveContext(problem, None)
        answers = {a.id: a for a in report.answers}
        refs = []
        alts = alternatives(report)
        for q in problem.questions:
            a = answers[q.id]
            subs = ctx.substitutions(problem.working_at(q))     # a follower's: its reference's overrides beneath
            refs.append(QuestionRef(
                id=q.id, type=q.type, marks=q.marks, grade=tuple(q.grade), error=a.error,
                symbolic=dict(a.symbolic), numeric=dict(a.numeric), extra=dict(a.extra),
                subs=subs, roles=_roles(problem, q, subs, answers), frame=q.frame or problem.last_frame,
                form=tuple(q.options), alternatives=alts.get(q.id, {}),
                reach=reach_data(report.model, problem, q, subs) if question_type(q.type).reaches else ()))
        grading = problem.grading or {}
        tol = Tolerance(
            rtol if rtol is not None else grading.get("rtol", DEFAULT_TOLERANCE.rtol),
            atol if atol is not None else grading.get("atol", DEFAULT_TOLERANCE.atol))
        return cls(problem, refs, tol)


def _float(v) -> float | None:
    try:
        x = float(sp.N(v))
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def _roles(problem, q, subs, answers) -> SymbolRoles:
    params = {}
    for s, v in problem.parameters.items():
        value = subs.get(s)
        params[s] = _float(value) if value is not None else None
    joints = {}
    for j in problem.joints:
        lo, hi = -math.pi, math.pi
        if j.limits is not None:
            a, b = _float(j.limits[0].xreplace(subs)), _float(j.limits[1].xreplace(subs))
            if a is not None and b is not None and a < b:
                lo, hi = a, b
        joints[j.symbol] = (lo, hi)
    rates = {j.dot for j in problem.joints} | {j.ddot for j in problem.joints}
    actuators = {j.actuator for j in problem.joints}
    # t runs over the motion's duration: the answer's own T, else its profile's (a type with `uses_profile`)
    T = None
    own = answers.get(q.id)
    if own is not None and isinstance(own.numeric.get("T"), (int, float)):
        T = float(own.numeric["T"])
    ref = q.options.get("profile") if isinstance(q.options, dict) else None
    if T is None and isinstance(ref, str) and ref in answers:
        t_val = answers[ref].numeric.get("T")
        T = float(t_val) if isinstance(t_val, (int, float)) else None
    return SymbolRoles(params, joints, rates, actuators, problem.names.get("t"),
                       (0.0, T if T and T > 0 else 1.0))
