"""Inverse kinematics of a pose (the `target: {pose: M}` / `{position, R | zyz | rpy}` form).

The chain from frame 0 to the question's frame, with the parameters' values, goes to
`robosolve.ik.pose.solve_pose` (kinematic decoupling at a spherical wrist, else numeric); a point
target is turned into the frame's pose first (p_frame = p − R·c, c the point in the frame).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.errors import SolverError
from robosolve.ik.pose import P_SYMS, R_SYMS, solve_pose
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step, missing_note
from robosolve.core.printing import latex


def solve_pose_question(question, ctx: SolveContext, ans: Answer, ik_joints, params, tex):
    """Fill `ans`; returns the engine's result (its solutions for the figure)."""
    model = ctx.model
    target = question.options["target"]
    frame = question.frame
    if question.point_given:
        frame = model.point_local(question.point)[0]    # the point's orientation is its frame's
    chain = model.chain(frame)
    if not chain:
        raise SolverError("a pose target needs a frame other than 0")
    try:
        factors = [with_values(model.M_local(f), params, model) for f in chain]
        R = np.array(ctx.numeric(target.R, params), dtype=float).reshape(3, 3)
        p = np.array(ctx.numeric(target.p, params), dtype=float).reshape(3)
    except MissingValues as exc:
        return _numbers_missing(ans, ctx, exc.names)
    if target.note:
        ans.note(target.note)
    if not is_rotation(R):
        raise SolverError("the target's R is not a rotation (RᵀR ≠ I or det R ≠ 1 within 1e-3)")
    c = None
    if question.point_given:
        c = np.array(ctx.numeric(model.point_local(question.point)[1], params), dtype=float).reshape(3)
        p = p - R @ c
    q_syms = {j.symbol for j in ik_joints}
    used = [j for j in ik_joints if any(j.symbol in f.free_symbols for f in factors)]
    extra = set().union(*(f.free_symbols for f in factors)) - q_syms
    if extra:
        return _numbers_missing(ans, ctx, sorted(map(str, extra)))
    if len(used) > 6:
        raise SolverError(f"a pose fixes 6 coordinates and this arm moves it with {len(used)} joints: the "
                          "target is reached along a continuum (self-motion), not at isolated solutions; "
                          "pose targets are solved for arms of up to 6 joints")
    free = [j.symbol.name for j in ik_joints if j not in used]
    if free:
        ans.note(", ".join(free) + (" does" if len(free) == 1 else " do") + f" not move frame {frame}: "
                 "any value reaches the target, and the solutions give the other joints")
    opts = question.options
    select = opts.get("select", "limits")
    if isinstance(select, dict):
        select = {k: ctx.numeric(v, params) for k, v in select.items()}
    names = {j.symbol: latex(j.symbol, symbol_names=dict(ctx.symbol_latex)) for j in used}
    res = solve_pose(factors, used, R, p, select=select, latex_names=names, tex=tex,
                     time_limit_s=ctx.budgets.closed_form_seconds)
    ans.steps.append(_target_step(target, R, p, frame, question, c, tex))
    for st in res.steps:
        ans.steps.append(Step(st.title, st.text, equations=list(st.equations)))
    for n in res.notes:
        ans.note(n)
    if res.closed_form:
        ans.symbolic["closed_form"] = [{j.name: b[j.name] for j in used if j.name in b} for b in res.closed_form]
        ans.steps.append(Step("Closed form", f"{len(res.closed_form)} branches (each formula may use the "
                              "joints found before it), in the target's entries r11…r33, px, py, pz."))
    ans.steps.append(_solutions_step(res, used))
    ans.numeric["solutions"] = [dict(d) for d in res.solutions]
    if res.status == "unreachable":
        ans.extra["unreachable"] = True
        ans.extra["reason"] = res.reason
        ans.numeric["solutions"] = []
        ans.steps.append(Step("Unreachable target", Text("No solution: ", res.reason_tex or res.reason, ".")))
        return res
    ans.numeric["selected"] = dict(res.selected)
    if opts.get("velocity"):
        ans.note("`velocity` is not used with a pose target: q_dot is given for coordinate targets only")
    ans.steps.append(Step("Selected solution",
                          "Selected: " + ("the first of the sorted solutions inside the joint limits."
                                          if not isinstance(select, dict) else "the solution nearest the given configuration."),
                          equations=[(names[j.symbol], res.selected[j.name]) for j in used]))
    return res


def _numbers_missing(ans: Answer, ctx: SolveContext, names) -> None:
    """A pose target is solved with numbers (the decoupling's wrist centre, the numeric search):
    with a null parameter in the target or the chain, no solution can be given — a note names
    it (spec: the numeric key omitted, never an error)."""
    ans.note(missing_note("solutions", names, ctx.problem))
    ans.steps.append(Step("Pose of the target", "The solutions of a pose target are computed with numbers: "
                          + missing_note("solutions", names, ctx.problem) + "."))
    return None


def with_values(m, params, model):
    q = set(model.q)
    out = m.xreplace({k: v for k, v in params.items() if k not in q})
    return out.evalf() if out.atoms(sp.Float) else out


def is_rotation(R) -> bool:
    return (float(np.max(np.abs(R.T @ R - np.eye(3)))) < 1e-3 + 1e-12
            and abs(float(np.linalg.det(R)) - 1) < 1e-3)


def _target_step(target, R, p, frame, question, c, tex) -> Step:
    where = (f"the point {question.point} (fixed in frame {frame}, $\\vec c$ below)" if c is not None
             else f"frame {frame}")
    M_sym = sp.Matrix(sp.BlockMatrix([[R_SYMS, P_SYMS], [sp.zeros(1, 3), sp.ones(1, 1)]]))
    text = (f"The pose of {where} in frame 0 is given: ${{}}^{{0}}M = M$. The 12 equations "
            "${}^{0}M(q) = M$ (9 of the rotation, 3 of the position) count as 6: the rotation's "
            "columns are orthonormal. The target's entries are written $r_{ij}$ and $p_x, p_y, p_z$.")
    if target.given in ("zyz", "rpy"):
        text += (" The orientation is given as " + ("ZYZ angles, $R = R_z(\\varphi)R_y(\\theta)R_z(\\psi)$"
                                                     if target.given == "zyz" else
                                                     "roll, pitch, yaw, $R = R_z(\\text{yaw})R_y(\\text{pitch})R_x(\\text{roll})$") + ".")
    eqs = [("M", M_sym), ("M", [list(map(float, R[i])) + [float(p[i])] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]])]
    if c is not None:
        eqs.append(("\\vec c", [[float(v)] for v in c]))
        text += " The frame's origin is then at $\\vec p - R\\,\\vec c$."
    return Step("Pose of the target", text, equations=eqs)


def _solutions_step(res, joints) -> Step:
    header = ["#"] + [f"${latex(j.symbol)}$" for j in joints] + ["joint limits"]
    rows = []
    rejected = {id(d): b for d, b in res.rejected}
    for k, d in enumerate(res.all_solutions, 1):
        status = "inside" if id(d) not in rejected else "rejected: " + Text.join("; ", rejected[id(d)])
        rows.append([str(k)] + [Text(Num(d[j.name]), " (", Num(math.degrees(d[j.name])), "°)") if j.revolute
                                else Text(Num(d[j.name])) for j in joints] + [status])
    how = {"decoupling": "kinematic decoupling",
           "three parallel axes": "the row along the parallel axes and the planar 3R"}.get(
        res.method, "a multi-start Newton search on the 12 equations")
    text = (f"By {how}, {len(res.all_solutions)} distinct solution{'s' if len(res.all_solutions) != 1 else ''}, "
            "each polished by Newton's method on the 12 equations and checked with the direct kinematics "
            "(every entry of ${}^{0}M$ within $10^{-9}$); angles wrapped into (−π, π].")
    return Step("Every solution", text, table=(header, rows) if rows else None)
