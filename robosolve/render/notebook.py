"""report.ipynb: the report as a Jupyter notebook that recomputes its answers with sympy.

* Markdown cells: report.md split at its `## ` sections (figures stay relative links to
  figures/, which sit beside the notebook).
* Code cells, importing only sympy, numpy and matplotlib (not robosolve, so the notebook
  runs anywhere): one "data" cell that rebuilds the problem — parameters, joints, each
  frame's pose from its elementary motions or DH row, points — so that a teacher can change
  a number and re-run; then, after each question's section, a cell that recomputes the main
  results from that data. Recomputed types: position, velocity_acceleration, jacobian,
  statics (a force, or the weight), ellipsoids, motion_profile (bang-bang), dof,
  equations_of_motion (Lagrange with T = 1/2 tr(dM J dM^T) from each body's pseudo-inertia,
  U from gravity, generalized external forces), inverse_kinematics (numpy Newton steps from a
  grid of starts, within the joint limits; point-coordinate targets), displacement (Q and its
  helical axis, or Q and L from a screw), orientation (ZYZ, RPY, axis-angle, quaternion) and
  forward_dynamics (fixed-step RK4 of the recomputed equations). Each prints "recomputed ..."
  beside robosolve's numbers. The other types (joint_torques, p_control, and option layouts a
  cell cannot rebuild) get a cell that shows robosolve's numbers from results.json (stdlib
  json) and says so.
* Cell ids are deterministic (`md-003`, `code-004`): the same problem gives the same bytes.
"""

from __future__ import annotations

import re

import sympy as sp

SETUP = '''\
import numpy as np
import sympy as sp

sp.init_printing()


def Rx(a):
    return sp.Matrix([[1, 0, 0, 0], [0, sp.cos(a), -sp.sin(a), 0], [0, sp.sin(a), sp.cos(a), 0], [0, 0, 0, 1]])


def Ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a), 0], [0, 1, 0, 0], [-sp.sin(a), 0, sp.cos(a), 0], [0, 0, 0, 1]])


def Rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0, 0], [sp.sin(a), sp.cos(a), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def Tx(d):
    return sp.Matrix([[1, 0, 0, d], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def Ty(d):
    return sp.Matrix([[1, 0, 0, 0], [0, 1, 0, d], [0, 0, 1, 0], [0, 0, 0, 1]])


def Tz(d):
    return sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, d], [0, 0, 0, 1]])


def dh(theta, d, a, alpha):
    """Standard Denavit-Hartenberg: Rz(theta) Tz(d) Tx(a) Rx(alpha)."""
    return Rz(theta) * Tz(d) * Tx(a) * Rx(alpha)


def mdh(alpha, a, theta, d):
    """Modified Denavit-Hartenberg: Rx(alpha) Tx(a) Rz(theta) Tz(d)."""
    return Rx(alpha) * Tx(a) * Rz(theta) * Tz(d)


def inverse_pose(M):
    """[R, t; 0, 1]^-1 = [R^T, -R^T t; 0, 1]."""
    R, p = M[:3, :3], M[:3, 3]
    return sp.Matrix(sp.BlockMatrix([[R.T, -R.T * p], [sp.zeros(1, 3), sp.ones(1, 1)]]))
'''

MODEL = '''\
def M0(frame):
    """Pose of `frame` in frame 0: the product of the poses along the chain."""
    out = sp.eye(4)
    while frame != "0":
        parent, M = frames[frame]
        out = M * out
        frame = parent
    return out


def point0(name):
    """Coordinates in frame 0 of a named point."""
    frame, at = points[name]
    return (M0(frame) * sp.Matrix([*at, 1]))[:3, :]


def values(at=None):
    """Parameters (with the question's overrides) and joint values, resolved to numbers."""
    given = dict(parameters)
    given.update(at or {})
    out = {}
    for _ in range(len(given) + 1):
        out = {s: sp.sympify(v).subs(out) for s, v in given.items()}
    return out


def number(expr, at=None):
    """A sympy object evaluated to floats at the data and `at`."""
    v = sp.N(sp.sympify(expr).subs(values(at)))
    return np.array(v.tolist(), dtype=float) if hasattr(v, "tolist") else float(v)


np.set_printoptions(precision=6, suppress=True)
'''

GEOMETRY = '''\
def skew(u):
    return np.array([[0, -u[2], u[1]], [u[2], 0, -u[0]], [-u[1], u[0], 0]])


def canonical(u):
    """Of +u and -u, the one whose first non-zero component is positive."""
    first = next(x for x in u if abs(x) > 1e-9)
    return u if first > 0 else -u


def axis_angle(R):
    """alpha in [0, pi] and the unit axis u (None for the identity); near pi from R's symmetric part."""
    v = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / 2
    alpha = np.arctan2(np.linalg.norm(v), (np.trace(R) - 1) / 2)
    if alpha < 1e-9:
        return 0.0, None
    if np.pi - alpha < 1e-6:
        w, V = np.linalg.eigh((R + R.T) / 2)
        return alpha, canonical(V[:, np.argmax(w)])
    return alpha, v / np.linalg.norm(v)


def helical_axis(Q):
    """u, alpha, h, P (nearest the origin) and the pitch of a displacement Q = [R, dT; 0, 1]."""
    R, dT = Q[:3, :3], Q[:3, 3]
    alpha, u = axis_angle(R)
    if u is None:                                  # pure translation (or the identity)
        h = np.linalg.norm(dT)
        return (dT / h if h > 1e-12 else None), 0.0, h, None, None
    h = u @ dT
    A = np.vstack([np.eye(3) - R, u])              # (I - R) P = dT - h u and P.u = 0
    P = np.linalg.lstsq(A, np.append(dT - h * u, 0), rcond=None)[0]
    return u, alpha, h, P, h / alpha


def wrap(a):
    """An angle in (-pi, pi]."""
    a = (a + np.pi) % (2 * np.pi) - np.pi
    return np.pi if abs(a + np.pi) < 1e-12 else a
'''

DYNAMICS = '''\
def lagrange(at=None):
    """M(q), c(q, q'), g(q) and the external forces' generalized forces Q, by Lagrange:
    T = 1/2 sum tr(dM J dM^T) over the bodies (J the pseudo-inertia, dM = d(0M_i)/dt),
    U = -sum m g.G, so that M q'' + c + g = tau + Q. Parameters are fixed from the data and
    `at`; joints and rates stay symbols."""
    moving = set(joints) | set(rates) | set(accelerations)
    fixed = {s: v for s, v in values(at).items() if s not in moving}
    n = len(joints)
    T, U = sp.Integer(0), sp.Integer(0)
    for name, (frame, J) in pseudo_inertia.items():
        M = M0(frame).subs(fixed)
        J = J.subs(fixed)
        dM = sp.zeros(4, 4)
        for q, r in zip(joints, rates):
            dM += M.diff(q) * r
        T += (dM * J * dM.T).trace() / 2
        mG = M * J[:, 3]                          # (m G, m) in frame 0
        U -= (gravity.subs(fixed).T * mG[:3, :])[0]
    mass = sp.Matrix(n, n, lambda i, j: sp.expand(T.diff(rates[i], rates[j])))
    grav = sp.Matrix([U.diff(q) for q in joints])
    momenta = sp.Matrix([T.diff(r) for r in rates])
    c = momenta.jacobian(joints) * sp.Matrix(rates) - sp.Matrix([T.diff(q) for q in joints])
    Q = sp.zeros(n, 1)
    for name, (frame, point, f, tau, in_frame) in forces.items():
        R = M0(in_frame).subs(fixed)[:3, :3]
        M = M0(frame).subs(fixed)
        if f is not None:
            P = (M * sp.Matrix([*point, 1]))[:3, :]
            Q += P.jacobian(joints).T * R * sp.Matrix(f)
        if tau is not None:                       # angular Jacobian from dM/dq_j M^-1
            inv = inverse_pose(M)
            Jw = sp.Matrix.hstack(*[sp.Matrix([(M.diff(q) * inv)[k] for k in ((2, 1), (0, 2), (1, 0))])
                                    for q in joints])
            Q += Jw.T * R * sp.Matrix(tau)
    return mass, c, grav, Q.subs(fixed)
'''


def _s(expr) -> str:
    """A sympy expression as Python source the notebook evaluates with S(...)."""
    return f'S("{_str(expr)}")'


def _str(expr) -> str:
    expr = sp.sympify(expr)
    rep = {s: sp.Symbol(s.name.replace(".", "_")) for s in expr.free_symbols if "." in s.name}
    return str(expr.xreplace(rep)) if rep else str(expr)


def _vec(v) -> str:
    return "[" + ", ".join(_s(x) for x in v) + "]"


def _data_cell(problem) -> str:
    names = [s.name for s in problem.parameters] + [j.name for j in problem.joints]
    names += [str(j.dot) for j in problem.joints] + [str(j.ddot) for j in problem.joints]
    lines = ["# The problem's data: change a value and re-run the notebook.",
             f'{", ".join(names)} = sp.symbols("{" ".join(names)}", real=True)' if len(names) > 1 else
             (f'{names[0]}, = sp.symbols("{names[0]}", real=True),' if names else ""),
             "NAMES = {s.name: s for s in [" + ", ".join(names) + "]}" if names else "NAMES = {}",
             "", "def S(text):", "    return sp.sympify(text, locals=NAMES)", ""]
    lines.append("parameters = {")
    for s, v in problem.parameters.items():
        lines.append(f"    {s.name}: {'None' if v is None else _s(v)},")
    lines.append("}")
    lines.append("parameters = {s: v for s, v in parameters.items() if v is not None}")
    lines.append("joints = [" + ", ".join(j.name for j in problem.joints) + "]")
    lines.append("rates = [" + ", ".join(str(j.dot) for j in problem.joints) + "]")
    lines.append("accelerations = [" + ", ".join(str(j.ddot) for j in problem.joints) + "]")
    lines.append("")
    lines.append("# frame: (parent, pose in the parent)")
    lines.append("frames = {")
    for f in problem.frames.values():
        if f.kind == "pose":
            pose = " * ".join(f"{op}({_s(arg)})" for op, arg in f.factors) or "sp.eye(4)"
        elif f.kind in ("dh", "mdh"):
            pose = f"{f.kind}(" + ", ".join(_s(x) for x in f.factors) + ")"
        else:
            pose = "sp.Matrix([" + ", ".join(_vec(list(f.matrix.row(i))) for i in range(4)) + "])"
        lines.append(f'    "{f.name}": ("{f.parent}", {pose}),')
    lines.append("}")
    if problem.bodies:
        lines.append("# body: (frame, mass, centre of mass in that frame)")
        lines.append("bodies = {")
        for b in problem.bodies:
            com = _centre_of_mass(b)
            if com is not None:
                lines.append(f'    "{b.name}": ("{b.frame}", {_s(b.mass)}, {_vec(com)}),')
        lines.append("}")
        lines.append(f"gravity = sp.Matrix({_vec(list(problem.gravity))})")
        lines.extend(_pseudo_inertia_lines(problem))
        lines.extend(_force_lines(problem))
    lines.append("# point: (frame, coordinates in that frame)")
    lines.append("points = {")
    for p in problem.points.values():
        lines.append(f'    "{p.name}": ("{p.frame}", {_vec(list(p.at))}),')
    lines.append("}")
    return "\n".join(lines)


def _pseudo_inertia_lines(problem) -> list[str]:
    """Each body's pseudo-inertia J in its own frame (the course's 4x4 matrix of moments)."""
    from robosolve.core import matrices as mx

    lines = ["# body: (frame, pseudo-inertia J in that frame)", "pseudo_inertia = {"]
    for b in problem.bodies:
        d = b.data
        if b.kind == "point":
            J = mx.pseudo_inertia_point(b.mass, d["at"])
        elif b.kind == "rod":
            J = mx.pseudo_inertia_rod(b.mass, d["from"], d["to"])
        elif b.kind == "com":
            J = mx.pseudo_inertia_from_com(b.mass, d["com"], d["inertia"])
        else:
            J = d["J"]
        J = sp.Matrix(J)
        rows = ", ".join(_vec(list(J.row(i))) for i in range(4))
        lines.append(f'    "{b.name}": ("{b.frame}", sp.Matrix([{rows}])),')
    lines.append("}")
    return lines


def _force_lines(problem) -> list[str]:
    """External forces: (frame, point in that frame, force, torque, frame of the components)."""
    lines = ["# force: (frame it acts on, point in that frame, force, torque, components' frame)",
             "forces = {"]
    for f in getattr(problem, "forces", None) or []:
        force = _vec(list(f.force)) if f.force is not None else "None"
        torque = _vec(list(f.torque)) if f.torque is not None else "None"
        lines.append(f'    "{f.name}": ("{f.frame}", {_vec(list(f.at))}, {force}, {torque}, "{f.in_frame}"),')
    lines.append("}")
    return lines


def _centre_of_mass(body):
    d = body.data
    if body.kind == "point":
        return list(d["at"])
    if body.kind == "rod":
        return [(a + b) / 2 for a, b in zip(d["from"], d["to"])]
    if body.kind == "com":
        return list(d["com"])
    return None                     # pseudo_inertia: not rebuilt here


def _point_names_cell(problem) -> str:
    """P.x, P.y, P.z of every point, usable in coordinates as P_x, P_y, P_z."""
    lines = []
    for p in problem.points:
        lines.append(f'{p}_x, {p}_y, {p}_z = point0("{p}")')
        lines.append(f'NAMES.update({{"{p}_x": {p}_x, "{p}_y": {p}_y, "{p}_z": {p}_z}})')
    return "\n".join(lines)


# The fixed parts of the code cells are written out as code (raw blocks: a backslash in them
# is the notebook's own), the parts that depend on the problem are f-strings in the _cell_*
# functions that join them.
def _code(text: str) -> str:
    """Code lines written as a raw triple-quoted block, without the newline after the opening
    quotes and the one before the closing quotes."""
    return text[1:-1]


def _at(question) -> str:
    return "{" + ", ".join(f"{s.name}: {_s(v)}" for s, v in question.at.items()) + "}"


def _coords(question) -> str:
    coords = question.options.get("coordinates")
    if coords:
        return _vec(coords)
    p = question.point
    return f"[{p}_x, {p}_y, {p}_z]"


def _expected(answer, keys) -> str:
    lines = ["# robosolve's numbers, for comparison (they hold for the data as given)"]
    for k in keys:
        if k in answer.numeric:
            lines.append(f"print('robosolve: {k} =', {answer.numeric[k]!r})")
    return "\n".join(lines)


_POSITION_CODE = _code(r'''
M = sp.simplify(M0(frame))
P = point0(point)
display(M, P)
print('M =', number(M, at), sep='\n')
print('position =', number(P, at).ravel())
''')


def _cell_position(q, answer, problem):
    return "\n".join([
        f'frame, point, at = "{q.frame}", "{q.point}", {_at(q)}',
        _POSITION_CODE,
        _expected(answer, ["M", "position"]),
    ])


_VELOCITY_CODE = _code(r'''
t = sp.Symbol('t')
of_t = {q: sp.Function(q.name)(t) for q in joints}
back = {}
for q, qd, qdd in zip(joints, rates, accelerations):
    back[of_t[q].diff(t, 2)] = qdd
    back[of_t[q].diff(t)] = qd
M = M0(frame).subs(values({k: v for k, v in at.items() if k not in joints + rates + accelerations}))
Mt = M.subs(of_t)
inv = inverse_pose(Mt)
W = (Mt.diff(t) * inv).subs(back).subs({v: k for k, v in of_t.items()})
H = (Mt.diff(t, 2) * inv).subs(back).subs({v: k for k, v in of_t.items()})
P = sp.Matrix([*point0(point), 1])
print('W =', number(W, at), 'H =', number(H, at), sep='\n')
print('velocity =', number(W * P, at).ravel()[:3])
print('acceleration =', number(H * P, at).ravel()[:3])
''')


def _cell_velocity(q, answer, problem):
    return "\n".join([
        f'frame, point, at = "{q.frame}", "{q.point}", {_at(q)}',
        _VELOCITY_CODE,
        _expected(answer, ["W", "H", "velocity", "acceleration"]),
    ])


def _jacobian_lines(q):
    return [f"at = {_at(q)}",
            f"coordinates = sp.Matrix({_coords(q)})",
            "J = coordinates.jacobian(joints)",
            "Jn = number(J, at)"]


_JACOBIAN_CODE = _code(r'''
display(sp.simplify(J))
print('J =', Jn, sep='\n')
if J.rows == J.cols:
    print('det J =', np.linalg.det(Jn))
else:
    print('manipulability =', np.prod(np.linalg.svd(Jn, compute_uv=False)))
''')


def _cell_jacobian(q, answer, problem):
    if q.options.get("geometric"):
        return None
    return "\n".join(_jacobian_lines(q) + [
        _JACOBIAN_CODE,
        _expected(answer, ["J", "det", "manipulability"]),
    ])


_WEIGHT_CODE = _code(r'''
# the bodies' own weight: Fq = -sum_i J_Gi^T m_i g (J_Gi the Jacobian of the centre of mass)
Fq = sp.zeros(len(joints), 1)
for name, (frame, mass, com) in bodies.items():
    G0 = (M0(frame) * sp.Matrix([*com, 1]))[:3, :]
    Fq -= G0.jacobian(joints).T * mass * gravity
display(sp.simplify(Fq))
print('Fq =', number(Fq, at).ravel())
''')


def _cell_weight(q, answer, problem):
    if not problem.bodies or any(_centre_of_mass(b) is None for b in problem.bodies):
        return None
    return "\n".join([
        f"at = {_at(q)}",
        _WEIGHT_CODE,
        _expected(answer, ["Fq"]),
    ])


def _cell_statics(q, answer, problem):
    force = q.options.get("force")
    if q.options.get("weight") and force is None and q.options.get("torque") is None:
        return _cell_weight(q, answer, problem)
    if force is None or q.options.get("torque") is not None or q.options.get("weight"):
        return None
    return "\n".join(_jacobian_lines(q) + [
        f"F = np.array({[float(sp.N(x)) for x in force]!r})",
        "Fq = -Jn.T @ F          # what the joints exert to balance F",
        "print('Fq =', Fq)",
        _expected(answer, ["Fq"]),
    ])


_ELLIPSOIDS_CODE = _code(r'''
with np.errstate(divide='ignore'):
    force_lengths = Kf / np.sqrt(nu)       # infinite where nu = 0 (singular)
velocity_lengths = Kv * np.sqrt(nu)
print('A =', A, 'eigenvalues =', nu, sep='\n')
print('force semi-axes:', np.sort(force_lengths)[::-1])
print('velocity semi-axes:', np.sort(velocity_lengths)[::-1])
print('condition number:', nu.max() / nu.min() if nu.min() > 0 else float('inf'))
''')


def _cell_ellipsoids(q, answer, problem):
    budgets = q.options.get("budgets") or {}
    kf, kv, ka = (float(sp.N(budgets.get(k, 1))) for k in ("force", "velocity", "compliance"))
    kq = q.options.get("joint_compliance")
    lines = _jacobian_lines(q) + [
        "A = Jn @ Jn.T",
        "nu, vectors = np.linalg.eigh(A)          # unit eigenvectors in the columns",
        f"Kf, Kv, Ka = {kf!r}, {kv!r}, {ka!r}",
        _ELLIPSOIDS_CODE,
    ]
    if kq:
        lines += [f"Kq = np.diag({[float(sp.N(x)) for x in kq]!r})",
                  "kappa = np.linalg.eigvalsh(Jn @ Kq @ Jn.T)",
                  "print('compliance semi-axes:', np.sort(Ka * kappa)[::-1])"]
    lines.append(_expected(answer, ["condition_number"]))
    return "\n".join(lines)


_MOTION_PROFILE_CODE = _code(r'''
durations = {n: float(sp.sqrt(4 * abs(end[n] - start[n]) / max_acceleration[n])) for n in max_acceleration}
T = max(durations.values())
rescaled_accelerations = {n: float(4 * abs(end[n] - start[n]) / T**2) for n in end}
print('durations:', durations)
print('T =', T)
print('rescaled accelerations:', rescaled_accelerations)
''')


def _cell_motion_profile(q, answer, problem):
    if q.options.get("shape", "bang-bang") != "bang-bang":
        return None
    start, end, acc = (q.options.get(k) or {} for k in ("from", "to", "max_acceleration"))
    names = [j.name for j in problem.joints if j.name in end]
    return "\n".join([
        "# bang-bang: each joint alone needs T_i = sqrt(4|D_i|/a_i); all end together at T = max T_i",
        f"start = {{{', '.join(f'{n!r}: {_s(start.get(n, 0))}' for n in names)}}}",
        f"end = {{{', '.join(f'{n!r}: {_s(end[n])}' for n in names)}}}",
        f"max_acceleration = {{{', '.join(f'{n!r}: {_s(acc[n])}' for n in names if n in acc)}}}",
        _MOTION_PROFILE_CODE,
        _expected(answer, ["durations", "T", "accelerations"]),
    ])


def _cell_dof(q, answer, problem):
    o = q.options
    m, c1, c2, c3 = (int(o.get(k, 0)) for k in ("bodies", "joints_1dof", "joints_2dof", "joints_3dof"))
    planar = o.get("space", "planar") == "planar"
    formula = (f"3 * ({m} - 1) - 2 * {c1} - {c2}" if planar
               else f"6 * ({m} - 1) - 5 * {c1} - 4 * {c2} - 3 * {c3}")
    return f"dof = {formula}   # {'Grübler (planar)' if planar else 'Kutzbach (spatial)'}\nprint('dof =', dof)"


_EQUATIONS_OF_MOTION_CODE = _code(r'''
mass, c, grav, Q = lagrange(at)
if len(joints) <= 3:
    display(sp.simplify(mass), sp.simplify(grav))
tau = mass * sp.Matrix(accelerations) + c + grav - Q   # what the joints exert
print('recomputed M =', number(mass, at), sep='\n')
print('recomputed c =', number(c, at).ravel())
print('recomputed g =', number(grav, at).ravel())
print('recomputed Q (external forces) =', number(Q, at).ravel())
''')


def _cell_equations_of_motion(q, answer, problem):
    names = [j.name for j in problem.joints]
    return "\n".join([
        f"at = {_at(q)}",
        _EQUATIONS_OF_MOTION_CODE,
        f"print('recomputed joint actions tau = M q\\'\\' + c + g - Q:', dict(zip({names!r}, number(tau, at).ravel().tolist())))",
        _expected(answer, ["mass_matrix", "velocity_terms", "gravity_terms", "actuators"]),
    ])


def _matrix(m) -> str:
    m = sp.Matrix(m)
    return "sp.Matrix([" + ", ".join(_vec(list(m.row(i))) for i in range(m.rows)) + "])"


def _pose_source(side, q) -> str:
    """One end of a displacement: a given matrix, or 0M of the frame at a configuration."""
    if "matrix" in side:
        return _matrix(side["matrix"])
    config = "{" + ", ".join(f"NAMES[{k!r}]: {_s(v)}" for k, v in side["config"].items()) + "}"
    return f'M0("{q.frame}").subs({config})'


_SCREW_Q_CODE = _code(r'''
u0 = axis / np.linalg.norm(axis)
K = skew(u0)
R = np.eye(3) + K * np.sin(alpha_given) + K @ K * (1 - np.cos(alpha_given))
Q = np.eye(4)
Q[:3, :3], Q[:3, 3] = R, (np.eye(3) - R) @ through + h_given * u0
''')


_SCREW_L_CODE = _code(r'''
L = np.zeros((4, 4))
if P is None:                              # pure translation: Q = exp(h L)
    L[:3, 3] = np.zeros(3) if u is None else u
else:
    L[:3, :3], L[:3, 3] = skew(u), np.cross(P, u) + pitch * u
print('recomputed L =', np.round(L, 12) + 0.0, sep='\n')
''')


def _cell_displacement(q, answer, problem):
    o = q.options
    if "axis" in o:
        lines = [
            "# from a screw: Q = [R, (I - R) P + h u; 0, 1], R = I + [u] sin(alpha) + [u]^2 (1 - cos(alpha))",
            f"axis = np.array({[float(sp.N(x)) for x in o['axis']]!r})",
            f"alpha_given = {float(sp.N(o['angle']))!r}",
            f"through = np.array({[float(sp.N(x)) for x in o.get('through') or [0, 0, 0]]!r})",
            f"h_given = {float(sp.N(o.get('translation') or 0))!r}",
            _SCREW_Q_CODE,
        ]
    else:
        if "matrix" in o["from"] and "matrix" in o["to"] and problem.frames and q.options.get("frame"):
            return None                              # Q written in another frame: not rebuilt here
        lines = [
            "# Q = M_to * M_from^-1: every body point P2 = Q P1 (in frame 0)",
            f"M_from = {_pose_source(o['from'], q)}",
            f"M_to = {_pose_source(o['to'], q)}",
            f"at = {_at(q)}",
            "Q = number(M_to * inverse_pose(M_from), at)",
        ]
    lines += [
        "Q = np.round(Q, 12) + 0.0                  # no -0.0 in the print",
        "u, alpha, h, P, pitch = helical_axis(Q)",
        "print('recomputed Q =', Q, sep='\\n')",
    ]
    if "axis" in o:                                  # L from the normalised u, P*, pitch
        lines += [
            _SCREW_L_CODE,
        ]
    lines += [
        "print('recomputed u =', u, ' alpha =', alpha, ' h =', h, ' P =', P, ' pitch =', pitch)",
        _expected(answer, ["Q", "L", "u", "alpha", "h", "P", "pitch"]),
    ]
    return "\n".join(lines)


_ORIENTATION_CODE = _code(r'''
# ZYZ: R = Rz(phi) Ry(theta) Rz(psi); RPY: R = Rz(yaw) Ry(pitch) Rx(roll)
theta = np.arctan2(np.hypot(R[0, 2], R[1, 2]), R[2, 2])
if abs(np.sin(theta)) > 1e-9:
    phi, psi = np.arctan2(R[1, 2], R[0, 2]), np.arctan2(R[2, 1], -R[2, 0])
    zyz = [[wrap(phi), theta, wrap(psi)], [wrap(phi + np.pi), -theta, wrap(psi + np.pi)]]
else:                                    # only phi +- psi is fixed: psi = 0
    zyz = [[wrap(np.arctan2(R[1, 0], R[0, 0]) if R[2, 2] > 0 else np.arctan2(-R[1, 0], -R[0, 0])), theta, 0.0]]
pitch = np.arctan2(-R[2, 0], np.hypot(R[0, 0], R[1, 0]))
if abs(np.cos(pitch)) > 1e-9:
    roll, yaw = np.arctan2(R[2, 1], R[2, 2]), np.arctan2(R[1, 0], R[0, 0])
    rpy = [[roll, pitch, yaw], [wrap(roll + np.pi), wrap(np.pi - pitch), wrap(yaw + np.pi)]]
else:                                    # only roll -+ yaw is fixed: yaw = 0
    rpy = [[np.arctan2(R[0, 1], R[1, 1]) * np.sign(pitch), pitch, 0.0]]
alpha, u = axis_angle(R)
quaternion = [np.cos(alpha / 2)] + ([0.0] * 3 if u is None else list(np.sin(alpha / 2) * u))
print('recomputed zyz =', np.round(zyz, 12).tolist())
print('recomputed rpy =', np.round(rpy, 12).tolist())
print('recomputed axis-angle =', u, alpha)
print('recomputed quaternion =', np.round(quaternion, 12).tolist())
''')


def _cell_orientation(q, answer, problem):
    if q.options.get("matrix") is not None:
        source = _matrix(q.options["matrix"])
    else:
        source = f'M0("{q.frame}")'
    return "\n".join([
        f"at = {_at(q)}",
        f"R = number({source}, at)[:3, :3]",
        _ORIENTATION_CODE,
        _expected(answer, ["zyz", "rpy", "axis_angle", "quaternion"]),
    ])


_INVERSE_KINEMATICS_CODE = _code(r'''
per_joint = max(2, int(round(200 ** (1 / len(joints)))))
grid = np.meshgrid(*[np.linspace(lo, hi, per_joint + 2)[1:-1] for lo, hi in limits])
solutions = []
for start in np.stack([g.ravel() for g in grid], axis=1):
    x = start.astype(float)
    for _ in range(60):
        r = np.asarray(f(x), dtype=float).ravel()
        if np.linalg.norm(r) < 1e-12:
            break
        x = x - np.linalg.lstsq(np.asarray(jac(x), dtype=float), r, rcond=None)[0]
    x = np.where(revolute, (x + np.pi) % (2 * np.pi) - np.pi, x)
    ok = np.linalg.norm(np.asarray(f(x), dtype=float)) < 1e-9
    inside = np.all((x >= limits[:, 0] - 1e-9) & (x <= limits[:, 1] + 1e-9))
    if ok and inside and not any(np.allclose(x, s, atol=1e-6) for s in solutions):
        solutions.append(x)
solutions.sort(key=lambda s: tuple(np.round(s, 9)))
''')


def _cell_inverse_kinematics(q, answer, problem):
    target = q.options.get("target") or []
    if not isinstance(target, list) or not target or any(not re.fullmatch(r"\w+\.[xyz]", str(name)) or str(name).split(".")[0]
                         not in problem.points for name, _, _ in target):
        return None                                  # orientation targets: not rebuilt here
    limits = []
    for j in problem.joints:
        lo, hi = j.limits if j.limits else ((-sp.pi, sp.pi) if j.kind == "revolute" else (-1, 1))
        limits.append((float(sp.N(lo)), float(sp.N(hi))))
    revolute = [j.kind == "revolute" for j in problem.joints]
    residual = ", ".join(f"{str(name).replace('.', '_')} - {float(sp.N(v))!r}" for name, _, v in target)
    return "\n".join([
        f"at = {_at(q)}",
        "# Newton iterations (least-squares steps) from a grid of starts, kept within the joint limits",
        f"residual = sp.Matrix([{residual}]).subs(values({{k: v for k, v in at.items() if k not in joints}}))",
        "f = sp.lambdify([joints], residual, 'numpy')",
        "jac = sp.lambdify([joints], residual.jacobian(joints), 'numpy')",
        f"limits = np.array({limits!r})",
        f"revolute = np.array({revolute!r})",
        _INVERSE_KINEMATICS_CODE,
        f"names = {[j.name for j in problem.joints]!r}",
        "for s in solutions:",
        "    print('recomputed solution:', dict(zip(names, np.round(s, 12).tolist())))",
        _expected(answer, ["solutions"]),
    ])


_FORWARD_DYNAMICS_EQUATIONS_CODE = _code(r'''
# M(q) q'' + c + g = tau + Q, integrated by fixed-step RK4 (step 1 ms)
mass, c, grav, Q = lagrange(at)
t = sp.Symbol('t')
fixed = {s: v for s, v in values(at).items() if s not in joints + rates}
''')


_FORWARD_DYNAMICS_DERIVATIVE_CODE = _code(r'''
mass_f = sp.lambdify([t, joints, rates], mass, 'numpy')
rest_f = sp.lambdify([t, joints, rates], tau + Q - c - grav, 'numpy')

def derivative(time, state):
    n = len(joints)
    x, v = state[:n], state[n:]
    a = np.linalg.solve(np.asarray(mass_f(time, x, v), dtype=float),
                        np.asarray(rest_f(time, x, v), dtype=float).ravel())
    return np.concatenate([v, a])

''')


_FORWARD_DYNAMICS_RK4_CODE = _code(r'''
dt = duration / steps
track = [state]
for k in range(steps):
    time = k * dt
    k1 = derivative(time, state)
    k2 = derivative(time + dt / 2, state + dt / 2 * k1)
    k3 = derivative(time + dt / 2, state + dt / 2 * k2)
    k4 = derivative(time + dt, state + dt * k3)
    state = state + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    track.append(state)
track = np.array(track)
n = len(joints)
''')


_FORWARD_DYNAMICS_PRINT_CODE = _code(r'''
print('recomputed final =', dict(zip(names, np.round(track[-1, :n], 8).tolist())))
print('recomputed final_velocity =', dict(zip(names, np.round(track[-1, n:], 8).tolist())))
print('recomputed max (samples) =', dict(zip(names, np.round(track[:, :n].max(axis=0), 8).tolist())))
print('recomputed min (samples) =', dict(zip(names, np.round(track[:, :n].min(axis=0), 8).tolist())))
''')


def _cell_forward_dynamics(q, answer, problem):
    laws = q.options.get("actuators") or {}
    by_actuator = {str(j.actuator): j for j in problem.joints}
    if any(str(a) not in by_actuator for a in laws):
        return None
    start = q.options.get("start") or {}
    tau = ", ".join(_s(laws.get(str(j.actuator), 0)) for j in problem.joints)
    q0 = [_s(start.get(j.name, 0)) for j in problem.joints]
    v0 = [_s(start.get(f"{j.name}_dot", 0)) for j in problem.joints]
    duration = float(sp.N(q.options["duration"]))
    names = [j.name for j in problem.joints]
    return "\n".join([
        f"at = {_at(q)}",
        _FORWARD_DYNAMICS_EQUATIONS_CODE,
        f"tau = sp.Matrix([{tau}]).subs(fixed)",
        _FORWARD_DYNAMICS_DERIVATIVE_CODE,
        f"duration, steps = {duration!r}, {max(1000, int(round(duration * 1000)))}",
        f"state = np.array([float(number(x, at)) for x in [{', '.join(q0 + v0)}]])",
        _FORWARD_DYNAMICS_RK4_CODE,
        f"names = {names!r}",
        _FORWARD_DYNAMICS_PRINT_CODE,
        _expected(answer, ["final", "final_velocity", "max", "min"]),
    ])


RECOMPUTE = {
    "forward_dynamics": _cell_forward_dynamics,
    "inverse_kinematics": _cell_inverse_kinematics,
    "displacement": _cell_displacement,
    "orientation": _cell_orientation,
    "equations_of_motion": _cell_equations_of_motion,
    "position": _cell_position,
    "velocity_acceleration": _cell_velocity,
    "jacobian": _cell_jacobian,
    "statics": _cell_statics,
    "ellipsoids": _cell_ellipsoids,
    "motion_profile": _cell_motion_profile,
    "dof": _cell_dof,
}


def _fallback(answer) -> str:
    return "\n".join([
        f"# This notebook does not recompute `{answer.type}` answers; robosolve's numbers:",
        "import json",
        "with open('results.json', encoding='utf-8') as f:",
        f"    print(json.dumps(json.load(f)['answers'][{answer.id!r}].get('numeric', {{}}), indent=1)[:3000])",
    ])


def _sections(markdown: str) -> list[str]:
    """report.md split before each `## ` heading."""
    parts = re.split(r"(?m)^(?=## )", markdown)
    return [p.strip() for p in parts if p.strip()]


def _add_setup(add, problem, report) -> None:
    add("code", SETUP)
    add("code", _data_cell(problem))
    points = "\n" + _point_names_cell(problem) if problem.points and problem.frames else ""
    add("code", MODEL + points)
    if any(q.type in ("displacement", "orientation") for q in problem.questions):
        add("code", GEOMETRY)
    if problem.bodies:
        add("code", DYNAMICS)


def build_notebook(report, markdown: str):
    import nbformat
    from nbformat import v4

    problem = report.problem
    cells, counter = [], [0]

    def add(kind: str, source: str):
        counter[0] += 1
        cell = v4.new_markdown_cell(source) if kind == "md" else v4.new_code_cell(source)
        cell["id"] = f"{kind}-{counter[0]:03d}"
        cells.append(cell)

    sections = _sections(markdown)
    answers = {a.id: a for a in report.answers}
    questions = {q.id: q for q in problem.questions}
    intro_done = False
    for section in sections:
        heading = re.match(r"## \d+\. .* — `([^`]+)`", section)
        if heading is None and not intro_done and not section.startswith("## Notes"):
            add("md", section)                      # title, description, data
            continue
        if not intro_done:
            _add_setup(add, problem, report)
            intro_done = True
        add("md", section)
        if heading is not None and heading.group(1) in answers:
            answer, q = answers[heading.group(1)], questions.get(heading.group(1))
            make = RECOMPUTE.get(answer.type)
            code = None
            if answer.error is None and q is not None and make is not None:
                try:
                    code = make(q, answer, problem)
                except Exception:  # noqa: BLE001 - an option layout the cell cannot rebuild:
                    code = None    # the cell shows robosolve's numbers instead (the tests check
                    #                that every bundled question gets its recomputing cell)
            add("code", code if code is not None else _fallback(answer))
    if not intro_done:
        _add_setup(add, problem, report)
    nb = v4.new_notebook(cells=cells, metadata={
        "kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"},
        "language_info": {"name": "python"},
        "robosolve": {"problem": problem.name}})
    nb.nbformat, nb.nbformat_minor = 4, 5
    nbformat.validate(nb)
    return nb


def render_notebook_file(report, markdown: str, figure_paths, files) -> str:
    """The `ipynb` format (robosolve.render.formats)."""
    import nbformat

    return nbformat.writes(build_notebook(report, markdown)) + "\n"
