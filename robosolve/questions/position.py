"""The `position` question type (Position (direct kinematics)): options, checks, answer schema."""

from __future__ import annotations

from robosolve.core.prose import name_tex
from robosolve.questions.schema import MATRIX, MATRIX_LIST, VECTOR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, guarded, lines, robosolve_numbers


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    return lines(
        f"at = {at_literal(q)}",
        f"M = robot.pose({q.frame!r})",
        f"P = robot.point0({q.point!r})",
        "show(M, P)",
        robosolve_numbers(answer, ["M", "position"]),
        *guarded(answer, ("M", compare_line("M", "robot.number(M, at)")),
                  ("position", compare_line("position", "robot.number(P, at).ravel()"))),
    )

def chain_frames(problem, frame: str, point: str) -> list[str]:
    """The frames whose pose in their parent the `chain` answer lists: from frame 1 to the
    farther of `frame` and the point's frame, in the order of the frames (both branches of a
    tree), as the solver's `answer_chain`; known before solving."""
    def up(name):
        out = []
        while name in problem.frames:
            out.append(name)
            name = problem.frames[name].parent
        return out

    point_frame = problem.points[point].frame if point in problem.points else frame
    used = set(up(frame)) | set(up(point_frame))
    return [f for f in problem.frames if f in used]


def _words(q, say) -> dict:
    chain = ", ".join(f"${{}}^{{{name_tex(say.problem.frames[f].parent)}}}M_{{{name_tex(f)}}}$"
                      for f in chain_frames(say.problem, q.frame, q.point))
    return {"M": f"the pose ${{}}^{{0}}M_{{{name_tex(q.frame)}}}$ of {say.frame(q)} in frame 0",
            "position": f"the coordinates of {say.point(q)} in frame 0",
            "chain": f"the pose of each frame in its parent along the chain ({chain})"}


def _statement(q, say) -> str:
    """The paper's statement (papers.md): the graded keys of the question's frame and point,
    as functions of the joint variables, with the numbers at its `at`."""
    at = say.at(q)
    return (f"Compute {listing(asked(q, say, _words(q, say)))} as functions of the joint variables "
            f"({say.joints()})" + (f"; give the numbers {at}" if at else "") + ".")


def paper_layout(q, problem) -> dict:
    """The `chain` answer's matrices, one per frame of the chain (papers: the template)."""
    return {"chain": (chain_frames(problem, q.frame, q.point), "m")}


TYPE = QuestionType(
    "position", "Position (direct kinematics)", "§8 question 1",
    statement=_statement,
    options={},
    answers=(
        _k("M", MATRIX, "pose ⁰Mₖ of the frame in frame 0", principal=True, unit="m", shape=(4, 4),
           pose=True, dh_built="pose", notation="⁰M{sub}", hints=(
               ("transposed", "the columns of R are the axes of frame {frame} in frame 0, and the "
                              "last column is the origin of frame {frame} in frame 0"),
               ("inverse", "that is the pose of frame 0 in frame {frame}; {symbol} gives frame "
                           "{frame} in frame 0 ({symbol} = ⁰M₁·¹M₂·…)"))),
        _k("position", VECTOR, "the point in frame 0", principal=True, unit="m", shape=(3,),
           dh_built="point"),
        _k("chain", MATRIX_LIST, "ⁱ⁻¹Mᵢ of each frame in its parent, from frame 1 on", unit="m"),
    ),
    figures=(("robot", "robot"),),
    cost=0.1,
    notebook_cells=notebook_cell, paper_layout=paper_layout,
)
