"""The code cell of each question type in report.ipynb, built from the question and its answer.

A builder `(question, answer, problem) -> str | None` returns the Python source of the cell that
recomputes the answer with the notebook's runtime (robosolve/render/notebook_runtime.py, whose
names the cell uses: `robot`, `compare`, ...), or None for an option layout it does not rebuild
(the notebook then shows robosolve's numbers and says so). Every value from the problem reaches
the source through `literal` (Python literals: repr), never as code.
"""

from __future__ import annotations

import math

import sympy as sp

# -- literals -----------------------------------------------------------------------------------


def text(expr) -> str:
    """A sympy value as the text the runtime parses (`Robot.parse`): sympy's own printing, the
    point coordinates P.x written P_x."""
    expr = sp.sympify(expr)
    rep = {s: sp.Symbol(s.name.replace(".", "_")) for s in expr.free_symbols if "." in s.name}
    return str(expr.xreplace(rep)) if rep else str(expr)


def literal(value) -> str:
    """Python source of plain data: numbers, strings, None, booleans, lists, mappings; a sympy
    value becomes its text (a string), a float that is not finite float('inf') / float('nan')."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{literal(k)}: {literal(v)}" for k, v in value.items()) + "}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(literal(v) for v in value) + "]"
    if value is None or isinstance(value, (bool, str, int)):
        return repr(value)
    if isinstance(value, float) or hasattr(value, "dtype"):
        value = float(value)
        return repr(value) if math.isfinite(value) else f"float({repr(value)!r})"
    if isinstance(value, sp.MatrixBase):
        return literal([[text(x) for x in value.row(i)] for i in range(value.rows)])
    return repr(text(value))


def at_literal(question) -> str:
    """The question's configuration `at` as {name: text}."""
    return literal({s.name: text(v) for s, v in question.at.items()})


def robosolve_numbers(answer, keys) -> str:
    """robosolve's numbers of the answer (the keys it has), as one literal assignment."""
    return "robosolve = " + literal({k: answer.numeric[k] for k in keys if k in answer.numeric})


def _lines(*parts) -> str:
    return "\n".join(p for p in parts if p is not None)


def _compare(key, expr, *, want=None, rtol=None) -> str:
    tol = "" if rtol is None else f", rtol={rtol!r}"
    return f"compare({key!r}, {expr}, robosolve[{key!r}]{want or ''}{tol})"


def _guarded(answer, *calls) -> list[str]:
    """compare(...) lines, each only when robosolve answered that key."""
    return [c for key, c in calls if key in answer.numeric]


# -- kinematics ---------------------------------------------------------------------------------

def position(q, answer, problem):
    return _lines(
        f"at = {at_literal(q)}",
        f"M = robot.pose({q.frame!r})",
        f"P = robot.point0({q.point!r})",
        "show(M, P)",
        robosolve_numbers(answer, ["M", "position"]),
        *_guarded(answer, ("M", _compare("M", "robot.number(M, at)")),
                  ("position", _compare("position", "robot.number(P, at).ravel()"))),
    )


def velocity_acceleration(q, answer, problem):
    return _lines(
        f"at = {at_literal(q)}",
        "# W = M' M^-1 and H = M'' M^-1 of 0M (in frame 0); a point's velocity W P, acceleration H P",
        f"W, H = robot.velocity_matrices({q.frame!r})",
        f"P = sp.Matrix([*robot.point0({q.point!r}), 1])",
        robosolve_numbers(answer, ["W", "H", "velocity", "acceleration"]),
        *_guarded(answer, ("W", _compare("W", "robot.number(W, at)")),
                  ("H", _compare("H", "robot.number(H, at)")),
                  ("velocity", _compare("velocity", "robot.number(W * P, at).ravel()[:3]")),
                  ("acceleration", _compare("acceleration", "robot.number(H * P, at).ravel()[:3]"))),
    )


def _coordinates(q) -> str:
    coords = q.options.get("coordinates")
    if coords:
        return literal([text(c) for c in coords])
    return literal([f"{q.point}_{axis}" for axis in "xyz"])


def _jacobian_lines(q) -> list[str]:
    return [f"at = {at_literal(q)}",
            f"J = robot.jacobian({_coordinates(q)})",
            "Jn = robot.number(J, at)"]


def jacobian(q, answer, problem):
    if q.options.get("geometric"):
        head = [f"at = {at_literal(q)}",
                "# geometric: the point's linear velocity over the angular velocity, column by joint",
                f"J = robot.geometric_jacobian({q.point!r})",
                "Jn = robot.number(J, at)"]
    else:
        head = _jacobian_lines(q)
    return _lines(
        *head,
        "show(J)",
        robosolve_numbers(answer, ["J", "det", "manipulability"]),
        *_guarded(answer, ("J", _compare("J", "Jn")),
                  ("det", _compare("det", "np.linalg.det(Jn)")),
                  ("manipulability", _compare("manipulability", "np.prod(np.linalg.svd(Jn, compute_uv=False))"))),
    )


def statics(q, answer, problem):
    force, torque, weight = q.options.get("force"), q.options.get("torque"), q.options.get("weight")
    if weight and force is None and torque is None:
        return _lines(
            f"at = {at_literal(q)}",
            "# the bodies' own weight: Fq = -sum J_G^T m g (J_G the Jacobian of a centre of mass)",
            "Fq = robot.weight_forces(at)",
            "show(Fq)",
            robosolve_numbers(answer, ["Fq"]),
            _compare("Fq", "robot.number(Fq, at).ravel()") if "Fq" in answer.numeric else None,
        )
    if force is None or torque is not None or weight:
        return None
    return _lines(
        *_jacobian_lines(q),
        f"F = robot.number(robot.vector({literal([text(x) for x in force])}), at).ravel()",
        "Fq = -Jn.T @ F          # what the joints exert to balance F",
        robosolve_numbers(answer, ["Fq"]),
        _compare("Fq", "Fq") if "Fq" in answer.numeric else None,
    )


def ellipsoids(q, answer, problem):
    budgets = q.options.get("budgets") or {}
    kf, kv, ka = (text(budgets.get(k, 1)) for k in ("force", "velocity", "compliance"))
    kq = q.options.get("joint_compliance")
    want = {"eigenvalues": sorted(answer.numeric.get("eigenvalues") or [])}
    for kind in ("force", "velocity", "compliance"):
        lengths = (answer.numeric.get(kind) or {}).get("lengths")
        if lengths is not None:                     # None: infinite (a singular direction)
            want[kind] = sorted((math.inf if x is None else x for x in lengths), reverse=True)
    if "condition_number" in answer.numeric:            # None: infinite (singular)
        cond = answer.numeric["condition_number"]
        want["condition_number"] = math.inf if cond is None else cond
    kq_arg = "" if not kq else f", Kq=robot.number(robot.vector({literal([text(x) for x in kq])}), at).ravel()"
    compared = [_compare(k, f"axes[{k if k != 'eigenvalues' else 'nu'!r}]") for k in want
                if k != "condition_number" and (k != "compliance" or kq)]
    if "condition_number" in want:
        compared.append(_compare("condition_number", "axes['condition_number']"))
    return _lines(
        *_jacobian_lines(q),
        "# A = J J^T: force semi-axes K_f / sqrt(nu), velocity K_v sqrt(nu), compliance K_a kappa",
        f"Kf, Kv, Ka = (robot.number(robot.parse(k), at) for k in {literal([kf, kv, ka])})",
        f"axes = ellipsoid_axes(Jn, Kf, Kv, Ka{kq_arg})",
        "robosolve = " + literal(want) + "   # lengths largest first",
        *compared,
    )


def inverse_kinematics(q, answer, problem):
    target = q.options.get("target") or []
    if not target:
        return None
    limits = []
    for j in problem.joints:
        lo, hi = j.limits if j.limits else ((-sp.pi, sp.pi) if j.kind == "revolute" else (-10, 10))
        limits.append([text(lo), text(hi)])
    residual = [f"({text(lhs)}) - ({text(rhs)})" for _, lhs, rhs in target]
    names = [j.name for j in problem.joints]
    want = {"solutions": sorted(answer.numeric.get("solutions") or [], key=lambda s: tuple(s.values()))}
    lines = [
        f"at = {at_literal(q)}",
        "# Newton iterations (least-squares steps) from a grid of starts, kept within the joint limits",
        f"task = robot.vector({literal([text(lhs) for _, lhs, _ in target])})",
        f"residual = (task - robot.vector({literal([text(rhs) for _, _, rhs in target])})).subs(robot.fixed(at))",
        f"limits = [[robot.number(robot.parse(x), at) for x in pair] for pair in {literal(limits)}]",
        f"solutions = newton_solutions(residual, robot.joints, limits, {literal([j.kind == 'revolute' for j in problem.joints])})",
        "# (at a workspace boundary a solution is a double root: Newton then finds it to ~1e-7 only)",
        f"compare('solutions', [dict(zip({names!r}, s)) for s in solutions], robosolve['solutions'], atol=1e-6)",
    ]
    velocity = q.options.get("velocity")
    if velocity and "q_dot" in answer.numeric and answer.numeric.get("selected"):
        want["selected"] = answer.numeric["selected"]
        want["q_dot"] = answer.numeric["q_dot"]
        lines += [
            "# velocity IK at the solution robosolve selected: J(q) q' = v",
            "selected = robosolve['selected']",
            "if solutions:",
            "    selected = dict(zip(" + repr(names) + ", min(solutions, key=lambda s: np.linalg.norm(s - list(selected.values())))))",
            f"v = robot.number(robot.vector({literal([text(v) for _, _, v in velocity])}), at).ravel()",
            f"rates_of = robot.vector({literal([text(lhs) for _, lhs, _ in velocity])})",
            "Jq = robot.number(rates_of.jacobian(robot.joints), {**at, **{k: repr(float(x)) for k, x in selected.items()}})",
            "q_dot = np.linalg.lstsq(Jq, v, rcond=None)[0]",
            _compare("q_dot", f"dict(zip({names!r}, q_dot))"),
        ]
    return _lines(lines[0], lines[1], lines[2], lines[3], lines[4], lines[5],
                  "robosolve = " + literal(want), *lines[6:])


# -- geometry -------------------------------------------------------------------------------------

def _pose_source(side, q) -> str:
    """One end of a displacement: a given matrix, or 0M of the frame at a configuration."""
    if "matrix" in side:
        return f"robot.matrix({literal(sp.Matrix(side['matrix']))})"
    config = {str(k): text(v) for k, v in side["config"].items()}
    return f"robot.pose({q.frame!r}).subs(robot.configuration({literal(config)}))"


def displacement(q, answer, problem):
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
        if "matrix" in o["from"] and "matrix" in o["to"] and problem.frames and o.get("frame"):
            return None                              # Q written in another frame: not rebuilt here
        head = [
            "# Q = M_to M_from^-1: every body point P2 = Q P1 (in frame 0)",
            f"at = {at_literal(q)}",
            f"M_from = {_pose_source(o['from'], q)}",
            f"M_to = {_pose_source(o['to'], q)}",
            "Q = robot.number(M_to * inverse_pose(M_from), at)",
        ]
    keys = ["Q", "u", "alpha", "h", "P", "pitch"] + (["L"] if "axis" in o else [])
    compared = [_compare(k, k if k != "L" else "screw_matrix(u, P, pitch)") for k in keys if k in answer.numeric]
    return _lines(
        *head,
        "u, alpha, h, P, pitch = helical_axis(Q)",
        robosolve_numbers(answer, keys),
        *compared,
    )


def orientation(q, answer, problem):
    if q.options.get("matrix") is not None:
        source = f"robot.matrix({literal(sp.Matrix(q.options['matrix']))})"
    else:
        source = f"robot.pose({q.frame!r})"
    n = answer.numeric
    want = {"zyz": (n.get("zyz") or {}).get("solutions"), "rpy": (n.get("rpy") or {}).get("solutions"),
            "axis": (n.get("axis_angle") or {}).get("axis"), "angle": (n.get("axis_angle") or {}).get("angle"),
            "quaternion": n.get("quaternion")}
    want = {k: v for k, v in want.items() if v is not None}
    calls = {"zyz": "euler_zyz(R)", "rpy": "euler_rpy(R)", "axis": "axis_angle(R)[1]", "angle": "axis_angle(R)[0]",
             "quaternion": "quaternion(R)"}
    return _lines(
        f"at = {at_literal(q)}",
        f"R = robot.number({source}, at)[:3, :3]",
        "# ZYZ: R = Rz(phi) Ry(theta) Rz(psi); RPY: R = Rz(yaw) Ry(pitch) Rx(roll)",
        "robosolve = " + literal(want),
        *[_compare(k, calls[k]) for k in want],
    )


def dof(q, answer, problem):
    o = q.options
    counts = [int(o.get(k, 0)) for k in ("bodies", "joints_1dof", "joints_2dof", "joints_3dof")]
    planar = o.get("space", "planar") == "planar"
    return _lines(
        f"dof = mobility({', '.join(map(str, counts))}, planar={planar!r})"
        f"   # {'Grübler (planar)' if planar else 'Kutzbach (spatial)'}",
        robosolve_numbers(answer, ["dof"]),
        _compare("dof", "dof") if "dof" in answer.numeric else None,
    )


# -- dynamics and motion ---------------------------------------------------------------------------

def equations_of_motion(q, answer, problem):
    actuators = [str(j.actuator) for j in problem.joints]
    return _lines(
        f"at = {at_literal(q)}",
        "# M, c, g and the external forces' Q at the configuration (numbers along the chain)",
        "mass, c, grav, Q = robot.dynamics_at(at)",
        "accelerations = robot.number(sp.Matrix(robot.accelerations), at).ravel()",
        "if len(robot.joints) <= 2:                # the formulas of a small arm, by Lagrange",
        "    show(*robot.lagrange(at)[:3])",
        robosolve_numbers(answer, ["mass_matrix", "velocity_terms", "gravity_terms", "actuators"]),
        *_guarded(answer, ("mass_matrix", _compare("mass_matrix", "mass")),
                  ("velocity_terms", _compare("velocity_terms", "c")),
                  ("gravity_terms", _compare("gravity_terms", "grav")),
                  ("actuators", "# the joint actions tau = M q'' + c + g - Q\n"
                   + _compare("actuators", f"dict(zip({actuators!r}, mass @ accelerations + c + grav - Q))"))),
    )


def _profile_question(problem, pid):
    profiles = [x for x in problem.questions if x.type == "motion_profile"]
    return next((x for x in profiles if x.id == pid), None) if pid else (profiles[0] if profiles else None)


def _profile_lines(pq, problem) -> list[str] | None:
    """`profile = Profile(...)` of a motion_profile question, or None when it is not numeric."""
    o = pq.options
    shape = o.get("shape", "bang-bang")
    names = [j.name for j in problem.joints]

    def values(key):
        m = o.get(key) or {}
        return [text(m.get(n, 0)) for n in names]

    vel = f", max_velocity=numbers({literal(values('max_velocity'))})" if shape == "trapezoidal" else ""
    return [f"at = {at_literal(pq)}",
            "numbers = lambda texts: [robot.number(robot.parse(x), at) for x in texts]",
            f"profile = Profile(numbers({literal(values('from'))}), numbers({literal(values('to'))}), "
            f"numbers({literal(values('max_acceleration'))}), shape={shape!r}{vel})"]


def motion_profile(q, answer, problem):
    names = [j.name for j in problem.joints]
    keys = ["durations", "T", "accelerations", "velocities"]
    return _lines(
        *_profile_lines(q, problem),
        "# each joint alone needs its own time; all end together at T, the largest",
        robosolve_numbers(answer, keys),
        *_guarded(answer, ("durations", _compare("durations", f"dict(zip({names!r}, profile.durations))")),
                  ("T", _compare("T", "profile.T")),
                  ("accelerations", _compare("accelerations", f"dict(zip({names!r}, profile.accelerations))")),
                  ("velocities", _compare("velocities", f"dict(zip({names!r}, profile.velocities))"))),
    )


def joint_torques(q, answer, problem):
    pq = _profile_question(problem, q.options.get("profile"))
    if pq is None or "actuators" not in answer.numeric:
        return None
    want = answer.numeric["actuators"]
    return _lines(
        "# the profile followed (its motion_profile question)",
        *_profile_lines(pq, problem),
        f"at = {at_literal(q)}",
        "# tau(t) = M(q) q'' + c(q, q') + g(q) - Q along the profile; the signed peak of each actuator",
        "peaks, t_peaks = torque_peaks(robot, profile, at)",
        "robosolve = " + literal({"peak": [v["peak"] for v in want.values()],
                                  "t_peak": [v["t_peak"] for v in want.values()]}),
        _compare("peak", "peaks"),
        _compare("t_peak", "t_peaks", rtol=1e-5),
    )


def p_control(q, answer, problem):
    o = q.options
    if "profile" not in o and o.get("trajectory") is not None:
        return None                                  # a work-space reference: not rebuilt here
    pq = _profile_question(problem, o.get("profile"))
    if pq is None or "max_error" not in answer.numeric:
        return None
    names = [j.name for j in problem.joints]

    def gains(key):
        return f"numbers({literal([text(o[key][n]) for n in names])})" if key in o else "None"

    duration = f"robot.number(robot.parse({text(o['duration'])!r}), at)" if "duration" in o else "None"
    return _lines(
        "# the reference followed (its motion_profile question)",
        *_profile_lines(pq, problem),
        f"at = {at_literal(q)}",
        f"law = {o.get('law', 'p')!r}",
        f"kp, kd, start = {gains('gains')}, {gains('gains_d')}, {gains('start')}",
        f"max_error, t_max_error, final_error, times, errors = simulate_control(robot, profile, law, kp, kd, "
        f"start, {duration}, at)",
        robosolve_numbers(answer, ["max_error", "t_max_error", "final_error"]),
        _compare("max_error", f"dict(zip({names!r}, max_error))", rtol=1e-4),
        f"compare('final_error', dict(zip({names!r}, final_error)), robosolve['final_error'], rtol=1e-3, atol=1e-7)",
        "plot_errors(times, errors, " + literal(names) + ", law)",
    )


def forward_dynamics(q, answer, problem):
    laws = {str(k): text(v) for k, v in (q.options.get("actuators") or {}).items()}
    actuators = {str(j.actuator) for j in problem.joints}
    if any(a not in actuators for a in laws):
        return None
    start = q.options.get("start") or {}
    names = [j.name for j in problem.joints]
    q0 = [text(start.get(n, 0)) for n in names]
    v0 = [text(start.get(f"{n}_dot", 0)) for n in names]
    keys = ["final", "final_velocity", "max", "min"]
    return _lines(
        f"at = {at_literal(q)}",
        "# M(q) q'' + c + g = tau + Q with the actuator laws, integrated by Dormand-Prince 5(4)",
        f"laws = {literal(laws)}",
        "numbers = lambda texts: [robot.number(robot.parse(x), at) for x in texts]",
        f"duration = robot.number(robot.parse({text(q.options['duration'])!r}), at)",
        f"times, qs, rates = forward_run(robot, laws, numbers({literal(q0)}), numbers({literal(v0)}), duration, at)",
        robosolve_numbers(answer, keys),
        "low, high = extremes(times, qs, rates)",
        *_guarded(answer, ("final", _compare("final", f"dict(zip({names!r}, qs[-1]))", rtol=1e-6)),
                  ("final_velocity", _compare("final_velocity", f"dict(zip({names!r}, rates[-1]))", rtol=1e-6)),
                  ("max", _compare("max", f"dict(zip({names!r}, high))", rtol=1e-6)),
                  ("min", _compare("min", f"dict(zip({names!r}, low))", rtol=1e-6))),
        "plot_joints(times, qs, " + literal(names) + ")",
    )


CELLS = {
    "position": position,
    "velocity_acceleration": velocity_acceleration,
    "jacobian": jacobian,
    "statics": statics,
    "ellipsoids": ellipsoids,
    "inverse_kinematics": inverse_kinematics,
    "motion_profile": motion_profile,
    "equations_of_motion": equations_of_motion,
    "joint_torques": joint_torques,
    "p_control": p_control,
    "forward_dynamics": forward_dynamics,
    "displacement": displacement,
    "orientation": orientation,
    "dof": dof,
}
