"""The `jacobian` question type:
Jacobian and singular configurations; its options, checks and answer schema.
"""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP_SET, MATRIX, MATRIX_MAP, N, R, SCALAR, QuestionType, _k


def _check(ql, path, item, q):
    if q.options.get("geometric") and "coordinates" in item:
        ql.chk.error(path + ("geometric",), "geometric: true cannot be combined with coordinates")


TYPE = QuestionType(
    "jacobian", "Jacobian and singular configurations", "§8 question 3",
    options={"coordinates": V.v_coordinates, "geometric": V.v_bool, "bodies": V.v_bool},
    defaults={"geometric": False, "bodies": False},
    answers=(
        _k("J", MATRIX, "the Jacobian of the coordinates", principal=True, shape=(R, N), in_frame0=True,
           hints=(("transposed", "J has one row per coordinate and one column per joint: "
                                 "column i is ∂(coordinates)/∂qᵢ"),)),
        _k("det", SCALAR, "det J (square J)", principal=True),
        _k("manipulability", SCALAR, "product of the singular values (J not square)", principal=True),
        _k("singularities", JOINT_MAP_SET, "conditions joint -> value making J lose rank",
           principal=True, angle=True, unordered=True, by_value=True),
        _k("com_jacobians", MATRIX_MAP, "body -> 3xn Jacobian of its centre of mass", shape=(3, N)),
    ),
    cost=0.5, cost_growth=2,
    check=_check, has_jacobian=True,
)
