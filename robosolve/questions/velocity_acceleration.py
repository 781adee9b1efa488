"""The `velocity_acceleration` question type:
Velocity and acceleration; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.questions.schema import MATRIX, VECTOR, QuestionType, _k


TYPE = QuestionType(
    "velocity_acceleration", "Velocity and acceleration", "§8 question 2",
    options={},
    answers=(
        _k("velocity", VECTOR, "velocity of the point in frame 0", principal=True, shape=(3,), in_frame0=True),
        _k("acceleration", VECTOR, "acceleration of the point in frame 0", principal=True, shape=(3,), in_frame0=True),
        _k("angular_velocity", VECTOR, "ω of the frame in frame 0", principal=True, shape=(3,), in_frame0=True),
        _k("angular_acceleration", VECTOR, "ω̇ of the frame in frame 0", shape=(3,)),
        _k("W", MATRIX, "W₀ₖ = Ṁ M⁻¹, expressed in frame 0", shape=(4, 4)),
        _k("H", MATRIX, "H₀ₖ = M̈ M⁻¹ = Ẇ + W², expressed in frame 0", shape=(4, 4)),
        _k("W_aux", MATRIX, "W in the auxiliary frame (origin at the point)", shape=(4, 4)),
        _k("H_aux", MATRIX, "H in the auxiliary frame", shape=(4, 4)),
    ),
    cost=0.8, cost_growth=2,
)
