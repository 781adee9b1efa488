"""The `ellipsoids` question type:
Force, velocity and compliance ellipsoids; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import AXES, JOINT_MAP, M, MATRIX, RECORD, SCALAR, VECTOR, QuestionType, _k


def _ellipse(name: str, what: str, principal: bool) -> AnswerKey:
    return _k(name, RECORD, f"the {what} ellipsoid", fields=(
        _k("semi_axes", AXES, "semi-axes scaled to their lengths, by decreasing length",
           shape=(M, M), sign_free=True, symbolic=False),
        _k("lengths", VECTOR, "semi-axis lengths, decreasing", principal=principal, shape=(M,)),
        _k("directions", AXES, "unit directions of the semi-axes", shape=(M, M), sign_free=True,
           symbolic=False),
    ))


def _check(ql, path, item, q):
    chk, opts, joints = ql.chk, q.options, ql.b.joints
    ncoord = len(opts["coordinates"]) if "coordinates" in opts else 3
    if isinstance(opts.get("velocity"), V.CoordinateMapping):
        point = q.point
        coordinates = opts.get("coordinates") or [ql.b.ns_points.parse_text(f"{point}.{a}") for a in "xyz"]
        if "coordinates" in item and opts.get("coordinates") is None:
            return                      # the coordinates have their own error
        opts["velocity"] = V.in_coordinate_order(ql, path + ("velocity",), opts["velocity"], coordinates)
        if opts["velocity"] is None:
            del opts["velocity"]
    elif "velocity" in opts and len(opts["velocity"]) != ncoord:
        chk.error(path + ("velocity",), f"expected {ncoord} components (one per coordinate), "
                  f"got {len(opts['velocity'])}")
    if "joint_compliance" in opts and len(opts["joint_compliance"]) != len(joints):
        chk.error(path + ("joint_compliance",),
                  f"expected {len(joints)} values (one per joint), got {len(opts['joint_compliance'])}")


TYPE = QuestionType(
    "ellipsoids", "Force, velocity and compliance ellipsoids", "§8 question 5",
    options={"coordinates": V.v_coordinates, "budgets": V.v_budgets,
             "joint_compliance": V.v_exprs, "velocity": V.v_exprs_or_coordinate_map},
    required=("at",),
    defaults={"budgets": {"force": 1, "velocity": 1, "compliance": 1}},
    answers=(
        _ellipse("force", "force", True),
        _ellipse("velocity", "velocity", True),
        _k("condition_number", SCALAR, "max/min eigenvalue of A", principal=True),
        _ellipse("compliance", "compliance", False),
        _k("A", MATRIX, "A = J Jᵀ", shape=(M, M)),
        _k("eigenvalues", VECTOR, "eigenvalues of A, decreasing", shape=(M,)),
        _k("q_dot", JOINT_MAP, "joint rates giving the desired velocity", symbolic=False),
    ),
    figures=(("ellipsoids", "ellipsoids"),),
    cost=0.3,
    check=_check, has_jacobian=True,
)
