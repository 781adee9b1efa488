"""The `motion_profile` question type (Motion profile): options, checks, answer schema."""

from __future__ import annotations

from robosolve.load import validators as V
from robosolve.questions.schema import JOINT_MAP, SCALAR, QuestionType, _k
from robosolve.questions.wording import asked, listing
from robosolve.questions.notebook_code import compare_line, guarded, lines, profile_lines, robosolve_numbers


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

ACCELERATIONS = {"bang-bang": "the accelerations the joints use to finish together (rescaled)",
                 "trapezoidal": "the acceleration of each joint in the synchronized motion",
                 "quintic": "the peak acceleration of each joint in the synchronized motion"}


def _statement(q, say) -> str:
    """The paper's statement (papers.md), from the start, goal, limits and shape, then what the
    question grades (the durations, T, the accelerations, the profiles q(t))."""
    o = q.options
    shape = o.get("shape", "bang-bang")
    text = (f"The joints move from {say.joint_values(o['from'])} to {say.joint_values(o['to'])}, "
            f"synchronized, each with a {shape} profile and the maximum accelerations "
            f"{say.per_joint(o['max_acceleration'], 'joint/s²')}")
    if "max_velocity" in o:
        text += f" and maximum velocities {say.per_joint(o['max_velocity'], 'joint/s')}"
    words = {"durations": "the duration of each joint alone at its limits",
             "T": "the synchronized duration $T$",
             "accelerations": ACCELERATIONS.get(shape, ACCELERATIONS["bang-bang"]),
             "profiles": "the motion $q(t)$ of each joint as a piecewise expression of the time $t$",
             "velocities": "the cruise velocity of each joint in the synchronized motion"}
    return text + f". Compute {listing(asked(q, say, words))}."


def notebook_cell(q, answer, problem):
    """The notebook's cell that recomputes the answer (questions/notebook_code.py)."""
    names = [j.name for j in problem.joints]
    keys = ["durations", "T", "accelerations", "velocities"]
    return lines(
        *profile_lines(q, problem),
        "# each joint alone needs its own time; all end together at T, the largest",
        robosolve_numbers(answer, keys),
        *guarded(answer, ("durations", compare_line("durations", f"dict(zip({names!r}, profile.durations))")),
                  ("T", compare_line("T", "profile.T")),
                  ("accelerations", compare_line("accelerations", f"dict(zip({names!r}, profile.accelerations))")),
                  ("velocities", compare_line("velocities", f"dict(zip({names!r}, profile.velocities))"))),
    )


TYPE = QuestionType(
    "motion_profile", "Motion profile", "§8 question 7",
    statement=_statement,
    options={"from": V.v_joint_values, "to": V.v_joint_values, "max_acceleration": V.v_joint_values,
             "shape": V.v_shape, "max_velocity": V.v_joint_values},
    required=("from", "to", "max_acceleration"),
    defaults={"shape": "bang-bang"},
    answers=(
        _k("durations", JOINT_MAP, "each joint alone at its limits", principal=True, unit="s"),
        _k("T", SCALAR, "the synchronized duration", principal=True, unit="s"),
        _k("accelerations", JOINT_MAP, "each joint's acceleration in the synchronized motion", principal=True, unit="joint/s²"),
        _k("profiles", JOINT_MAP, "joint -> piecewise expression in t, written piecewise(t <= t1, e1, e2) "
           "with t1 a number and e1, e2 expressions in t",
           unit="joint", numeric=False),
        _k("velocities", JOINT_MAP, "each joint's cruise velocity in the synchronized motion (trapezoidal)",
           unit="joint/s",
           needs=lambda q, joints: "" if q.options.get("shape") == "trapezoidal" else
           "the cruise velocities are computed only for a trapezoidal profile"),
    ),
    figures=(("profile", "motion_profile"),),
    cost=0.1, unit="dynamics",
    check=_check, makes_profile=True,
    notebook_cells=notebook_cell,
)
