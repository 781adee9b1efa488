"""The `statics` question type (Statics): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, QuestionType, _k


def _check(ql, path, item, q):
    chk, opts = ql.chk, q.options
    ncoord = len(opts["coordinates"]) if "coordinates" in opts else 3
    if not any(k in item for k in ("force", "torque")) and not opts.get("weight"):
        chk.error(path, "expected force, torque or weight: true")
    if "force" in opts and len(opts["force"]) != ncoord:
        chk.error(path + ("force",), f"expected {ncoord} components (one per coordinate), "
                  f"got {len(opts['force'])}")
    if "torque" in opts and "coordinates" in item:
        chk.error(path + ("torque",), "a torque needs the default coordinates (the point's x, y, z)")
    if opts.get("weight"):
        ql.require_gravity(path)
        if not ql.b.problem.bodies and not ql.b.bodies_given:
            chk.error(path + ("weight",), "weight: true needs bodies (masses)")


TYPE = QuestionType(
    "statics", "Statics", "§8 question 4",
    options={"force": V.v_exprs, "torque": V.v_vector3, "weight": V.v_bool, "coordinates": V.v_coordinates},
    defaults={"weight": False},
    answers=(
        _k("Fq", JOINT_MAP, "joint forces balancing the load, Fq = −Jᵀ·Fs", principal=True,
           hints=(("negated", "Fq = −Jᵀ·Fs is what the joints exert to balance the load; "
                              "+Jᵀ·Fs is the load's own action on the joints"),)),
    ),
    cost=0.2,
    check=_check, has_jacobian=True,
)
