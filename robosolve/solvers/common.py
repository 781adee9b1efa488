"""Helpers shared by solvers: LaTeX names of matrices, robot drawings, joint values,
budgeted symbolic parts."""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import Num, Text, name_tex
from robosolve.core.simplify import exact_geometry
from robosolve.core.transforms import nearest_rotation, rotation_defect
from robosolve.errors import SymbolicTimeout
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step


def nearest_rotation_if_rounded(ans: Answer, r, what: str = "R"):
    """A numeric rotation block orthonormal only to the input check's tolerance (entries rounded
    by hand, as load.validators accepts them, the tolerance of an IK pose target): the nearest
    rotation, R = U·Vᵀ from its SVD, with a note naming it (`what`); any other block as it is."""
    if r.free_symbols:
        return r
    a = r.evalf().tolist()
    err, det = rotation_defect(a)
    if err <= 1e-9 and abs(det - 1) <= 1e-9:
        return r        # orthonormal to the input check's own 1e-9: kept as given (exact stays exact)
    ans.note(Text(what + " is orthonormal only to ", Num(err, digits=2), " (entries rounded by hand): it is "
                  "replaced by the nearest rotation (polar decomposition, R = U·Vᵀ from its SVD)"))
    return nearest_rotation(a)


def frame_tex(name: str) -> str:
    return name_tex(name)


def m_name(i: str, j: str, letter: str = "M") -> str:
    """{}^{i}M_{j}: pose of frame j in frame i."""
    return f"{{}}^{{{frame_tex(i)}}}{letter}_{{{frame_tex(j)}}}"


def rel_name(base: str, i: str, j: str, letter: str) -> str:
    """{}^{base}W_{i,j}: relative motion of j in i, expressed in base."""
    return f"{{}}^{{{frame_tex(base)}}}{letter}_{{{frame_tex(i)},{frame_tex(j)}}}"


def joint_values(ctx: SolveContext, subs: dict, rates: bool = False) -> list | None:
    """Numeric joint values (q, or q and q_dot) when all are given."""
    model = ctx.model
    syms = model.q + (model.qd if rates else [])
    if any(s not in subs for s in syms):
        return None
    return [float(sp.N(subs[s])) for s in syms]


def robot_drawing(ctx: SolveContext, subs: dict) -> dict | None:
    """Numbers to draw the robot: link polylines, frame origins and axes, points.

    From the numeric chain (numpy products of the local poses evaluated once), not by
    evaluating the symbolic poses built for the report. None when some joint or parameter
    value is missing.
    """
    from robosolve.core.transforms import ELEMENTARY
    from robosolve.model.numeric import NumericChain, evaluate

    model = ctx.model
    frames = model.frame_names()
    chain = NumericChain(model, subs)
    try:
        origins = {"0": [0.0, 0.0, 0.0]}
        axes = {"0": [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]}
        links = []
        for f in frames:
            m = chain.M0(f)
            origins[f] = [_plain(m[r, 3]) for r in range(3)]
            axes[f] = [[_plain(m[r, c]) for r in range(3)] for c in range(3)]    # columns: x, y, z axes
            path = [origins[model.frames[f].parent]]
            frame = model.frames[f]
            if frame.kind == "pose":
                # the origins after each translation but the last (the frame's own origin)
                factors = list(frame.factors)
                last_t = max((k for k, (op, _) in enumerate(factors) if op[0] == "T"), default=-1)
                at = chain.M0(frame.parent)
                for op, arg in factors[:last_t]:
                    at = at @ evaluate(ELEMENTARY[op](arg), subs)
                    if op[0] == "T":
                        path.append([_plain(x) for x in at[:3, 3]])
            path.append(origins[f])
            links.append(path)
        points = {name: [_plain(x) for x in chain.point0(name)] for name in model.points}
    except MissingValues:
        return None
    return {
        "frames": [{"name": f, "origin": origins[f], "axes": axes[f]} for f in ["0", *frames]],
        "links": links,
        "points": [{"name": n, "at": p} for n, p in points.items()],
    }


def _plain(x) -> float:
    x = float(x)
    return 0.0 if x == 0 else x


def symbolic_within_budget(ctx: SolveContext, ans: Answer, part, what: str) -> bool:
    """Run `part()` (the symbolic steps) within the symbolic-step budget; past it, drop the
    symbolic steps and answers with a note (the numeric answers follow). True when done."""
    try:
        with ctx.time_limit():
            part()
        return True
    except SymbolicTimeout:
        ans.steps, ans.symbolic = [], {}
        ans.note(f"the symbolic {what} was cut short by its time limit; numeric answers only")
        return False


def geometry_matrix(ctx: SolveContext, m, seconds: float = 10.0):
    """A rotation or displacement matrix through the `exact_geometry` simplification, within
    `seconds` (the matrix as it is past them)."""
    ops = ctx.budgets.simplify.geometry_ops
    try:
        with ctx.time_limit(seconds):
            return m.applyfunc(lambda e: exact_geometry(e, ops))
    except SymbolicTimeout:
        return m


def potential_step(eng, shown) -> Step:
    """The gravity matrix and each body's potential energy U_j, written as `shown(body)` gives it
    (the sympy route of the equations of motion, and the trig ring's of a big robot)."""
    return Step(
        "Gravity matrix and potential energy",
        "${}^{0}H_g$ holds the gravity vector in its last column; "
        "$U_j = -\\mathrm{tr}({}^{0}H_g\\,{}^{0}J_j)$ ($= m_j\\,g\\,z_{G}$ for gravity $(0, 0, -g)$).",
        equations=[("{}^{0}H_g", eng.hg())]
        + [(f"U_{{{name_tex(b.name, False)}}}", shown(b)) for b in eng.bodies],
    )
