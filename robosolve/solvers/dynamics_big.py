"""The equations of motion of a big robot (a 7-joint arm: the dynamics engine's `large`).

Same method and steps as for any robot (J, L, energies, actions, Lagrange, matrix form), but
the derivation's polynomials (thousands of terms) are never turned into sympy expressions:

* the symbolic answers are the engine's text of its reduced polynomials in cos/sin
  (`DynamicsEngine.answer_texts`, nested by joint; sympy reads them back);
* the report writes out the entries of at most `SHOW_TERMS` terms in their readable form and
  says of the others how long they are (entry by entry for the matrices);
* the numbers come from numeric code (`dynamics.numeric.ChainDynamics`: numpy products of the
  local poses and their derivatives), not from evaluating the long expressions.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.dynamics.engine import SHOW_TERMS
from robosolve.dynamics.numeric import ChainDynamics
from robosolve.core.prose import name_tex
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step
from robosolve.solvers.common import potential_step
from robosolve.core.printing import latex

__all__ = ["solve_big"]


def _long(count: int, in_results: bool) -> str:
    """The note for an expression too long to show; it points to results.json only for what
    results.json holds (the energies, the equations, M, c, g — not 𝓛 or ∂𝓛/∂q̇)."""
    where = "; see results.json" if in_results else ""
    return f"\\text{{(long: {count} terms{where})}}"


def _entry(eng, p, in_results: bool = True):
    expr, count = eng.shown(p)
    return _long(count, in_results) if expr is None else expr


def _sum(eng, pairs, in_results: bool = True):
    """Σ factor·p over (sympy factor, element): written out when short, else its length."""
    pairs = [(f, p) for f, p in pairs if p != 0]
    count = sum(eng.term_count(p) for _, p in pairs)
    if count > SHOW_TERMS:
        return _long(count, in_results)
    return sp.Add(*[f * eng.shown(p)[0] for f, p in pairs])


def _rates(eng, j, k, half=False):
    w = sp.S.Half if (half and j == k) else sp.S.One
    return w * eng.qd[j] * eng.qd[k]


def solve_big(question, ctx: SolveContext, ans: Answer, dyn, shared: dict) -> Answer:
    """`shared`: the steps this route has in common with the general one (the solver's
    "inertia", "velocity", "actions" steps and its "rates", the state with unset rates 0)."""
    eng = dyn.engine
    model = ctx.model
    poly = eng.polynomials()
    texts = eng.answer_texts()
    ans.note(f"{eng.n} joints: the symbolic answers are polynomials in cos/sin of "
             f"{sum(eng.term_count(x) for row in poly['mass_matrix'] for x in row)} terms (mass "
             "matrix) and more, written in results.json nested by joint; the report writes out the "
             f"entries of at most {SHOW_TERMS} terms; the numbers come from numeric code")
    shared["inertia"](ans, model, eng)
    shared["velocity"](ans, model, eng)
    _steps_energy(ans, eng, poly)
    shared["actions"](ans, model, eng, dyn)
    _steps_lagrange(ans, eng, dyn, poly)
    f = dyn.generalized_forces
    names = [j.name for j in dyn.joints]
    ans.symbolic["kinetic_energy"] = texts["kinetic_energy"]
    ans.symbolic["potential_energy"] = texts["potential_energy"]
    ans.symbolic["generalized_forces"] = {names[i]: f[i] for i in range(eng.n)}
    ans.symbolic["equations"] = [f"{lhs} = {f[i]}" for i, lhs in enumerate(texts["lhs"])]
    ans.symbolic["mass_matrix"] = texts["mass_matrix"]
    ans.symbolic["velocity_terms"] = texts["velocity_terms"]
    ans.symbolic["gravity_terms"] = texts["gravity_terms"]
    if question.at:
        _numeric(question, ctx, ans, dyn, shared["rates"])
    return ans


def _kinetic(eng, m):
    n = eng.n
    return _sum(eng, [(_rates(eng, i, k, half=True), m[i][k]) for i in range(n) for k in range(i, n)])


def _steps_energy(ans, eng, poly) -> None:
    kin = Step(
        "Kinetic energy",
        "$T_j = \\frac{1}{2}\\,\\mathrm{tr}({}^{0}W_{0j}\\,{}^{0}J_j\\,{}^{0}W_{0j}^T) = \\frac{1}{2}"
        "\\sum_{i,k}\\dot q_i\\dot q_k\\,\\mathrm{tr}(L_i J_j L_k^T)$, the trace taken in the body's own "
        "frame (${}^{j}L_i = M_{0j}^{-1}\\,\\partial M_{0j}/\\partial q_i$, ${}^{j}J$ constant).",
    )
    for b in eng.bodies:
        kin.equations.append((f"T_{{{name_tex(b.name, False)}}}",
                              _kinetic(eng, poly["body_mass_matrices"][b.name])))
    ans.steps.append(kin)
    ans.steps.append(potential_step(eng, lambda b: _entry(eng, poly["potential_energy"][b.name])))
    m = poly["mass_matrix"]
    n = eng.n
    u = sum(poly["potential_energy"].values(), eng.alg.zero)
    lagrangian = _sum(eng, [(_rates(eng, i, k, half=True), m[i][k]) for i in range(n) for k in range(i, n)]
                      + [(sp.S.NegativeOne, u)], in_results=False)
    ans.steps.append(Step(
        "Lagrangian",
        "$\\mathcal{L} = \\sum_j (T_j - U_j)$. Its kinetic part is $\\frac{1}{2}\\dot q^T M(q)\\,\\dot q$, "
        "which defines the mass matrix $M_{ik} = \\sum_j \\mathrm{tr}(L_i J_j L_k^T)$ (written entry "
        "by entry in the matrix form below; its entries are polynomials in $\\cos q_i$, $\\sin q_i$ "
        "reduced by $\\cos^2 + \\sin^2 = 1$).",
        equations=[("\\mathcal{L}", lagrangian)],
    ))


def _matrix(eng, m):
    return [[_entry(eng, x) for x in row] for row in m]


def _steps_lagrange(ans, eng, dyn, poly) -> None:
    n = eng.n
    m, c, g = poly["mass_matrix"], poly["velocity_terms"], poly["gravity_terms"]
    step = Step(
        "Lagrange equations",
        "$\\frac{d}{dt}\\frac{\\partial \\mathcal{L}}{\\partial \\dot q_i} - "
        "\\frac{\\partial \\mathcal{L}}{\\partial q_i} = f_i$. With "
        "$\\partial\\mathcal{L}/\\partial\\dot q_i = \\sum_k M_{ik}\\dot q_k$ the left side is "
        "$\\sum_k M_{ik}\\ddot q_k + c_i + g_i$, where $c_i = \\sum_{j,k}\\Gamma_{ijk}\\dot q_j\\dot q_k$ "
        "with $\\Gamma_{ijk} = \\frac{1}{2}(\\partial M_{ij}/\\partial q_k + \\partial M_{ik}/\\partial q_j "
        "- \\partial M_{jk}/\\partial q_i)$ and $g_i = \\partial U/\\partial q_i$.",
    )
    f = dyn.generalized_forces
    for i, j in enumerate(dyn.joints):
        name = latex(j.q)
        step.equations.append((f"\\frac{{\\partial \\mathcal{{L}}}}{{\\partial \\dot{{{name}}}}}",
                               _sum(eng, [(eng.qd[k], m[i][k]) for k in range(n)], in_results=False)))
        lhs = [(eng.qdd[k], m[i][k]) for k in range(n)]
        lhs += [(_rates(eng, a, b), v) for (a, b), v in c[i].items()] + [(sp.S.One, g[i])]
        step.equations.append((f"\\text{{joint {i + 1} ({j.name})}}:\\;{latex(f[i])} ", _sum(eng, lhs)))
    ans.steps.append(step)
    velocity = [_sum(eng, [(_rates(eng, a, b), v) for (a, b), v in c[i].items()]) for i in range(n)]
    ans.steps.append(Step(
        "Matrix form",
        "$M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = f$, with $f$ = actuators + external forces.",
        equations=[("M(q)", _matrix(eng, m)), ("c(q, \\dot q)", [[v] for v in velocity]),
                   ("g(q)", [[_entry(eng, x)] for x in g]), ("f", f)],
    ))


def _numeric(question, ctx, ans, dyn, rates) -> None:
    eng = dyn.engine
    subs = rates(question, ctx, ans, dyn)
    joint_syms = set(dyn.q) | set(dyn.qd) | set(dyn.qdd)
    missing = [s.name for s in dyn.q if s not in subs]
    if missing:
        ans.note(MissingValues(missing).args[0] + " needed in `at` for the numeric values")
        return
    params = {k: v for k, v in subs.items() if k not in joint_syms}
    try:
        chain = ChainDynamics(eng, params)
    except ValueError as exc:
        ans.note(f"numeric values omitted: {exc}")
        return
    q, qd, qdd = ([float(sp.N(subs[s])) for s in syms] for syms in (dyn.q, dyn.qd, dyn.qdd))
    out = chain.evaluate(q, qd)
    tau = out["mass_matrix"] @ np.array(qdd) + out["velocity_terms"] + out["gravity_terms"] - chain.external(q)
    ans.numeric["mass_matrix"] = out["mass_matrix"].tolist()
    ans.numeric["velocity_terms"] = out["velocity_terms"].tolist()
    ans.numeric["gravity_terms"] = out["gravity_terms"].tolist()
    for key in ("kinetic_energy", "potential_energy"):
        ans.numeric[key] = {**out[key], "total": float(sum(out[key].values()))}
    ans.numeric["actuators"] = {a.name: float(t) for a, t in zip(dyn.actuators, tau)}
    eqs = [("M", ans.numeric["mass_matrix"]), ("c", ans.numeric["velocity_terms"]),
           ("g", ans.numeric["gravity_terms"])]
    eqs += [(latex(a), v) for a, v in zip(dyn.actuators, ans.numeric["actuators"].values())]
    ans.steps.append(Step(
        "Numeric values",
        "At the configuration of the question, from numeric code (numpy products of the local "
        "poses and their derivatives: the same formulas with numbers); the actuator values are "
        "those that produce the given accelerations: actuators = $M\\ddot q + c + g$ − external forces.",
        equations=eqs,
    ))
