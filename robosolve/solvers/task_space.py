"""The task space of a jacobian / statics / ellipsoids question, from the robot model.

Shared by the three solvers: the coordinates S = F(Q) (default the point's x, y, z
in frame 0), their LaTeX names, the analytic or geometric Jacobian, and the
time-limited symbolic steps with their numeric fall-back.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import sympy as sp

from robosolve.kinematics.jacobian_math import analytic_jacobian, geometric_jacobian, tidy
from robosolve.core.printing import latex, sstr

__all__ = ["TaskSpace", "task_space", "limited", "over_input_budget", "tidy_limited",
           "coordinate_latex", "joint_kinds", "position_axes", "joint_l0"]


@dataclass
class TaskSpace:
    coords: list                      # expressions in q (placeholders replaced)
    labels: list                      # LaTeX names of the coordinates
    texts: list                       # plain names (E.x, theta1 + theta2, ...)
    J: sp.Matrix
    geometric: bool = False
    default: bool = True              # the point's x, y, z
    notes: list = field(default_factory=list)


def joint_kinds(model) -> dict:
    return {j.symbol: j.kind for j in model.joints}


def over_input_budget(ctx, args) -> str | None:
    """Why a symbolic step on `args` is not attempted (more expression nodes than the context's
    `Budgets.symbolic_nodes`: a count, the same on every machine), or None."""
    from robosolve.core.simplify import expression_nodes

    limit = getattr(getattr(ctx, "budgets", None), "symbolic_nodes", None)
    size = expression_nodes(args) if limit else 0
    if limit and size > limit:
        return (f"its input has {size:,} expression nodes, above the budget of {limit:,}: "
                "a count, so the outcome is the same on every machine")
    return None


def limited(ctx, seconds, fn, *args, **kwargs):
    """Run fn under the context's time limit; (result, None) or (None, why it stopped)."""
    from sympy.polys.polyerrors import BasePolynomialError

    from robosolve.errors import SymbolicTimeout

    why = over_input_budget(ctx, args)
    if why is not None:
        return None, why
    try:
        with ctx.time_limit(seconds):
            return fn(*args, **kwargs), None
    except SymbolicTimeout as exc:
        return None, str(exc)
    except (BasePolynomialError, NotImplementedError) as exc:
        # sympy cannot do this algebra (e.g. a DH alpha left symbolic gives sqrt(sin(al)**4 - 1)
        # terms that factor() rejects): the step is skipped like one past its limit
        return None, f"sympy cannot complete this step symbolically ({type(exc).__name__})"


def tidy_limited(ctx, m, seconds, long_chain=False):
    """Tidied matrix, or the raw one past the time limit. Long chains (5+ joints) use the
    addition formulas only (core.simplify.tidy_products: trigsimp and factor cost seconds
    per entry of a 6R Jacobian and its report shows the method, not a factored look)."""
    from robosolve.core.simplify import tidy_products

    out, _err = limited(ctx, seconds, lambda mm: sp.Matrix(mm).applyfunc(tidy_products if long_chain else tidy), m)
    return out if out is not None else sp.Matrix(m)


def coordinate_latex(expr, names: dict) -> str:
    """LaTeX of a coordinate as the user wrote it (E.x -> E_{x}), with the problem's symbol
    names (`ctx.symbol_latex`)."""
    return latex(expr, symbol_names=names)


def position_axes(question, model, coords_raw) -> list | None:
    """Indices (0, 1, 2 for x, y, z) when every coordinate is a coordinate of the
    question's point (so the robot can be drawn in the same space), else None."""
    out = []
    for c in coords_raw:
        if not isinstance(c, sp.Symbol) or "." not in c.name:
            return None
        pname, axis = c.name.split(".")
        if pname != question.point:
            return None
        out.append("xyz".index(axis))
    return out


def task_space(question, ctx, seconds, geometric=False) -> TaskSpace:
    """Coordinates and Jacobian of the question (analytic, or 6 x n geometric)."""
    model = ctx.model
    q = model.q
    point = question.point
    if geometric:
        pframe, _ = model.point_local(point)
        frame = question.frame or model.problem.last_frame
        p0 = model.point0(point)
        J = None
        if len(q) > 4:
            # long chains: products in the trig ring, canonical entries, no trigsimp
            from robosolve.kinematics.structured_det import geometric_jacobian_ring

            J, _err = limited(ctx, seconds, geometric_jacobian_ring, model, pframe,
                              model.point_local(point)[1], frame)
        if J is None:
            # the velocity rows: the point's tidy coordinates differentiated (= [u_i] P + t_i, written
            # short: a 4-joint arm with a tool stays within the symbolic budget)
            l_frame = [joint_l0(model, i, frame) for i in range(len(q))]
            jp = analytic_jacobian(list(p0), q)
            jw = geometric_jacobian(l_frame, p0)[3:, :]
            J = tidy_limited(ctx, sp.Matrix.vstack(jp, jw), seconds, long_chain=len(q) > 4)
        coords = list(p0)
        labels = [f"{point}_{{{a}}}" for a in "xyz"] + [f"\\omega_{{{a}}}" for a in "xyz"]
        texts = [f"{point}.{a}" for a in "xyz"] + [f"omega_{a}" for a in "xyz"]
        return TaskSpace(coords, labels, texts, J, geometric=True, default=True)
    raw = question.options.get("coordinates")
    default = raw is None
    if default:
        p0 = model.point0(point)
        coords = list(p0)
        labels = [f"{point}_{{{a}}}" for a in "xyz"]
        texts = [f"{point}.{a}" for a in "xyz"]
    else:
        coords = [model.coordinate(c) for c in raw]
        labels = [coordinate_latex(c, ctx.symbol_latex) for c in raw]
        texts = [sstr(c) for c in raw]
    # the model's coordinates are already trig-tidied: their derivatives need no more
    J = analytic_jacobian(coords, q)
    return TaskSpace(coords, labels, texts, J, geometric=False, default=default)


def joint_l0(model, index, frame):
    """⁰Lᵢ for the motion of `frame`, zero when joint i does not move it.

    Built from the model's (tidied, cached) poses without simplifying the product: the
    Jacobian entries are tidied afterwards under the time limit. Small robots use the
    model's own tidied L (cached and shared with other solvers)."""
    chain = model.chain(frame) if frame != "0" else []
    frames = [f for f in chain if index in model.joints_in(f)]
    if not frames:
        return sp.zeros(4, 4)
    if len(model.q) <= 4:
        return model.L0(index, frame)
    from robosolve.core.matrices import change_frame

    total = sp.zeros(4, 4)
    for f in frames:
        total += change_frame(model.M0(model.frames[f].parent), model.L_local(index, f))
    return total
