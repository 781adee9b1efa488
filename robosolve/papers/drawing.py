"""The data of a paper's drawing (papers.md "The drawing"): the robot at its reference
configuration, each frame's axes, the joint variables at the joints, the named points, the
forces as arrows, gravity; drawn by `render/plots/robot_paper.py`.

The reference configuration: the problem's `paper: {at}`, else the first question's `at`
joint values, else every joint at 0 clamped into its limits. Only given data: nothing solved.
A null parameter is drawn at 1 (the drawing only illustrates).
"""

from __future__ import annotations

import re

import numpy as np
import sympy as sp

from robosolve.core.prose import PLAIN_NAME, name_plot
from robosolve.core.printing import latex

PLANE_TOL = 1e-9
IDENT = re.compile(r"[A-Za-z][A-Za-z0-9_]*")   # a name sympy's LaTeX writes as a symbol (F, F_1)


def reference_configuration(problem) -> dict:
    """Joint symbol -> exact value of the drawing."""
    chosen = dict(problem.paper_at)
    if not chosen:
        first = next((q for q in problem.questions if any(j.symbol in q.at for j in problem.joints)), None)
        if first is not None:
            chosen = {j.symbol: first.at[j.symbol] for j in problem.joints if j.symbol in first.at}
    values = _parameter_values(problem)
    out = {}
    for j in problem.joints:
        if j.symbol in chosen:        # a value may name parameters (`at: {theta1: q1a}`, as variants do)
            out[j.symbol] = sp.sympify(chosen[j.symbol]).xreplace(values)
            continue
        v = sp.Integer(0)
        if j.limits is not None:
            lo, hi = (float(sp.N(x.xreplace(values))) for x in j.limits)
            v = sp.Integer(0) if lo <= 0 <= hi else (j.limits[0] if lo > 0 else j.limits[1])
        out[j.symbol] = v
    return out


def _parameter_values(problem) -> dict:
    subs = {}
    for s, v in problem.parameters.items():
        subs[s] = sp.Integer(1) if v is None else v
    for _ in range(len(subs)):              # parameters defined from others
        subs = {s: sp.sympify(v).xreplace(subs) for s, v in subs.items()}
    return subs


def _latex(sym) -> str:
    return latex(sym)


LABEL_CHARS = 10     # a longer name is cut in the drawing (the paper's text gives it whole)


def _shown(name: str) -> str:
    """A name as the drawing labels it: whole up to LABEL_CHARS characters, else its first
    characters and an ellipsis, so that a long name cannot run past the drawing's edge."""
    return name if len(name) <= LABEL_CHARS else name[:LABEL_CHARS - 1] + "…"


def _axis_labels(name: str) -> list[str]:
    """The labels of a frame's x, y, z axes: x₁ as mathtext for a plain name (1, tool, B2),
    else the name as written beside the axis letter (mathtext would misread or refuse it);
    a long name cut (`_shown`)."""
    if PLAIN_NAME.fullmatch(name) and len(name) <= LABEL_CHARS:
        sub = name if name.isdigit() else f"\\mathrm{{{name}}}"
        return [f"${a}_{{{sub}}}$" for a in "xyz"]
    return [f"{a} ({name_plot(_shown(name))})" for a in "xyz"]


def _force_label(name: str) -> str:
    if IDENT.fullmatch(name) and len(name) <= LABEL_CHARS:
        return f"${_latex(sp.Symbol(name))}$"
    return name_plot(_shown(name))


def joint_places(model, chain, subs) -> list[dict]:
    """Where each joint's variable is written: the pose just before the factor it moves."""
    from robosolve.core.transforms import ELEMENTARY
    from robosolve.model.numeric import evaluate

    out = []
    for j in model.problem.joints:
        place = None
        for name in model.frame_names():
            f = model.frames[name]
            if f.kind != "pose":
                if j.symbol in sp.Matrix(model.local_derivative(name, 0)).free_symbols:
                    m = chain.M0(f.parent if f.kind == "dh" else name)
                    place = (m[:3, 3], m[:3, 3], m[:3, 2])
                    break
                continue
            at = chain.M0(f.parent)
            for op, arg in f.factors:
                nxt = at @ evaluate(ELEMENTARY[op](arg), subs)
                if j.symbol in sp.sympify(arg).free_symbols:
                    place = (at[:3, 3], nxt[:3, 3], at[:3, "xyz".index(op[1])])
                    break
                at = nxt
            if place is not None:
                break
        if place is None:
            continue
        a, b = np.asarray(place[0], float), np.asarray(place[1], float)
        where = (a + b) / 2 if not j.is_revolute else a
        out.append({"label": f"${_latex(j.symbol)}$", "at": [float(x) for x in where],
                    "revolute": j.is_revolute, "axis": [float(x) for x in place[2]]})
    return out


def force_arrows(problem, chain, subs) -> list[dict]:
    out = []
    t = problem.names.get("t")
    extra = {t: sp.Integer(0)} if t is not None else {}
    for f in problem.forces:
        try:
            p = chain.M0(f.frame) @ np.array([*(float(sp.N(x.xreplace({**subs, **extra}))) for x in f.at), 1.0])
            for vec, kind in ((f.force, "force"), (f.torque, "torque")):
                if vec is None:
                    continue
                r = chain.M0(f.in_frame)[:3, :3]
                v = r @ np.array([float(sp.N(x.xreplace({**subs, **extra}))) for x in vec])
                if np.linalg.norm(v) > 1e-12:
                    out.append({"label": _force_label(f.name), "at": [float(x) for x in p[:3]],
                                "direction": [float(x) for x in v / np.linalg.norm(v)], "kind": kind})
        except (TypeError, ValueError):
            continue
    return out


def gravity_direction(problem, subs) -> list | None:
    if problem.gravity is None or not (problem.bodies or problem.gravity_given):
        return None
    try:
        g = np.array([float(sp.N(x.xreplace(subs))) for x in problem.gravity])
    except (TypeError, ValueError):
        return None
    n = np.linalg.norm(g)
    return [float(x) for x in g / n] if n > 1e-12 else None


def plane_of(points, joints) -> tuple | None:
    """(horizontal axis, vertical axis) of frame 0 when the robot moves in a coordinate plane
    of frame 0 (y–z, x–z or x–y): every point in it, every revolute axis normal to it, every
    prismatic direction in it; else None (a 3-D drawing)."""
    a = np.array(points, dtype=float)
    spread = a.max(axis=0) - a.min(axis=0)
    scale = max(float(spread.max()), 1.0)
    for normal, axes in ((0, (1, 2)), (1, (0, 2)), (2, (0, 1))):
        if spread[normal] > PLANE_TOL * scale:
            continue
        if all(abs(abs(j["axis"][normal]) - 1) < 1e-9 if j["revolute"] else abs(j["axis"][normal]) < 1e-9
               for j in joints):
            return axes
    return None


def paper_figure(problem, model):
    """The FigureSpec of figures/robot.png, or None (no robot)."""
    from robosolve.model.numeric import NumericChain
    from robosolve.render.chain_names import ChainNames
    from robosolve.solvers.base import FigureSpec, SolveContext
    from robosolve.solvers.common import robot_drawing

    if model is None or not problem.has_robot:
        return None
    config = reference_configuration(problem)
    subs = {**_parameter_values(problem), **config}
    drawing = robot_drawing(SolveContext(problem, model, names=ChainNames(problem)), subs)
    if drawing is None:
        return None
    chain = NumericChain(model, subs)
    for f in drawing["frames"]:
        f["axis_labels"] = _axis_labels(f["name"])
    drawing["joints"] = joint_places(model, chain, subs)
    drawing["forces"] = force_arrows(problem, chain, subs)
    drawing["gravity"] = gravity_direction(problem, subs)
    points = [f["origin"] for f in drawing["frames"]] + [p["at"] for p in drawing["points"]]
    points += [pt for link in drawing["links"] for pt in link]
    drawing["plane"] = plane_of(points, drawing["joints"])
    shown = ", ".join(f"{_latex(j.symbol)} = {_latex(config[j.symbol])}" for j in problem.joints)
    import textwrap

    name = name_plot("\n".join(textwrap.wrap(problem.title or problem.name, 72)[:2]))
    title = f"{name}\nat ${shown}$" if shown else name
    return FigureSpec("robot", "robot_paper", title, drawing)
