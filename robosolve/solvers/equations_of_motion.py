"""Question 8: equations of motion by the course's matrix method (seed §6, §7.3; docs/course-notes.md, Dynamics).

Steps of the report: pseudo-inertia J of each body (own frame and frame 0), L and W
matrices, kinetic energies ½ tr(W J Wᵀ), gravity matrix and potential energies −tr(H_g J),
the Lagrangian, the matrices of actions Φ of each link and the generalized forces
(Σ_{j≥i} ⁰Φⱼ) ⊗ ⁰Lᵢ, the Lagrange equations, the matrix form M q̈ + c + g = f and, at `at`,
the actuator values needed. The derivation itself is robosolve.dynamics (one per model).
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.course_notes import note_link
from robosolve.core.printing import SharedStrPrinter, latex
from robosolve.dynamics.bridge import NUMERIC_ONLY_NOTE, numeric_energies, numeric_for
from robosolve.errors import SolverError, SymbolicTimeout
from robosolve.load.problem import Question
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step
from robosolve.solvers.common import frame_tex, m_name, potential_step
from robosolve.core.prose import name_tex
from robosolve.core.opcount import count_ops

# Largest expression (count_ops) written out in a report step; bigger ones are named only.
SHOW_OPS = 400
# Beyond this many joints the report skips the frame-0 matrices (J, W, Φ in frame 0).
BIG_JOINTS = 4


def _show(expr, limit: int = SHOW_OPS, in_results: bool = False):
    """The expression, or a LaTeX note when it is too long to be useful in a report.

    The note points to results.json only for what results.json holds (the energies, the
    equations, M, c, g): ⁰J, ⁰L, ⁰W, Φ, 𝓛 and ∂𝓛/∂q̇ are the report's steps alone."""
    ops = count_ops(expr)       # a matrix: the sum of its entries' (each node counted once)
    if ops <= limit:
        return expr
    where = "; see results.json" if in_results else ""
    return f"\\text{{(long: {ops} operations{where})}}"


def _latex_name(sym) -> str:
    return latex(sym)


def solve(question: Question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    if model is None or not model.joints:
        raise SolverError("equations_of_motion needs a robot (joints and frames)")
    if not model.bodies:
        ans.note("no bodies are given: every mass is zero, so M = c = g = 0")
    dyn = ctx.dynamics()
    if dyn is None:
        return _numeric_only(question, ctx, ans)

    eng = dyn.engine
    if getattr(eng, "large", False):
        from robosolve.solvers.dynamics_big import solve_big
        shared = {"inertia": _steps_inertia, "velocity": _steps_velocity, "actions": _steps_actions,
                  "rates": _rates}
        return solve_big(question, ctx, ans, dyn, shared)
    n = len(dyn.joints)
    names = [j.name for j in dyn.joints]
    _steps_inertia(ans, model, eng)
    _steps_velocity(ans, model, eng)
    _steps_energy(ans, model, eng, dyn)
    _steps_actions(ans, model, eng, dyn)
    _steps_lagrange(ans, model, dyn)

    # ---------------------------------------------------------------- answers
    t_total = sp.Add(*dyn.kinetic_energy.values())
    u_total = sp.Add(*dyn.potential_energy.values())
    ans.symbolic["kinetic_energy"] = {**dyn.kinetic_energy, "total": t_total}
    ans.symbolic["potential_energy"] = {**dyn.potential_energy, "total": u_total}
    f = dyn.generalized_forces
    ans.symbolic["generalized_forces"] = {names[i]: f[i] for i in range(n)}
    lhs = dyn.lhs()
    text = SharedStrPrinter().doprint      # str(), each shared subexpression printed once
    ans.symbolic["equations"] = [f"{text(lhs[i])} = {text(f[i])}" for i in range(n)]
    ans.symbolic["mass_matrix"] = dyn.mass_matrix
    ans.symbolic["velocity_terms"] = list(dyn.velocity_terms)
    ans.symbolic["gravity_terms"] = list(dyn.gravity_terms)

    if question.at:
        _numeric(question, ctx, ans, dyn)
    return ans


# -------------------------------------------------------------------- steps
def _steps_inertia(ans, model, eng):
    step = Step(
        "Pseudo-inertia of each body",
        "$J = \\int p\\,p^T\\,dm$ with homogeneous $p$ (" + note_link("pseudo-inertia") + "): the upper-left block holds "
        "$\\int x^2 dm$, $\\int xy\\,dm$, …, the last column $m\\,x_G, m\\,y_G, m\\,z_G, m$. "
        "In frame 0: ${}^{0}J = {}^{0}M_j\\,{}^{j}J\\,{}^{0}M_j^T$.",
    )
    big = eng.n > BIG_JOINTS
    for b in eng.bodies:
        fb = frame_tex(b.frame)
        step.equations.append((f"{{}}^{{{fb}}}J_{{{name_tex(b.name, False)}}}", b.J))
        if big:
            continue
        step.equations.append((f"{{}}^{{0}}J_{{{name_tex(b.name, False)}}} = {m_name('0', b.frame)}\\,"
                               f"{{}}^{{{fb}}}J\\,{m_name('0', b.frame)}^T", _show(eng.J0(b, SHOW_OPS), SHOW_OPS)))
    if big:
        step.text += (" With more than four joints ${}^{0}J$ is long and is not written out: "
                      "the energies below are computed in each body's own frame.")
    ans.steps.append(step)


def _steps_velocity(ans, model, eng):
    step = Step(
        "L and velocity matrices",
        "${}^{0}L_i = \\partial M_{0i}/\\partial q_i \\, M_{0i}^{-1}$ (the joint's axis in frame 0) "
        "and ${}^{0}W_{0j} = \\sum_{i} {}^{0}L_i\\,\\dot q_i$ over the joints that move frame $j$ "
        "(Rivals, every term in frame 0).",
    )
    for i, j in enumerate(eng.joints):
        step.equations.append((f"{{}}^{{0}}L_{{{i + 1}}}\\;({_latex_name(j.q)})",
                               _show(eng.L0(i))))
    frames = []
    for b in eng.bodies:
        if b.frame not in frames:
            frames.append(b.frame)
    if eng.n > BIG_JOINTS:
        frames = []
        step.text += " (The $W$ matrices of a robot with more than four joints are not written out.)"
    for fr in frames:
        step.equations.append((f"{{}}^{{0}}W_{{0,{frame_tex(fr)}}}", _show(eng.W0(fr))))
    ans.steps.append(step)


def _steps_energy(ans, model, eng, dyn):
    qd = sp.Matrix(dyn.qd)
    kin = Step(
        "Kinetic energy",
        "$T_j = \\frac{1}{2}\\,\\mathrm{tr}({}^{0}W_{0j}\\,{}^{0}J_j\\,{}^{0}W_{0j}^T)$. With "
        "$W_{0j} = \\sum_i L_i\\dot q_i$ this is $\\frac{1}{2}\\sum_{i,k}\\dot q_i\\dot q_k\\,"
        "\\mathrm{tr}(L_i J_j L_k^T)$; the trace is the same in the body's own frame "
        "(${}^{j}L_i = M_{0j}^{-1}\\,\\partial M_{0j}/\\partial q_i$ and ${}^{j}J$ constant), which "
        "keeps every product short.",
    )
    for b in eng.bodies:
        kin.equations.append((f"T_{{{name_tex(b.name, False)}}}", _show(dyn.kinetic_energy[b.name], in_results=True)))
    ans.steps.append(kin)
    ans.steps.append(potential_step(eng, lambda b: _show(dyn.potential_energy[b.name], in_results=True)))
    t_total = sp.Add(*dyn.kinetic_energy.values())
    u_total = sp.Add(*dyn.potential_energy.values())
    ans.steps.append(Step(
        "Lagrangian",
        "$\\mathcal{L} = \\sum_j (T_j - U_j)$. Its kinetic part is "
        "$\\frac{1}{2}\\dot q^T M(q)\\,\\dot q$, which defines the mass matrix "
        "$M_{ik} = \\sum_j \\mathrm{tr}(L_i J_j L_k^T)$.",
        equations=[("\\mathcal{L}", _show(t_total - u_total, 2 * SHOW_OPS)),
                   ("M(q)", _show(dyn.mass_matrix, 3 * SHOW_OPS, in_results=True))],
    ))
    del qd


def _steps_actions(ans, model, eng, dyn):
    n = len(dyn.joints)
    text = (
        "Each link's matrix of actions collects $+$ its own actuator, $-$ the reaction of the "
        "next joint's actuator and the external loads on it (" + note_link("matrix-of-actions") + "): "
        "$\\Phi = \\sum (F P^T - P F^T) + [C]$, components rotated from their `in` frame, "
        "moved to frame 0 with ${}^{0}\\Phi = M\\,\\Phi\\,M^T$. "
        "A revolute actuator is a pure torque along the joint axis, a prismatic one a force "
        "along it. The generalized force of joint $i$ is "
        "$f_i = (\\sum_{j \\ge i} {}^{0}\\Phi_j) \\otimes {}^{0}L_i$ with the pseudo scalar "
        "product $A \\otimes B = A_{32}B_{32} + A_{13}B_{13} + A_{21}B_{21} + A_{14}B_{14} + "
        "A_{24}B_{24} + A_{34}B_{34}$ (" + note_link("pseudo-scalar-product") + ")."
    )
    step = Step("Matrices of actions and generalized forces", text)
    if n > BIG_JOINTS:
        for i in range(n):
            step.equations.append((f"\\Phi_{{\\text{{actuator }}{i + 1}}}\\;(\\text{{in frame "
                                   f"{eng.joint_frame(i)}}})", eng.actuator_action(i)))
        for load in eng.loads:
            step.equations.append((f"{{}}^{{{frame_tex(load.frame)}}}\\Phi_{{{name_tex(load.name, False)}}}",
                                   eng.load_in_body(load)))
    else:
        for link, phi in eng.link_actions0().items():
            step.equations.append((f"{{}}^{{0}}\\Phi_{{{frame_tex(link)}}}", _show(phi)))
    f = dyn.generalized_forces
    for i in range(n):
        step.equations.append((f"f_{{{i + 1}}}", f[i]))
    if n <= BIG_JOINTS and not eng.course_forces_agree():  # pragma: no cover - an internal consistency check
        ans.note("the literal course formula (Σ Φ) ⊗ L differs from actuator + external forces")
    ans.steps.append(step)


def _steps_lagrange(ans, model, dyn):
    n = len(dyn.joints)
    m = dyn.mass_matrix
    step = Step(
        "Lagrange equations",
        "$\\frac{d}{dt}\\frac{\\partial \\mathcal{L}}{\\partial \\dot q_i} - "
        "\\frac{\\partial \\mathcal{L}}{\\partial q_i} = f_i$ (" + note_link("lagrange") + "). With "
        "$\\partial\\mathcal{L}/\\partial\\dot q_i = \\sum_k M_{ik}\\dot q_k$ the left side is "
        "$\\sum_k M_{ik}\\ddot q_k + c_i + g_i$, where $c_i = \\sum_{j,k}\\Gamma_{ijk}\\dot q_j\\dot q_k$ "
        "with $\\Gamma_{ijk} = \\frac{1}{2}(\\partial M_{ij}/\\partial q_k + \\partial M_{ik}/\\partial q_j "
        "- \\partial M_{jk}/\\partial q_i)$ (Coriolis and centrifugal terms) and "
        "$g_i = \\partial U/\\partial q_i$.",
    )
    qd = dyn.qd
    lhs = dyn.lhs()
    f = dyn.generalized_forces
    for i, j in enumerate(dyn.joints):
        p = sp.Add(*[m[i, k] * qd[k] for k in range(n)])
        name = _latex_name(j.q)
        step.equations.append((f"\\frac{{\\partial \\mathcal{{L}}}}{{\\partial \\dot{{{name}}}}}",
                               _show(p)))
        step.equations.append((f"\\text{{joint {i + 1} ({j.name})}}:\\;{latex(f[i])} ",
                               _show(lhs[i], in_results=True)))
    ans.steps.append(step)
    ans.steps.append(Step(
        "Matrix form",
        "$M(q)\\,\\ddot q + c(q, \\dot q) + g(q) = f$, with $f$ = actuators + external forces.",
        equations=[("M(q)", _show(m, 3 * SHOW_OPS, in_results=True)),
                   ("c(q, \\dot q)", _show(dyn.velocity_terms, 3 * SHOW_OPS, in_results=True)),
                   ("g(q)", _show(dyn.gravity_terms, 3 * SHOW_OPS, in_results=True)),
                   ("f", f)],
    ))


# -------------------------------------------------------------------- numbers
def _rates(question, ctx, ans, dyn):
    """The question's values with joint rates that are not given taken as zero."""
    subs = ctx.substitutions(question.at)
    unset = [s for s in dyn.qd + dyn.qdd if s not in subs]
    if unset and all(q in subs for q in dyn.q):
        for s in unset:
            subs[s] = sp.S.Zero
        ans.note("joint rates not given in `at` are taken as 0: " +
                 ", ".join(s.name for s in unset))
    return subs


def _numeric(question, ctx, ans, dyn):
    subs = _rates(question, ctx, ans, dyn)
    ctx.try_numeric(ans, "mass_matrix", dyn.mass_matrix, subs, "mass_matrix")
    ctx.try_numeric(ans, "velocity_terms", list(dyn.velocity_terms), subs, "velocity_terms")
    ctx.try_numeric(ans, "gravity_terms", list(dyn.gravity_terms), subs, "gravity_terms")
    ctx.try_numeric(ans, "kinetic_energy", ans.symbolic["kinetic_energy"], subs, "kinetic_energy")
    ctx.try_numeric(ans, "potential_energy", ans.symbolic["potential_energy"], subs,
                    "potential_energy")
    tau = dyn.actuator_expressions()
    values = ctx.try_numeric(ans, "actuators", {a.name: tau[i] for i, a in
                                                enumerate(dyn.actuators)}, subs, "actuators")
    eqs = []
    for key, tex in (("mass_matrix", "M"), ("velocity_terms", "c"), ("gravity_terms", "g")):
        if key in ans.numeric:
            eqs.append((tex, ans.numeric[key]))
    if values is not None:
        for a, v in values.items():
            eqs.append((_latex_name(sp.Symbol(a)), v))
    if eqs:
        ans.steps.append(Step(
            "Numeric values",
            "At the configuration of the question; the actuator values are those that produce "
            "the given accelerations: actuators = $M\\ddot q + c + g$ − external forces.",
            equations=eqs,
        ))


def _numeric_only(question, ctx, ans):
    """The symbolic derivation was cut short: M, c, g and actuators at `at` numerically."""
    model = ctx.model
    ans.note(f"the symbolic equations of motion took longer than {ctx.budgets.dynamics_seconds:g} s: "
             "answered numerically at `at` (mass matrix, velocity and gravity terms, actuators)")
    if not question.at:
        ans.note("give `at` (joint values, rates, accelerations) for numeric answers")
        return ans
    subs = ctx.substitutions(question.at)
    params = {k: v for k, v in subs.items() if k in ctx.problem.parameters}
    try:
        nd, note = numeric_for(model, params, ctx.budgets.dynamics_seconds)
    except ValueError as exc:
        ans.note(f"numeric answers omitted: {exc}")
        return ans
    if note and note != NUMERIC_ONLY_NOTE:     # the first note already says the derivation was cut
        ans.note(note)
    missing = [s.name for s in model.q if s not in subs]
    if missing:
        ans.note(MissingValues(missing).args[0] + " needed in `at`")
        return ans
    q = [float(sp.N(subs[s])) for s in model.q]
    qd = [float(sp.N(subs.get(s, 0))) for s in model.qd]
    qdd = [float(sp.N(subs.get(s, 0))) for s in model.qdd]
    ans.numeric["mass_matrix"] = nd.mass(q).tolist()
    ans.numeric["velocity_terms"] = nd.velocity_terms(q, qd).tolist()
    ans.numeric["gravity_terms"] = nd.gravity(q).tolist()
    tau = nd.actuators(q, qd, qdd)
    ans.numeric["actuators"] = {j.actuator.name: float(t) for j, t in zip(model.joints, tau)}
    try:
        ans.numeric.update(numeric_energies(model, params, q, qd))
    except ValueError as exc:
        ans.note(f"numeric energies omitted: {exc}")
    ans.steps.append(Step("Numeric values", "From the numeric-only path.",
                          equations=[("M", ans.numeric["mass_matrix"]),
                                     ("c", ans.numeric["velocity_terms"]),
                                     ("g", ans.numeric["gravity_terms"])]))
    return ans
