"""The `displacement` question type:
Rigid displacement (helical axis); its options, checks and answer schema.
"""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.load.expressions import missing_keys
from robosolve.questions.schema import MATRIX, SCALAR, VECTOR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import at_literal, compare_line, lines, literal, robosolve_numbers, text


def _needs_robot(item: dict) -> bool:
    return any(isinstance(item.get(k), dict) for k in ("from", "to"))


def _principal(options: dict) -> tuple:
    """grading.md: u, alpha, h, P given from/to; Q, L given a screw."""
    return ("Q", "L") if "axis" in options else ("u", "alpha", "h", "P")


def _check(ql, path, item, q):
    """Two forms: `from` and `to`, or a screw (`axis`, `angle`, `through`, `translation`)."""
    chk = ql.chk
    screw_keys = [k for k in ("axis", "angle", "through", "translation") if k in item]
    pose_keys = [k for k in ("from", "to") if k in item]
    if screw_keys and pose_keys:
        chk.error(path, f"give either from/to or a screw (axis, angle, through, translation), not both "
                  f"(found {', '.join(pose_keys + screw_keys)})")
        return
    if not screw_keys:
        missing = [k for k in ("from", "to") if k not in item]
        if missing:
            chk.error(path, missing_keys(missing) + " (or give a screw: axis and angle)")
        return
    if "axis" not in item:
        chk.error(path, f"{', '.join(screw_keys)} describe a screw: give its axis too")
        return
    if "angle" not in item:
        chk.error(path, "missing required key 'angle' (the rotation about the axis, any real value)")
    if "frame" in item:
        chk.error(path + ("frame",), "a screw is given in frame 0: `frame` goes with from/to")
    axis = q.options.get("axis")
    if axis is not None:
        values = ql.b._values()
        vals = [sp.sympify(e).xreplace(values) for e in axis]
        if all(v.is_number for v in vals) and all(abs(complex(v)) <= 1e-12 for v in vals):
            chk.error(path + ("axis",), "the zero vector has no direction (give the axis direction, "
                      "any non-zero length)")

def _pose(v, say) -> str:
    if isinstance(v, dict) and "config" in v:
        return f"its pose at the configuration {say.joint_values(v['config'])}"
    if isinstance(v, dict) and "matrix" in v:
        return "the pose " + say.math(v["matrix"])
    if isinstance(v, dict) and "frame" in v:
        return f"frame {v['frame']}"
    return say.math(v)


WORDS = {
    "u": "the unit vector $u$ of its helical axis",
    "alpha": "the rotation angle $\\alpha \\in [0, \\pi]$ about the axis",
    "h": "the translation $h$ along the axis",
    "P": "the point $P$ of the axis nearest the origin",
    "Q": "its displacement matrix $Q$",
    "pitch": "the pitch $h / \\alpha$ of the screw",
    "L": "the matrix $L$ of the screw",
}


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from from/to (the poses, or the question's frame at two
    configurations) or the screw, then what the question grades."""
    o = q.options
    give = f" Give {listing(asked(q, say, WORDS))}."
    if "axis" in o:
        text = (f"A screw displacement turns by {say.value(o['angle'])} rad about the axis of direction "
                f"{say.math(list(o['axis']))}")
        if "through" in o:
            text += f" through the point {say.math(list(o['through']))}"
        if "translation" in o:
            text += f" and translates by {say.value(o['translation'])} m along it"
        return text + "." + give
    configs = any(isinstance(o[k], dict) and "config" in o[k] for k in ("from", "to"))
    who = f"of {say.frame(q)} " if configs or q.frame_given else ""
    return f"The rigid displacement {who}takes {_pose(o['from'], say)} to {_pose(o['to'], say)}." + give


def _pose_source(side, q) -> str:
    """One end of a displacement: a given matrix, or 0M of the frame at a configuration."""
    if "matrix" in side:
        # rounded by hand (0.707), robosolve reads the nearest rotation: so does the notebook
        return f"nearest_rotation_pose(robot.matrix({literal(sp.Matrix(side['matrix']))}))"
    config = {str(k): text(v) for k, v in side["config"].items()}
    return f"robot.pose({q.frame!r}).subs(robot.configuration({literal(config)}))"


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    o = q.options
    if "axis" in o:
        head = [
            "# from a screw: Q = [R, (I - R) P + h u; 0, 1], R = I + [u] sin(alpha) + [u]^2 (1 - cos(alpha))",
            f"at = {at_literal(q)}",
            f"axis = robot.number(robot.vector({literal([text(x) for x in o['axis']])}), at).ravel()",
            f"through = robot.number(robot.vector({literal([text(x) for x in o.get('through') or [0, 0, 0]])}), at).ravel()",
            f"alpha_given = robot.number(robot.parse({text(o['angle'])!r}), at)",
            f"h_given = robot.number(robot.parse({text(o.get('translation') or 0)!r}), at)",
            "Q = screw_displacement(axis, alpha_given, through, h_given)",
        ]
    else:
        in_frame = ("matrix" in o["from"] and "matrix" in o["to"] and problem.frames and q.frame_given
                    and q.frame != "0")
        head = [
            "# Q = M_to M_from^-1: every body point P2 = Q P1 (in frame 0)",
            f"at = {at_literal(q)}",
            f"M_from = {_pose_source(o['from'], q)}",
            f"M_to = {_pose_source(o['to'], q)}",
            "Q = M_to * inverse_pose(M_from)",
            *(["# written in the question's frame k (its pose 0M_k at `at`): Q_k = 0M_k^-1 Q 0M_k",
               f"M_k = robot.pose({q.frame!r})",
               "Q = inverse_pose(M_k) * Q * M_k"] if in_frame else []),
            "Q = robot.number(Q, at)" if "Q" in answer.numeric else "show(Q)",
        ]
    keys = ["Q", "u", "alpha", "h", "P", "pitch"] + (["L"] if "axis" in o else [])
    compared = [compare_line(k, k if k != "L" else "screw_matrix(u, P, pitch)") for k in keys if k in answer.numeric]
    if "Q" not in answer.numeric:                    # a value is not given (a null parameter)
        return lines(*head) if "axis" not in o else \
            "# robosolve gives no numbers here (a value is not given): nothing to recompute"
    return lines(
        *head,
        "u, alpha, h, P, pitch = helical_axis(Q)",
        robosolve_numbers(answer, keys),
        *compared,
    )


TYPE = QuestionType(
    "displacement", "Rigid displacement (helical axis)", "§3.1",
    statement=_statement,
    # two forms: from/to (two poses or configurations) or a screw (axis, angle, through,
    # translation); "from/to or a screw" is checked by `_check`
    options={"from": V.v_pose_or_config, "to": V.v_pose_or_config, "axis": V.v_vector3_params,
             "angle": V.v_expr, "through": V.v_vector3_params, "translation": V.v_expr},
    needs_robot=_needs_robot,
    answers=(
        _k("u", VECTOR, "unit vector of the helical axis", principal=True, shape=(3,)),
        _k("alpha", SCALAR, "rotation angle in [0, π]", principal=True, unit="rad", angle=True),
        _k("h", SCALAR, "translation along the axis", principal=True, unit="m"),
        _k("P", VECTOR, "the axis point nearest the origin", principal=True, unit="m", shape=(3,)),
        _k("Q", MATRIX, "the displacement matrix", unit="m", shape=(4, 4), pose=True,
           hints=(("inverse", "this is the displacement back, from `to` to `from`"),)),
        _k("pitch", SCALAR, "h / α", unit="m/rad"),
        _k("L", MATRIX, "the matrix of the screw, Q = exp(α·L) (given a screw)", shape=(4, 4),
           needs=lambda q, joints: "" if "axis" in q.options else "L is computed only for a displacement given by a screw"),
    ),
    principal_for=_principal,
    figures=(("helical_axis", "helical_axis"),),
    cost=0.05,
    check=_check, needs_joints=False,
    notebook_cells=notebook_cell,
)
