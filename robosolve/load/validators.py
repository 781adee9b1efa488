"""The validators of question options, shared by the question types.

A question type (``robosolve/questions/<type>.py``) maps each of its option keys to one of
these functions. Each is called as ``validator(ql, path, value, question)`` by the question
loader ``ql`` (``load/questions.py``: its checker ``ql.chk``, the problem builder ``ql.b``, the
parameters' namespace ``ql.params_ns``, the joint names ``ql.joint_names`` and the name of the
profile type ``ql.profile_type``); it reports a mistake with ``ql.chk.error(path, ...)`` and
returns the parsed value, or None. A type's cross-field ``check(ql, path, item, question)``
gets the same loader, with ``ql.require_gravity(path)`` and ``ql.type_name(flag)``.
"""

from __future__ import annotations

import sympy as sp

from robosolve.load.expressions import ExpressionError, Namespace, did_you_mean, meant_value

SHAPES = ("bang-bang", "trapezoidal", "quintic")
LAWS = ("p", "pd", "pd_gravity", "computed_torque")


def v_bool(ql, path, value, q):
    return ql.chk.boolean(path, value)


def v_expr(ql, path, value, q):
    return ql.chk.expr(path, value, ql.params_ns)


def v_exprs(ql, path, value, q):
    v = ql.chk.vector(path, value, ql.b.ns, length=None)
    return list(v) if v is not None else None


class CoordinateMapping(list):
    """A mapping coordinate -> value given where a list in the order of `coordinates` is read:
    [(text, coordinate, value)], put in that order by the type's check."""


def v_exprs_or_coordinate_map(ql, path, value, q):
    """A list in the order of `coordinates`, or a mapping coordinate: value (as
    the rates of an IK `velocity` are written)."""
    if isinstance(value, dict):
        pairs = v_equations(ql, path, value, q)
        return CoordinateMapping(pairs) if pairs is not None else None
    if not isinstance(value, list):
        ql.chk.error(path, "expected a list of values in the order of `coordinates` (default: the "
                     "point's x, y, z), or a mapping coordinate: value such as {E.x: 0.1, E.y: 0}")
        return None
    return v_exprs(ql, path, value, q)


def in_coordinate_order(ql, path, given: CoordinateMapping, coordinates: list):
    """The values of `given` in the order of `coordinates` (sympy expressions), or None with
    one error naming the coordinates that are missing or unknown."""
    out, used = [], set()
    for c in coordinates:
        hit = [k for k, (_, lhs, _) in enumerate(given) if lhs == c and k not in used]
        if not hit:
            out.append(None)
            continue
        used.add(hit[0])
        out.append(given[hit[0]][2])
    extra = [given[k][0] for k in range(len(given)) if k not in used]
    if extra or any(v is None for v in out):
        names = ", ".join(str(c) for c in coordinates)
        ql.chk.error(path, f"the keys must be the coordinates {names}"
                     + (f" (not {', '.join(extra)})" if extra else "")
                     + "; or give a list in that order")
        return None
    return out


def v_vector3_params(ql, path, value, q):
    v = ql.chk.vector(path, value, ql.params_ns, length=3)
    return list(v) if v is not None else None


def v_vector3(ql, path, value, q):
    v = ql.chk.vector(path, value, ql.b.ns, length=3)
    return list(v) if v is not None else None


def v_coordinates(ql, path, value, q):
    """Task coordinates: expressions of the joints or of points' coordinates, each given once."""
    if not isinstance(value, list) or not value:
        ql.chk.error(path, "expected a non-empty list of coordinate expressions (e.g. [E.x, E.y])")
        return None
    out = [ql.chk.expr(path + (i,), v, ql.b.ns_points) for i, v in enumerate(value)]
    if any(e is None for e in out):
        return None
    moving = {j.symbol for j in ql.b.joints}
    ok = True
    for i, e in enumerate(out):
        if not any(s in moving or "." in s.name for s in e.free_symbols):
            ql.chk.error(path + (i,), f"{value[i]!r} does not depend on the joints: a coordinate is a "
                         "point's coordinate (E.x, E.y, E.z) or an expression of the joints")
            ok = False
        elif any(sp.expand(e - f) == 0 for f in out[:i]):
            ql.chk.error(path + (i,), f"the coordinate {value[i]!r} is given twice")
            ok = False
    return out if ok else None


def v_budgets(ql, path, value, q):
    if not ql.chk.mapping(path, value, ("force", "velocity", "compliance")):
        return None
    out = {}
    for k, v in value.items():
        if k in ("force", "velocity", "compliance"):
            e = ql.chk.expr(path + (k,), v, ql.params_ns)
            if e is not None:
                out[k] = e
    return out


def v_equations(ql, path, value, q):
    chk = ql.chk
    if value == {}:     # a mapping already: say what it lacks
        chk.error(path, "an empty mapping: give at least one coordinate expression: value (e.g. {E.x: 1.2})")
        return None
    if not isinstance(value, dict):
        chk.error(path, "expected a mapping coordinate expression: value (e.g. {E.x: 1.2, E.y: 0.3})")
        return None
    out = []
    for key, v in value.items():
        try:
            lhs = ql.b.ns_points.parse_text(str(key))
        except ExpressionError as exc:
            chk.error(path + (key,), _pose_key_hint(key) or str(exc))
            continue
        rhs = chk.expr(path + (key,), v, ql.params_ns)
        if rhs is not None:
            out.append((str(key), lhs, rhs))
    return out if len(out) == len(value) else None


def _pose_key_hint(key) -> str | None:
    """The message for a target key that is no coordinate but a misspelt key of a pose target
    (`postion`): a did-you-mean, not the expression parser's "unknown name"."""
    from robosolve.load.pose_target import POSE_KEYS

    hint = did_you_mean(str(key), POSE_KEYS) if str(key).isidentifier() else ""
    if not hint:
        return None
    return (f"unknown key '{key}'{hint} (a pose target has `pose`, or `position` with `R`, `zyz` or "
            "`rpy`; other targets are equations on coordinates such as E.x)")


def v_ik_target(ql, path, value, q):
    """An inverse-kinematics target: equations on coordinates, or a pose (load/pose_target.py)."""
    from robosolve.load.pose_target import is_pose_target, v_pose_target

    if is_pose_target(value):
        return v_pose_target(ql, path, value, q)
    if value == {}:
        ql.chk.error(path, "an empty target: give the coordinates to reach (e.g. {E.x: 1.2, E.y: 0.3}) "
                     "or a pose ({pose: M}, or {position: [x, y, z], rpy: [roll, pitch, yaw]})")
        return None
    return v_equations(ql, path, value, q)


def v_joint_values(ql, path, value, q, require_all=True):
    chk = ql.chk
    if not isinstance(value, dict):
        chk.error(path, "expected a mapping joint: value")
        return None
    # a misspelt joint is one of those not given (q9 among q1…q6 with q1 missing: q1), and its
    # did-you-mean says so: it is not "missing" a second time
    absent = [n for n in ql.joint_names if n not in value]
    meant = set()
    for key in value:
        if key not in ql.joint_names and not ql.b.joint_name_refused:
            guess = meant_value(str(key), absent)
            meant.add(guess)
            chk.error(path + (key,), f"unknown joint '{key}'" + (f" (did you mean '{guess}'?)" if guess else
                                                                  did_you_mean(str(key), ql.joint_names))
                      + f" (joints: {', '.join(ql.joint_names)})")
    missing = [n for n in absent if n not in meant]
    # as many unknown keys left without a guess as joints missing: each stands for one of them (a
    # joint renamed where it is defined), said already where the old name is used
    unmatched = sum(1 for key in value if key not in ql.joint_names) - len(meant - {None})
    if require_all and missing and unmatched < len(missing):
        chk.error(path, f"missing joint(s) {', '.join(missing)} (give a value for every joint)")
    out = {}
    for n in ql.joint_names:
        if n in value:
            e = chk.expr(path + (n,), value[n], ql.params_ns)
            if e is not None:
                out[n] = e
    return out


def v_select(ql, path, value, q):
    if value == "limits":
        return "limits"
    if isinstance(value, dict):
        return v_joint_values(ql, path, value, q)
    ql.chk.error(path, "expected 'limits' or a configuration (mapping joint: value)")
    return None


def v_shape(ql, path, value, q):
    return _choice(ql, path, value, SHAPES)


def v_law(ql, path, value, q):
    return _choice(ql, path, value, LAWS)


def v_space(ql, path, value, q):
    return _choice(ql, path, value, ("planar", "spatial"))


def _choice(ql, path, value, choices):
    if value not in choices:
        ql.chk.error(path, f"unknown value {value!r}"
                       + (did_you_mean(value, choices) if isinstance(value, str) else "")
                       + f" (expected one of: {', '.join(choices)})")
        return meant_value(value, choices)      # the rest checked as meant: one message
    return value


def v_profile_ref(ql, path, value, q):
    if not isinstance(value, str):
        ql.chk.error(path, f"expected the id of a {ql.profile_type} question")
        return None
    return value


def v_count(ql, path, value, q):
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        ql.chk.error(path, "expected a whole number >= 0")
        return None
    if value > 10_000:
        ql.chk.error(path, "unreasonably large count (at most 10000)")
        return None
    return value


def v_pose_or_config(ql, path, value, q):
    if isinstance(value, dict):
        return {"config": v_joint_values(ql, path, value, q)}
    m = ql.chk.matrix(path, value, ql.params_ns, shapes=((4, 4),))
    if m is not None and list(m[3, :]) == [0, 0, 0, 1] and not m.free_symbols and _rounded_rotation(m[:3, :3]):
        return {"matrix": m}    # rounded by hand: projected by the solver, with a note (as an IK pose target)
    if m is not None and (list(m[3, :]) != [0, 0, 0, 1] or not ql.b._is_rigid(m)):
        ql.chk.error(path, "not a rototranslation: the last row must be [0, 0, 0, 1] and the 3x3 "
                       "rotation block orthonormal with determinant 1")
        return None
    return {"matrix": m} if m is not None else None


def v_start_state(ql, path, value, q):
    """`start`: joint values and `<joint>_dot` rates at t = 0 (missing ones: 0)."""
    chk, joints = ql.chk, ql.b.joints
    if not isinstance(value, dict):
        chk.error(path, "expected a mapping joint: value and <joint>_dot: rate (e.g. {theta: 0, theta_dot: 1})")
        return None
    allowed = [j.name for j in joints] + [j.dot.name for j in joints]
    ddots = {j.ddot.name for j in joints}
    out = {}
    for key, v in value.items():
        if key in ddots:
            chk.error(path + (key,), f"'{key}' cannot be given: the accelerations follow from the "
                      "equations of motion (give joint values and <joint>_dot rates)")
            continue
        if key not in allowed:
            if not ql.b.joint_name_refused:
                chk.error(path + (key,), f"unknown joint or joint rate '{key}'" + did_you_mean(key, allowed)
                          + f" (expected: {', '.join(allowed)})")
            continue
        e = chk.expr(path + (key,), v, ql.params_ns)
        if e is not None:
            out[key] = e
    return {k: out[k] for k in allowed if k in out}


def v_actuator_laws(ql, path, value, q):
    """`actuators`: actuator -> expression in t, the joints, their rates and the parameters."""
    chk, b = ql.chk, ql.b
    if not isinstance(value, dict):
        chk.error(path, "expected a mapping actuator: law (e.g. {C: 70*sin(t)})")
        return None
    acts = [str(j.actuator) for j in b.joints]
    names = {s.name: s for s in b.parameters}
    for j in b.joints:
        names[j.name], names[j.dot.name] = j.symbol, j.dot
    names["t"] = b.names["t"]
    ns = Namespace(names, what="name in the law (it may use t, the joints, their _dot rates, the parameters)",
                   unknown_ok=b.joint_name_refused or b.parameters_refused)
    out = {}
    for key, v in value.items():
        if key not in acts:
            if b.actuator_refused or b.joint_name_refused:
                continue         # maybe the refused actuator's (said already)
            chk.error(path + (str(key),), f"unknown actuator '{key}'" + did_you_mean(str(key), acts)
                      + f" (actuators: {', '.join(acts)})")
            continue
        e = chk.expr(path + (key,), v, ns)
        if e is not None:
            out[key] = e
    return {a: out[a] for a in acts if a in out}


def v_duration(ql, path, value, q):
    e = ql.chk.expr(path, value, ql.params_ns)
    if e is not None and e.is_number and not (e.is_real and e.is_positive and e.is_finite):
        ql.chk.error(path, f"expected a positive duration in seconds, got {value!r}")
        return None
    return e


def _rounded_rotation(r) -> bool:
    """A numeric 3x3 block orthonormal with determinant 1 within the tolerance of an IK pose
    target (load/pose_target.ROTATION_TOL): entries rounded by hand (0.707 for cos 45°)."""
    from robosolve.core.transforms import rotation_defect
    from robosolve.load.pose_target import ROTATION_TOL

    try:
        err, det = rotation_defect(r.evalf().tolist())
    except (TypeError, ValueError):
        return False
    return err <= ROTATION_TOL and abs(det - 1) <= ROTATION_TOL


def v_rotation_matrix(ql, path, value, q):
    m = ql.chk.matrix(path, value, ql.params_ns, shapes=((3, 3), (4, 4)))
    if m is None:
        return None
    full = m if m.shape == (4, 4) else sp.diag(m, 1)
    if m.shape == (4, 4) and list(m[3, :]) != [0, 0, 0, 1]:
        ql.chk.error(path, "the last row of a pose matrix must be [0, 0, 0, 1]")
        return None
    if not m.free_symbols and _rounded_rotation(m[:3, :3]):
        return m        # rounded by hand: projected by the solver, with a note (as an IK pose target)
    if not ql.b._is_rigid(full):
        ql.chk.error(path, "not a rotation: the 3x3 block must be orthonormal with determinant 1"
                       + (" (checked at sample values of " + ", ".join(sorted(s.name for s in m.free_symbols))
                          + ")" if m.free_symbols else ""))
        return None
    return m


def joint_motion_in_at(ql, item) -> list:
    """The keys of a question's `at` that are joint values, rates or accelerations, each with
    its joint's name: for the types whose `at` may override parameters only."""
    at = item.get("at")
    if not isinstance(at, dict):
        return []
    motion = {}
    for j in ql.b.joints:
        motion[j.name] = motion[j.dot.name] = motion[j.ddot.name] = j.name
    return [(key, motion[key]) for key in at if key in motion]
