"""Question 1: pose of a frame in frame 0 (the chain product) and position of a point."""

from __future__ import annotations

import sympy as sp

from robosolve.core.course_notes import note_link
from robosolve.load.problem import Question
from robosolve.model.numeric import NumericChain
from robosolve.solvers.base import Answer, FigureSpec, MissingValues, SolveContext, Step, missing_note
from robosolve.solvers.common import frame_tex, m_name, robot_drawing, symbolic_within_budget
from robosolve.core.prose import name_md
from robosolve.core.printing import latex


def solve(question: Question, ctx: SolveContext) -> Answer:
    ans = Answer(question.type, question.id)
    symbolic_within_budget(ctx, ans, lambda: symbolic_part(question, ctx, ans), "chain product")
    numeric_part(question, ctx, ans)
    return ans


def answer_chain(model, frame: str, point: str) -> list[str]:
    """Frames whose M the answer uses: from frame 1 to the farther of `frame` and the
    point's frame (spec: `chain`); on a branched tree, both branches in file order."""
    used = set(model.chain(frame)) | set(model.chain(model.point_local(point)[0]))
    return [f for f in model.frame_names() if f in used]


def symbolic_part(question: Question, ctx: SolveContext, ans: Answer) -> None:
    model = ctx.model
    frame, point = question.frame, question.point
    chain = answer_chain(model, frame, point)

    elementary = Step(
        "Elementary rototranslations",
        "Each frame's pose in its parent is the product of elementary motions, each applied "
        "in the current (moving) frame, so the factors multiply left to right ("
        + note_link("frame-notation")
        + (", " + note_link("dh-order") if any(model.frames[f].kind in ("dh", "mdh") for f in chain) else "")
        + ").",
    )
    for f in chain:
        parent = model.frames[f].parent
        factors = ctx.names.factors(f)
        lhs = m_name(parent, f)
        if len(factors) > 1:
            lhs += " = " + " ".join(factors)
        elementary.equations.append((lhs, model.M_local(f)))
    ans.steps.append(elementary)

    if len(model.chain(frame)) > 1:
        product = " \\, ".join(m_name(model.frames[f].parent, f) for f in model.chain(frame))
        ans.steps.append(Step(
            "Chain product",
            f"The pose of frame {name_md(frame)} in frame 0 is the product along the chain "
            "(trigonometric products collected).",
            equations=[(f"{m_name('0', frame)} = {product}", model.M0(frame))],
        ))
    m0 = model.M0(frame) if frame != "0" else sp.eye(4)

    pframe, pat = model.point_local(point)
    p0 = model.point0(point)
    ans.steps.append(Step(
        f"Position of point {point}",
        f"Point {point} is fixed in frame {name_md(pframe)} at ${latex(tuple(pat))}$; in frame 0, "
        f"with homogeneous coordinates:",
        equations=[(f"{{}}^{{0}}{point} = {m_name('0', pframe)} \\, {{}}^{{{frame_tex(pframe)}}}{point}",
                    p0)],
    ))

    ans.symbolic["M"] = m0
    ans.symbolic["position"] = list(p0)
    ans.symbolic["chain"] = [model.M_local(f) for f in chain]


def numeric_part(question: Question, ctx: SolveContext, ans: Answer) -> None:
    model = ctx.model
    frame, point = question.frame, question.point
    subs = ctx.substitutions(question.at)
    chain = NumericChain(model, subs)
    try:
        ans.numeric["M"] = chain.M0(frame).tolist()
        ans.numeric["position"] = chain.point0(point).tolist()
        ans.numeric["chain"] = [ctx.numeric(model.M_local(f), subs)
                                for f in answer_chain(model, frame, point)]
    except MissingValues as exc:
        ans.numeric.clear()
        ans.note(missing_note("pose and position", exc.names, ctx.problem))
        return
    drawing = robot_drawing(ctx, subs)
    if drawing is not None:
        drawing["highlight"] = point
        ans.figures.append(FigureSpec("robot", "robot", f"Robot at the given configuration ({point} marked)",
                                      drawing))
    ans.steps.append(Step(
        "Numeric values",
        "With the data and the configuration of the question:",
        equations=[(m_name("0", frame), ans.numeric["M"]),
                   (f"{{}}^{{0}}{point}", ans.numeric["position"])],
    ))
