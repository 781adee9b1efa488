"""The `motion_profile` question type (Motion profile): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, SCALAR, QuestionType, _k


def _check(ql, path, item, q):
    chk, opts = ql.chk, q.options
    shape = opts.get("shape", "bang-bang")
    if shape == "trapezoidal" and "max_velocity" not in item:
        chk.error(path, "a trapezoidal profile needs max_velocity")
    if shape != "trapezoidal" and "max_velocity" in item:
        chk.error(path + ("max_velocity",), "max_velocity goes with shape: trapezoidal")
    for key in ("max_acceleration", "max_velocity"):
        for name, v in opts.get(key, {}).items():
            value = chk.number_value(v)
            if value is not None and not value > 0:
                chk.error(path + (key, name), f"must be positive, got {item[key][name]!r}"
                          + (f" (= {value:g})" if not v.is_number else ""))


TYPE = QuestionType(
    "motion_profile", "Motion profile", "§8 question 7",
    options={"from": V.v_joint_values, "to": V.v_joint_values, "max_acceleration": V.v_joint_values,
             "shape": V.v_shape, "max_velocity": V.v_joint_values},
    required=("from", "to", "max_acceleration"),
    defaults={"shape": "bang-bang"},
    answers=(
        _k("durations", JOINT_MAP, "each joint alone at its maximum acceleration", principal=True),
        _k("T", SCALAR, "the synchronized duration", principal=True),
        _k("accelerations", JOINT_MAP, "rescaled accelerations", principal=True),
        _k("profiles", JOINT_MAP, "joint -> piecewise expression in t", numeric=False),
    ),
    figures=(("profile", "motion_profile"),),
    cost=0.1, unit="dynamics",
    check=_check, makes_profile=True,
)
