"""The `velocity_acceleration` question type:
Velocity and acceleration; its options, checks and answer schema.
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.prose import name_tex
from robosolve.questions.schema import MATRIX, VECTOR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, guarded, lines, robosolve_numbers


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    carrier = problem.points[q.point].frame
    moved_by = None if carrier == q.frame else (
        "# the point is fixed in another frame than the question's: it moves with that frame's W and H\n"
        f"W_P, H_P = chain.W({carrier!r}), chain.H({carrier!r})")
    w_p, h_p = ("W", "H") if moved_by is None else ("W_P", "H_P")
    if "W" not in answer.numeric:                 # a value is not given (a rate, a null parameter)
        return lines(f"at = {at_literal(q)}", f"W, H = robot.velocity_matrices({q.frame!r})",
                     "show(W.subs(robot.fixed(at)), H.subs(robot.fixed(at)))")
    return lines(
        f"at = {at_literal(q)}",
        "# W and H of 0M in frame 0 at these numbers, by Rivals (W = W_0p + sum 0L_i q_i') and Coriolis",
        "# (H = H_0p + 2 W_0p W_pj + H_pj); robot.velocity_matrices gives them as M' M^-1, M'' M^-1",
        "chain = robot.chain_at(at)",
        f"W, H = chain.W({q.frame!r}), chain.H({q.frame!r})",
        moved_by,
        f"P = np.append(chain.point({q.point!r}), 1.0)       # the point, homogeneous",
        "# the auxiliary frame a: origin at the point, axes of frame 0 (aW = 0Ma^-1 W 0Ma)",
        "to_a = np.eye(4)",
        "to_a[:3, 3] = -P[:3]",
        "# omega = vex of W's rotation block; H's is [omega'] + [omega]^2, whose skew part is [omega']",
        robosolve_numbers(answer, KEYS),
        *guarded(answer, ("W", compare_line("W", "W")), ("H", compare_line("H", "H")),
                 ("W_aux", compare_line("W_aux", "to_a @ W @ np.linalg.inv(to_a)")),
                 ("H_aux", compare_line("H_aux", "to_a @ H @ np.linalg.inv(to_a)")),
                 ("velocity", compare_line("velocity", f"({w_p} @ P)[:3]")),
                 ("acceleration", compare_line("acceleration", f"({h_p} @ P)[:3]")),
                 ("angular_velocity", compare_line("angular_velocity", "np.array(vex(W), dtype=float).ravel()")),
                 ("angular_acceleration",
                  compare_line("angular_acceleration", "np.array(vex((H - H.T) / 2), dtype=float).ravel()"))),
    )


KEYS = ["W", "H", "W_aux", "H_aux", "velocity", "acceleration", "angular_velocity", "angular_acceleration"]

def _words(q, say) -> dict:
    k = name_tex(q.frame)
    aux = f"expressed in the auxiliary frame (origin at {say.point(q)}, axes parallel to frame 0)"
    return {
        "velocity": f"the velocity of {say.point(q)} in frame 0",
        "acceleration": f"the acceleration of {say.point(q)} in frame 0",
        "angular_velocity": f"the angular velocity of {say.frame(q)} in frame 0",
        "angular_acceleration": f"the angular acceleration of {say.frame(q)} in frame 0",
        "W": f"the velocity matrix $W = \\dot M\\,M^{{-1}}$ of {say.frame(q)}, $M = {{}}^{{0}}M_{{{k}}}$ "
             "(expressed in frame 0)",
        "H": f"the acceleration matrix $H = \\ddot M\\,M^{{-1}}$ of {say.frame(q)}, $M = {{}}^{{0}}M_{{{k}}}$ "
             "(expressed in frame 0)",
        "W_aux": f"the velocity matrix $W$ of {say.frame(q)} {aux}",
        "H_aux": f"the acceleration matrix $H$ of {say.frame(q)} {aux}",
    }


def _statement(q, say) -> str:
    """The paper's statement (papers.md): the graded keys of the question's point and frame, at
    its `at`."""
    at = say.at(q)
    return (f"Compute {listing(asked(q, say, _words(q, say)))}" + (f", {at}" if at else "")
            + " (symbolic in the joint variables and their rates, or the numbers of this configuration).")


TYPE = QuestionType(
    "velocity_acceleration", "Velocity and acceleration", "§8 question 2",
    statement=_statement,
    options={},
    answers=(
        _k("velocity", VECTOR, "velocity of the point in frame 0", principal=True, unit="m/s", shape=(3,),
           in_frame0=True),
        _k("acceleration", VECTOR, "acceleration of the point in frame 0", principal=True, unit="m/s²",
           shape=(3,), in_frame0=True),
        _k("angular_velocity", VECTOR, "ω of the frame in frame 0", principal=True, unit="rad/s", shape=(3,),
           in_frame0=True),
        _k("angular_acceleration", VECTOR, "ω̇ of the frame in frame 0", unit="rad/s²", shape=(3,)),
        _k("W", MATRIX, "W₀ₖ = Ṁ M⁻¹, expressed in frame 0", shape=(4, 4)),
        _k("H", MATRIX, "H₀ₖ = M̈ M⁻¹ = Ẇ + W², expressed in frame 0", shape=(4, 4)),
        _k("W_aux", MATRIX, "W in the auxiliary frame (origin at the point)", shape=(4, 4)),
        _k("H_aux", MATRIX, "H in the auxiliary frame", shape=(4, 4)),
    ),
    cost=0.8, cost_growth=2,
    notebook_cells=notebook_cell,
)
