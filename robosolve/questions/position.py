"""The `position` question type (Position (direct kinematics)): options, checks, answer schema."""

from __future__ import annotations

from robosolve.core.prose import name_tex
from robosolve.questions.schema import MATRIX, MATRIX_LIST, VECTOR, QuestionType, _k
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

def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the question's point, frame and `at`."""
    at = say.at(q)
    return (f"Compute the pose ${{}}^{{0}}M_{{{name_tex(q.frame)}}}$ of {say.frame(q)} in frame 0 as a function of the "
            f"joint variables ({say.joints()}), and the coordinates of {say.point(q)} in frame 0"
            + (f"; give the numbers {at}" if at else "") + ".")


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
        _k("chain", MATRIX_LIST, "ⁱ⁻¹Mᵢ of each frame in its parent, from frame 1 on"),
    ),
    figures=(("robot", "robot"),),
    cost=0.1,
    notebook_cells=notebook_cell,
)
