"""Question 5: force, velocity and compliance ellipsoids at one configuration, the
condition number, and the joint rates for a desired end-effector velocity.

Conventions (docs/course-notes.md#note-ellipsoid-axes): A = J·Jᵀ with unit eigenvectors ϑ̂ᵢ; force semi-axes Kf/√νᵢ, velocity
Kv·√νᵢ, compliance Ka·κᵢ (κᵢ eigenvalues of Ks = J·Kq·Jᵀ); condition number
max ν / min ν = cond(J)². Layout: spec "Ellipsoids" (robosolve.kinematics.ellipsoids_math).
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.core.course_notes import note_link
from robosolve.kinematics.ellipsoids_math import ellipsoids, exact_values, joint_rates
from robosolve.solvers.task_space import limited, position_axes, task_space
from robosolve.solvers.base import (
    Answer, FigureSpec, MissingValues, SolveContext, Step, missing_note)
from robosolve.core.printing import latex


def _col(labels):
    return r"\begin{bmatrix}" + r" \\ ".join(labels) + r"\end{bmatrix}"


def _vec_tex(v) -> Text:
    """A unit direction for a table: 4 digits are all a reader can use."""
    return Text("(", Text.join(", ", [Num(x, digits=4) for x in v]), ")")


def _num(x, unit: str = "") -> Text:
    return Text("∞" + (" " + unit if unit else "")) if x is None else Text(Num(x, unit))


def _units(question, model, ts):
    """Units of force, velocity, displacement along the coordinates (N, m/s, m when they
    are all positions)."""
    raw = question.options.get("coordinates")
    if raw is None or position_axes(question, model, raw) is not None:
        return "N", "m/s", "m"
    return "N or N·m", "m/s or rad/s", "m or rad"


def solve(question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    opts = question.options
    ts = task_space(question, ctx, ctx.step_seconds)
    J = ts.J
    m, n = J.shape
    subs = ctx.substitutions(question.at)
    f_unit, v_unit, c_unit = _units(question, model, ts)
    budgets = opts.get("budgets", {}) or {}
    kf_s = budgets.get("force", sp.Integer(1))
    kv_s = budgets.get("velocity", sp.Integer(1))
    ka_s = budgets.get("compliance", sp.Integer(1))
    kq_s = list(opts.get("joint_compliance") or [sp.Integer(1)] * n)

    A = J * J.T
    ans.symbolic["A"] = A
    ans.steps.append(_jacobian_step(ts, J, A))
    try:
        jn = ctx.numeric(J, subs)
    except MissingValues as exc:
        ans.note(missing_note("ellipsoids", exc.names, ctx.problem))
        return ans
    import numpy as np

    jn_a = np.array(jn, dtype=float).reshape(m, n)
    kf, kv, ka, kq = _numeric_budgets(ctx, subs, ans, kf_s, kv_s, ka_s, kq_s)
    res = ellipsoids(jn_a, kf=kf or 1.0, kv=kv or 1.0, ka=ka or 1.0,
                     kq=kq if kq is not None else [1.0] * n)
    for note in res.notes:
        ans.note(note)
    ans.numeric["A"] = res.A

    # exact values where the configuration is exact
    j_exact = J.xreplace(subs)
    exact = None
    if not j_exact.free_symbols and not j_exact.has(sp.Float):
        exact, _err = limited(ctx, min(ctx.step_seconds, 10), exact_values, j_exact,
                              kf_s.xreplace(subs), kv_s.xreplace(subs), ka_s.xreplace(subs),
                              [x.xreplace(subs) for x in kq_s])
    if exact is not None:
        ans.symbolic["eigenvalues"] = exact["eigenvalues"]

    ans.steps.append(_eigen_step(res, exact, jn, j_exact))
    ans.numeric["eigenvalues"] = res.eigenvalues
    ans.steps.append(_force_step(res, exact, kf_s, f_unit))
    _put(ans, "force", res.force, kf, exact, "force")
    ans.steps.append(_velocity_step(res, exact, kv_s, v_unit, m == n))
    _put(ans, "velocity", res.velocity, kv, exact, "velocity")
    ans.steps.append(_compliance_step(res, exact, J, kq_s, ka_s, c_unit))
    if kq is not None:
        _put(ans, "compliance", res.compliance, ka, exact, "compliance")
    _condition_number(ans, res, exact)
    if opts.get("velocity") is not None:
        _joint_rates(ans, ctx, model, list(opts["velocity"]), subs, jn_a, m == n)

    fig = _figure(question, ctx, ts, res, subs, (kf, kv, ka), (f_unit, v_unit, c_unit))
    if fig is not None:
        ans.figures.append(fig)
    elif m not in (2, 3):
        ans.note(f"No ellipsoid figure for {m} coordinates (only 2 or 3 can be drawn).")
    return ans


# -- compute ------------------------------------------------------------------------
def _numeric_budgets(ctx, subs, ans, kf_s, kv_s, ka_s, kq_s):
    """Kf, Kv, Ka and the joint compliances as floats (None, with a note, where a value is missing)."""
    def budget(expr, what):
        try:
            return float(ctx.numeric(expr, subs))
        except MissingValues as exc:
            ans.note(missing_note(what, exc.names, ctx.problem))
            return None

    kf = budget(kf_s, "force ellipsoid (budget Kf)")
    kv = budget(kv_s, "velocity ellipsoid (budget Kv)")
    ka = budget(ka_s, "compliance ellipsoid (budget Ka)")
    try:
        kq = [float(x) for x in ctx.numeric(kq_s, subs)]
    except MissingValues as exc:
        ans.note(missing_note("compliance ellipsoid (joint compliances)", exc.names, ctx.problem))
        kq = None
    return kf, kv, ka, kq


def _put(ans, key, ax, budget_value, exact, exact_key):
    """One ellipsoid's answer (only when its budget is known)."""
    if budget_value is None:
        return
    ans.numeric[key] = {"semi_axes": ax.semi_axes, "lengths": ax.lengths,
                        "directions": ax.directions}
    if exact is not None:
        ans.symbolic[key] = {"lengths": exact[exact_key]}


def _joint_rates(ans, ctx, model, velocity, subs, jn_a, square):
    """q_dot for the desired end-effector velocity, with its step."""
    try:
        v = [float(x) for x in ctx.numeric(velocity, subs)]
    except MissingValues as exc:
        ans.note(missing_note("q_dot", exc.names, ctx.problem))
        return
    qd, _resid, note = joint_rates(jn_a, v)
    if note:
        ans.note(note)
    names = [j.name for j in model.joints]
    ans.numeric["q_dot"] = {k: x for k, x in zip(names, qd)}
    how = ("$\\dot Q = J^{-1} V$" if square and note is None
           else "$\\dot Q = J^{+} V$ (pseudo-inverse: minimum-norm least squares)")
    ans.steps.append(Step(
        "Joint velocities for the desired velocity",
        f"{how}" + (f". {note}" if note else "") + ":",
        equations=[("V", v)] + [(ctx.symbol_latex.get(j.dot, latex(j.dot)), x)
                                for j, x in zip(model.joints, qd)],
    ))


# -- steps --------------------------------------------------------------------------
def _jacobian_step(ts, J, A) -> Step:
    m, n = J.shape
    return Step(
        "Jacobian and the matrix A",
        f"Task coordinates $S = {_col(ts.labels)}$ and $J = \\partial S / \\partial Q$ "
        f"({m}×{n}). The joint budget $\\|F_q\\| \\le K_f$ with $F_q = -J^T F$ gives "
        "$F^T J J^T F \\le K_f^2$: every ellipsoid below is governed by $A = J J^T$.",
        equations=[("J", J), ("A = J J^T", A)],
    )


def _eigen_step(res, exact, jn, j_exact) -> Step:
    if exact is not None:
        eqs = [("J", j_exact), ("A", exact["A"])]
    else:
        eqs = [("J", jn), ("A", res.A)]

    def exact_tex(i):
        if exact is None or exact["eigenvalues"][i].is_Integer:
            return ""
        return f" = ${latex(exact['eigenvalues'][i])}$"

    rows = [[str(i + 1), _num(nu) + exact_tex(i),
             _vec_tex(vec)] for i, (nu, vec) in enumerate(zip(res.eigenvalues, res.eigenvectors))]
    return Step(
        "Eigenvalues and unit eigenvectors of A",
        "At the configuration of the question. The eigenvalues $\\nu_i$ are the roots of "
        "$\\det(A - \\nu I) = 0$; each eigenvector $\\hat\\vartheta_i$ solves "
        "$(A - \\nu_i I)\\,\\vartheta_i = 0$ and is normalised to unit length (" + note_link("ellipsoid-axes") + "). A is symmetric, so the eigenvectors are orthogonal: they are the common axes "
        "of the three ellipsoids.",
        equations=eqs,
        table=(["i", "ν_i", "unit eigenvector ϑ̂_i"], rows),
    )


def _axes_table(ax, unit):
    return (["axis", "length", "direction", "semi-axis"],
            [[str(i + 1), _num(ln, unit), _vec_tex(d),
              _vec_tex(s) if s is not None else "∞ (unbounded)"]
             for i, (ln, d, s) in enumerate(zip(ax.lengths, ax.directions, ax.semi_axes))])


def _force_step(res, exact, kf_s, f_unit) -> Step:
    return Step(
        "Force ellipsoid",
        "The end-effector forces that the joints balance within the budget $K_f$ "
        "($F_q^T F_q = K_f^2$) satisfy $F^T A F = K_f^2$. Along $\\hat\\vartheta_i$, "
        "$s^2 \\nu_i = K_f^2$, so the semi-axes are $\\frac{K_f}{\\sqrt{\\nu_i}}\\,\\hat\\vartheta_i$ "
        f"(" + note_link("ellipsoid-axes") + f"), sorted by decreasing length; here $K_f = {latex(kf_s)}$ {f_unit}."
        + (" A zero eigenvalue makes the force semi-axis infinite: forces along it are carried "
           "by the structure (reported as null)." if res.singular else ""),
        table=_axes_table(res.force, f_unit),
        equations=([("a_i", exact["force"])] if exact is not None else []),
    )


def _velocity_step(res, exact, kv_s, v_unit, square) -> Step:
    vel_text = ("With $\\dot Q^T \\dot Q = K_v^2$ and $\\dot Q = J^{-1} V$: "
                "$V^T A^{-1} V = K_v^2$." if square else
                "With $\\dot Q^T \\dot Q = K_v^2$ and the minimum-norm $\\dot Q = J^{+} V$ "
                "(J not square): $V^T A^{-1} V = K_v^2$ (" + note_link("ellipsoid-axes") + ").")
    return Step(
        "Velocity ellipsoid",
        vel_text + " $A^{-1}$ has the same eigenvectors and eigenvalues $1/\\nu_i$, so the "
        "semi-axes are $K_v\\sqrt{\\nu_i}\\,\\hat\\vartheta_i$: the same axes as the force "
        "ellipsoid in inverse proportions (the direction of the longest force axis carries the "
        f"shortest velocity axis). Here $K_v = {latex(kv_s)}$ {v_unit}."
        + (" A zero eigenvalue flattens it: no velocity is possible along that axis."
           if res.singular else ""),
        table=_axes_table(res.velocity, v_unit),
        equations=([("c_i", exact["velocity"])] if exact is not None else []),
    )


def _compliance_step(res, exact, J, kq_s, ka_s, c_unit) -> Step:
    ks_sym = J * sp.diag(*kq_s) * J.T
    return Step(
        "Compliance ellipsoid",
        "The joints yield $\\delta Q = K_q\\,\\tau$ under their actions ($K_q$ the joint "
        "compliances, rad/(N·m) or m/N); with $\\tau = -J^T F$ the end effector moves "
        "$\\delta S = K_s F$ (sign aside), $K_s = J K_q J^T$. A force budget $F^T F = K_a^2$ gives "
        "$\\delta S^T K_s^{-T} K_s^{-1} \\delta S = K_a^2$ (" + note_link("compliance-ellipsoid") + "), with semi-axes "
        "$K_a\\,\\kappa_i$ along the unit eigenvectors of $K_s$ ($\\kappa_i$ its eigenvalues). "
        f"Here $K_q = \\mathrm{{diag}}({', '.join(latex(x) for x in kq_s)})$ and "
        f"$K_a = {latex(ka_s)}$ {c_unit}.",
        equations=[("K_s = J K_q J^T", ks_sym), ("K_s", res.Ks)]
        + ([("\\kappa_i", exact["compliance_eigenvalues"])] if exact is not None else []),
        table=_axes_table(res.compliance, c_unit),
    )


def _condition_number(ans, res, exact) -> None:
    """The condition number's answer and step (infinite, null, at a singular configuration)."""
    if res.condition_number is None:
        ans.numeric["condition_number"] = None
        ans.steps.append(Step(
            "Condition number",
            "$\\min \\nu = 0$: the configuration is singular and the condition number "
            "$\\max\\nu / \\min\\nu$ is infinite (reported as null)."))
        return
    ans.numeric["condition_number"] = res.condition_number
    if exact is not None and exact["condition_number"] is not None:
        ans.symbolic["condition_number"] = exact["condition_number"]
    ratio = res.condition_number ** 0.5
    ans.steps.append(Step(
        "Condition number",
        Text("The isotropy of the robot at this configuration is measured by the condition "
             "number of A, $\\max\\nu / \\min\\nu$ (" + note_link("condition-number") + "). It equals $\\mathrm{cond}(J)^2$, "
             "the square of the ratio of the largest to the smallest singular value of J, and the "
             "ratio of the ellipse's longest to shortest semi-axis is its square root (",
             Num(ratio), "). 1 would be an isotropic configuration."),
        equations=([("\\frac{\\max \\nu}{\\min \\nu}", exact["condition_number"])]
                   if exact is not None and exact["condition_number"] is not None else [])
        + [("\\frac{\\max \\nu}{\\min \\nu}", res.condition_number)],
    ))


def _figure(question, ctx, ts, res, subs, budgets, units):
    model = ctx.model
    m = ts.J.shape[0]
    if m not in (2, 3):
        return None
    raw = question.options.get("coordinates")
    axes = [0, 1, 2] if raw is None else position_axes(question, model, raw)
    robot, end = None, [0.0] * m
    if axes is not None:
        try:
            from robosolve.solvers.common import robot_drawing

            drawing = robot_drawing(ctx, subs)
        except ImportError:
            drawing = None
        if drawing is not None:
            robot = [[[p[a] for a in axes] for p in link] for link in drawing["links"]]
            try:
                p = ctx.numeric(list(model.point0(question.point)), subs)
                end = [p[a] for a in axes]
            except MissingValues:
                return None
    panels = []
    for key, title, ax, b, unit in (("force", "Force ellipse", res.force, budgets[0], units[0]),
                                    ("velocity", "Velocity ellipse", res.velocity, budgets[1],
                                     units[1]),
                                    ("compliance", "Compliance ellipse", res.compliance,
                                     budgets[2], units[2])):
        if b is None:
            continue
        panels.append({"key": key, "title": title if m == 2 else title.replace("ellipse", "ellipsoid"),
                       "unit": unit, "lengths": ax.lengths, "directions": ax.directions})
    if not panels:
        return None
    data = {"dims": m, "axis_labels": ts.texts, "robot": robot, "end": end, "panels": panels}
    return FigureSpec("ellipsoids", "ellipsoids",
                      "Ellipsoids at the configuration of the question", data)
