"""§5.6: ZYZ Euler angles, roll-pitch-yaw, axis-angle and unit quaternion of a rotation.

The rotation is `matrix` (3x3 or 4x4, no robot needed) or the orientation of
`frame` in frame 0 (at the question's `at`, symbolic where joints are not given).
Engines and conventions: robosolve.geometry.rotations.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from robosolve.core.prose import Num, Text
from robosolve.core.course_notes import note_link
from robosolve.errors import SymbolicTimeout
from robosolve.geometry.rotations import (
    axis_angle_numeric, axis_angle_symbolic, quaternion_numeric,
    quaternion_symbolic, rpy_numeric, rpy_symbolic, zyz_numeric, zyz_symbolic,
)
from robosolve.load.problem import Question
from robosolve.solvers.base import Answer, MissingValues, SolveContext, Step, missing_note
from robosolve.solvers.common import geometry_matrix, m_name, nearest_rotation_if_rounded
from robosolve.core.printing import latex

FAMILY_TEX = {"phi + psi": "\\varphi + \\psi", "phi - psi": "\\varphi - \\psi",
              "roll - yaw": "\\text{roll} - \\text{yaw}", "roll + yaw": "\\text{roll} + \\text{yaw}"}


def solve(question: Question, ctx: SolveContext) -> Answer:
    ans = Answer(question.type, question.id)
    if "matrix" in question.options:
        r = sp.Matrix(question.options["matrix"])[:3, :3]
        where = "The rotation is the given matrix."
        r = nearest_rotation_if_rounded(ans, r)
    else:
        frame = question.frame
        subs = {s: v for s, v in question.at.items() if s in set(ctx.model.q)}
        r = ctx.model.M0(frame)[:3, :3].xreplace(subs)
        where = f"The rotation is the orientation block of ${m_name('0', frame)}$."
    if r.free_symbols or not r.atoms(sp.Float):
        r = geometry_matrix(ctx, r)     # floats alone are kept as given: no round-off dropped
    steps = [Step("Rotation matrix", where, equations=[("R", r)])]

    try:
        with ctx.time_limit():
            z, y = zyz_symbolic(r), rpy_symbolic(r)
            aa, q = axis_angle_symbolic(r), quaternion_symbolic(r)
        ans.symbolic = _representations(z, y, aa, q)
        steps += _symbolic_steps(z, y, aa, q)
        if z.singular is None:
            ans.note("symbolic ZYZ angles hold where sin(theta) != 0 and RPY angles where cos(pitch) != 0")
    except SymbolicTimeout:
        ans.note("the symbolic angles were cut short by their time limit; numeric answers only")
    except ValueError as exc:
        ans.error = str(exc)
        return ans

    subs = ctx.substitutions(question.at)
    try:
        rn = np.array(ctx.numeric(r, subs), dtype=float)
    except MissingValues as exc:
        ans.note(missing_note("angles", exc.names, ctx.problem))
        ans.steps = steps
        return ans
    if not np.allclose(rn.T @ rn, np.eye(3), atol=1e-6) or abs(np.linalg.det(rn) - 1) > 1e-6:
        ans.error = "the matrix is not a proper rotation (R^T R != I or det R != 1)"
        return ans
    z, y = zyz_numeric(rn), rpy_numeric(rn)
    aa, q = axis_angle_numeric(rn), quaternion_numeric(rn)
    ans.numeric = _representations(z, y, aa, q)
    steps.append(_numeric_step(z, y, aa, q))
    for e, name in ((z, "ZYZ"), (y, "RPY")):
        if e.singular:
            ans.note(Text(f"{name} singular: only {e.family[0]} = ", Num(e.family[1]),
                          " is determined; the representative sets the last angle to 0"))
    if aa.case == "zero":
        ans.note("zero rotation: the axis of the axis-angle representation is undefined (null)")
    if aa.case == "half_turn":
        ans.note("half turn: u and -u give the same rotation; the one with its first non-zero component "
                 "positive is given (and its quaternion, eta = 0)")
    ans.steps = steps
    return ans


def _family_text(e, angles: str) -> str:
    combo, value = e.family
    v = value if isinstance(value, (sp.Basic,)) else sp.Float(value, 6)
    return (f"**Singular:** only ${FAMILY_TEX[combo]} = {latex(v)}$ is determined: every "
            f"{angles} with that combination gives the same R (an infinite family). The representative "
            "sets the last angle to 0.")


def _symbolic_steps(z, y, aa, q) -> list:
    out = []
    text = ("$R = R_z(\\varphi) R_y(\\theta) R_z(\\psi)$: $\\theta = \\operatorname{atan2}(\\pm\\sqrt{r_{13}^2 + "
            "r_{23}^2}, r_{33})$, $\\varphi = \\operatorname{atan2}(\\pm r_{23}, \\pm r_{13})$, "
            "$\\psi = \\operatorname{atan2}(\\pm r_{32}, \\mp r_{31})$; the upper signs give $\\theta \\in [0, \\pi]$, "
            "the lower ones the second solution $-\\theta$. Singular where $\\sin\\theta = 0$ (" + note_link("orientation") + ").")
    if z.singular:
        text += " " + _family_text(z, "$(\\varphi, \\theta, \\psi)$")
    out.append(Step("ZYZ Euler angles", text, equations=[
        (f"(\\varphi, \\theta, \\psi)_{{{k + 1}}}", list(s)) for k, s in enumerate(z.solutions)]))
    text = ("$R = R_z(\\text{yaw}) R_y(\\text{pitch}) R_x(\\text{roll})$ (" + note_link("orientation") + "): "
            "$\\text{pitch} = \\operatorname{atan2}(-r_{31}, \\pm\\sqrt{r_{11}^2 + r_{21}^2})$, "
            "$\\text{yaw} = \\operatorname{atan2}(\\pm r_{21}, \\pm r_{11})$, "
            "$\\text{roll} = \\operatorname{atan2}(\\pm r_{32}, \\pm r_{33})$; the upper signs give "
            "pitch in $[-\\pi/2, \\pi/2]$. Singular where $\\cos(\\text{pitch}) = 0$, i.e. pitch $= \\pm\\pi/2$.")
    if y.singular:
        text += " " + _family_text(y, "(roll, pitch, yaw)")
    out.append(Step("Roll-pitch-yaw", text, equations=[
        (f"(\\text{{roll}}, \\text{{pitch}}, \\text{{yaw}})_{{{k + 1}}}", list(s))
        for k, s in enumerate(y.solutions)]))
    eqs = [("\\cos\\alpha = \\frac{\\operatorname{tr} R - 1}{2}", aa.cos_angle), ("\\alpha", aa.angle)]
    if aa.axis is not None:
        eqs.append(("u", sp.Matrix(aa.axis)))
    out.append(Step(
        "Axis-angle",
        "$\\alpha \\in [0, \\pi]$ with $\\sin\\alpha = \\tfrac12|\\operatorname{vex}(R - R^T)| \\geq 0$, "
        "$u = \\operatorname{vex}(R - R^T)/(2\\sin\\alpha)$; at $\\alpha = 0$ the axis is undefined, at "
        "$\\alpha = \\pi$ it comes from the symmetric part (" + note_link("helical-axis") + ").",
        equations=eqs))
    out.append(Step(
        "Unit quaternion",
        "$\\eta = \\cos(\\alpha/2) = \\tfrac12\\sqrt{1 + \\operatorname{tr} R} \\geq 0$, "
        "$\\varepsilon = \\sin(\\alpha/2)\\,u$, $\\eta^2 + |\\varepsilon|^2 = 1$ (" + note_link("orientation") + "; "
        "$-q$ is the same rotation).",
        equations=[("[\\eta, \\varepsilon_x, \\varepsilon_y, \\varepsilon_z]", q)]))
    return out


def _representations(z, y, aa, q) -> dict:
    """The answer layout of the four representations (symbolic or numeric alike)."""
    return {
        "zyz": {"solutions": z.solutions, "singular": z.singular},
        "rpy": {"solutions": y.solutions, "singular": y.singular},
        "axis_angle": {"axis": aa.axis, "angle": aa.angle},
        "quaternion": q,
    }


def _numeric_step(z, y, aa, q) -> Step:
    deg = 180.0 / math.pi
    rows = []
    for name, e in (("ZYZ (φ, θ, ψ)", z), ("RPY (roll, pitch, yaw)", y)):
        for k, s in enumerate(e.solutions):
            rows.append((f"{name} #{k + 1}" + (" (singular)" if e.singular else ""),
                         Text.join(", ", [Num(x) for x in s]), Text.join(", ", [Num(x * deg) for x in s])))
    rows.append(("axis-angle α", Num(aa.angle), Num(aa.angle * deg)))
    return Step("Numeric values", "Angles in radians and degrees:",
                equations=[("u", aa.axis), ("q", q)],
                table=(("representation", "rad", "deg"), rows))
