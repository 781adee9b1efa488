"""Question 4: joint actions that balance a load (virtual work), Fq = −Jᵀ·Fs.

* `force`: one component per coordinate (default the point's x, y, z in frame 0),
  Fq = −Jᵀ·F;
* `torque` (frame 0, default coordinates): Fq = −(J_Pᵀ·F + J_ωᵀ·τ) with the geometric
  Jacobian;
* `weight: true`: the bodies' own weight, Fq = −Σ J_Giᵀ·mᵢ·g (centre of mass from the
  pseudo-inertia, gravity vector g of the problem). This equals ∂U/∂q.
Loads given together are added. Fq is what the joints must exert (spec §3, docs/course-notes.md#note-statics-sign).
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.course_notes import note_link
from robosolve.core.simplify import is_zero
from robosolve.kinematics.statics_math import balance_force, balance_weight, balance_wrench
from robosolve.solvers.task_space import limited, task_space, tidy_limited
from robosolve.solvers.base import Answer, SolveContext, Step
from robosolve.core.prose import name_tex
from robosolve.core.printing import latex


def _actuator_tex(model):
    return [latex(j.actuator) for j in model.joints]


def solve(question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    opts = question.options
    point = question.point
    q = model.q
    n = len(q)
    total = sp.zeros(n, 1)
    force = opts.get("force")
    torque = opts.get("torque")
    weight = bool(opts.get("weight"))

    ans.steps.append(Step(
        "Principle of virtual work",
        "In equilibrium the virtual work of the joint actions $F_q$ and of the external load "
        "$F_s$ vanishes for every virtual displacement: $\\delta Q^T F_q + \\delta S^T F_s = 0$. "
        "With $\\delta S = J\\,\\delta Q$ this gives $\\delta Q^T (F_q + J^T F_s) = 0$ for every "
        "$\\delta Q$, hence the joint actions that balance the load are $F_q = -J^T F_s$ ("
        + note_link("statics-sign") + ").",
    ))

    if force is not None or torque is not None:
        total += _load_part(question, ctx, ans, force, torque)

    if weight:
        total += _weight_part(ctx, ans)

    if (force is not None or torque is not None) and weight:
        total = tidy_limited(ctx, total, ctx.step_seconds)
        ans.steps.append(Step("Total", "The loads add up:", equations=[("F_q", total)]))

    names = [j.name for j in model.joints]
    ans.symbolic["Fq"] = {name: total[i] for i, name in enumerate(names)}
    acts = _actuator_tex(model)
    ans.steps.append(Step(
        "Result",
        "Joint actions (torques for revolute joints, forces for prismatic ones) that balance "
        "the load; a positive value acts in the direction in which the joint variable grows:",
        equations=[(a, total[i]) for i, a in enumerate(acts)],
    ))

    if question.at or not (total.free_symbols & set(q)):
        subs = ctx.substitutions(question.at)
        vals = ctx.try_numeric(ans, "Fq", {name: total[i] for i, name in enumerate(names)}, subs,
                               "Fq")
        if vals is not None:
            ans.steps.append(Step(
                "Numeric values",
                "At the configuration of the question (N·m for revolute joints, N for prismatic):",
                equations=[(a, vals[name]) for a, name in zip(acts, names)],
            ))
    return ans


def _load_part(question, ctx: SolveContext, ans: Answer, force, torque) -> sp.Matrix:
    """F_q = -J^T F_s for the external force (and torque: geometric Jacobian), with its steps."""
    point = question.point
    geometric = torque is not None
    ts = task_space(question, ctx, ctx.step_seconds, geometric=geometric)
    if geometric:
        f = sp.Matrix(force if force is not None else [0, 0, 0])
        tau = sp.Matrix(torque)
        part = balance_wrench(ts.J, f, tau)
        ans.steps.append(Step(
            "Geometric Jacobian",
            f"A torque needs the angular rows: $J = [J_P; J_\\omega]$ (velocity of {point}, "
            "angular velocity of the frame), and $F_q = -(J_P^T F + J_\\omega^T \\tau)$ with "
            "$F$ and $\\tau$ in frame 0:",
            equations=[("J", ts.J), ("F", f), ("\\tau", tau)],
        ))
    else:
        f = sp.Matrix(force)
        part = balance_force(ts.J, f)
        label = r"\begin{bmatrix}" + r" \\ ".join(ts.labels) + r"\end{bmatrix}"
        ans.steps.append(Step(
            "Jacobian of the load's coordinates",
            f"The load acts along the coordinates $S = {label}$ (one force component per "
            "coordinate):",
            equations=[("S", sp.Matrix(ts.coords)), ("J = \\frac{\\partial S}{\\partial Q}", ts.J),
                       ("F_s", f)],
        ))
    part = tidy_limited(ctx, part, ctx.step_seconds)
    ans.steps.append(Step(
        "Joint actions for the load",
        "",
        equations=[("F_q = -J^T F_s", part)],
    ))
    return part


def _weight_part(ctx: SolveContext, ans: Answer) -> sp.Matrix:
    """F_q = -sum J_G^T m g for the bodies' weights, with its steps and an energy cross-check."""
    model = ctx.model
    q = model.q
    g = sp.Matrix(model.gravity)
    jgs, masses, eqs = [], [], []
    for b in model.bodies:
        c0 = model.com0(b)
        jg = tidy_limited(ctx, c0.jacobian(q), ctx.step_seconds)
        jgs.append(jg)
        masses.append(b.mass)
        eqs.append((f"{{}}^{{0}}G_{{{name_tex(b.name, False)}}}", c0))
        eqs.append((f"J_{{G,{name_tex(b.name, False)}}}", jg))
    part = tidy_limited(ctx, balance_weight(jgs, masses, g), ctx.step_seconds)
    ans.steps.append(Step(
        "Weight of the bodies",
        "Each body's weight $m_i g$ acts at its centre of mass $G_i$ (from the pseudo-inertia: "
        "$c = J[1{:}3,4]/J[4,4]$, moved to frame 0). Its Jacobian $J_{G_i}$ maps joint rates "
        "to the velocity of $G_i$, so the joint actions that hold the robot still are "
        "$F_q = -\\sum_i J_{G_i}^T m_i\\, g$ (equal to $\\partial U/\\partial Q$, "
        "$U = -\\sum_i m_i\\, g\\cdot G_i$):",
        equations=eqs + [("g", g), ("F_q = -\\sum_i J_{G_i}^T m_i g", part)],
    ))
    # cross-check with the potential energy
    u = sum((-(b.mass * g.dot(model.com0(b))) for b in model.bodies), sp.Integer(0))
    check, _err = limited(ctx, ctx.step_seconds,
                          lambda: all(is_zero(d - p) for d, p in zip([u.diff(s) for s in q], part)))
    if check is False:
        ans.note("internal check failed: −ΣJ_Gᵀ m g differs from ∂U/∂q")
    return part
