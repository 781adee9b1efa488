"""§6.5: forward dynamics — the motion of the arm under given actuator laws.

The plant is the problem's own equations of motion (the same derivation as
equations_of_motion), M(q) q'' + c(q, q') + g(q) = tau(t, q, q') + f_ext, with the
actuators replaced by the question's laws (missing actuators: 0).  `compute` runs the
integration (robosolve.simulation.forward) and returns the numbers; `solve` adds the steps
of the report and the figures.
"""

from __future__ import annotations

import contextlib

from dataclasses import dataclass, field

import sympy as sp

from robosolve.errors import SolverError
from robosolve.load.problem import Question
from robosolve.core.prose import Num, Text
from robosolve.core.symbols import TIME
from robosolve.solvers.base import Answer, FigureSpec, SolveContext, Step, missing_note
from robosolve.core.opcount import count_ops
from robosolve.core.printing import latex

T = TIME
# The run is accurate to ~1e-9 of its scale (tests: 1e-8 against pinocchio); 10 digits keep it,
# more would be integration noise.
ANSWER_DIGITS = 10
FIGURE_SAMPLES = 801          # stored samples per curve (the figures' data are capped)
# Closed-form work of a law that depends on its own joint only: skipped past this size.
WORK_OPS = 60


@dataclass
class Setup:
    """What the run integrates: the symbolic pieces, then their numeric versions."""

    laws: list            # tau_i(t, q, q') per joint (sympy, parameters kept)
    forces: list          # tau_i + f_ext_i (sympy, parameters kept)
    equations: list       # "lhs = rhs" strings
    kinetic: sp.Expr
    potential: sp.Expr
    names: dict = field(default_factory=dict)   # the symbols' LaTeX (ctx.symbol_latex)


def _unit(kind: str, rate: bool = False) -> str:
    base = "rad" if kind == "revolute" else "m"
    return base + "/s" if rate else base


def _sig(x: float, scale: float = 0.0) -> float:
    """x, or 0 when it is below the run's accuracy relative to ``scale`` (integration noise);
    the digits kept in results.json are the registry's (AnswerKey.digits)."""
    x = float(x)
    if abs(x) <= 1e-12 * abs(scale):
        return 0.0
    return x + 0.0


def setup(question: Question, ctx: SolveContext, dyn) -> Setup:
    """The laws substituted into the equations of motion (symbolic)."""
    model = ctx.model
    given = question.options.get("actuators", {})
    laws = [given.get(str(j.actuator), sp.S.Zero) for j in model.joints]
    ext = list(dyn.external_forces)
    forces = [laws[i] + ext[i] for i in range(len(laws))]
    lhs = dyn.lhs()
    equations = [f"{lhs[i]} = {forces[i]}" for i in range(len(laws))]
    return Setup(laws, forces, equations, sp.Add(*dyn.kinetic_energy.values()),
                 sp.Add(*dyn.potential_energy.values()), ctx.symbol_latex)


def _numbers(question, ctx, dyn, st: Setup):
    """(subs, start q, start qd, duration) as floats, or the names of the missing values."""
    model = ctx.model
    subs = ctx.substitutions(question.at)
    params = {k: v for k, v in subs.items() if k in ctx.problem.parameters}
    start = question.options.get("start", {})
    q0 = [start.get(j.name, sp.S.Zero).xreplace(params) for j in model.joints]
    qd0 = [start.get(j.dot.name, sp.S.Zero).xreplace(params) for j in model.joints]
    duration = sp.sympify(question.options["duration"]).xreplace(params)
    pieces = (list(dyn.mass_matrix) + list(dyn.velocity_terms) + list(dyn.gravity_terms) + st.forces
              + [st.kinetic, st.potential])
    allowed = {T, *model.q, *model.qd}
    missing = set()
    for e in pieces:
        missing |= sp.sympify(e).xreplace(params).free_symbols - allowed
    for e in q0 + qd0 + [duration]:
        missing |= e.free_symbols
    if missing:
        return None, sorted(s.name for s in missing)
    return (params, [float(v) for v in q0], [float(v) for v in qd0], float(duration)), None


def compute(question: Question, ctx: SolveContext, dyn, st: Setup, values):
    """Integrate the run (robosolve.simulation.forward.Run)."""
    from robosolve.simulation.forward import RunTooLong, compile_plant, integrate

    params, q0, qd0, duration = values
    if not duration > 0:
        raise SolverError(f"the duration must be positive (got {duration:g} s)")
    rep = lambda e: sp.sympify(e).xreplace(params)   # noqa: E731
    try:
        plant = compile_plant(dyn.mass_matrix.xreplace(params), dyn.velocity_terms.xreplace(params),
                              dyn.gravity_terms.xreplace(params), [rep(f) for f in st.forces],
                              dyn.q, dyn.qd, T, kinetic=rep(st.kinetic), potential=rep(st.potential))
        return integrate(plant, q0, qd0, duration, samples=FIGURE_SAMPLES)
    except RunTooLong as exc:
        raise SolverError(str(exc)) from None


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    dyn = ctx.dynamics()
    if dyn is None:
        raise SolverError("the symbolic equations of motion took too long: the run needs them")
    with _singular_mass_is_an_error():
        st = setup(question, ctx, dyn)
    ans.symbolic["equations"] = st.equations
    ans.steps.extend(_steps_setup(question, model, dyn, st))
    values, missing = _numbers(question, ctx, dyn, st)
    if values is None:
        ans.note(missing_note("run", missing, ctx.problem))
        return ans
    with _singular_mass_is_an_error():
        run = compute(question, ctx, dyn, st, values)
    names = [j.name for j in model.joints]
    scale = [max(abs(run.q_max[i]), abs(run.q_min[i]), 1e-300) for i in range(len(names))]
    vscale = [max(abs(x) for x in run.qd[i]) for i in range(len(names))]
    ans.numeric["final"] = {n: _sig(run.final[i], scale[i]) for i, n in enumerate(names)}
    ans.numeric["max"] = {n: _sig(run.q_max[i], scale[i]) for i, n in enumerate(names)}
    ans.numeric["min"] = {n: _sig(run.q_min[i], scale[i]) for i, n in enumerate(names)}
    ans.numeric["final_velocity"] = {n: _sig(run.final_velocity[i], vscale[i]) for i, n in enumerate(names)}
    escale = run.energy_scale or 0.0
    # below 1e-9 of the run's energy scale a value is integration noise (the run's accuracy)
    ans.numeric["energy"] = {"start": _sig(run.energy_start, 1e3 * escale),
                             "end": _sig(run.energy_end, 1e3 * escale)}
    for n in run.notes:
        ans.note(n)
    _limit_notes(ans, model, run, values[0])
    ans.steps.append(_step_results(question, model, st, run, values))
    ans.steps.append(_step_energy(question, model, st, run, values[0], ans.numeric["energy"]))
    ans.figures.extend(_figures(model, st, run))
    return ans


@contextlib.contextmanager
def _singular_mass_is_an_error():
    """A joint that moves no mass (a point mass on its axis, a body of mass 0) leaves M(q)
    singular: the accelerations are not defined, which the answer says (as a controller's run does)."""
    import numpy as np
    from sympy.matrices.exceptions import NonInvertibleMatrixError

    try:
        yield
    except (NonInvertibleMatrixError, np.linalg.LinAlgError, ZeroDivisionError) as exc:
        if isinstance(exc, np.linalg.LinAlgError) and "singular" not in str(exc).lower():
            raise
        raise SolverError("the mass matrix M(q) is singular (a joint moves no mass: a point mass on "
                          "its axis, a body of mass 0?), so the motion is not defined") from None


# ---------------------------------------------------------------------- report
def _tex(st, e) -> str:
    return latex(e, symbol_names=st.names)


def _law_tex(model, st) -> list[str]:
    return [f"{_tex(st, j.actuator)} = {_tex(st, st.laws[i])}" for i, j in enumerate(model.joints)]


def _steps_setup(question, model, dyn, st) -> list:
    start = question.options.get("start", {})
    joints = model.joints
    start_tex = ",\\quad ".join(
        f"{_tex(st, j.symbol)}(0) = {_tex(st, start.get(j.name, 0))},\\;"
        f"{_tex(st, j.dot)}(0) = {_tex(st, start.get(j.dot.name, 0))}" for j in joints)
    given = question.options.get("actuators", {})
    idle = [str(j.actuator) for j in joints if str(j.actuator) not in given]
    text = ("The arm starts at the values below and moves under the actuator laws for "
            f"$t \\in [0, {_tex(st, question.options['duration'])}]$ s. "
            + (f"Actuators not given act with zero force ({', '.join(idle)}). " if idle else "")
            + "The plant is the problem's own equations of motion (the same derivation as "
            "`equations_of_motion`), with the laws in place of the actuators:")
    lhs = dyn.lhs()
    eqs = [("", start_tex)] + [("", s) for s in _law_tex(model, st)]
    eqs.append(("", "M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = \\tau(t, q, \\dot q) + f_{ext}"))
    for i, j in enumerate(joints):
        eqs.append((f"\\text{{joint {i + 1} ({j.name})}}:\\;{_tex(st, st.forces[i])}", lhs[i]))
    return [Step("Start, laws and equations of motion", text, equations=eqs)]


def _and(items) -> str:
    return ", ".join(items[:-1]) + (" and " if len(items) > 1 else "") + items[-1]


def _stillness(question, model, st, run) -> str:
    """The joints that stay at their start all along the run (within its error: the rule of the
    extremes, core/extremes.py), said in words; every joint: the start is an equilibrium."""
    still = [j for i, j in enumerate(model.joints) if run.still is not None and run.still[i]]
    if not still:
        return ""
    start = question.options.get("start", {})
    syms = [f"${_tex(st, j.symbol)}$" for j in still]
    vals = [f"${_tex(st, start.get(j.name, 0))}$" for j in still]
    if len(still) == len(model.joints):
        each = [f"{syms[0]} stays at its start, {vals[0]},"] + [f"{s} at {v}," for s, v in zip(syms[1:], vals[1:])]
        if len(each) > 1:
            each[-1] = "and " + each[-1]
        return (f" {' '.join(each)} all along the run "
                "(within the run's error): the start is an equilibrium, the arm does not move.")
    if len(still) == 1:
        return f" {syms[0]} does not move: it stays at its start, {vals[0]}, all along the run (within its error)."
    return (f" {_and(syms)} do not move: they stay at their starts, {_and(vals)}, all along the run "
            "(within its error).")


def _step_results(question, model, st, run, values) -> Step:
    rows = []
    for i, j in enumerate(model.joints):
        u = _unit(j.kind)
        rows.append([f"${_tex(st, j.symbol)}$", Num(values[1][i], u), Num(run.final[i], u),
                     Text(Num(run.q_min[i], u), " (t = ", Num(run.t_min[i]), " s)"),
                     Text(Num(run.q_max[i], u), " (t = ", Num(run.t_max[i]), " s)"),
                     Num(run.final_velocity[i], _unit(j.kind, True))])
    how = ("Radau (implicit; the equations are stiff)" if run.method == "Radau"
           else "DOP853 (explicit Runge-Kutta of order 8)")
    return Step(
        "The run",
        f"Integrated numerically with {how}, relative tolerance $10^{{-10}}$ on the state, in "
        f"{run.steps} steps. The joint values are continuous (unwrapped): a joint that turns keeps "
        "counting its turns. The extremes are the ends or the instants where the joint's rate is "
        "zero, located on the integrator's continuous solution (not only at samples)."
        + _stillness(question, model, st, run),
        table=(["joint", "start", Text("at t = ", Num(run.duration), " s"), "min", "max", "final rate"],
               rows),
    )


def _closed_form_work(model, st, params, start, final):
    """W = sum of the integrals of tau_i + f_i over q_i when each depends on its own joint only."""
    total = sp.S.Zero
    for i, j in enumerate(model.joints):
        f = sp.sympify(st.forces[i]).xreplace(params)
        if f.free_symbols - {j.symbol}:
            return None
        if count_ops(f) > WORK_OPS:
            return None
        prim = sp.integrate(f, j.symbol)
        if prim.has(sp.Integral):
            return None
        total += prim.subs(j.symbol, sp.Float(final[i], 17)) - prim.subs(j.symbol, sp.Float(start[i], 17))
    return float(total)


def _no_closed_work(model, st, params) -> str:
    """Why the work has no closed form, in what the forces really depend on."""
    t = sp.Symbol("t", real=True)
    rates = {j.dot for j in model.joints}
    found = []
    for i, j in enumerate(model.joints):
        free = sp.sympify(st.forces[i]).xreplace(params).free_symbols
        others = {k.symbol for k in model.joints if k is not j} & free
        for what, hit in (("time", any(s.name == "t" for s in free) or t in free),
                          ("the rates", bool(free & rates)), ("the other joints", bool(others))):
            if hit and what not in found:
                found.append(what)
    if not found:
        return "The forces are not integrable in closed form here, so the work is the run's. "
    return (f"A generalized force depends on {' and on '.join(found)}, so the work has no closed "
            "form here. ")


def _bound(x: float) -> str:
    """A power of ten above x (round-off sized numbers are shown as a bound, not as noise)."""
    import math

    exp = max(-14, math.ceil(math.log10(x))) if x > 0 else -14
    return f"$10^{{{exp}}}$"


def _step_energy(question, model, st, run, params, energy) -> Step:
    e0, e1 = energy["start"], energy["end"]
    scale = run.energy_scale or 1.0
    eqs = [("E = T + U", _tex(st, st.kinetic + st.potential)),
           ("E(0)", e0), (f"E({run.duration:g})", e1), ("\\Delta E", e1 - e0)]
    nothing_acts = all(sp.sympify(f).xreplace(params) == 0 for f in st.forces)
    if nothing_acts:
        text = Text("No actuator and no external force acts: only gravity, which is conservative, so the "
                f"energy is conserved; the run keeps it to within {_bound(run.energy_drift / scale)} of the "
                "energy scale (", Num(scale, "J"), ", the largest $T + |U|$ along the run).")
        return Step("Energy balance", text, equations=eqs)
    text = ("The actuators and the external forces do the work "
            "$W = \\int_0^t (\\tau + f_{ext}) \\cdot \\dot q \\, dt$, so $E(t) - E(0) = W(t)$. ")
    eqs.append(("W \\text{ (integrated with the run)}", run.work))
    start = [float(x) for x in _start_values(question, model, params)]
    closed = _closed_form_work(model, st, params, start, [float(x) for x in run.final])
    if closed is not None:
        text += ("Each generalized force depends on its own joint only, so the work has a closed form, "
                 "$W = \\sum_i \\int_{q_i(0)}^{q_i(t)} (\\tau_i + f_i)\\,dq_i$. ")
        eqs.append(("W \\text{ (closed form)}", closed))
    else:
        text += _no_closed_work(model, st, params)
    text += Text(f"The balance holds to within {_bound(run.energy_drift / scale)} of the energy scale "
             "(", Num(scale, "J"), ") all along the run.")
    return Step("Energy balance", text, equations=eqs)


def _start_values(question, model, params):
    start = question.options.get("start", {})
    return [sp.sympify(start.get(j.name, 0)).xreplace(params) for j in model.joints]


def _limit_notes(ans, model, run, params):
    for i, j in enumerate(model.joints):
        if not j.limits:
            continue
        lo, hi = (float(sp.sympify(v).xreplace(params)) for v in j.limits)
        if run.q_min[i] < lo or run.q_max[i] > hi:
            ans.note(Text(f"{j.name} leaves its limits [", Num(lo), ", ", Num(hi), "] during the run (min ",
                          Num(run.q_min[i]), ", max ", Num(run.q_max[i]), "); the limits are not enforced"))


def _figures(model, st, run) -> list:
    laws = _law_tex(model, st)
    law_title = ", ".join(f"${s}$" for s in laws)
    if len(law_title) > 90:
        law_title = "the laws of the report"
    out = []
    r = lambda a: [float(f"{float(x):.10g}") + 0.0 for x in a]   # noqa: E731
    for i, j in enumerate(model.joints):
        sym = _tex(st, j.symbol)
        out.append(FigureSpec(
            f"joint_{j.name}", "forward_dynamics", f"${sym}(t)$ with {law_title}",
            {"t": r(run.t), "q": r(run.q[i]), "qd": r(run.qd[i]), "label": sym,
             "rate_label": _tex(st, j.dot), "unit": _unit(j.kind), "rate_unit": _unit(j.kind, True),
             "max": float(run.q_max[i]), "t_max": float(run.t_max[i]),
             "min": float(run.q_min[i]), "t_min": float(run.t_min[i])}))
    return out
