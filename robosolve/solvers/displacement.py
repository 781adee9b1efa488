"""§3.1: the displacement matrix Q between two poses and its helical axis.

`from`/`to` are two 4x4 poses (no robot needed) or two configurations of the
robot (then the poses are those of `frame`, default the last frame). Q is
expressed in frame 0; with explicit matrices and a robot, `frame` asks for Q in
that frame instead: Q_k = M_0k^-1 Q_0 M_0k, M_0k taken at the question's `at`.
Engines: robosolve.geometry.helical (formulas and special cases there).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import sympy as sp

from robosolve.core.course_notes import note_link
from robosolve.core.simplify import exact_geometry
from robosolve.core.simplify import full as full_simplify
from robosolve.errors import SymbolicTimeout
from robosolve.geometry.helical import (
    Screw, displacement_matrix, express_in_frame, helical_numeric, helical_symbolic, normalise_screw,
    screw_matrices,
)
from robosolve.load.problem import Question
from robosolve.solvers.base import Answer, FigureSpec, MissingValues, SolveContext, Step, missing_note
from robosolve.solvers.common import frame_tex, geometry_matrix, m_name, nearest_rotation_if_rounded
from robosolve.core.prose import name_md, name_plot

CASE_TEXT = {
    "general": "$0 < \\alpha < \\pi$: $\\sin\\alpha > 0$, so the axis comes from the skew-symmetric part, "
               "$u = \\operatorname{vex}(R - R^T)/(2\\sin\\alpha)$ (" + note_link("helical-axis") + ").",
    "generic": "symbolic rotation: the general formulas $u = \\operatorname{vex}(R - R^T)/(2\\sin\\alpha)$, "
               "valid where $\\sin\\alpha \\neq 0$.",
    "half_turn": "$\\alpha = \\pi$: $R - R^T = 0$ gives no axis, so it comes from the symmetric part, "
                 "$u_i^2 = (R_{ii} + 1)/2$, $u_i u_j = (R_{ij} + R_{ji})/4$ (" + note_link("helical-axis") + "); "
                 "$u$ and $-u$ are the same displacement, the one with its first non-zero component "
                 "positive is given.",
    "translation": "$\\alpha = 0$: a pure translation, $u = \\Delta T/|\\Delta T|$, $h = |\\Delta T|$; "
                   "there is no axis point and the pitch is infinite (" + note_link("helical-axis") + ").",
    "identity": "$Q = I$: no displacement; the axis is undefined.",
}


def solve(question: Question, ctx: SolveContext) -> Answer:
    if "axis" in question.options:
        return _solve_screw(question, ctx)
    ans = Answer(question.type, question.id)
    try:
        m01, m02, where, expressed, m0k = _poses(question, ctx, ans)
    except MissingValues as exc:
        ans.error = missing_note("poses", exc.names, ctx.problem)
        return ans
    q0 = displacement_matrix(m01, m02)
    q = express_in_frame(q0, m0k) if m0k is not None else q0
    q = geometry_matrix(ctx, q)
    f = frame_tex(expressed)

    steps = [Step(
        "Displacement matrix",
        f"{where} Every body point moves as ${{}}^0P_2 = Q_0\\,{{}}^0P_1$ (" + note_link("displacement-matrix") + "), so "
        "$Q_0 = {}^0M_2\\,{}^0M_1^{-1}$."
        + (f" In frame {name_md(expressed)}: $Q_{{{f}}} = {m_name('0', expressed)}^{{-1}}\\,Q_0\\,{m_name('0', expressed)}$ "
           "(item 24)." if m0k is not None else ""),
        equations=[("{}^0M_1", m01), ("{}^0M_2", m02), (f"Q_{{{f}}}", q)],
    )]
    ans.symbolic["Q"] = q
    sym_case = None
    try:
        with ctx.time_limit():
            hx = helical_symbolic(q)
        ops = ctx.budgets.simplify.geometry_ops
        sym = {k: _tidy(v, ops) for k, v in _layout(hx).items()}
        ans.symbolic.update(sym)
        hx = dataclasses.replace(hx, axis=sym["u"], angle=sym["alpha"], h=sym["h"], point=sym["P"],
                                 pitch=sym["pitch"], cos_alpha=_tidy(hx.cos_alpha, ops),
                                 sin_alpha=_tidy(hx.sin_alpha, ops))
        steps.append(_formula_step(hx))
        sym_case = hx.case
        for n in hx.notes:
            ans.note(n)
    except SymbolicTimeout:
        ans.note("the symbolic helical axis was cut short by its time limit; numeric answers only")
    except ValueError as exc:
        ans.error = f"not a rigid displacement: {exc}"
        return ans

    subs = ctx.substitutions(question.at)
    try:
        qn = np.array(ctx.numeric(q, subs), dtype=float)
        m1n = np.array(ctx.numeric(m01, subs), dtype=float)
        m2n = np.array(ctx.numeric(m02, subs), dtype=float)
        mkn = np.array(ctx.numeric(m0k, subs), dtype=float) if m0k is not None else np.eye(4)
    except MissingValues as exc:
        ans.note(missing_note("helical axis", exc.names, ctx.problem))
        ans.steps = steps
        return ans
    problem = _rigidity(qn)
    if problem:
        ans.error = f"not a rigid displacement: {problem}"
        return ans
    hn = helical_numeric(qn)
    ans.numeric = _layout(hn, qn.tolist())
    steps.append(_numeric_step(hn, f))
    if sym_case != hn.case:  # no symbolic step, or the numbers fall in a special case
        steps[-1].text += " Case: " + CASE_TEXT[hn.case]
    ans.steps = steps
    ans.figures.append(FigureSpec(
        "helical_axis", "helical_axis", f"Helical axis and the initial and final frames (in frame {name_plot(expressed)})",
        _figure_data(hn, m1n, m2n, mkn, expressed)))
    return ans


# ---------------------------------------------------------------------------


def _projected(ans, opts):
    """`from`/`to` with a rotation block rounded by hand replaced by the nearest rotation (a note)."""
    out = {}
    for side in ("from", "to"):
        o = opts[side]
        if "matrix" in o:
            m = sp.Matrix(o["matrix"])          # a copy: the question's own matrix stays as given
            m[:3, :3] = nearest_rotation_if_rounded(ans, m[:3, :3], f"The rotation block of `{side}`")
            o = {**o, "matrix": m}
        out[side] = o
    return out["from"], out["to"]


def _poses(question, ctx, ans):
    opts = question.options
    src, dst = _projected(ans, opts)
    model = ctx.model
    if "config" in src or "config" in dst:
        frame = question.frame

        def pose(o):
            if "matrix" in o:
                return o["matrix"]
            subs = {j.symbol: o["config"][j.name] for j in model.joints if j.name in o["config"]}
            return model.M0(frame).xreplace(subs)

        where = (f"The body is frame {name_md(frame)}: its poses ${{}}^0M_1$, ${{}}^0M_2$ are "
                 f"${m_name('0', frame)}$ at the two configurations.")
        return pose(src), pose(dst), where, "0", None
    where = "The two poses are given."
    if question.frame_given and model is not None and question.frame != "0":
        subs = {s: v for s, v in question.at.items() if s in set(model.q)}
        return src["matrix"], dst["matrix"], where, question.frame, model.M0(question.frame).xreplace(subs)
    return src["matrix"], dst["matrix"], where, "0", None


def _rigidity(q: np.ndarray) -> str:
    r = q[:3, :3]
    if not np.allclose(r.T @ r, np.eye(3), atol=1e-6) or abs(np.linalg.det(r) - 1) > 1e-6:
        return "the rotation block of Q is not a proper rotation (check the poses)"
    if not np.allclose(q[3], [0, 0, 0, 1], atol=1e-9):
        return "the last row of Q is not [0, 0, 0, 1]"
    return ""


def _layout(hx, q=None) -> dict:
    out = {} if q is None else {"Q": q}
    out.update({"u": hx.axis, "alpha": hx.angle, "h": hx.h, "P": hx.point, "pitch": hx.pitch})
    return out


def _formula_step(hx) -> Step:
    eqs = [("\\cos\\alpha = \\frac{x_x + y_y + z_z - 1}{2}", hx.cos_alpha),
           ("\\sin\\alpha = \\tfrac12\\left|\\operatorname{vex}(R - R^T)\\right|", hx.sin_alpha),
           ("\\alpha", hx.angle)]
    if hx.axis is not None:
        eqs.append(("u", sp.Matrix(hx.axis)))
    eqs.append(("h = u \\cdot \\Delta T" if hx.case not in ("translation", "identity") else "h = |\\Delta T|",
                hx.h))
    if hx.point is not None:
        eqs.append(("P^* = \\frac{(I - R^T)\\,\\Delta T}{2(1 - \\cos\\alpha)}", sp.Matrix(hx.point)))
        eqs.append(("p = h/\\alpha", hx.pitch))
    return Step(
        "Helical axis (Mozzi-Chasles)",
        "Q is a rotation by $\\alpha \\in [0, \\pi]$ about the axis $(u, P^*)$ plus a translation $h$ "
        "along it. $\\sin\\alpha$ is taken $\\geq 0$, which fixes the sign of $u$ (" + note_link("helical-axis") + "). "
        "Case: " + CASE_TEXT[hx.case] + (" $P^*$ is the point of the axis nearest the origin "
                                         "($P^* \\cdot u = 0$)." if hx.point is not None else ""),
        equations=eqs,
    )


def _numeric_step(hn, f) -> Step:
    text = "With the numbers (robust formulas: $\\alpha = \\operatorname{atan2}(\\sin\\alpha, \\cos\\alpha)$; " \
           "$P^* = \\tfrac12(\\Delta T_\\perp + \\cot(\\alpha/2)\\,u \\times \\Delta T)$, the same point " \
           "without the cancellation of $1 - \\cos\\alpha$ at small angles)."
    eqs = [(f"Q_{{{f}}}", [list(r) + [t] for r, t in zip(hn.R, hn.dT)] + [[0.0, 0.0, 0.0, 1.0]]),
           ("\\alpha", hn.angle), ("u", hn.axis), ("h", hn.h)]
    if hn.point is not None:
        eqs += [("P^*", hn.point), ("p", hn.pitch)]
    return Step("Numeric values", text, equations=eqs)


def _figure_data(hn, m1, m2, mk, expressed) -> dict:
    inv = np.linalg.inv(mk)
    a, b = inv @ m1, inv @ m2

    def frame(m, name):
        return {"name": name, "origin": m[:3, 3].tolist(), "axes": [m[:3, c].tolist() for c in range(3)]}

    return {
        "frames": [frame(np.eye(4), expressed), frame(a, "initial"), frame(b, "final")],
        "axis": None if hn.axis is None else {"u": hn.axis, "point": hn.point},
        "alpha": hn.angle, "h": hn.h, "case": hn.case,
    }


def _tidy(v, ops: int):
    if v is None:
        return None
    if isinstance(v, list):
        return [exact_geometry(x, ops) for x in v]
    return exact_geometry(v, ops)


# --------------------------------------------------------------------------- a screw given
SCREW_CASE = {
    "general": "",
    "half_turn": " At $\\alpha = \\pi$ the axis $u$ and $-u$ give the same displacement: the one whose "
                 "first non-zero component is positive is kept (with $h$ following it).",
    "translation": " The angle is a whole number of turns: the displacement is a pure translation, "
                   "$u = \\Delta T/|\\Delta T|$, $h = |\\Delta T|$, with no axis point and no pitch.",
    "identity": " The angle is a whole number of turns and there is no translation: $Q = I$, the axis is "
                "undefined.",
}


def _solve_screw(question: Question, ctx: SolveContext) -> Answer:
    """§3.1.5-3.1.6: Q and L from a helical axis (u, alpha, P*, h), normalised as from/to gives it."""
    ans = Answer(question.type, question.id)
    o = question.options
    axis, angle = o["axis"], o["angle"]
    through = o.get("through", [sp.S.Zero] * 3)
    h_given = o.get("translation", sp.S.Zero)
    subs = ctx.substitutions(question.at)
    params = {k: v for k, v in subs.items() if k in ctx.problem.parameters}
    given = list(axis) + [angle] + list(through) + [h_given]
    missing = ctx.missing(given, params)
    if missing:
        # the branch (turns, sign of u) needs the numbers: keep the given angle, with a note
        ans.note(missing_note("screw", missing, ctx.problem))
        ans.note("without the numbers the angle is taken as given, assumed in (0, π)")
        norm = sp.sqrt(sum((sp.sympify(x) ** 2 for x in axis), sp.S.Zero))
        u = [full_simplify(x / norm) for x in axis]
        uu = sp.Matrix(u)
        p0 = sp.Matrix(through)
        point = [full_simplify(x) for x in (p0 - p0.dot(uu) * uu)]
        screw = Screw("general", u, angle, h_given, point, full_simplify(h_given / angle))
    else:
        try:
            screw = normalise_screw(axis, angle, through, h_given, values=params)
        except ValueError as exc:
            ans.error = f"not a screw: {exc}"
            return ans
    q, l_mat = screw_matrices(screw)
    ans.symbolic.update({"Q": q, "L": l_mat, "u": screw.axis, "alpha": screw.angle, "h": screw.h,
                         "P": screw.point, "pitch": screw.pitch})
    ans.steps.extend(_screw_steps(question, screw, q, l_mat))
    if missing:
        return ans
    num = ctx.numeric({"Q": q, "L": l_mat, "u": screw.axis, "alpha": screw.angle, "h": screw.h,
                       "P": screw.point, "pitch": screw.pitch}, subs)
    ans.numeric = num
    ans.steps.append(Step("Numeric values", "With the data:", equations=[
        ("Q", num["Q"]), ("L", num["L"]), ("\\alpha", num["alpha"]), ("h", num["h"])]
        + ([("u", num["u"])] if num["u"] is not None else [])
        + ([("P^*", num["P"]), ("p", num["pitch"])] if num["P"] is not None else [])))
    qn = np.array(num["Q"], dtype=float)
    hn = helical_numeric(qn)
    ans.figures.append(FigureSpec(
        "helical_axis", "helical_axis", "Helical axis and the frame before and after the displacement (in frame 0)",
        _figure_data(hn, np.eye(4), qn, np.eye(4), "0")))
    return ans


def _screw_steps(question, screw, q, l_mat) -> list:
    o = question.options
    a = sp.Matrix(o["axis"])
    given = [("\\text{axis}", a), ("\\text{angle}", o["angle"]),
             ("P_{\\text{given}}", sp.Matrix(o.get("through", [0, 0, 0]))),
             ("h_{\\text{given}}", o.get("translation", 0))]
    text = ("The screw is given by a direction of its axis, an angle, a point of the axis and a translation "
            "along it. It is written as the from/to form would find it from $Q$, so that the two forms give "
            "the same answers: $u = a/|a|$; the angle is brought into $[0, \\pi]$ (whole turns removed; an "
            "angle beyond $\\pi$, e.g. a negative one, is the rotation by $2\\pi - \\alpha$ about $-u$, and "
            "$h$ changes sign with $u$); $P^*$ is the point of the axis nearest the origin, "
            "$P^* = P - (P \\cdot u)\\,u$; the pitch is $p = h/\\alpha$."
            + SCREW_CASE[screw.case])
    eqs = given + [("\\alpha", screw.angle), ("h", screw.h)]
    if screw.axis is not None:
        eqs.insert(len(given), ("u", sp.Matrix(screw.axis)))
    if screw.point is not None:
        eqs += [("P^*", sp.Matrix(screw.point)), ("p = h/\\alpha", screw.pitch)]
    steps = [Step("Screw (helical axis)", text, equations=eqs)]
    if screw.case == "identity":
        steps.append(Step("Displacement and L matrices", "No motion: $Q = I$ and $L = 0$.",
                          equations=[("Q", q), ("L", l_mat)]))
        return steps
    if screw.case == "translation":
        steps.append(Step(
            "Displacement and L matrices",
            "A translation by $h$ along $u$: $R = I$, $\\Delta T = h\\,u$. With no rotation, "
            "$L = [0, u; 0, 0]$ and $Q = e^{h L} = I + h L$.",
            equations=[("Q", q), ("L", l_mat)]))
        return steps
    steps.append(Step(
        "Displacement matrix (Rodrigues)",
        "$[u]$ is the skew-symmetric matrix of $u$ ($[u]\\,v = u \\times v$). The rotation about the axis "
        "and the translation along it give $Q = [R, \\Delta T; 0, 1]$ with",
        equations=[("[u]", sp.Matrix([[0, -screw.axis[2], screw.axis[1]], [screw.axis[2], 0, -screw.axis[0]],
                                      [-screw.axis[1], screw.axis[0], 0]])),
                   ("R = I + [u]\\sin\\alpha + [u]^2(1 - \\cos\\alpha)", q[:3, :3]),
                   ("\\Delta T = (I - R)\\,P^* + h\\,u", q[:3, 3]),
                   ("Q", q)]))
    steps.append(Step(
        "L matrix",
        "An infinitesimal turn $d\\alpha$ about the same screw moves the body by $Q(d\\alpha) = I + d\\alpha\\,L$ "
        "with $L = [[u], t; 0, 0]$, $t = -[u]\\,P^* + p\\,u = P^* \\times u + p\\,u$; the finite displacement is "
        "$Q = e^{\\alpha L}$.",
        equations=[("t", l_mat[:3, 3]), ("L", l_mat)]))
    return steps
