"""The `displacement` question type:
Rigid displacement (helical axis); its options, checks and answer schema.
"""

from __future__ import annotations

import sympy as sp

from robosolve.load import validators as V
from robosolve.questions.schema import MATRIX, SCALAR, VECTOR, QuestionType, _k


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
        for k in ("from", "to"):
            if k not in item:
                chk.error(path, f"missing required key '{k}' (or give a screw: axis and angle)")
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


TYPE = QuestionType(
    "displacement", "Rigid displacement (helical axis)", "§3.1",
    # two forms: from/to (two poses or configurations) or a screw (axis, angle, through,
    # translation); "from/to or a screw" is checked by `_check`
    options={"from": V.v_pose_or_config, "to": V.v_pose_or_config, "axis": V.v_vector3_params,
             "angle": V.v_expr, "through": V.v_vector3_params, "translation": V.v_expr},
    needs_robot=_needs_robot,
    answers=(
        _k("u", VECTOR, "unit vector of the helical axis", principal=True, shape=(3,)),
        _k("alpha", SCALAR, "rotation angle in [0, π]", principal=True, angle=True),
        _k("h", SCALAR, "translation along the axis", principal=True),
        _k("P", VECTOR, "the axis point nearest the origin", principal=True, shape=(3,)),
        _k("Q", MATRIX, "the displacement matrix", shape=(4, 4), pose=True,
           hints=(("inverse", "this is the displacement back, from `to` to `from`"),)),
        _k("pitch", SCALAR, "h / α"),
        _k("L", MATRIX, "[[u], P×u + pitch·u; 0, 0] (given a screw)", shape=(4, 4)),
    ),
    principal_for=_principal,
    figures=(("helical_axis", "helical_axis"),),
    cost=0.05,
    check=_check, needs_joints=False,
)
