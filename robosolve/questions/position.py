"""The `position` question type (Position (direct kinematics)): options, checks, answer schema."""

from __future__ import annotations

from robosolve.questions.schema import MATRIX, MATRIX_LIST, VECTOR, QuestionType, _k


TYPE = QuestionType(
    "position", "Position (direct kinematics)", "§8 question 1",
    options={},
    answers=(
        _k("M", MATRIX, "pose ⁰Mₖ of the frame in frame 0", principal=True, shape=(4, 4),
           pose=True, dh_built="pose", notation="⁰M{sub}", hints=(
               ("transposed", "the columns of R are the axes of frame {frame} in frame 0, and the "
                              "last column is the origin of frame {frame} in frame 0"),
               ("inverse", "that is the pose of frame 0 in frame {frame}; {symbol} gives frame "
                           "{frame} in frame 0 ({symbol} = ⁰M₁·¹M₂·…)"))),
        _k("position", VECTOR, "the point in frame 0", principal=True, shape=(3,), dh_built="point"),
        _k("chain", MATRIX_LIST, "ⁱ⁻¹Mᵢ of each frame in its parent, from frame 1 on"),
    ),
    figures=(("robot", "robot"),),
    cost=0.1,
)
