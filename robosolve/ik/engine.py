"""Inverse kinematics: equations in, every solution out (closed form + numeric).

`solve_ik` takes plain sympy: equations ``lhs(q) = rhs`` (parameters may stay
symbolic in them; `values` gives every non-joint symbol a number), the joints
with their kind and limits, and returns an `IKResult`: the solutions inside
the limits (sorted, angles wrapped into (-pi, pi]), those rejected with the
limit they break, the selected one, the closed form with its derivation when
one was found, and for an unreachable target a reason a student understands.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from robosolve.core.plain import plain
from robosolve.core.prose import Num, Text
from robosolve.core.simplify import factored
from robosolve.core.timing import time_limit
from robosolve.errors import SymbolicTimeout as Timeout
from robosolve.ik import closed_form as cfm
from robosolve.ik.numeric import (
    DEDUPE_TOL,
    lambdify_system,
    solve_all,
    sort_solutions,
    wrap_angle,
)
from robosolve.core.printing import latex

LIMIT_TOL = 1e-9


@dataclass
class IKJoint:
    symbol: sp.Symbol
    revolute: bool = True
    limits: tuple[float, float] | None = None

    @property
    def name(self) -> str:
        return str(self.symbol)


@dataclass
class IKResult:
    status: str = "ok"                  # ok | unreachable | redundant | overdetermined | family
    solutions: list[dict] = field(default_factory=list)      # inside the limits, sorted
    all_solutions: list[dict] = field(default_factory=list)  # before the limits
    singular: list[bool] = field(default_factory=list)       # per solution: J loses rank there
    rejected: list[tuple[dict, list[str]]] = field(default_factory=list)
    selected: dict | None = None
    selected_index: int | None = None
    closed_form: cfm.ClosedForm | None = None
    closed_form_branches: list[dict] = field(default_factory=list)
    closed_form_values: list[dict] = field(default_factory=list)   # valid branches, evaluated
    closed_form_note: str | None = None
    closed_form_subset: list | None = None   # over-determined: the equations the closed form uses
    agree: bool | None = None           # closed-form and numeric sets are the same
    reason: str | None = None           # plain text (results.json)
    reason_tex: str | None = None       # with $...$ (report)
    notes: list[str] = field(default_factory=list)
    family: dict | None = None          # a continuum: free joints, parametrization
    subsets: list[dict] = field(default_factory=list)   # over-determined: each choice of n equations
    nearest: dict | None = None         # unreachable: the closest configuration found
    nearest_residual: float | None = None   # its largest equation residual (over-determined)
    angular: list[bool] = field(default_factory=list)


# ---------------------------------------------------------------------------
# helpers

def is_angular(expr, joints: list[IKJoint]) -> bool:
    """An orientation equation: an integer combination of angles (+ constants), compared mod 2 pi."""
    qs = [j.symbol for j in joints]
    e = sp.expand(expr)
    if not any(q in e.free_symbols for q in qs):
        return False
    try:
        p = sp.Poly(e, *qs)
    except sp.PolynomialError:
        return False
    if p.total_degree() != 1:
        return False
    const = e.subs({q: 0 for q in qs})
    if any(q in const.free_symbols for q in qs):
        return False
    for j in joints:
        c = p.coeff_monomial(j.symbol)
        if c == 0:
            continue
        if not j.revolute or not (c.is_Integer):
            return False
    return True


def chop_noise(e):
    """Float noise such as cos(pi/2) = 6e-17 from a float twist would hide the structure."""
    tiny = {f: 0 for f in e.atoms(sp.Float) if abs(f) < 1e-12}
    return sp.expand(e.xreplace(tiny)) if tiny else e


def _fmt(v: float) -> Num:
    """A number in a reason: raw, with the 4 digits a reader needs (the renderer formats)."""
    return Num(v, digits=4)


def in_limits(q: dict, joints: list[IKJoint]) -> list[Text]:
    """The limits a configuration breaks (empty when inside), as sentences."""
    broken = []
    for j in joints:
        if j.limits is None:
            continue
        lo, hi = j.limits
        v = q[j.name]
        if j.revolute:
            # any representative v + 2 pi k inside the limits will do
            ok = False
            k0 = math.floor((lo - v) / (2 * math.pi)) - 1
            for k in range(k0, k0 + 4):
                w = v + 2 * math.pi * k
                if lo - LIMIT_TOL <= w <= hi + LIMIT_TOL:
                    ok = True
                    break
        else:
            ok = lo - LIMIT_TOL <= v <= hi + LIMIT_TOL
        if not ok:
            if v < lo:
                broken.append(Text(f"{j.name} = ", _fmt(v), " < ", _fmt(lo), " (lower limit)"))
            else:
                broken.append(Text(f"{j.name} = ", _fmt(v), " > ", _fmt(hi), " (upper limit)"))
    return broken


def _distance(a: dict, b: dict, joints) -> float:
    s = 0.0
    for j in joints:
        d = a[j.name] - b[j.name]
        if j.revolute:
            d = wrap_angle(d)
        s += d * d
    return math.sqrt(s)


def _same(a: dict, b: dict, joints, tol=DEDUPE_TOL) -> bool:
    for j in joints:
        d = abs(a[j.name] - b[j.name])
        if j.revolute:
            d = min(d, 2 * math.pi - d)
        if d > tol * max(1.0, abs(a[j.name])):
            return False
    return True


def _scale(values: dict) -> float:
    nums = [abs(float(v)) for v in values.values() if v is not None]
    return max([1.0] + nums)


def _boxes(joints, scale):
    out = []
    for j in joints:
        if j.revolute:
            out.append((-math.pi, math.pi))
        else:
            lo, hi = -3.0 * scale, 3.0 * scale
            if j.limits is not None:
                w = max(j.limits[1] - j.limits[0], 1e-3)
                lo = min(lo, j.limits[0] - w)
                hi = max(hi, j.limits[1] + w)
            out.append((lo, hi))
    return out


def _numeric_system(exprs, joints, values, angular):
    subs = {k: v for k, v in values.items()}
    num = [sp.sympify(e).subs(subs) for e in exprs]
    for e in num:
        extra = e.free_symbols - {j.symbol for j in joints}
        if extra:
            raise ValueError("no value for " + ", ".join(sorted(map(str, extra))))
    return lambdify_system(num, [j.symbol for j in joints], [j.revolute for j in joints], angular,
                           _scale(values))


# ---------------------------------------------------------------------------
# unreachable: reasons

def _positive(expr):
    """Simplify assuming every symbol positive (lengths): sqrt((L1 + L2)^2) -> L1 + L2."""
    reps = {s: sp.Symbol(s.name, positive=True) for s in expr.free_symbols}
    back = {v: k for k, v in reps.items()}
    e = expr.xreplace(reps)
    if isinstance(e, sp.Pow) and e.exp == sp.Rational(1, 2):
        e = sp.sqrt(factored(e.base))
    return e.xreplace(back)


class _Fmt:
    """Formats reasons as LaTeX (report) or as plain text (results.json)."""

    def __init__(self, tex=None, plain=False):
        self.plain = plain
        self.tex = tex or latex

    def __call__(self, e) -> str:
        if self.plain:
            return e if isinstance(e, str) else plain(e)
        return "$" + (e if isinstance(e, str) else self.tex(e)) + "$"

    def name(self, latex_name: str, joint) -> str:
        return str(joint) if self.plain else f"${latex_name}$"

    def fn(self, fn: str, latex_name: str, joint, shift=False) -> str:
        if self.plain:
            return f"{fn}({joint} - phi)" if shift else f"{fn}({joint})"
        return f"$\\{fn}({latex_name} - \\varphi)$" if shift else f"$\\{fn} {latex_name}$"


def _distance_reason(st: cfm.Stage, target_syms: set, values: dict, F: _Fmt, aux=None):
    """'distance sqrt(x^2 + y^2) = 1.31 > L1 + L2 = 1.10' for a cos/sin/phase stage, or None."""
    if st.equation is None or st.rule not in ("cos", "sin", "phase"):
        return None
    abc = cfm.trig_linear(st.equation, st.joint)
    if abc is None:
        return None
    a, b, c = abc
    T = sorted([s for s in c.free_symbols if s in target_syms], key=sp.default_sort_key)
    if not T:
        return None
    c = sp.expand(c)
    d2 = sp.Integer(0)
    for t in T:
        if sp.expand(c.coeff(t, 2) - 1) != 0:
            return None
        d2 += (t + c.coeff(t, 1) / 2) ** 2
    rest = sp.expand(c - sp.expand(d2))
    rest_red = rest
    args = sorted({x.args[0] for x in rest.atoms(sp.sin, sp.cos) if x.args[0].is_Symbol}, key=sp.default_sort_key)
    if args:
        g, back, rel = cfm._to_poly_symbols(rest, args)
        rest_red = sp.expand(cfm._reduce_pythagoras(g, rel).subs(back))
    if any(s in rest_red.free_symbols for s in T):
        return None
    # e = a cos + b sin + d2 + rest = 0  ->  d2 in [-rest - r, -rest + r]
    r = sp.sqrt(a**2 + b**2)
    lo2, hi2 = -rest_red - r, -rest_red + r
    try:
        dv = math.sqrt(max(0.0, float(d2.evalf(subs=values))))
        hv = math.sqrt(max(0.0, float(hi2.evalf(subs=values))))
        lv = math.sqrt(max(0.0, float(lo2.evalf(subs=values))))
    except (TypeError, ValueError):
        return None
    d_sym = sp.sqrt(d2.subs(aux or {}))
    if dv > hv:
        return Text(f"distance {F(d_sym)} = ", _fmt(dv), " > ", *_bound(sp.sqrt(hi2), hv, F),
                    ": the target is beyond the reach of the arm")
    if dv < lv:
        return Text(f"distance {F(d_sym)} = ", _fmt(dv), " < ", *_bound(sp.sqrt(lo2), lv, F),
                    ": the target is too close, inside the unreachable inner region")
    return None


def _bound(expr, value: float, F: _Fmt) -> tuple:
    """'L2 + L3 = 0.7', or the value alone when the bound is a number (an arm of decimals: its
    sympy string, 1.18430000000000, was written before the value)."""
    if not expr.free_symbols:
        return (_fmt(value),)
    return (f"{F(_positive(expr))} = ", _fmt(value))


def _stage_reason(fail, cf: cfm.ClosedForm, target_syms, values, names, F: _Fmt, aux=None) -> str:
    k, joint, ex = fail
    st = cf.stages[k]
    lname = names.get(joint, latex(joint))
    name = F.name(lname, joint)
    dist = _distance_reason(st, target_syms, values, F, aux or {})
    if ex.what in ("acos", "asin"):
        fn = "cos" if ex.what == "acos" else "sin"
        word = "cosine" if fn == "cos" else "sine"
        base = Text(f"the equation for {name} needs {F.fn(fn, lname, joint, st.rule == 'phase')} = ",
                    _fmt(ex.value), f", impossible because a {word} lies in [-1, 1]")
        return dist + Text(" (", base, ")") if dist else base
    if ex.what == "sqrt":
        return Text(f"solving for {name} needs the square root of a negative number (", _fmt(ex.value), ")")
    if ex.what == "atan2":
        return f"{name} is undetermined (atan2(0, 0)): the configuration is singular"
    return f"solving for {name} fails ({ex.what})"


# main entry

def solve_ik(
    equations: list[tuple],
    joints: list[IKJoint],
    values: dict,
    select="limits",
    closed_form: bool = True,
    time_limit_s: float | None = 20.0,
    target_symbols=(),
    latex_names: dict | None = None,
    budget: int | None = None,
    tex=None,
    labels: list[str] | None = None,
    subsets: bool = True,
    derived=None,
) -> IKResult:
    """Solve ``lhs_k(q) = rhs_k`` for the joints. See the module docstring.

    The counts decide: equations involving fewer joints than there are, fewer equations than
    joints (redundant), more (over-determined), or a square system (closed form, then numbers).
    An over-determined system with no solution has each choice of n equations solved unless
    `subsets` is false (a pose's 12 equations: the choices mean nothing there); `nearest` is then
    the closest configuration found. `derived`: the closed form of these same (square) equations,
    derived before for other values of the known symbols, evaluated instead of derived again.
    """
    res = IKResult()
    names = latex_names or {j.symbol: latex(j.symbol) for j in joints}
    exprs = [chop_noise(sp.sympify(l) - sp.sympify(r)) for l, r in equations]
    kept = _leave_out_constant_equations(res, equations, exprs, joints, values, labels)
    if kept is None:
        return res
    equations, exprs = kept
    res.angular = [is_angular(e, joints) for e in exprs]
    n, m = len(joints), len(exprs)

    used = [j for j in joints if any(j.symbol in e.free_symbols for e in exprs)]
    unused = [j.name for j in joints if j not in used]
    if unused:
        res.notes.append(f"{', '.join(unused)} appear{'s' if len(unused) == 1 else ''} in no equation: "
                         f"{'it is' if len(unused) == 1 else 'they are'} not determined by this target")
    if m > len(used) and unused:
        _overdetermined_with_free_joints(res, exprs, used, unused, values, budget)
    elif m < n:
        res.status = "redundant"
        _redundant(res, exprs, joints, values, names, time_limit_s, tex)
    elif m > n:
        _overdetermined(res, exprs, joints, values, names, select, closed_form, time_limit_s, budget, tex,
                        subsets)
    else:
        _square(res, equations, exprs, joints, values, names, select, closed_form, time_limit_s,
                set(target_symbols), budget, tex, derived)
    return res


def _leave_out_constant_equations(res, equations, exprs, joints, values, labels):
    """Leave out, with a note, the equations with no joint in them (the robot cannot change that
    coordinate): (equations, exprs) kept, or None when one contradicts the target (res says why)."""
    qset = {j.symbol for j in joints}
    constant = [k for k, e in enumerate(exprs) if not (e.free_symbols & qset)]
    if not constant:
        return equations, exprs
    for k in constant:
        lhs, rhs = equations[k]
        try:
            lv = float(sp.sympify(lhs).evalf(subs=values))
            rv = float(sp.sympify(rhs).evalf(subs=values))
        except (TypeError, ValueError):
            continue
        if abs(lv - rv) > 1e-9 * max(1.0, abs(rv)):
            res.status = "unreachable"
            lab = labels[k] if labels else str(sp.sympify(lhs))
            res.reason = Text(f"{lab} is ", _fmt(lv), " whatever the joints, but the target asks ", _fmt(rv))
            res.reason_tex = Text(f"`{lab}` is ", _fmt(lv), " whatever the joints, but the target asks ",
                                  _fmt(rv))
            return None
    which = ", ".join(labels[k] if labels else f"equation {k + 1}" for k in constant)
    if len(constant) == len(exprs):
        return _every_configuration(res, joints, which)
    res.notes.append(f"{which} {'hold' if len(constant) > 1 else 'holds'} whatever the joints "
                     f"(no joint in {'them' if len(constant) > 1 else 'it'}): left out")
    return ([eq for k, eq in enumerate(equations) if k not in constant],
            [e for k, e in enumerate(exprs) if k not in constant])


def _every_configuration(res, joints, which):
    """No joint in any equation, and each holds: the point does not depend on the joints (a chain
    with zero-length links), so every configuration reaches the target. One example inside the
    limits (0, else the middle of the range) stands for the continuum; returns None (res is final)."""
    example = {}
    for j in joints:
        lo, hi = j.limits if j.limits is not None else (None, None)
        inside = (lo is None or lo <= 0) and (hi is None or hi >= 0)
        example[j.name] = 0.0 if inside else float(lo + hi) / 2
    res.status = "family"
    res.family = {"free": [j.name for j in joints], "fixed": {}, "example": example}
    res.notes.append(f"{which} {'hold' if ',' in which else 'holds'} whatever the joints: the point does "
                     "not depend on them (a chain with zero-length links), so every configuration "
                     "reaches the target, a continuum of solutions; the one listed is an example")
    res.solutions, res.all_solutions, res.singular = [example], [example], [True]
    res.selected, res.selected_index = example, 0
    return None


def _overdetermined_with_free_joints(res, exprs, used, unused, values, budget):
    """More equations than the joints they involve, while other joints are in none."""
    m, m_eff = len(exprs), len(used)
    res.status = "overdetermined"
    res.reason = (f"{m} equations involve only {m_eff} joint{'s' if m_eff != 1 else ''} "
                  f"({', '.join(j.name for j in used)}); {', '.join(unused)} "
                  f"{'is' if len(unused) == 1 else 'are'} free. Choose {m_eff} of the {m} equations "
                  f"for {', '.join(j.name for j in used)}, and add an equation for {', '.join(unused)}.")
    _solve_subsets(res, exprs, used, values, budget)


def _overdetermined(res, exprs, joints, values, names, select, closed_form, time_limit_s, budget, tex,
                    subsets=True):
    """More equations than joints: solved together when they are consistent here, else each
    choice of n of them is solved."""
    n, m = len(joints), len(exprs)
    system = _numeric_system(exprs, joints, values, res.angular)
    boxes = _boxes(joints, _scale(values))
    num = solve_all(system, boxes, budget, deflation=False)
    if num.solutions:
        res.notes.append(f"{m} equations for {n} unknowns: they are consistent here, "
                         f"so the solutions satisfy all of them.")
        cf_sols = None
        if closed_form and n <= 4:
            cf, subset = _closed_form_subset(exprs, joints, names, tex, time_limit_s)
            if cf is not None:
                res.closed_form, res.closed_form_subset = cf, subset
                res.closed_form_branches = cf.branches()
                cf_sols, _, _ = _cf_solutions(cf, values, joints, system)
                res.closed_form_values = cf_sols
        if not _confirmed(num, cf_sols, joints):
            num = solve_all(system, boxes, budget)
        _finish(res, num, cf_sols, joints, values, select, system)
        return
    res.status = "overdetermined"
    if not subsets:
        if num.best_q is not None:
            res.nearest = {j.name: (wrap_angle(v) if j.revolute else v) for j, v in zip(joints, num.best_q)}
            res.nearest_residual = float(num.best_residual)
        res.reason = f"{m} equations for {n} unknown joints: no configuration satisfies all of them"
        return
    res.reason = (f"{m} equations for {n} unknown joints: no configuration satisfies all of "
                  f"them. Choose {n} of the {m} equations (each choice is solved below).")
    _solve_subsets(res, exprs, joints, values, budget)


def _square(res, equations, exprs, joints, values, names, select, closed_form, time_limit_s,
            target_syms, budget, tex, derived=None):
    """As many equations as joints: closed form first (under a time limit), then numbers; the
    two sets are merged, and an unreachable target gets its reason."""
    if derived is not None:
        cf = res.closed_form = derived
        res.closed_form_branches = cf.branches()
    else:
        cf = _square_closed_form(res, exprs, joints, names, time_limit_s, tex) if closed_form else None
    system = _numeric_system(exprs, joints, values, res.angular)
    cf_fail, cf_partial = None, {}
    if cf is not None:
        cf_fail, cf_partial = _evaluate_closed_form(res, cf, values, joints, system, tex)
    boxes = _boxes(joints, _scale(values))
    num = solve_all(system, boxes, budget, deflation=False) if cf is not None else None
    if not _confirmed(num, res.closed_form_values if cf is not None else None, joints):
        num = solve_all(system, boxes, budget)
    _finish(res, num, res.closed_form_values if cf is not None else None, joints, values, select, system)
    if res.status == "unreachable" and res.reason is None:
        _unreachable_reason(res, cf, cf_fail, cf_partial, equations, joints, values, names, target_syms, tex)
    if res.reason_tex is None:
        res.reason_tex = res.reason


def _confirmed(num, cf_sols, joints) -> bool:
    """The solutions from the numeric search's starts are exactly the closed form's verified ones
    (at least one, no continuum): two independent methods agree, and the deflation pass that
    looks for solutions the starts missed is not needed."""
    if num is None or not cf_sols or num.family or len(num.solutions) != len(cf_sols):
        return False
    found = [{j.name: v for j, v in zip(joints, s.q)} for s in num.solutions]
    return (all(any(_same(c, d, joints) for d in found) for c in cf_sols)
            and all(any(_same(c, d, joints) for c in cf_sols) for d in found))


def _square_closed_form(res, exprs, joints, names, time_limit_s, tex):
    """The closed form (also in res.closed_form), or None with res.closed_form_note saying why."""
    cf = None
    try:
        with time_limit(time_limit_s):
            cf = cfm.derive(exprs, [j.symbol for j in joints], [j.revolute for j in joints], names,
                            res.angular, tex=tex)
            res.closed_form_branches = cf.branches()
    except cfm.NoClosedForm as ex:
        res.closed_form_note = f"no closed form: {ex}"
    except Timeout:
        res.closed_form_note = f"no closed form within {time_limit_s:g} s"
    except (RecursionError, sp.PolynomialError, ValueError, TypeError, ZeroDivisionError,
            NotImplementedError) as ex:  # pragma: no cover - defensive
        res.closed_form_note = f"no closed form ({type(ex).__name__})"
    if cf is None:
        res.closed_form_branches = []
    res.closed_form = cf
    return cf


def _evaluate_closed_form(res, cf, values, joints, system, tex):
    """res.closed_form_values: the verified branches, none when the target breaks one of the
    closed form's compatibility conditions (res.reason names them).  Returns the first failing
    branch's (failure, values found before it)."""
    cf_sols, cf_fail, cf_partial = _cf_solutions(cf, values, joints, system)
    bad = []
    for c in cf.conditions:
        try:
            v = float(c.evalf(subs=values))
        except (TypeError, ValueError):
            continue
        if abs(v) > 1e-9 * _scale(values):
            bad.append(c)
    if bad:
        cf_sols = []
        res.reason = ("the target is incompatible with the robot: it requires "
                      + ", ".join(f"{c} = 0" for c in bad))
        res.reason_tex = ("the target is incompatible with the robot: it requires "
                          + ", ".join(f"${(tex or latex)(c)} = 0$" for c in bad))
    res.closed_form_values = sort_solutions(cf_sols, get=lambda d: [d[j.name] for j in joints])
    return cf_fail, cf_partial


def _unreachable_reason(res, cf, cf_fail, cf_partial, equations, joints, values, names, target_syms, tex):
    """Why no configuration reaches the target: the closed-form stage that fails (beyond reach,
    a cosine outside [-1, 1]...), else what the closest configuration found gives."""
    if cf is not None and cf_fail is not None and not res.all_solutions:
        aux = {st.joint: st.alternatives[0] for st in cf.stages if st.rule == "aux"}
        vals = dict(values)
        vals.update(cf_partial)
        tsyms = set(target_syms) | set(aux)
        res.reason = _stage_reason(cf_fail, cf, tsyms, vals, names, _Fmt(plain=True), aux)
        res.reason_tex = _stage_reason(cf_fail, cf, tsyms, vals, names, _Fmt(tex), aux)
    if res.reason is None and not res.all_solutions:
        res.reason = _nearest_reason(res, equations, joints, values, _Fmt(plain=True))
        res.reason_tex = _nearest_reason(res, equations, joints, values, _Fmt(tex))


def _solve_subsets(res, exprs, joints, values, budget):
    """Solve each choice of len(joints) of the equations for `joints` (the first 20 choices)."""
    for combo in itertools.combinations(range(len(exprs)), len(joints)):
        if len(res.subsets) >= 20:
            break
        sub = [exprs[k] for k in combo]
        system = _numeric_system(sub, joints, values, [res.angular[k] for k in combo])
        found = solve_all(system, _boxes(joints, _scale(values)), budget)
        res.subsets.append({
            "equations": list(combo),
            "solutions": [{j.name: v for j, v in zip(joints, s.q)} for s in found.solutions],
            "family": found.family,
        })


def _cf_solutions(cf, values, joints, system):
    """Closed-form branches evaluated, wrapped, verified on every equation, deduplicated, sorted."""
    fail, partial, sols = None, {}, []
    for bv in cfm.evaluate(cf, values):
        if bv.q is None:
            if fail is None:
                fail, partial = bv.failure, bv.partial or {}
            continue
        q = {j.name: (wrap_angle(bv.q[j.symbol]) if j.revolute else bv.q[j.symbol] + 0.0) for j in joints}
        vec = np.array([[q[j.name] for j in joints]])
        if float(np.max(np.abs(system.residual(vec)[0]), initial=0.0)) > system.tol:
            continue
        if any(_same(q, o, joints) for o in sols):
            continue
        sols.append(q)
    return sort_solutions(sols, get=lambda d: [d[j.name] for j in joints]), fail, partial


def _closed_form_subset(exprs, joints, names, tex, time_limit_s, tries=20):
    """Over-determined but consistent: a closed form from all m equations, else from n of them (the
    others checked). All first: a joint that is the only unknown left in two of them is one atan2 of
    its sine and cosine (a wrist's angles from ³R₆'s nine entries), where n equations would leave one
    of the two and a second, spurious branch (±acos, asin and π − asin)."""
    n = len(joints)
    budget = time_limit_s or 20.0
    import time as _time

    start = _time.process_time()          # CPU time, as core.timing's limits
    combos = itertools.chain([tuple(range(len(exprs)))], itertools.combinations(range(len(exprs)), n))
    for k, combo in enumerate(combos):
        left = budget - (_time.process_time() - start)
        if k >= tries or left <= 0.5:
            break
        sub = [exprs[i] for i in combo]
        if any(not any(j.symbol in e.free_symbols for e in sub) for j in joints):
            continue
        try:
            with time_limit(min(left, 10.0)):
                cf = cfm.derive(sub, [j.symbol for j in joints], [j.revolute for j in joints], names, tex=tex)
                cf.branches()
            return cf, list(combo)
        except (cfm.NoClosedForm, Timeout, sp.PolynomialError, ValueError, TypeError, ZeroDivisionError,
                NotImplementedError):
            continue
    return None, None


def _nearest_reason(res, equations, joints, values, F) -> str:
    if res.nearest is None:
        return "no configuration of the joints satisfies the equations"
    parts = []
    subs = dict(values)
    subs.update({j.symbol: res.nearest[j.name] for j in joints})
    for lhs, rhs in equations:
        try:
            got = float(sp.sympify(lhs).evalf(subs=subs))
            want = float(sp.sympify(rhs).evalf(subs=subs))
        except (TypeError, ValueError):
            continue
        parts.append(Text(f"{F(sp.sympify(lhs))} = ", _fmt(got), " (target ", _fmt(want), ")"))
    return ("no configuration of the joints satisfies the equations; the closest one gives "
            + Text.join(", ", parts))


def _finish(res: IKResult, num, cf_sols, joints, values, select, system):
    """Merge closed-form and numeric sets, apply limits, select."""
    numeric = [{j.name: v for j, v in zip(joints, s.q)} for s in num.solutions]
    sing = {id(d): s.rank_deficient for d, s in zip(numeric, num.solutions)}
    if num.family:
        res.status = "family"
        free = [joints[i].name for i in num.family_free]
        fixed = {}
        for j in joints:
            if j.name in free or not numeric:
                continue
            vals = [d[j.name] for d in numeric]
            if all(_same({j.name: v}, {j.name: vals[0]}, [j], 1e-6) for v in vals):
                fixed[j.name] = vals[0]
        res.family = {"free": free, "fixed": fixed, "example": numeric[0] if numeric else None}
        # one joint moving along the continuum takes any value; several move together (a curve of
        # configurations, not every combination of their values)
        moving = (f" ({free[0]} can take any value" if len(free) == 1 else
                  f" (along it {', '.join(free[:-1])} and {free[-1]} change together" if free else "")
        res.notes.append("infinitely many solutions: the target is reached along a continuum" + moving
                         + (", with " + Text.join(", ", [Text(f"{k} = ", Num(v)) for k, v in fixed.items()])
                            if fixed else "")
                         + (")" if free else "") + ".")
        numeric = numeric[:1]
    merged = list(numeric)
    if cf_sols is not None:
        missing_num = [c for c in cf_sols if not any(_same(c, d, joints) for d in numeric)]
        missing_cf = [d for d in numeric if not any(_same(c, d, joints) for c in cf_sols)]
        res.agree = not missing_num and not missing_cf
        if not num.family:
            # prefer the closed-form values (exact formulas) where both found a solution
            merged = []
            for d in numeric:
                match = [c for c in cf_sols if _same(c, d, joints)]
                merged.append(match[0] if match else d)
                sing[id(merged[-1])] = sing.get(id(d), False)
            for c in missing_num:
                merged.append(c)
                sing[id(c)] = False
            if not res.agree:
                res.notes.append(
                    f"the closed form and the numeric search disagree ({len(cf_sols)} vs {len(numeric)} "
                    f"solutions); every verified solution is listed")
    merged = sort_solutions(merged, get=lambda d: [d[j.name] for j in joints])
    res.all_solutions = merged
    for d in merged:
        broken = in_limits(d, joints)
        if broken:
            res.rejected.append((d, broken))
        else:
            res.solutions.append(d)
            res.singular.append(bool(sing.get(id(d), False)))
    if any(res.singular) and res.status != "family":
        res.notes.append("the Jacobian of the equations is singular at a solution: the target is on "
                         "the boundary of the workspace (two solutions merge into one)")
    if not res.solutions:
        # also for a family found without a verified member (a chain with zero-length links):
        # no solution is an answer, never a selection of nothing
        family = res.status == "family"
        res.status = "unreachable"
        broken = Text.join("; ", [Text.join(", ", b) for _, b in res.rejected]) if merged else ""
        if merged and family:
            res.reason = ("the target is reached along a continuum of configurations, but the one "
                          "found breaks a joint limit (" + broken
                          + "); other members of the continuum may respect the limits")
        elif merged:
            res.reason = "every solution breaks a joint limit: " + broken
        elif num.best_q is not None:
            res.nearest = {j.name: (wrap_angle(v) if j.revolute else v) for j, v in zip(joints, num.best_q)}
        return
    if isinstance(select, dict):
        target = {k: float(v) for k, v in select.items()}
        for j in joints:
            target.setdefault(j.name, 0.0)
        dists = [_distance(d, target, joints) for d in res.solutions]
        res.selected_index = int(min(range(len(dists)), key=lambda i: (dists[i], i)))
    else:
        res.selected_index = 0
    res.selected = res.solutions[res.selected_index]


def _redundant(res, exprs, joints, values, names, time_limit_s, tex=None):
    n, m = len(joints), len(exprs)
    res.reason = (f"{m} equation{'s' if m != 1 else ''} for {n} unknown joints: infinitely many "
                  f"solutions ({n - m} free parameter{'s' if n - m > 1 else ''}).")
    # try to express the family: the last joints free, the others in closed form
    for free in itertools.combinations(list(reversed(range(n))), n - m):
        unk = [j for i, j in enumerate(joints) if i not in free]
        try:
            with time_limit(time_limit_s):
                cf = cfm.derive(exprs, [j.symbol for j in unk], [j.revolute for j in unk], names, tex=tex)
                branches = cf.branches()
        except (cfm.NoClosedForm, Timeout, sp.PolynomialError, ValueError, TypeError, ZeroDivisionError,
                NotImplementedError):
            continue
        res.family = {"free": [joints[i].name for i in sorted(free)], "closed_form": cf,
                      "branches": branches}
        res.reason += (" For each value of " + ", ".join(joints[i].name for i in sorted(free))
                       + " the others follow from the closed form below; add an equation to fix it.")
        return
    res.reason += " Add equations (one per free joint) to get a finite set of solutions."


# ---------------------------------------------------------------------------
# velocity

@dataclass
class VelocityIK:
    q_dot: dict
    J: np.ndarray
    method: str                          # inverse | least_squares | min_norm
    note: str | None = None
    residual: float = 0.0
    condition: float = 1.0


def velocity_ik(coords, rates, joints: list[IKJoint], q: dict, values: dict) -> VelocityIK:
    """q_dot with J q_dot = rates, J = d coords / dq at q (J^-1, else least squares)."""
    subs = dict(values)
    qs = [j.symbol for j in joints]
    exprs = [sp.sympify(c).subs(subs) for c in coords]
    Jsym = sp.Matrix(exprs).jacobian(qs)
    f = sp.lambdify(qs, Jsym, modules="numpy")
    J = np.array(f(*[q[j.name] for j in joints]), dtype=float).reshape(len(exprs), len(qs))
    v = np.array([float(sp.sympify(r).evalf(subs=subs)) for r in rates])
    s = np.linalg.svd(J, compute_uv=False) if J.size else np.array([0.0])
    cond = float(s[0] / s[-1]) if s[-1] > 0 else math.inf
    m, n = J.shape
    note = None
    if m == n and s[-1] > 1e-9 * max(s[0], 1e-300):
        qd = np.linalg.solve(J, v)
        method = "inverse"
        if cond > 1e6:
            note = Text("J is nearly singular here (condition number ", Num(cond, digits=3),
                        "): small velocity errors become large joint rates")
    else:
        qd = np.linalg.lstsq(J, v, rcond=1e-9)[0]
        method = "least_squares" if m >= n else "min_norm"
        if m == n:
            note = ("J is singular at this configuration: q_dot is the least-squares "
                    "(pseudo-inverse) solution, the velocity may not be reachable exactly")
        elif m < n:
            note = "fewer velocity components than joints: minimum-norm q_dot (pseudo-inverse)"
        else:
            note = "more velocity components than joints: least-squares q_dot"
    resid = float(np.linalg.norm(J @ qd - v))
    if resid > 1e-9 * max(1.0, float(np.linalg.norm(v))):
        note = (note + "; " if note else "") + Text("the desired velocity is not reachable exactly (residual ",
                                                    Num(resid, digits=3), ")")
    big = float(np.max(np.abs(qd))) if qd.size else 0.0
    qd = np.where(np.abs(qd) < 1e-13 * max(1.0, big), 0.0, qd)
    return VelocityIK({j.name: float(x) + 0.0 for j, x in zip(joints, qd)}, J, method, note, resid, cond)
