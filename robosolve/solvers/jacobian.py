"""Question 3: the Jacobian of the task coordinates, its determinant (or manipulability)
and the singular configurations; optionally the geometric Jacobian and the
centre-of-mass Jacobians.

Conventions: J = ∂S/∂Q with S = F(Q) the chosen coordinates (rows) and Q the joints
(columns, joint order; docs/course-notes.md#note-jacobian-shape); the geometric Jacobian is 6 x n (velocity of the
point, angular velocity of the frame), built from the L matrices ⁰Lᵢ; singularities as
in the spec ("Singularities") and robosolve.kinematics.singularities.
"""

from __future__ import annotations

import copy
import math

import sympy as sp

from robosolve.core.numpy_code import numpy_modules
from robosolve.core.prose import Num, Text, name_md, name_tex
from robosolve.core.simplify import DEFAULT_BUDGETS
from robosolve.kinematics.jacobian_math import numeric_manipulability
from robosolve.kinematics.naming import name_conditions
from robosolve.kinematics.singularities import find_singularities
from robosolve.solvers.task_space import (
    joint_kinds, joint_l0, limited, over_input_budget, task_space, tidy_limited)
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step
from robosolve.core.opcount import count_ops
from robosolve.core.printing import latex


def _col(labels):
    return r"\begin{bmatrix}" + r" \\ ".join(labels) + r"\end{bmatrix}"


def _qtex(model):
    return [latex(s) for s in model.q]


def solve(question, ctx: SolveContext) -> Answer:
    model = ctx.model
    ans = Answer(question.type, question.id)
    opts = question.options
    geometric = bool(opts.get("geometric"))
    point = question.point
    q = model.q
    qtex = _qtex(model)
    ts = task_space(question, ctx, ctx.step_seconds, geometric=geometric)
    J = ts.J
    m, n = J.shape

    # -- S = F(Q) and the derivative, column by column -----------------------
    if geometric:
        _geometric_steps(ans, question, ctx, ts)
    else:
        what = (f"the coordinates of point {point} in frame 0" if ts.default
                else "the coordinates chosen in the question")
        ans.steps.append(Step(
            "Task coordinates S = F(Q)",
            f"The joint variables are $Q = ({', '.join(qtex)})$; the task coordinates are "
            f"{what}, as functions of the joints:",
            equations=[(f"S = {_col(ts.labels)}", sp.Matrix(ts.coords))],
        ))
        ans.steps.append(Step(
            "Derivatives, column by column",
            "Column $i$ of the Jacobian is the derivative of $S$ with respect to joint $i$ "
            "(the velocity of the coordinates when only that joint moves, at unit rate):",
            equations=[(f"\\frac{{\\partial S}}{{\\partial {t}}}", J[:, i]) for i, t in enumerate(qtex)],
        ))
        ans.steps.append(Step(
            "Jacobian",
            f"$\\dot S = J(Q)\\,\\dot Q$, with $J$ of size {m}×{n} (coordinates × joints):",
            equations=[("J = \\frac{\\partial S}{\\partial Q}", J)],
        ))
    ans.symbolic["J"] = J

    # -- determinant / manipulability and singular configurations -------------
    derived = _singularity_steps(ans, question, ctx, ts)

    # -- centre-of-mass Jacobians ----------------------------------------------
    com = {}
    if opts.get("bodies"):
        com = _com_steps(ans, ctx)
        ans.symbolic["com_jacobians"] = com

    # -- numbers ----------------------------------------------------------------
    _numeric(ans, question, ctx, J, com, distance=not derived)
    return ans


# ---------------------------------------------------------------------------

def _geometric_steps(ans, question, ctx, ts):
    model = ctx.model
    point = question.point
    frame = question.frame or model.problem.last_frame
    ls = [joint_l0(model, i, frame) for i in range(len(model.q))]
    ans.steps.append(Step(
        "L matrices of the joints in frame 0",
        "$^{0}L_i = \\frac{\\partial\\, {}^{0}M_i}{\\partial q_i}\\,{}^{0}M_i^{-1}$: its 3×3 block is "
        "$[u_i]$ (the joint's unit angular velocity, zero for a prismatic joint) and its last "
        "column $t_i$ is the velocity of the point of the moving body passing through $O_0$.",
        equations=[(f"{{}}^{{0}}L_{{{i + 1}}}", lm) for i, lm in enumerate(ls)],
    ))
    ans.steps.append(Step(
        "Geometric Jacobian",
        f"Column $i$ holds the velocity of point {point} and the angular velocity of frame "
        f"{name_md(frame)} produced by a unit rate of joint $i$: $v_i = [u_i]\\,{{}}^{{0}}{point} + t_i$ "
        "(the first three rows of $^{0}L_i$ times the homogeneous point), $\\omega_i = u_i$.",
        equations=[(f"{{}}^{{0}}{point}", model.point0(point)),
                   ("J = \\begin{bmatrix} J_P \\\\ J_\\omega \\end{bmatrix}", ts.J)],
    ))


def _singularity_steps(ans, question, ctx, ts):
    model = ctx.model
    kinds = joint_kinds(model)
    params = {s: v for s, v in ctx.parameter_values(
        {s: v for s, v in question.at.items() if s in ctx.problem.parameters}).items()}
    res, err, wide, det_parts = _rank_conditions_exact(ans, question, ctx, ts, kinds, params)
    if res is None:
        ans.note(f"The rank conditions (singular configurations) were not derived symbolically ({err}); "
                 "the numeric answers are given, with the distance from singularity at the question's "
                 "configuration.")
        ans.steps.append(Step("Singular configurations",
                              "The symbolic search was not completed (see the note): the smallest singular "
                              "value of J at the question's configuration, below, says how far it is from "
                              "a singular configuration."))
        return False
    if res.kind == "det":
        ans.symbolic["det"] = res.measure
        ans.steps.append(Step(
            "Determinant",
            "J is square: it loses rank where its determinant vanishes. Simplified and factored:",
            equations=[("\\det J", res.measure)],
        ))
        intro = ("Each factor of $\\det J$ that contains a joint is set to zero and solved "
                 "for a joint (every value in $(-\\pi, \\pi]$ for a revolute joint):")
    else:
        _manipulability_steps(ans, ctx, res, wide, ts)
        intro = ("J loses rank where all its maximal minors vanish together: a factor of one "
                 "minor is solved for a joint and substituted into the others:")
    conds = name_conditions(res.conditions, model.q, kinds, None,
                            model.point0(question.point), params,
                            m0_frames=[_joint_pose(model, i) for i in range(len(model.q))])
    conds = _tag_decoupled(conds, det_parts)
    ans.symbolic["singularities"] = [c.mapping() for c in conds]
    for note in res.notes:
        ans.note(note)
    rows, long_families = [], []
    for c in conds:
        rows.append([_condition_cell(c, long_families),
                     "; ".join(c.names) if c.names else "",
                     _within_limits(c, model, params)])
    if conds:
        text = intro + " " + _count_text(conds)
        ans.steps.append(Step("Singular configurations", text,
                              table=(["condition", "configuration", "within the joint limits"], rows)))
        ans.steps.extend(_family_step(k, c) for k, c in enumerate(long_families, 1))
    else:
        ans.steps.append(Step("Singular configurations",
                              "No factor vanishes for any joint value: J never loses rank "
                              "(for generic, non-zero parameters)."))
    return True


def _manipulability_steps(ans, ctx, res, wide, ts):
    """The minors of a non-square J (shown) and its manipulability w, the root of the sum of
    their squares (Cauchy–Binet)."""
    from robosolve.kinematics.jacobian_math import tidy

    m, n = ts.J.shape
    shape = "wide (redundant)" if m < n else "tall"
    minors = [mi for mi in res.minors]
    if wide is not None:
        # the minors by structure: w as the root of their squares (written out it is pages long)
        manip = "\\sqrt{" + " + ".join(f"\\Delta_{{{k + 1}}}^2" for k, mi in enumerate(minors) if mi != 0) + "}"
        ans.steps.append(_wide_step(wide, ts))
    else:
        # tidied only when short once expanded (a count, not the clock: a 4-joint arm's sum
        # of squared minors expands to 1,200 operations, and trigsimp spent 30 s on it)
        gram = None
        if count_ops(sp.expand(res.measure)) <= DEFAULT_BUDGETS.chain_ops:
            gram, _err = limited(ctx, ctx.step_seconds, tidy, res.measure)
        manip = sp.sqrt(gram if gram is not None else res.measure)
        ans.symbolic["manipulability"] = manip
    ans.steps.append(Step(
        "Manipulability",
        f"J is {m}×{n} ({shape}), so it has no determinant. Its manipulability is the product "
        "of its singular values, $w = \\sqrt{\\det(J J^T)}$ "
        + ("" if m < n else "(here $\\sqrt{\\det(J^T J)}$) ")
        + "and by the Cauchy–Binet formula $\\det(J J^T)$ is the sum of the squares of the "
          f"maximal ({min(m, n)}×{min(m, n)}) minors of J"
        + (":" if len(minors) <= 6 else
           f" ({len(minors)} minors, {sum(1 for x in minors if x != 0)} not identically zero; "
           "the first six of these are shown):"),
        equations=([(f"\\Delta_{{{k + 1}}}", mi) for k, mi in enumerate(minors)]
                   if len(minors) <= 6 else
                   [(f"\\Delta_{{{k + 1}}}", mi) for k, mi in enumerate(minors) if mi != 0][:6])
        + [("w", manip)],
    ))


# A condition longer than this (LaTeX characters) is written below the table, one equation a
# line, instead of in its cell: a wide Jacobian's family can be several long minors together.
LONG_CONDITION = 600


def _condition_cell(c, long_families: list) -> str:
    if not (c.values or c.equations):
        return "every configuration"
    tex = c.latex()
    if len(tex) <= LONG_CONDITION:
        return f"${tex}$"
    long_families.append(c)
    k = len(long_families)
    return f"family ({k}) below: {len(c.equations) + len(c.values)} conditions together"


def _family_step(k: int, c) -> Step:
    return Step(f"Singular family ({k})",
                "All of these hold together (a minor's equation, or a joint's value):",
                equations=[("0", e) for e in c.equations]
                + [(latex(q), v) for q, v in c.values])


STRUCTURE_MIN_JOINTS = 5     # below, det J is small: the direct route and its settled form


def _rank_conditions_exact(ans, question, ctx, ts, kinds, params):
    """`_rank_conditions`, with the decimals of the chain (a tool Tz(0.12) after d6, one DH entry
    written as a number, or a whole DH table of numbers) searched as symbols of their own, then
    written back: over RR[d6, …] nothing cancels exactly, and the search of a 6-joint arm's minors
    ran past its budget (or sympy's factoring failed); over RR alone round-off residues (1e-17·cos q1)
    stayed in det J and kept its factors together; as symbols they factor like parameters."""
    shadow = _decimal_shadow(ctx)
    if shadow is None:
        return _rank_conditions(ans, question, ctx, ts, kinds, params)
    sctx, back = shadow
    sts = task_space(question, sctx, ctx.step_seconds, geometric=ts.geometric)
    first = len(ans.steps)
    res, err, wide, det_parts = _rank_conditions(ans, question, sctx, sts, kinds, {**params, **back})
    for st in ans.steps[first:]:
        st.equations = [(lhs, _xreplaced(rhs, back)) for lhs, rhs in st.equations]
    if det_parts is not None:
        det_parts = tuple((_xreplaced(d, back), tag) for d, tag in det_parts)
    if res is not None:
        res = _xreplaced_result(res, back)
    return res, err, wide, det_parts


def _decimal_shadow(ctx):
    """(a context whose model has each decimal of the chain's poses and points as a positive
    symbol, {symbol: decimal}), or None when the chain has no decimal. A float of integer value
    (`alpha: 0.0`, `d: 1.0`) is that integer: as a symbol, cos(alpha) of a zero twist hid the
    chain's structure and the search ran past its budget (sympy's Float(0.0) != 0)."""
    import dataclasses

    from robosolve.model import RobotModel

    problem = ctx.problem
    exprs = [e for f in problem.frames.values() for e in _frame_exprs(f)]
    exprs += [e for pt in problem.points.values() for e in pt.at]
    exprs = [sp.sympify(e) for e in exprs]
    mags = sorted({abs(v) for e in exprs for v in e.atoms(sp.Float) if not _integral(v)})
    if not mags:
        return None
    named = {v: sp.Dummy(f"decimal{k}", positive=True) for k, v in enumerate(mags)}

    def sym(x):
        if isinstance(x, (list, tuple)):
            return type(x)(sym(y) for y in x)
        if not isinstance(x, sp.Basic):
            return x
        return x.xreplace({v: (sp.Integer(int(v)) if _integral(v) else named[abs(v)] if v > 0 else -named[abs(v)])
                           for v in x.atoms(sp.Float)})

    frames = {n: dataclasses.replace(f, factors=sym(list(f.factors)), matrix=None if f.matrix is None else sym(f.matrix))
              for n, f in problem.frames.items()}
    points = {n: dataclasses.replace(pt, at=sym(pt.at)) for n, pt in problem.points.items()}
    shadow = dataclasses.replace(problem, frames=frames, points=points)
    sctx = copy.copy(ctx)
    sctx.problem, sctx.model = shadow, RobotModel(shadow)
    return sctx, {d: v for v, d in named.items()}


def _integral(v: sp.Float) -> bool:
    return float(v) == int(float(v))


def _frame_exprs(f):
    if f.kind == "pose":
        return [e for _, e in f.factors]
    return list(f.matrix) if f.kind == "matrix" else list(f.factors)


def _xreplaced(x, back):
    if isinstance(x, (list, tuple)):
        return type(x)(_xreplaced(y, back) for y in x)
    return x.xreplace(back) if isinstance(x, sp.Basic) else x


def _xreplaced_result(res, back):
    from dataclasses import replace

    res.measure = _xreplaced(res.measure, back)
    res.minors = [_xreplaced(m, back) for m in res.minors]
    res.conditions = [replace(c, values=tuple((q, _xreplaced(v, back)) for q, v in c.values),
                              equations=tuple(_xreplaced(e, back) for e in c.equations),
                              factor=_xreplaced(c.factor, back)) for c in res.conditions]
    return res


def _rank_conditions(ans, question, ctx, ts, kinds, params):
    """(result or None, why not, WideMinors or None, det parts): det J by structure (square), the
    minors by structure (wide, 5+ joints), else the direct route; each within its counted budget."""
    det, det_parts = _structured_det_steps(ans, question, ctx, ts)
    wide, err = _wide_minors(question, ctx, ts)
    if wide is not None:
        res, err = _counted_search(ctx, ctx.model, kinds, params, minors=wide.minors)
    elif err is None:
        res, err = _counted_search(ctx, ctx.model, kinds, params, j=ts.J, det=det)
    else:
        res = None
    return res, err, wide, det_parts


def _wide_minors(question, ctx, ts):
    """(WideMinors, None) for a wide J of 5+ joints (the point's x, y, z or the geometric
    Jacobian) whose maximal minors fit the counted budget `Budgets.rank_terms`; (None, why)
    past it; (None, None) for the other Jacobians (the direct route)."""
    from robosolve.kinematics.wide_rank import OverBudget, wide_minors

    model = ctx.model
    m, n = ts.J.shape
    if m >= n or n < STRUCTURE_MIN_JOINTS or not ts.default:
        return None, None
    pframe, plocal = model.point_local(question.point)
    frame = question.frame or model.problem.last_frame
    try:
        return wide_minors(model, pframe, plocal, frame, ts.geometric, ctx.budgets.rank_terms), None
    except OverBudget as exc:
        return None, (f"the maximal minors of J need {exc}: a count, so the outcome is the same on "
                      "every machine")


def _counted_search(ctx, model, kinds, params, j=None, det=None, minors=None):
    """The search for the rank conditions (on J and its det by structure, or on a wide J's
    structured minors), within its counted budget (`Budgets.rank_nodes`) after the input's
    (`Budgets.symbolic_nodes`); the time limit around it is a safety net only, so the answer is
    the same on every machine. (result, None) or (None, why)."""
    from sympy.polys.polyerrors import BasePolynomialError

    from robosolve.errors import SymbolicTimeout
    from robosolve.kinematics.singularities import SearchBudget, SearchTooLong

    # with det J by structure the search reads the det alone (J only for its shape): that is its input
    searched = (det, model.q, kinds, params) if det is not None else (j, model.q, kinds, params, det)
    why = over_input_budget(ctx, searched) if j is not None else None
    if why is not None:
        return None, why
    try:
        with ctx.time_limit(ctx.budgets.rank_search_seconds) as token:
            return find_singularities(j, model.q, kinds, params, det, minors=minors,
                                      work=SearchBudget(ctx.budgets.rank_nodes)), None
    except SearchTooLong as exc:
        return None, str(exc)
    except SymbolicTimeout as exc:
        if exc.token is not token:
            raise
        return None, f"{exc}, a safety limit of CPU time that a usual exam does not reach"
    except (BasePolynomialError, NotImplementedError) as exc:
        return None, f"sympy cannot complete this step symbolically ({type(exc).__name__})"


def _wide_step(wide, ts) -> Step:
    rows = "the geometric Jacobian's rows (the velocity taken at its origin)" if ts.geometric else "J's rows"
    zero = ""
    if wide.zero_columns:
        cols = ", ".join(str(c + 1) for c in wide.zero_columns)
        zero = (f" Column{'s' if len(wide.zero_columns) > 1 else ''} {cols} "
                f"{'are' if len(wide.zero_columns) > 1 else 'is'} zero (the joint does not move the point): "
                "every minor containing it vanishes.")
    return Step(
        "Minors by structure",
        f"The minors are computed with {rows} written in the axes of frame {name_md(wide.frame)}: a rotation "
        "(and a shear), of determinant 1, so each maximal minor is unchanged, and the entries are the "
        "shortest there (the fewest terms, counted on every frame of the chain). Each minor is a "
        "polynomial in the cosines and sines of the joints, factored." + zero)


def _structured_det_steps(ans, question, ctx, ts):
    """det J by structure for a square J of 5+ joints (None otherwise or past the limit):
    decoupled at the wrist centre for a 6-joint arm's geometric Jacobian, else split along
    its zero blocks. The report shows the blocks and their determinants."""
    from robosolve.kinematics import structured_det as sd

    model = ctx.model
    m, n = ts.J.shape
    if m != n or n < STRUCTURE_MIN_JOINTS:
        return None, None
    if ts.geometric:
        pframe, _ = model.point_local(question.point)
        frame = question.frame or model.problem.last_frame
        wrist, err = limited(ctx, ctx.step_seconds, sd.wrist_decoupled_det, model, pframe, frame)
        if err is not None:
            return None, None
        if wrist is not None:
            (_, _, j11, d11), (_, _, j22, d22) = wrist.det.blocks[:2] if len(wrist.det.blocks) == 2 else (
                (None, None, wrist.jacobian[:3, :3], None), (None, None, wrist.jacobian[3:, 3:], None))
            eqs = [(f"W = {{}}^{{0}}O_{{{wrist.frame}}}", wrist.centre),
                   ("J_{11}", j11), ("J_{22}", j22)]
            if d11 is not None:
                eqs += [("\\det J_{11}", d11), ("\\det J_{22}", d22)]
            ans.steps.append(Step(
                "Decoupling at the wrist",
                f"The axes of the last three joints meet at the origin W of frame {name_md(wrist.frame)} "
                "(a spherical wrist). Taking the velocity at W instead of at "
                f"{question.point}, $v_W = v_{{{question.point}}} + \\omega \\times (W - {question.point})$, "
                "multiplies J by a shear of determinant 1, and the wrist joints do not move W, so "
                "$J_W = \\begin{bmatrix} J_{11} & 0 \\\\ J_{21} & J_{22} \\end{bmatrix}$ and "
                "$\\det J = \\det J_{11}\\,\\det J_{22}$: the arm's factor (rows 1–3, joints 1–3: "
                "the velocity of W) times the wrist's (the angular velocities of joints 4–6).",
                equations=eqs))
            return wrist.det.det, ((d11, "arm singularity (det J₁₁ = 0)"), (d22, "wrist singularity (det J₂₂ = 0)"))
    J = _at_frame_origin(ans, question, ctx, ts) if ts.geometric else None
    split, _err = limited(ctx, ctx.step_seconds, sd.structured_det, ts.J if J is None else J, model.q)
    if split is None or len(split.blocks) < 2:
        return (split.det if split is not None else None), None
    ans.steps.append(Step(
        "Block structure",
        "The zero entries of J split it into a block triangular form (rows and columns "
        "reordered), so det J is the product of the diagonal blocks' determinants:",
        equations=[(f"\\det J_{{{k + 1}}}", d) for k, (_, _, _, d) in enumerate(split.blocks)]))
    return split.det, None


def _at_frame_origin(ans, question, ctx, ts):
    """The geometric J of the origin O of the point's frame, when the point is elsewhere on the
    body every joint moves (a tool tip off the last axis, Tx(0.02)): v_O = v_P + ω × (O − P) is a
    shear of determinant 1, so det J is the same, and shorter (the tool's J ran the search past its
    budget). None when it does not apply or cannot be formed."""
    from robosolve.kinematics.structured_det import geometric_jacobian_ring

    model = ctx.model
    pframe, plocal = model.point_local(question.point)
    frame = question.frame or model.problem.last_frame
    q = set(model.q)
    chain = model.chain(pframe)
    moving = [f for f in chain if model.M_local(f).free_symbols & q]
    if not moving or not q <= set().union(*(model.M_local(f).free_symbols for f in chain)):
        return None
    body = moving[-1]          # the frame of the last joint: P and O are fixed in it
    if (body == pframe and all(sp.sympify(c) == 0 for c in plocal)) or body not in model.chain(frame):
        return None
    if any(model.M_local(f).free_symbols & q for f in model.chain(frame)[model.chain(frame).index(body) + 1:]):
        return None            # ω is not the angular velocity of P's body
    J, err = limited(ctx, ctx.step_seconds, geometric_jacobian_ring, model, body, [0, 0, 0], frame)
    if J is None or err is not None:
        return None
    ans.steps.append(Step(
        "Determinant at the last joint's frame",
        f"Every joint moves {question.point}, fixed in the body of frame {name_md(body)}: taking the velocity "
        f"at that frame's origin O instead, $v_O = v_{{{question.point}}} + \\omega \\times (O - {question.point})$, "
        "multiplies J by a shear of determinant 1, so $\\det J = \\det J_O$:",
        equations=[("J_O", J)]))
    return J


def _tag_decoupled(conds, det_parts):
    """After decoupling at the wrist: say which factor each condition comes from (a
    condition's factor shares its joints with the arm's or the wrist's determinant)."""
    if not det_parts or any(d is None for d, _ in det_parts):
        return conds
    from dataclasses import replace

    out = []
    for c in conds:
        joints = c.factor.free_symbols if c.factor is not None else set()
        tags = [tag for d, tag in det_parts if joints and joints <= sp.sympify(d).free_symbols]
        out.append(replace(c, names=tuple(tags[:1]) + tuple(c.names)) if tags else c)
    return out


def _count_text(conds):
    k = len(conds)
    return f"{k} singular condition{'s' if k != 1 else ''}."


def _joint_pose(model, i):
    """⁰M of the frame joint i moves (its L = ∂M/∂qᵢ·M⁻¹ gives the joint's axis)."""
    frame = model.joint_frame(i)
    return model.M0(frame) if frame is not None else sp.eye(4)


def _within_limits(cond, model, params) -> str | Text:
    if cond.equations or not cond.values:
        return ""
    verdicts = []
    for s, v in cond.values:
        joint = next(j for j in model.joints if j.symbol == s)
        if joint.limits is None:
            continue
        try:
            val = float(sp.sympify(v).xreplace(params))
            lo, hi = (float(sp.sympify(x).xreplace(params)) for x in joint.limits)
        except (TypeError, ValueError):
            return "depends on the other joints"
        if not (lo - 1e-12 <= val <= hi + 1e-12):
            verdicts.append(Text(f"no (${latex(s)} \\notin [", Num(lo, digits=4), ", ",
                                 Num(hi, digits=4), "]$)"))
    return Text.join("; ", verdicts) if verdicts else "yes"


def _check_geometric(ans, ctx, question, jn, subs):
    """Built-in cross-check: the L-matrix columns against ∂P/∂q (central differences)."""
    import numpy as np

    model = ctx.model
    try:
        qv = [float(sp.N(subs[s])) for s in model.q]
        p = sp.lambdify([model.q], model.point0(question.point).xreplace(
            {k: v for k, v in subs.items() if k not in model.q}), numpy_modules())
    except (KeyError, TypeError, ValueError):
        return
    eps = 1e-6
    fd = []
    for i in range(len(qv)):
        a, b = list(qv), list(qv)
        a[i] += eps
        b[i] -= eps
        fd.append((np.array(p(a), dtype=float) - np.array(p(b), dtype=float)).reshape(3) / (2 * eps))
    err = float(np.max(np.abs(np.array(jn, dtype=float)[:3] - np.column_stack(fd))))
    if err > 1e-6 * max(1.0, float(np.max(np.abs(jn)))):
        ans.note(Text("internal check failed: the geometric Jacobian differs from dP/dq by ",
                      Num(err, digits=3)))


def _distance(ans, jn) -> list:
    """The numeric distance from singularity where the rank conditions were not derived: the
    smallest singular value of J and its condition number, said plainly in a note."""
    import numpy as np

    sv = np.linalg.svd(np.array(jn, dtype=float), compute_uv=False)
    smin, smax = float(sv[-1]), float(sv[0])
    if smin <= 1e-12 * max(1.0, smax):
        ans.note("Distance from singularity: the smallest singular value of J is 0 at the question's "
                 "configuration: J loses rank there (a singular configuration).")
        return [("\\sigma_{\\min}", 0.0)]
    ans.note(Text("Distance from singularity: at the question's configuration the smallest singular value of "
                  "J is σ_min = ", Num(smin), " (the largest ", Num(smax), ", condition number κ = ",
                  Num(smax / smin), "): J has full rank there; σ_min is how far J is from losing it."))
    return [("\\sigma_{\\min}", smin), ("\\sigma_{\\max}", smax), ("\\kappa = \\sigma_{\\max}/\\sigma_{\\min}", smax / smin)]


def _com_steps(ans, ctx):
    model = ctx.model
    out = {}
    eqs = []
    for b in model.bodies:
        c0 = model.com0(b)
        jg = tidy_limited(ctx, c0.jacobian(model.q), ctx.step_seconds)
        out[b.name] = jg
        eqs.append((f"{{}}^{{0}}G_{{{name_tex(b.name, False)}}}", c0))
        eqs.append((f"J_{{G,{name_tex(b.name, False)}}}", jg))
    ans.steps.append(Step(
        "Centre-of-mass Jacobians",
        "The centre of mass of each body, $c = J[1{:}3,4]/J[4,4]$ from its pseudo-inertia, moved "
        "to frame 0, and its 3×n Jacobian (used for the statics of the bodies' weight):",
        equations=eqs,
    ))
    return out


def _numeric(ans, question, ctx, J, com, distance=False):
    model = ctx.model
    if not question.at and (J.free_symbols & set(model.q)):
        return
    subs = ctx.substitutions(question.at)
    jn = ctx.try_numeric(ans, "J", J, subs, "J")
    eqs = []
    if jn is not None:
        eqs.append(("J", jn))
        if J.shape[0] == 6 and question.options.get("geometric"):
            _check_geometric(ans, ctx, question, jn, subs)
        m, n = J.shape
        if m == n:
            import numpy as np

            try:
                det = float(ctx.numeric(ans.symbolic["det"], subs))   # exact, then rounded
            except (KeyError, MissingValues, ValueError, TypeError):
                det = float(np.linalg.det(np.array(jn, dtype=float)))
            det = 0.0 if abs(det) < 1e-12 else det
            ans.numeric["det"] = det
            eqs.append(("\\det J", det))
            if abs(det) < 1e-9:
                ans.note("J is singular at the given configuration (det J = 0).")
        else:
            w = numeric_manipulability(jn)
            w = 0.0 if abs(w) < 1e-12 else w
            ans.numeric["manipulability"] = w
            eqs.append(("w", w))
            if w < 1e-9:
                ans.note("J loses rank at the given configuration (manipulability 0).")
        if distance:
            eqs += _distance(ans, jn)
    sing = ans.symbolic.get("singularities")
    if sing and all(isinstance(c, dict) for c in sing):
        params = ctx.parameter_values()
        try:
            ans.numeric["singularities"] = [
                {k: float(sp.sympify(v, locals={s.name: s for s in model.q}).xreplace(params))
                 for k, v in c.items()} for c in sing]
        except (TypeError, ValueError):
            pass
        else:
            if any(not math.isfinite(x) for c in ans.numeric["singularities"] for x in c.values()):
                ans.numeric.pop("singularities")
    if com:
        try:
            ans.numeric["com_jacobians"] = {k: ctx.numeric(v, subs) for k, v in com.items()}
            for k, v in ans.numeric["com_jacobians"].items():
                eqs.append((f"J_{{G,{name_tex(k, False)}}}", v))
        except MissingValues as exc:
            from robosolve.solvers.base import missing_note

            ans.note(missing_note("com_jacobians", exc.names, ctx.problem))
    if eqs:
        ans.steps.append(Step("Numeric values", "At the configuration of the question:",
                              equations=eqs))
