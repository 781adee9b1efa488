"""Question 2: velocity and acceleration matrices W and H, the auxiliary frame,
and the velocity and acceleration of a point.

W by Rivals' theorem and H by Coriolis' theorem, every term in frame 0
(docs/course-notes.md#note-w-matrix, #note-h-matrix); the L matrices are generated
from M (dM/dq M^-1, #note-l-matrix).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.core.course_notes import note_link
from robosolve.core.simplify import tidy
from robosolve.core.transforms import vex
from robosolve.load.problem import Question
from robosolve.model.numeric import NumericChain, rigid_inverse
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step, missing_note
from robosolve.solvers.common import frame_tex, m_name, rel_name, symbolic_within_budget
from robosolve.core.prose import name_md
from robosolve.core.printing import latex


def _composition_step(title, text, model, chain, letter, relative, absolute, composed) -> Step:
    """The matrices `letter` (W or H) of each frame of `chain` relative to its parent, then
    composed with the parent's in frame 0 (`composed(parent, frame)` is the right-hand side)."""
    step = Step(title, text)
    for f in chain:
        parent = model.frames[f].parent
        step.equations.append((rel_name("0", parent, f, letter), relative(f)))
        if parent != "0":
            step.equations.append((f"{rel_name('0', '0', f, letter)} = {composed(parent, f)}", absolute(f)))
    return step


def angular_acceleration(h: sp.Matrix) -> sp.Matrix:
    """alpha from H = Wdot + W^2: the rotation block of W^2 is symmetric, that of
    Wdot is [alpha], so alpha = vex of the antisymmetric part of H's rotation block."""
    r = h[:3, :3]
    return (vex(r) - vex(r.T)).applyfunc(lambda e: tidy(e / 2))


def solve(question: Question, ctx: SolveContext) -> Answer:
    ans = Answer(question.type, question.id)
    symbolic_within_budget(ctx, ans, lambda: symbolic_part(question, ctx, ans), "derivation")
    if question.at:
        numeric_part(question, ctx, ans)
    return ans


def numeric_part(question: Question, ctx: SolveContext, ans: Answer) -> None:
    """Numeric answers from the numeric chain (products done in numpy)."""
    model = ctx.model
    frame, point = question.frame, question.point
    chain = NumericChain(model, ctx.substitutions(question.at))
    pframe, _ = model.point_local(point)

    def aux(mat, p):
        a = np.eye(4)
        a[:3, 3] = p
        return rigid_inverse(a) @ mat @ a

    def velocity():
        w, p = chain.W0(frame), chain.point0(point)
        return {"W": w, "W_aux": aux(w, p), "velocity": aux(chain.W0(pframe), p)[:3, 3],
                "angular_velocity": np.array([w[2, 1], w[0, 2], w[1, 0]])}

    def acceleration():
        h, p = chain.H0(frame), chain.point0(point)
        r = (h[:3, :3] - h[:3, :3].T) / 2
        return {"H": h, "H_aux": aux(h, p), "acceleration": aux(chain.H0(pframe), p)[:3, 3],
                "angular_acceleration": np.array([r[2, 1], r[0, 2], r[1, 0]])}

    subs = chain.subs
    for group, what, needed in ((velocity, "velocities", model.q + model.qd),
                                (acceleration, "accelerations", model.q + model.qd + model.qdd)):
        missing = sorted(s.name for s in needed if s not in subs)
        if missing:
            ans.note(missing_note(what, missing, ctx.problem))
            continue
        try:
            values = group()
        except MissingValues as exc:
            ans.note(missing_note(what, exc.names, ctx.problem))
            continue
        for key, v in values.items():
            ans.numeric[key] = [[float(x) for x in row] for row in v] if v.ndim == 2 else [float(x) for x in v]
    order = ["W", "H", "W_aux", "H_aux", "velocity", "acceleration", "angular_velocity", "angular_acceleration"]
    ans.numeric = {k: ans.numeric[k] for k in order if k in ans.numeric}
    shown = [(lhs, ans.numeric[k]) for lhs, k in (
        (f"\\dot{{{point}}}", "velocity"), (f"\\ddot{{{point}}}", "acceleration"),
        ("\\omega", "angular_velocity"), ("\\dot\\omega", "angular_acceleration")) if k in ans.numeric]
    if shown:
        ans.steps.append(Step("Numeric values", "At the configuration of the question:", equations=shown))


def _l_matrices_step(model, chain) -> Step:
    """The L matrix of each joint of `chain`, in its parent and moved to frame 0."""
    lstep = Step(
        "L matrices of the joints",
        "For joint $i$, moving frame $j$ relative to its parent $p$: "
        "${}^{p}L = \\partial\\, {}^{p}M_{j} / \\partial q_i \\cdot {}^{p}M_{j}^{-1}$, "
        "then moved to frame 0 with ${}^{0}L = {}^{0}M_{p}\\, {}^{p}L\\, {}^{0}M_{p}^{-1}$ ("
        + note_link("l-matrix") + ").",
    )
    for f in chain:
        parent = model.frames[f].parent
        for i in model.joints_in(f):
            j = model.joints[i]
            q = latex(j.symbol)
            lstep.equations.append((f"{{}}^{{{frame_tex(parent)}}}L_{{{q}}}", model.L_local(i, f)))
            if parent != "0":
                lstep.equations.append((f"{{}}^{{0}}L_{{{q}}} = {m_name('0', parent)}\\,"
                                        f"{{}}^{{{frame_tex(parent)}}}L_{{{q}}}\\,{m_name('0', parent)}^{{-1}}",
                                        model.L0(i, f)))
    return lstep


def symbolic_part(question: Question, ctx: SolveContext, ans: Answer) -> None:
    model = ctx.model
    frame, point = question.frame, question.point
    chain = model.chain(frame)

    ans.steps.append(_l_matrices_step(model, chain))

    # Rivals
    ans.steps.append(_composition_step(
        "Velocity matrices (Rivals' theorem)",
        "Every term is expressed in frame 0: "
        "${}^{0}W_{0,j} = {}^{0}W_{0,p} + {}^{0}W_{p,j}$ with ${}^{0}W_{p,j} = \\sum {}^{0}L_i\\, \\dot q_i$ "
        "over the joints that move frame $j$ relative to its parent (" + note_link("w-matrix") + ").",
        model, chain, "W", model.W_relative0, model.W0,
        lambda parent, f: f"{rel_name('0', '0', parent, 'W')} + {rel_name('0', parent, f, 'W')}"))

    # Coriolis
    ans.steps.append(_composition_step(
        "Acceleration matrices (Coriolis' theorem)",
        "${}^{0}H_{0,j} = {}^{0}H_{0,p} + 2\\,{}^{0}W_{0,p}\\,{}^{0}W_{p,j} + {}^{0}H_{p,j}$, every term in "
        "frame 0; the relative term is ${}^{0}H_{p,j} = {}^{0}L\\,\\ddot q + {}^{0}L^2\\,\\dot q^2$ for one "
        "joint (in general $\\ddot M M^{-1}$ moved to frame 0). $H = \\dot W + W^2$ "
        "(not $\\dot W\\, W^2$: " + note_link("h-matrix") + ").",
        model, chain, "H", model.H_relative0, model.H0,
        lambda parent, f: (f"{rel_name('0', '0', parent, 'H')} + "
                           f"2\\,{rel_name('0', '0', parent, 'W')}\\,{rel_name('0', parent, f, 'W')} + "
                           f"{rel_name('0', parent, f, 'H')}")))

    w0 = model.W0(frame) if frame != "0" else sp.zeros(4, 4)
    h0 = model.H0(frame) if frame != "0" else sp.zeros(4, 4)
    pframe, _ = model.point_local(point)
    w_aux, h_aux = model.W_aux(frame, point), model.H_aux(frame, point)
    # The point's own frame carries it (it may differ from the question's frame).
    w_p = model.W_aux(pframe, point) if pframe != frame else w_aux
    h_p = model.H_aux(pframe, point) if pframe != frame else h_aux
    velocity = w_p[:3, 3]
    acceleration = h_p[:3, 3]
    omega = vex(w0[:3, :3])
    alpha = angular_acceleration(h0)

    ans.steps.append(Step(
        f"Auxiliary frame at {point}",
        "The last column of $W$ is the velocity of the body point passing through $O_0$, not of "
        f"{point}. The auxiliary frame $a$ has its origin at {point} and the axes of frame 0: "
        "${}^{a}W = {}^{a}M_{0}\\,{}^{0}W\\,{}^{0}M_{a}$, whose last column is the velocity of the "
        "point (and likewise for $H$).",
        equations=[(m_name("0", "a"), model.auxiliary(point)),
                   (f"{{}}^{{a}}W_{{0,{frame_tex(frame)}}}", w_aux),
                   (f"{{}}^{{a}}H_{{0,{frame_tex(frame)}}}", h_aux)],
    ))
    if pframe != frame:
        ans.note(f"point {point} is fixed in frame {name_md(pframe)}: its velocity and acceleration use the "
                 f"motion of frame {name_md(pframe)}; W_aux and H_aux are those of frame {name_md(frame)}")
    ans.steps.append(Step(
        f"Velocity and acceleration of {point}",
        "Read from the last columns of ${}^{a}W$ and ${}^{a}H$; the angular velocity "
        "$\\omega$ is the vector of the skew block of $W$, the angular acceleration that of "
        "the antisymmetric part of $H$'s rotation block.",
        equations=[(f"\\dot{{{point}}}", velocity), (f"\\ddot{{{point}}}", acceleration),
                   ("\\omega", omega), ("\\dot\\omega", alpha)],
    ))

    ans.symbolic.update({
        "W": w0, "H": h0, "W_aux": w_aux, "H_aux": h_aux,
        "velocity": list(velocity), "acceleration": list(acceleration),
        "angular_velocity": list(omega), "angular_acceleration": list(alpha),
    })
