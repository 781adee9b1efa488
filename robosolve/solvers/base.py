"""What a solver receives (SolveContext) and returns (Answer).

A solver is a module `robosolve.solvers.<type>` with `solve(question, ctx) -> Answer`.
It does no I/O: the derivation is returned as `Step`s, figures as `FigureSpec`s
(plain numbers), and the renderers turn them into Markdown, JSON and PNG.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
from dataclasses import dataclass, field
import sympy as sp

from robosolve.core.parameters import resolve_parameters
from robosolve.core.simplify import DEFAULT_BUDGETS, SimplifyBudgets
from robosolve.core.timing import time_limit
from robosolve.dynamics.bridge import DYNAMICS_SECONDS, simulation_dynamics, dynamics_for
from robosolve.dynamics.numeric import NumericDynamics
from robosolve.dynamics.types import Dynamics
from robosolve.errors import MissingValues, SolverError, SymbolicTimeout
from robosolve.load.problem import Problem
from robosolve.motion.profiles import SyncProfile

__all__ = ["Answer", "Budgets", "FigureSpec", "MissingValues", "SolveContext", "Step",
           "missing_note"]


@dataclass(frozen=True)
class Budgets:
    """How much symbolic work a solve may spend before answering numerically.

    Frozen: a solve reads its budgets from its context; a test that wants a tiny budget
    builds a context with one (``SolveContext(problem, model, budgets=Budgets(...))``).
    """

    symbolic_seconds: float = 30.0      # one symbolic step (Jacobian, statics, ellipsoids)
    closed_form_seconds: float = 20.0   # a closed form (IK derivation, torques along a profile)
    dynamics_seconds: float = DYNAMICS_SECONDS   # the symbolic equations of motion (the bridge's)
    # The deterministic measure (spec §2: whether a step is done symbolically is decided by a
    # count, not the clock): a symbolic step whose input has more expression-tree nodes than
    # this is not attempted, and is answered numerically with a note. The seconds above are
    # then only a safety net for a machine much slower than usual (their note says so).
    symbolic_nodes: int = 800          # a 6R arm's Jacobian has ~1000 (its det search never ends)
    # The rank conditions of a wide Jacobian (kinematics/wide_rank.py, singularities.py): the ring
    # terms of its maximal minors and sub-minors (a UR5 flange's 3×6: 390, a Panda's 6×7: 479),
    # then the distinct expression nodes the search may factor: the UR5 flange's 3×6 about 1,300;
    # the flanges of random spherical-wrist 6R arms (tests/support/singular_probe.py) 2,400–8,200;
    # the Panda's 6×7 8,500 (its 24 mapped families checked singular by Robotics Toolbox's jacob0);
    # random 7-joint arms (a spherical arm plus a joint) 550–17,400; past it: the numeric distance
    # from singularity. 20,000 nodes are about 9 s of factoring here.
    rank_terms: int = 3000
    rank_nodes: int = 20000
    # The safety net around that counted search (CPU s): within rank_nodes it needs 1-9 s here
    # (a UR5 flange's 3×6: 1.7 s); the net is wide so that only a runaway step meets it, never
    # a slow or busy machine (a 30 s net was once met in CI, where the same step takes 1.7 s).
    rank_search_seconds: float = 120.0
    # Whole-question and whole-file wall-clock safety nets (s), covering the numeric route and
    # rendering too: past them a question is answered with an error, and the remaining
    # questions of the file are not attempted (each says why).
    question_seconds: float = 900.0
    file_seconds: float = 3600.0
    # op-count budgets of the simplification variants (robosolve/core/simplify.py)
    simplify: SimplifyBudgets = DEFAULT_BUDGETS


# Default budget of one symbolic step before a solver falls back to numbers.
SYMBOLIC_SECONDS = Budgets().symbolic_seconds


@dataclass
class Step:
    """One step of the worked solution.

    `text` is Markdown (inline LaTeX with $...$); each equation is rendered as a
    display formula `lhs = value` (value: a sympy object, or a LaTeX string);
    `table` is (header, rows) of strings.
    """

    title: str
    text: str = ""
    equations: list = field(default_factory=list)
    table: tuple | None = None


@dataclass
class FigureSpec:
    """A figure to draw: `kind` names the module robosolve.render.plots.<kind>."""

    name: str
    kind: str
    title: str
    data: dict


@dataclass
class Answer:
    """The answer to one question, in the layout of results.json (spec §2)."""

    type: str
    id: str
    symbolic: dict = field(default_factory=dict)
    numeric: dict = field(default_factory=dict)
    steps: list = field(default_factory=list)
    figures: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)     # keys beside `type` (e.g. unreachable, reason)
    error: str | None = None
    # (figure paths, results.json record) when a question helper printed the record already
    # (run/split_solve); a plain attribute, not a field: not part of the answer itself
    printed_record = None
    # (figure paths, Markdown blocks, compact names) when a question helper printed them already
    printed_markdown = None

    def note(self, text: str):
        if text not in self.notes:
            self.notes.append(text)


class _PlainNames:
    """No names given: sympy's LaTeX of every symbol, poses shown without their factors."""

    @property
    def symbols(self) -> dict:
        return {}

    @staticmethod
    def factors(frame: str) -> list:
        return []


class SolveContext:
    """What one problem's solve shares: the problem, the model, the budgets, earlier
    results (by question id, through typed accessors) and numeric helpers."""

    def __init__(self, problem: Problem, model=None, budgets: Budgets | None = None, names=None):
        self.problem = problem
        self.model = model
        self.budgets = budgets or Budgets()
        self._names = names     # render.chain_names.ChainNames, given by the run layer
        self.answers: dict[str, Answer] = {}      # earlier answers, by question id
        self._profiles: dict[str, SyncProfile] = {}
        self._trajectories: dict = {}

    @property
    def names(self):
        """The LaTeX names of the problem's symbols and poses (`symbols`, `factors(frame)`),
        handed in by whoever builds the context (run.pipeline.solve_context); a context built
        without them writes sympy's own LaTeX and no factors."""
        return self._names if self._names is not None else _PlainNames()

    @property
    def symbol_latex(self) -> dict:
        """symbol -> LaTeX (theta1_dot -> \\dot{\\theta}_{1}, multi-letter names upright)."""
        return self.names.symbols

    @property
    def step_seconds(self) -> float:
        """Seconds (CPU) of one symbolic step: a safety net only, whatever the number of joints
        (what is attempted is decided by counts: `symbolic_nodes`, `rank_terms`, `rank_nodes`)."""
        return self.budgets.symbolic_seconds

    # -- results of earlier questions ------------------------------------
    def record_profile(self, qid: str, profile: SyncProfile) -> None:
        """The synchronized profile of the profile question `qid` (for the types with `uses_profile`)."""
        self._profiles[qid] = profile

    def profile(self, qid: str) -> SyncProfile:
        """The SyncProfile of the profile question `qid`; SolverError when it has no answer."""
        prof = self._profiles.get(qid)
        if prof is None:
            raise SolverError(f"the motion profile '{qid}' has no answer")
        return prof

    def record_trajectory(self, qid: str, trajectory) -> None:
        """The converted work-space trajectory of the work-space trajectory question `qid`; None
        for a path that cannot be followed (it leaves the workspace or meets a singularity)."""
        self._trajectories[qid] = trajectory

    def trajectory(self, qid: str):
        """The trajectory of `qid` (its solver's `TaskTrajectory`); SolverError when
        it has no answer or cannot be followed."""
        if qid in self._trajectories and self._trajectories[qid] is None:
            raise SolverError(f"the task trajectory '{qid}' cannot be followed (its answer says where and "
                              "when): there is no reference to track")
        tr = self._trajectories.get(qid)
        if tr is None:
            raise SolverError(f"the task trajectory '{qid}' has no answer")
        return tr

    def working_at(self, question, answer: Answer | None = None) -> dict:
        """The `at` a question computes everything with: its own, on the parameter overrides of
        the profile or trajectory it follows (`Problem.working_at`: a follower works on the arm of
        its reference). `answer` gets a note naming the parameters it takes from the reference."""
        at = self.problem.working_at(question)
        taken = sorted(s.name for s in at if s not in question.at)
        if answer is not None and taken:
            ref = self.problem.followed(question)
            kind = "trajectory" if "trajectory" in question.options else "profile"
            answer.note(f"the arm of the {kind} '{ref.id}' it follows: its override{'s' if len(taken) > 1 else ''} "
                        f"of {', '.join(taken)} (its `at`) hold{'' if len(taken) > 1 else 's'} here too")
        return at

    def reference_under(self, qid: str, at: dict | None):
        """The question `qid` (a profile or a trajectory another question follows) with the
        parameter overrides of the follower's `at` on top of its own, or None when they change no
        parameter's value. A question computes everything with its parameters: a follower with
        `at: {L2: 0.45}` tracks the reference as the arm with L2 = 0.45 draws it (its task map,
        its start), not the recorded one of L2 = 0.4 under dynamics of 0.45."""
        params = {s: v for s, v in (at or {}).items() if s in self.problem.parameters}
        ref = next((q for q in self.problem.questions if q.id == qid), None)
        if not params or ref is None:
            return None
        merged = {**(ref.at or {}), **params}
        if self.parameter_values(_parameter_part(merged, self.problem)) == \
                self.parameter_values(_parameter_part(ref.at or {}, self.problem)):
            return None
        return dataclasses.replace(ref, at=merged)

    # -- dynamics (one derivation per model, cached by the bridge) --------
    def dynamics(self) -> Dynamics | None:
        """The symbolic equations of motion, or None past the dynamics budget."""
        try:
            return dynamics_for(self.model, self.budgets.dynamics_seconds)
        except SymbolicTimeout:
            return None

    def simulation_dynamics(self, subs: dict) -> tuple[NumericDynamics, Dynamics | None]:
        """(NumericDynamics, Dynamics or None) with the parameters of `subs`.

        Raises ValueError naming the parameters without a value.
        """
        params = {k: v for k, v in subs.items() if k in self.problem.parameters}
        if self.dynamics() is not None:
            return simulation_dynamics(self.model, subs, self.budgets.dynamics_seconds)
        missing = sorted(s.name for s, v in self.problem.parameters.items()
                         if v is None and s not in params)
        if missing:
            raise ValueError("no value for " + ", ".join(missing))
        return simulation_dynamics(self.model, params, self.budgets.dynamics_seconds)

    # -- numbers ---------------------------------------------------------
    def parameter_values(self, overrides: dict | None = None) -> dict:
        """Parameter symbol -> exact value, resolving expressions of other parameters."""
        return resolve_parameters(self.problem.parameters, overrides)

    def substitutions(self, at: dict | None = None) -> dict:
        """Parameters and the question's `at` values (joints, rates, overrides)."""
        at = at or {}
        values = self.parameter_values({s: v for s, v in at.items() if s in self.problem.parameters})
        out = dict(values)
        for s, v in at.items():
            if s not in self.problem.parameters:
                out[s] = v.xreplace(values)
        return out

    def missing(self, obj, subs: dict) -> list[str]:
        free = _free_symbols(obj)
        return sorted(s.name for s in free if s not in subs)

    def numeric(self, obj, subs: dict):
        """Evaluate a sympy object (expr, matrix, list, dict) to floats.

        Raises MissingValues naming every symbol without a value.
        """
        missing = self.missing(obj, subs)
        if missing:
            raise MissingValues(missing)
        return _to_float(obj, subs)

    def try_numeric(self, answer: Answer, key: str, obj, subs: dict, what: str | None = None):
        """answer.numeric[key] = numeric(obj), or a note naming what is missing."""
        try:
            answer.numeric[key] = self.numeric(obj, subs)
            return answer.numeric[key]
        except MissingValues as exc:
            answer.note(missing_note(what or key, exc.names, self.problem))
            return None

    def time_limit(self, seconds: float | None = None):
        """A time limit of `seconds` (default: the symbolic-step budget)."""
        return time_limit(self.budgets.symbolic_seconds if seconds is None else seconds)

    @staticmethod
    @contextlib.contextmanager
    def no_limit():
        yield


def _parameter_part(at: dict, problem: Problem) -> dict:
    return {s: v for s, v in at.items() if s in problem.parameters}


def missing_note(what: str, names, problem: Problem) -> str:
    nulls = [n for n in names if any(s.name == n and v is None for s, v in problem.parameters.items())]
    others = [n for n in names if n not in nulls]
    parts = []
    if nulls:
        parts.append("the null parameter" + ("s " if len(nulls) > 1 else " ") + ", ".join(nulls))
    if others:
        parts.append(", ".join(others) + " (give " + ("them" if len(others) > 1 else "it") + " in `at`)")
    return f"numeric {what} omitted: it needs " + " and ".join(parts)


def _free_symbols(obj) -> set:
    if isinstance(obj, dict):
        out = set()
        for v in obj.values():
            out |= _free_symbols(v)
        return out
    if isinstance(obj, (list, tuple)):
        out = set()
        for v in obj:
            out |= _free_symbols(v)
        return out
    if isinstance(obj, (sp.Basic, sp.MatrixBase)):
        return set(obj.free_symbols)
    return set()


def _to_float(obj, subs, memo=None):
    memo = {} if memo is None else memo
    if isinstance(obj, dict):
        return {k: _to_float(v, subs, memo) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_to_float(v, subs, memo) for v in obj]
    if isinstance(obj, sp.MatrixBase):
        return [[_scalar(e, subs, memo) for e in obj.row(i)] for i in range(obj.rows)]
    if obj is None:
        return None
    return _scalar(obj, subs, memo)


def _scalar(e, subs, memo=None) -> float:
    if isinstance(e, (int, float)):
        return float(e)
    e = sp.sympify(e)
    try:
        v = _float_value(e, subs, {} if memo is None else memo)
        if math.isfinite(v):
            return _clean(v)
    except (_NotFloat, ValueError, TypeError, OverflowError, ZeroDivisionError):
        pass
    v = e.xreplace(subs).evalf(17)
    try:
        return _clean(float(v))
    except TypeError:
        c = complex(v)
        if abs(c.imag) > 1e-9 * max(1.0, abs(c.real)):
            raise ValueError(f"complex value {c}") from None
        return _clean(c.real)


class _NotFloat(Exception):
    """An expression (or a value substituted) the float evaluation does not handle."""


_FLOAT_FUNCTIONS = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "exp": math.exp, "log": math.log,
                    "asin": math.asin, "acos": math.acos, "atan": math.atan, "atan2": math.atan2,
                    "sinh": math.sinh, "cosh": math.cosh, "tanh": math.tanh, "Abs": abs}


def _float_value(e, subs, memo) -> float:
    """The value of e at `subs` in double precision, node by node (each node once: the entries of
    a report's matrices share their subexpressions), without building the substituted sympy
    expression. Anything else than numbers, symbols with a numeric value, sums, products,
    powers with a real result and the elementary functions raises _NotFloat: such an
    expression is evaluated by sympy's evalf instead."""
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e.is_Number or e.is_NumberSymbol:
        v = float(e)
    elif e.is_Symbol:
        if e not in subs:
            raise _NotFloat(e)
        x = subs[e]
        if not isinstance(x, (int, float)) and not (isinstance(x, sp.Basic) and x.is_number):
            raise _NotFloat(e)
        c = complex(x)
        if c.imag:
            raise _NotFloat(e)
        v = c.real
    elif e.is_Add:
        v = math.fsum(_float_value(a, subs, memo) for a in e.args)
    elif e.is_Mul:
        v = 1.0
        for a in e.args:
            v *= _float_value(a, subs, memo)
    elif e.is_Pow:
        b, x = _float_value(e.base, subs, memo), _float_value(e.exp, subs, memo)
        if b < 0 and x != int(x):
            raise _NotFloat(e)
        v = b ** x
    else:
        f = _FLOAT_FUNCTIONS.get(type(e).__name__) if e.is_Function else None
        if f is None:
            raise _NotFloat(e)
        v = f(*(_float_value(a, subs, memo) for a in e.args))
    if isinstance(v, complex):
        raise _NotFloat(e)
    memo[e] = v
    return v


def _clean(x: float) -> float:
    return 0.0 if x == 0 else x

