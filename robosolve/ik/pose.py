"""Inverse kinematics of a pose: every configuration putting a frame at a given ⁰M.

`solve_pose` takes the chain from frame 0 to the target frame as its local 4x4 matrices
(plain sympy, every parameter already a number, only joint symbols left), the joints and the
target rotation R and position p of the frame. The course's way first:

- **kinematic decoupling** when the last three joints form a spherical wrist (their axes meet
  at one point, the wrist centre, fixed in the target frame at ``c``): the wrist centre
  ``w = p + R·c`` depends on the first three joints only, which `solve_ik` finds (closed form
  when the elimination works); then ³R₆ = (⁰R₃)ᵀ·R gives the wrist's three angles (ZYZ-like,
  two branches, a continuum at the wrist singularity where one representative is kept);
- otherwise every solution of the 12 pose equations (counted as 6) by the deterministic
  multi-start search of `robosolve.ik.numeric`.

Every solution is polished by Newton on the 12 equations and kept only when the forward
kinematics reproduce the target to 1e-9. The result has the solutions inside the limits
(sorted, angles wrapped into (−π, π]), the rejected ones, the selection, the closed form in the
target's symbols r11…r33, px, py, pz, the derivation steps, and for an unreachable pose the reason.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from robosolve.core.numpy_code import numpy_modules
from robosolve.core.prose import Num, Text
from robosolve.ik.engine import IKJoint, in_limits, solve_ik
from robosolve.core.angles import wrap_angle
from robosolve.ik.numeric import DEDUPE_TOL, sort_solutions
from robosolve.core.opcount import count_ops
from robosolve.core.printing import latex

FK_TOL = 1e-9
R_SYMS = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"r{i + 1}{j + 1}"))
P_SYMS = sp.Matrix(sp.symbols("px py pz"))
W_SYMS = sp.symbols("w_x w_y w_z")
B_SYMS = sp.symbols("b_11 b_21 b_x b_y")       # ¹M₄'s entries in the planar 3R of the UR family
BETA = sp.Symbol("beta")                        # its angle about z, atan2(b_21, b_11)


@dataclass
class PoseStep:
    title: str
    text: object
    equations: list = field(default_factory=list)


@dataclass
class PoseResult:
    status: str = "ok"                      # ok | unreachable
    method: str = "numeric"                 # decoupling | numeric
    solutions: list[dict] = field(default_factory=list)
    all_solutions: list[dict] = field(default_factory=list)
    rejected: list[tuple[dict, list]] = field(default_factory=list)
    wrist_singular: list[bool] = field(default_factory=list)   # per entry of all_solutions
    selected: dict | None = None
    selected_index: int | None = None
    closed_form: list[dict] | None = None   # joint name -> expression in r11..r33, px, py, pz
    steps: list[PoseStep] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    reason: str | Text | None = None   # prose: numbers as Num, formatted by the renderer
    reason_tex: str | Text | None = None   # the same with its formulas in $...$ (report); None: as reason
    wrist_centre: list[float] | None = None
    centre_in_frame: list[float] | None = None
    joints: list = field(default_factory=list)
    nearest: dict | None = None             # (the figure's interface: no nearest configuration here)


@dataclass
class _Chain:
    factors: list
    joints: list
    q: list

    def product(self, lo, hi):
        m = sp.eye(4)
        for f in self.factors[lo:hi]:
            m = m * f
        return m

    def joints_of(self, lo, hi):
        s = set()
        for f in self.factors[lo:hi]:
            s |= f.free_symbols
        return s & set(self.q)


# ---------------------------------------------------------------------------
# forward kinematics and Newton on the 12 equations

class _FK:
    """The forward kinematics ⁰M(q) and the Jacobian of its 12 entries, numerically, as the
    product of the chain's local matrices (each lambdified with its own derivatives: no
    symbolic product of the whole chain and no symbolic differentiation of it)."""

    def __init__(self, chain: _Chain):
        self.n = len(chain.q)
        self.parts = []
        for F in chain.factors:
            moved = [i for i, qi in enumerate(chain.q) if qi in F.free_symbols]
            value = sp.lambdify(chain.q, F, modules=numpy_modules())
            derivatives = [(i, sp.lambdify(chain.q, F.diff(chain.q[i]), modules=numpy_modules())) for i in moved]
            self.parts.append((value, derivatives))

    def _product(self, mats):
        m = np.eye(4)
        for a in mats:
            m = m @ a
        return m

    def _local(self, q):
        return [np.array(value(*q), dtype=float) for value, _ in self.parts]

    def residual(self, q, target):
        return self._product(self._local(q))[:3, :].reshape(12) - target

    def jac(self, *q):
        """The 12 x n Jacobian, row-major entries of ⁰M's first three rows."""
        mats = self._local(q)
        before = [np.eye(4)]
        for a in mats:
            before.append(before[-1] @ a)
        after = [np.eye(4)]
        for a in reversed(mats):
            after.append(a @ after[-1])
        after.reverse()
        J = np.zeros((12, self.n))
        for k, (_, derivatives) in enumerate(self.parts):
            for i, d in derivatives:
                J[:, i] += (before[k] @ np.array(d(*q), dtype=float) @ after[k + 1])[:3, :].reshape(12)
        return J

    def polish(self, q, target, iters=30):
        q = np.array(q, dtype=float)
        best, best_q = np.inf, q.copy()
        for _ in range(iters):
            r = self.residual(q, target)
            nr = float(np.max(np.abs(r)))
            if nr < best:
                best, best_q = nr, q.copy()
            if nr < 1e-15:
                break
            J = np.array(self.jac(*q), dtype=float).reshape(12, self.n)
            step = np.linalg.lstsq(J, -r, rcond=1e-13)[0]
            if not np.all(np.isfinite(step)) or np.max(np.abs(step)) < 1e-17:
                break
            q = q + step
        return best_q, best


# ---------------------------------------------------------------------------
# the spherical wrist

def find_wrist(chain: _Chain):
    """(split, c_t, c_s): the first three joints in factors[:split], the last three after it,
    and a point c_t of the target frame (c_s in frame `split`) that they do not move; or None."""
    q = chain.q
    # the wrist's three joints revolute; the arm's may be prismatic (the Stanford arm)
    if len(q) != 6 or not all(j.revolute for j in chain.joints[3:]):
        return None
    split = next((s for s in range(1, len(chain.factors))
                  if chain.joints_of(0, s) == set(q[:3]) and chain.joints_of(s, len(chain.factors)) == set(q[3:])),
                 None)
    if split is None:
        return None
    tail = chain.product(split, len(chain.factors))
    f = sp.lambdify(q[3:], [tail[i, j] for i in range(3) for j in range(4)], modules=numpy_modules())
    rows, rhs = [], []
    for k, qs in enumerate(((0.3, 1.1, -0.7), (-1.2, 0.4, 2.0), (2.2, -1.9, 0.6), (0.9, 2.7, -2.4))):
        m = np.array(f(*qs), dtype=float).reshape(3, 4)
        rows.append(np.hstack([m[:, :3], -np.eye(3)]))
        rhs.append(-m[:, 3])
    A, b = np.vstack(rows), np.concatenate(rhs)
    if np.linalg.matrix_rank(A, tol=1e-9) < 6:
        return None
    x = np.linalg.lstsq(A, b, rcond=None)[0]
    if np.max(np.abs(A @ x - b)) > 1e-10:
        return None
    x = [0.0 if abs(v) < 1e-12 else float(f"{v:.12g}") for v in x]
    return split, x[:3], x[3:]


def _exact(v: float):
    return sp.Integer(int(round(v))) if abs(v - round(v)) < 1e-15 else sp.Float(v, 15)


def _wrist_centre_symbols(c_t):
    """w = p + R·c in the target's symbols."""
    c = sp.Matrix([_exact(v) for v in c_t])
    return list(P_SYMS + R_SYMS * c)


def _chop(m):
    """cos(pi/2) = 6e-17 from a float twist, 1.0 for 1: the structure shows again."""
    reps = {}
    for f in m.atoms(sp.Float):
        r = round(float(f))
        if abs(float(f) - r) < 1e-12:
            reps[f] = sp.Integer(r)
    return m.xreplace(reps).applyfunc(sp.expand) if reps else m


# ---------------------------------------------------------------------------
# the solver

def solve_pose(factors, joints: list[IKJoint], R, p, select="limits", latex_names=None, tex=None,
               time_limit_s: float | None = 20.0, derive: bool = True) -> PoseResult:
    """Every configuration of `joints` with the chain's last frame at (R, p). See the module docstring.
    `derive=False`: the same solutions without the closed form (no symbolic derivation: a variant's
    `reachable` condition asks this for every draw)."""
    chain = _Chain([_chop(sp.Matrix(f)) for f in factors], list(joints), [j.symbol for j in joints])
    R, p = np.asarray(R, dtype=float), np.asarray(p, dtype=float)
    target = np.hstack([R, p[:, None]]).reshape(12)
    fk = _FK(chain)
    res = PoseResult()
    names = latex_names or {j.symbol: latex(j.symbol) for j in joints}
    wrist = find_wrist(chain)
    raw, par = None, None
    if wrist is not None:
        raw = _decoupled(res, chain, wrist, R, p, names, tex, time_limit_s, derive)
    elif (par := find_parallel(chain)) is not None:
        raw = _three_parallel(res, chain, par, R, p, names, tex, time_limit_s, derive)
    if raw is None:
        raw = _numeric(res, chain, R, p, wrist is None and par is None)
    _verify(res, fk, raw, target, chain)
    _finish(res, select)
    return res


def _decoupled(res, chain, wrist, R, p, names, tex, time_limit_s, derive=True):
    """Arm from the wrist centre, wrist from ³R₆; raw solutions (lists), or None to fall back."""
    split, c_t, c_s = wrist
    w = p + R @ np.array(c_t)
    res.method, res.wrist_centre, res.centre_in_frame = "decoupling", [float(v) for v in w], list(c_t)
    head = chain.product(0, split)
    W = list(head * sp.Matrix([*c_s, 1]))[:3]
    # a prismatic arm joint keeps its limits: they set the box of the numeric search
    arm_joints = [IKJoint(j.symbol, j.revolute, None if j.revolute else j.limits) for j in chain.joints[:3]]
    arm = solve_ik([(sp.expand(W[k]), W_SYMS[k]) for k in range(3)], arm_joints,
                   dict(zip(W_SYMS, map(float, w))), closed_form=derive, time_limit_s=time_limit_s,
                   target_symbols=W_SYMS, latex_names=names, tex=tex)
    wc = _wrist_centre_symbols(c_t)
    res.steps.append(_centre_step(c_t, wc, w, split, names, chain))
    if arm.status == "unreachable":
        res.status = "unreachable"
        # (Text + Text: a reason's numbers stay numbers for the renderer, never a repr)
        lead = ("the wrist centre is reached only with the arm's joints outside their limits: "
                if arm.rejected else "the wrist centre is beyond the reach of the arm: ")
        res.reason = lead + Text(arm.reason or "")
        res.reason_tex = lead + Text(arm.reason_tex or arm.reason or "")
        return []
    arm_sols, shoulder = arm.all_solutions, False
    if arm.status == "family":
        arm_sols = _arm_representatives(arm, arm_joints, W, w)
        if arm_sols:
            shoulder = True
            free = arm.family["free"][0]
            res.notes.append(f"shoulder singularity: the wrist centre lies on the axis of {free}, which then "
                             "does not move it; the pose is reached along a continuum, and the representatives "
                             f"with {free} = 0 are given (the wrist takes up the rotation)")
    if arm.status != "ok" and not shoulder:
        res.notes.append("the first three joints do not have isolated solutions for this wrist centre: "
                         "searched numerically on the 12 pose equations")
        return None
    arm_cf = _arm_closed_form(res, arm, wc, names) if not shoulder else None
    R3 = head[:3, :3]
    tail, Rc = _wrist_and_tool(chain, split)
    wrist_joints = [IKJoint(j.symbol, True, None) for j in chain.joints[3:]]
    A = sp.Matrix(3, 3, lambda i, j: sp.Symbol(f"a{i + 1}{j + 1}"))
    raw, wrist_cf, singular_seen = [], None, False
    R3f = sp.lambdify(chain.q[:3], R3, modules=numpy_modules())
    Rcf = np.array(Rc, dtype=float)
    for k, sol in enumerate(arm_sols):
        q123 = [sol[j.name] for j in arm_joints]
        a = np.array(R3f(*q123), dtype=float).T @ R @ Rcf.T
        # the derivation is in the symbols a_ij, the same for every arm branch: tried once
        ws, cf, singular = _wrist(tail, A, a, wrist_joints, names, tex, time_limit_s, derive and k == 0)
        singular_seen |= singular
        if cf is not None and wrist_cf is None:
            wrist_cf = cf
        raw += [(q123 + list(wq), singular or ("shoulder" if shoulder else False)) for wq in ws]
    res.steps.append(_wrist_step(R3, tail, A, names, tex, singular_seen, Rc, _middle_function(tail, chain.q[3:])))
    if wrist_cf is not None and arm_cf is not None:
        sub = {A[i, j]: (R3.T * R_SYMS * Rc.T)[i, j] for i in range(3) for j in range(3)}
        res.closed_form = [{**a_b, **{k: v.xreplace(sub) for k, v in w_b.items()}}
                           for a_b in arm_cf for w_b in wrist_cf]
    if not raw and res.status == "ok":
        res.status = "unreachable"
        res.reason = "the orientation is not attainable: the wrist cannot give ³R₆ = (⁰R₃)ᵀ·R"
    return raw


def _wrist_and_tool(chain, split):
    """The wrist's rotation ³R₆(q4, q5, q6) up to the last joint's own frame, and the constant
    rotation R_c after it (a tool frame: Tz(d) Ry(π/6), say, as a frame of its own or written
    after the last joint's rotation in the same pose): the target frame's ³R = ³R₆·R_c, so the
    wrist is solved from ³R₆ = (⁰R₃)ᵀ·R·R_cᵀ, the product of its own three rotations (ZYZ-like).
    In the last joint's pose P·Rz(q6)·Q the rotation Q after the joint is found from the joint's
    axis u in the target frame (Qᵀ·z = u): the rotation turning z onto u about z × u."""
    n = len(chain.factors)
    last = max(k for k in range(split, n) if chain.joints_of(k, k + 1))
    Rc = chain.product(last + 1, n)[:3, :3]
    tail = chain.product(split, last + 1)[:3, :3]
    Q = _after_last_axis(chain.factors[last][:3, :3], chain.q[5])
    if Q is not None:
        # in floats: an exact √3/2 of the pose times Q's 0.866… would not cancel
        tail, Rc = _chop(sp.expand((tail * Q.T).evalf(15))), Q * Rc
    return tail, _chop(Rc)


def _without_tool(chain):
    """(chain, C): the chain up to the last joint's rotation (the constant factors after the last
    joint dropped, and the rotation after its axis in its own pose taken off, `_after_last_axis`),
    and the constant pose C of the target frame in that frame; (chain, I) when there is none."""
    n = len(chain.factors)
    last = max(k for k in range(n) if chain.joints_of(k, k + 1))
    C = chain.product(last + 1, n)
    F = chain.factors[last]
    moved = chain.joints_of(last, last + 1)
    Q = _after_last_axis(F[:3, :3], next(iter(moved))) if len(moved) == 1 else None
    if Q is not None:
        Q4 = sp.diag(Q, 1)
        F, C = _chop(sp.expand((F * Q4.T).evalf(15))), Q4 * C
    if last == n - 1 and Q is None:
        return chain, sp.eye(4)
    # in floats: cos(3/10)·sin(1/5) products kept exact swell every equation of the target
    return _Chain(chain.factors[:last] + [F], chain.joints, chain.q), _chop(C.evalf(15))


def _after_last_axis(F, q):
    """The rotation Q with F(q) = P·Rz(q)·Q and Qᵀ·z = u, the joint's axis in F's end frame (the
    rotation turning z onto u about z × u); None when the axis is already ±z."""
    f = sp.lambdify([q], F, modules=numpy_modules())
    df = sp.lambdify([q], F.diff(q), modules=numpy_modules())
    W = np.array(f(0.0), dtype=float).T @ np.array(df(0.0), dtype=float)
    u = np.array([W[2, 1], W[0, 2], W[1, 0]])
    if abs(np.linalg.norm(u) - 1.0) > 1e-9 or math.hypot(u[0], u[1]) < 1e-12:
        return None
    axis = np.cross([0.0, 0.0, 1.0], u)
    k = axis / np.linalg.norm(axis)
    angle = math.atan2(np.linalg.norm(axis), u[2])
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    Qt = np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K   # z -> u
    return _chop(sp.Matrix(Qt.T).applyfunc(lambda v: sp.Float(float(v), 15)))


def _arm_representatives(arm, arm_joints, W, w):
    """A continuum of the arm's solutions (the wrist centre on the axis of its first free joint):
    that joint at 0 and the other two from the wrist centre, or [] when they are not isolated then."""
    free = (arm.family or {}).get("free") or []
    fixed = next((j for j in arm_joints if j.name in free), None)
    if fixed is None:
        return []
    rest = [j for j in arm_joints if j is not fixed]
    eqs = [(sp.expand(W[k].xreplace({fixed.symbol: 0})), W_SYMS[k]) for k in range(3)]
    r = solve_ik(eqs, rest, dict(zip(W_SYMS, map(float, w))), closed_form=False, target_symbols=W_SYMS)
    if r.status != "ok":
        return []
    return [{fixed.name: 0.0, **d} for d in r.all_solutions]


def _arm_closed_form(res, arm, wc, names):
    if arm.closed_form is None:
        res.notes.append("the first three joints: " + (arm.closed_form_note or "no closed form")
                         + "; solved numerically")
        return None
    sub = dict(zip(W_SYMS, wc))
    for st in arm.closed_form.steps:
        res.steps.append(PoseStep("Arm: " + st.title, st.text, list(st.equations)))
    return [{str(k): v.xreplace(sub) for k, v in b.items()} for b in arm.closed_form_branches]


def _wrist(tail, A, a, wrist_joints, names, tex, time_limit_s, derive=True):
    """The wrist's solutions for ³R₆ = a (numbers): (list of [q4, q5, q6], closed form, singular)."""
    vals = {A[i, j]: float(a[i, j]) for i in range(3) for j in range(3)}
    eqs = [(tail[i, j], A[i, j]) for i in range(3) for j in range(3)]
    r = solve_ik(eqs, wrist_joints, vals, closed_form=derive, time_limit_s=time_limit_s,
                 target_symbols=set(vals), latex_names=names, tex=tex)
    cf = None
    if r.closed_form is not None:
        cf = [{str(k): v for k, v in b.items()} for b in r.closed_form_branches]
    if r.status == "ok":
        return [[d[j.name] for j in wrist_joints] for d in r.all_solutions], cf, False
    if r.status == "unreachable":
        return [], cf, False
    # the wrist singularity: a continuum; the representative with the last angle 0
    last = wrist_joints[-1].symbol
    eqs0 = [(sp.sympify(l).subs(last, 0), rhs) for l, rhs in eqs]
    r0 = solve_ik(eqs0, wrist_joints[:-1], vals, closed_form=False, target_symbols=set(vals))
    return [[d[j.name] for j in wrist_joints[:-1]] + [0.0] for d in r0.all_solutions], cf, True


# ---------------------------------------------------------------------------
# three parallel axes (the UR family)

def _axis_in(Mf, q, k, base_inv):
    """Direction of joint k's axis in the frame whose inverse pose is base_inv (finite differences)."""
    m0 = np.array(Mf(*q), dtype=float)
    d = list(q)
    d[k] += 1e-7
    dM = (np.array(Mf(*d), dtype=float) - m0) / 1e-7
    W = dM[:3, :3] @ m0[:3, :3].T
    a = np.array([W[2, 1], W[0, 2], W[1, 0]])
    return a / np.linalg.norm(a)


def find_parallel(chain: _Chain):
    """(split, Q): joint 1 in factors[:split], joints 2, 3, 4 with parallel axes along a coordinate
    axis of frame `split`, turned onto z by the constant rotation Q (4x4); or None."""
    q = chain.q
    if len(q) != 6 or not all(j.revolute for j in chain.joints):
        return None
    n = len(chain.factors)
    split = next((s for s in range(1, n) if chain.joints_of(0, s) == {q[0]} and chain.joints_of(s, n) == set(q[1:])),
                 None)
    if split is None:
        return None
    tail = chain.product(split, n)
    Mf = sp.lambdify(q[1:], tail, modules=numpy_modules())
    qv = [0.37, -0.81, 1.23, 0.55, -1.7]
    axes = [_axis_in(Mf, qv, k, None) for k in (0, 1, 2)]
    if not all(np.linalg.norm(np.cross(axes[0], a)) < 1e-6 for a in axes[1:]):
        return None
    u = axes[0]
    k = int(np.argmax(np.abs(u)))
    if abs(abs(u[k]) - 1) > 1e-9:
        return None
    sign = 1 if u[k] > 0 else -1
    from robosolve.core.transforms import rot_x, rot_y
    Q = {2: sp.eye(4) if sign > 0 else rot_x(sp.pi), 1: rot_x(-sign * sp.pi / 2), 0: rot_y(sign * sp.pi / 2)}[k]
    return split, Q.T       # Q.T·u = z: rows of Q.T are the new axes


def _planar_arm_unreachable(res, q, reasons) -> None:
    """No branch's planar arm (joints 2, 3, 4) reaches: the first branch's reason, plain and with
    its formulas."""
    res.status = "unreachable"
    lead = (f"the pose is beyond the reach: for every value of {q[0]}, {q[4]}, {q[5]} the planar arm of "
            f"{q[1]}, {q[2]}, {q[3]} cannot reach the point it must")
    res.reason = lead + (Text(" (", reasons[0][0], ")") if reasons else "")
    res.reason_tex = lead + (Text(" (", reasons[0][1], ")") if reasons else "")


def _three_parallel(res, chain, par, R, p, names, tex, time_limit_s, derive=True):
    """The UR way: in frame 1 (axes 2, 3, 4 along z) the z row of ¹M₆ depends on q5, q6 only;
    with q1 it gives q1, q5, q6, then the planar 3R gives q2, q3, q4."""
    split, Q = par
    from robosolve.core.transforms import rigid_inverse
    chain, tool = _without_tool(chain)
    n = len(chain.factors)
    head, tail = chain.product(0, split), chain.product(split, n)
    # the frame after the last joint's rotation is given: ⁰M₆ = M·(tool)⁻¹, in the target's symbols
    Msym = sp.Matrix(sp.BlockMatrix([[R_SYMS, P_SYMS], [sp.zeros(1, 3), sp.ones(1, 1)]])) * rigid_inverse(tool)
    lhs = (Q * rigid_inverse(head) * Msym).applyfunc(sp.expand)       # of q1 and the target
    rhs = (Q * tail).applyfunc(sp.expand)                               # of q2..q6
    q = chain.q
    zrow = [rhs[2, j].subs({q[1]: 0, q[2]: 0, q[3]: 0}) for j in range(4)]
    if not _independent_of(rhs, zrow, q):
        return None
    vals = {R_SYMS[i, j]: float(R[i, j]) for i in range(3) for j in range(3)}
    vals.update({P_SYMS[i]: float(p[i]) for i in range(3)})
    first = [IKJoint(q[k], True, None) for k in (0, 4, 5)]
    eqs1 = _first_equations(zrow, lhs, q)
    st1 = solve_ik(eqs1, first, vals, closed_form=derive, time_limit_s=time_limit_s,
                   target_symbols=set(vals), latex_names=names, tex=tex)
    res.method = "three parallel axes"
    eqs2, known, planar = _planar_equations(chain, split, Q, lhs, rhs, Msym, q)
    angle = next((lhs_ for lhs_, rhs_ in eqs2 if rhs_ == BETA), None)
    res.steps.append(_parallel_step(zrow, lhs, split, [names[x] for x in q], angle, tool))
    if st1.status == "unreachable":
        res.status = "unreachable"
        lead = "the pose is beyond the reach or its orientation is not attainable: "
        res.reason = lead + Text(st1.reason or "")
        res.reason_tex = lead + Text(st1.reason_tex or st1.reason or "")
        return []
    firsts = [(sol, False) for sol in st1.all_solutions]
    if st1.status != "ok":
        # a singular wrist (sin q5 = 0) on one branch of q1 at least: q1 alone first, then q5, q6 on
        # each branch, q6 = 0 as the representative where the row leaves it free
        firsts = _first_joints_stepwise(eqs1, first, vals, q)
        if firsts is None:
            res.notes.append(f"three parallel axes: {q[0]}, {q[4]}, {q[5]} are not isolated at this pose (a singularity); "
                             "searched numerically on the 12 pose equations")
            return None
        if not firsts:
            res.status = "unreachable"
            res.reason = ("the pose is beyond the reach or its orientation is not attainable: "
                          f"no {q[0]}, {q[4]}, {q[5]} fit it")
            return []
    for stp in (st1.closed_form.steps if st1.closed_form is not None else []):
        res.steps.append(PoseStep(f"{q[0]}, {q[4]}, {q[5]}: " + stp.title, stp.text, list(stp.equations)))
    rest = [IKJoint(q[k], True, None) for k in (1, 2, 3)]
    bf = sp.lambdify([*vals, *(j.symbol for j in first)], planar, modules=numpy_modules()) if planar else None
    raw, cf2, reasons = [], None, []       # reasons: (plain, with formulas) of each branch
    for k, (sol, singular) in enumerate(firsts):
        v2 = dict(vals)
        v2.update({j.symbol: sol[j.name] for j in first})
        if planar:
            v2 = dict(zip(known, map(float, bf(*v2.values()))))
        # the closed form from the first branch whose planar arm reaches (an unreachable branch
        # stops before deriving it)
        # (the later branches evaluate it: the same equations, other values of the known entries)
        st2 = solve_ik(eqs2, rest, v2, closed_form=derive and bool(planar) and cf2 is None,
                       time_limit_s=time_limit_s,
                       target_symbols=set(v2), latex_names=names, tex=tex,
                       derived=cf2.closed_form if cf2 is not None and len(eqs2) == len(rest) else None)
        if cf2 is None and st2.closed_form is not None:
            cf2 = st2
        if st2.status == "unreachable" and st2.reason:
            reasons.append((st2.reason, st2.reason_tex or st2.reason))
        for d in st2.all_solutions:
            raw.append(([sol[q[0].name], d[q[1].name], d[q[2].name], d[q[3].name], sol[q[4].name], sol[q[5].name]],
                        singular))
    if not raw:
        _planar_arm_unreachable(res, q, reasons)
    if cf2 is not None:
        for stp in cf2.closed_form.steps:
            res.steps.append(PoseStep(f"{q[1]}, {q[2]}, {q[3]}: " + stp.title, stp.text, list(stp.equations)))
    if st1.closed_form is not None and cf2 is not None:
        bsub = dict(zip(known, planar))
        res.closed_form = [{**{str(k): v for k, v in a.items()}, **{str(k): v.xreplace(bsub) for k, v in b.items()}}
                           for a in st1.closed_form_branches for b in cf2.closed_form_branches]
    return raw


def _first_joints_stepwise(eqs1, first, vals, q):
    """q1, q5, q6 one after the other where they are not isolated together: q1 from the position
    equation (free of q5, q6), then q5 and q6 from the three rotation equations of the row on each
    branch of q1; where those leave q6 free (sin q5 = 0: the axes of joints 2, 3, 4 and 6 parallel)
    the representative q6 = 0. A list of ({joint: value}, singular), or None when the row does not
    split this way."""
    q1, q5, q6 = (j.symbol for j in first)
    pos = eqs1[3][0]
    if pos.free_symbols & set(q) != {q1}:
        return None
    r1 = solve_ik([eqs1[3]], [first[0]], vals, closed_form=False, target_symbols=set(vals))
    if r1.status == "unreachable":
        return []
    if r1.status != "ok":
        return None
    out = []
    for s1 in r1.all_solutions:
        v = dict(vals)
        v[q1] = s1[q1.name]
        rows = [(e.xreplace({q1: v[q1]}), rhs) for e, rhs in eqs1[:3]]
        r56 = solve_ik(rows, list(first[1:]), v, closed_form=False, target_symbols=set(v))
        if r56.status == "ok":
            out += [({q1.name: v[q1], q5.name: d[q5.name], q6.name: d[q6.name]}, False) for d in r56.all_solutions]
            continue
        if r56.status == "unreachable" or r56.status == "overdetermined":
            continue
        rows0 = [(sp.expand(e.xreplace({q6: 0})), rhs) for e, rhs in rows]
        r5 = solve_ik(rows0, [first[1]], v, closed_form=False, target_symbols=set(v))
        if r5.status != "ok":
            return None
        out += [({q1.name: v[q1], q5.name: d[q5.name], q6.name: 0.0}, True) for d in r5.all_solutions]
    return out


def _planar_equations(chain, split, Q, lhs, rhs, Msym, q):
    """The planar 3R of q2, q3, q4 as (equations, the known quantities' symbols, their expressions
    in the target's symbols, or None when the equations are written in those symbols directly).

    When the chain splits after q4, ¹M₄ = ¹M₆·(⁴M₆)⁻¹ is known: its position's x, y rows
    (b_x, b_y), and, as the course writes it, the angle of its rotation about the parallel axes,
    a sum ±q2 ± q3 ± q4 (+ a constant) equal to β = atan2(b_21, b_11); where that angle is not
    such a sum, the two entries b_11, b_21 of the rotation's first column. Otherwise the first two
    rows of ¹M₆."""
    from robosolve.core.transforms import rigid_inverse
    n = len(chain.factors)
    s2 = next((k for k in range(split + 1, n) if chain.joints_of(split, k) == set(q[1:4])
               and chain.joints_of(k, n) == set(q[4:])), None)
    if s2 is None:
        return [(sp.expand(rhs[i, j] - lhs[i, j]), 0) for i in (0, 1) for j in range(4)], (), None
    mid = (Q * chain.product(split, s2)).applyfunc(sp.expand)
    target = (lhs * rigid_inverse(chain.product(s2, n))).applyfunc(sp.expand)
    b = {(i, j): _pythagoras(target[i, j], q) for j in (0, 3) for i in (0, 1)}     # b_11, b_21, b_x, b_y
    angle = _angle_sum(mid[0, 0], mid[1, 0], q[1:4])
    if angle is not None:
        return ([(mid[0, 3], B_SYMS[2]), (mid[1, 3], B_SYMS[3]), (angle, BETA)], (B_SYMS[2], B_SYMS[3], BETA),
                [b[0, 3], b[1, 3], sp.atan2(b[1, 0], b[0, 0])])
    return [(mid[key], sym) for key, sym in zip(b, B_SYMS)], B_SYMS, list(b.values())


def _pythagoras(expr, joints):
    """sin² q + cos² q = 1 applied where it shortens `expr` (an expanded product of the chain's
    matrices has c5² r33 + s5² r33 where the course writes r33). Not core/trigring's
    pythagorean_reduced: that one leaves decimal coefficients alone (its ring would add round-off
    terms), and a datasheet arm's entries have them; here equal coefficients cancel exactly."""
    for x in joints:
        s, c = sp.sin(x), sp.cos(x)
        if not (expr.has(s ** 2) and expr.has(c ** 2)):
            continue
        cands = [expr, sp.expand(expr.subs(s ** 2, 1 - c ** 2)), sp.expand(expr.subs(c ** 2, 1 - s ** 2))]
        expr = min(cands, key=count_ops)
    return expr


def _angle_sum(c, s, joints):
    """k·q + c0 with (c, s) = (cos, sin) of it for every q (k_i in -1, 0, 1; c0 a multiple of
    π/12, else a decimal), or None. Read off numerically at one point, then checked at others."""
    f = sp.lambdify(joints, [c, s], modules=numpy_modules())

    def theta(x):
        cv, sv = (float(v) for v in f(*x))
        return math.atan2(sv, cv)

    base = [0.31, -0.47, 0.73]
    t0 = theta(base)
    k = []
    for i in range(len(joints)):
        x = list(base)
        x[i] += 0.1
        d = wrap_angle(theta(x) - t0) / 0.1
        if abs(d - round(d)) > 1e-6 or abs(round(d)) > 1:
            return None
        k.append(int(round(d)))
    if not any(k):
        return None
    c0 = wrap_angle(t0 - sum(ki * xi for ki, xi in zip(k, base)))
    twelfths = c0 * 12 / math.pi
    c0e = sp.pi * sp.Rational(int(round(twelfths)), 12) if abs(twelfths - round(twelfths)) < 1e-9 \
        else sp.Float(c0, 15)
    expr = sum((ki * qi for ki, qi in zip(k, joints)), sp.Integer(0)) + c0e
    g = sp.lambdify(joints, [c - sp.cos(expr), s - sp.sin(expr)], modules=numpy_modules())
    for x in ((1.1, 0.2, -2.3), (-0.8, 2.6, 0.4), (2.9, -1.7, 1.5)):
        if max(abs(float(v)) for v in g(*x)) > 1e-10:
            return None
    return expr


def _first_equations(zrow, lhs, q):
    """The z row's four equations, the position one made free of q5, q6 by subtracting a constant
    combination of the rotation ones (for the UR: p_z - d6·r33), so that q1 comes first."""
    eqs = [sp.expand(zrow[j] - lhs[2, j]) for j in range(4)]
    f = sp.lambdify(q[4:], zrow, modules=numpy_modules())
    samples = [(0.3, 1.1), (-1.2, 0.4), (2.0, -2.2), (0.9, 2.7), (-0.4, -1.5)]
    rows = np.array([np.broadcast_to(np.array(f(*s), dtype=float), (4,)) for s in samples])
    A = np.hstack([rows[:, :3], np.ones((len(samples), 1))])
    lam, *_ = np.linalg.lstsq(A, rows[:, 3], rcond=None)
    if np.max(np.abs(A @ lam - rows[:, 3])) < 1e-10:
        lam = [0 if abs(v) < 1e-12 else _exact(float(f"{v:.12g}")) for v in lam[:3]]
        pos = sp.expand(eqs[3] - sum(l * e for l, e in zip(lam, eqs[:3])))
        eqs[3] = pos.xreplace({a: 0 for a in pos.atoms(sp.Float) if abs(a) < 1e-12})
    return [(e, 0) for e in eqs]


def _independent_of(rhs, zrow, q) -> bool:
    f = sp.lambdify(q[1:], [rhs[2, j] - zrow[j] for j in range(4)], modules=numpy_modules())
    for qs in ((0.3, 1.1, -0.7, 0.4, 2.0), (-1.2, 0.4, 2.0, -2.2, 0.9)):
        if np.max(np.abs(np.array(f(*qs), dtype=float))) > 1e-10:
            return False
    return True


def _parallel_step(zrow, lhs, split, names, angle, tool=None) -> PoseStep:
    """The split of the UR way, in the chain's joint names (`names`: LaTeX, in joint order); `tool`:
    the constant pose of the target frame after the last joint's rotation (identity: none)."""
    n1, n2, n3, n4, n5, n6 = names
    given, given_row = "({}^{0}M_{1})^{-1} M", "[({}^{0}M_{1})^{-1} M]_{3}"
    tool_text, eqs = "", []
    if tool is not None and tool != sp.eye(4):
        given, given_row = "({}^{0}M_{1})^{-1} M\\,T_{t}^{-1}", "[({}^{0}M_{1})^{-1} M\\,T_{t}^{-1}]_{3}"
        tool_text = (" The target frame is fixed after the last joint's rotation at the constant pose $T_{t}$ "
                     "(a tool), so frame 6 is at $M\\,T_{t}^{-1}$.")
        eqs = [("T_{t}", tool)]
    if angle is not None:
        planar = (f"its rotation is about $z$ by the angle ${latex(angle)} = \\beta$, "
                  "$\\beta = \\operatorname{atan2}(b_{21}, b_{11})$ from the first column of the rotation, "
                  "and its position gives $b_x, b_y$: the planar 3R with its orientation, two elbow branches")
    else:
        planar = ("its entries $b_{11}, b_{21}$ (the first column of the rotation) and $b_x, b_y$ (the position) "
                  "give two elbow branches")
    return PoseStep(
        "Three parallel axes: the row along them",
        f"The axes of joints 2, 3 and 4 are parallel (the UR family). Written in frame {split} (axes turned so "
        f"that they lie along $z$), ${{}}^{{1}}M_{{6}} = {given}$; rotations about $z$ leave the $z$ row "
        f"unchanged, so the third row of ${{}}^{{1}}M_{{6}}$ depends on ${n5}$, ${n6}$ only: four equations for "
        f"${n1}$, ${n5}$, ${n6}$. The first two rows are then a planar 3R problem for ${n2}$, ${n3}$, ${n4}$: "
        "${}^{1}M_{4} = {}^{1}M_{6}\\,({}^{4}M_{6})^{-1}$ is known; " + planar + ". The wrist is not "
        f"spherical: where $\\sin {n5} = 0$ the axes of joints 4 and 6 are parallel (with those of joints 2 "
        f"and 3), not aligned; the row then does not determine ${n6}$, and such a pose is reached along a "
        "continuum of configurations, or not at all." + tool_text,
        eqs + [("[{}^{1}M_{6}]_{3}", sp.Matrix([zrow])), (given_row, sp.Matrix([list(lhs[2, :])]))])


def _numeric(res, chain, R, p, no_wrist):
    """Every solution of the 12 pose equations by the multi-start search."""
    M = chain.product(0, len(chain.factors))
    target = np.hstack([R, p[:, None]])
    eqs = [(M[i, j], float(target[i, j])) for i in range(3) for j in range(4)]
    r = solve_ik(eqs, [IKJoint(j.symbol, j.revolute, None) for j in chain.joints], {}, closed_form=False,
                 subsets=False)
    res.method = "numeric"
    res.notes += list(r.notes)
    if no_wrist:
        res.notes.append(_no_wrist_note(chain))
    res.steps.append(PoseStep(
        "Numeric solution",
        "The 12 equations ⁰M(q) = M (nine of the rotation, three of the position; six independent) "
        "are solved by a deterministic multi-start Newton search over every joint's range."))
    if r.status == "unreachable" or not r.all_solutions:
        res.status = "unreachable"
        res.reason = _numeric_reason(r, chain, M, p)
        return []
    return [([d[j.name] for j in chain.joints], False) for d in r.all_solutions]


def _no_wrist_note(chain) -> str:
    if len(chain.q) == 6 and parallel_axes(chain):
        return ("three parallel axes (the UR family): no spherical wrist to decouple; the solutions are "
                "found numerically from the 12 pose equations")
    return "no spherical wrist: the solutions are found numerically from the 12 pose equations"


def parallel_axes(chain) -> bool:
    """Joints 2, 3, 4 with parallel axes (at a generic configuration)."""
    qv = [0.37, -0.81, 1.23, 0.55, -1.7, 0.9]
    axes, M = [], sp.eye(4)
    for f in chain.factors:
        M = M * f
    q = chain.q
    Mf = sp.lambdify(q, M, modules=numpy_modules())
    base = np.array(Mf(*qv), dtype=float)
    for k in (1, 2, 3):
        d = list(qv)
        d[k] += 1e-6
        dM = (np.array(Mf(*d), dtype=float) - base) / 1e-6
        W = dM[:3, :3] @ base[:3, :3].T
        axes.append(np.array([W[2, 1], W[0, 2], W[1, 0]]))
    axes = [a / np.linalg.norm(a) for a in axes]
    return all(np.linalg.norm(np.cross(axes[0], a)) < 1e-4 for a in axes[1:])


def _numeric_reason(r, chain, M, p) -> str:
    """Why the 12 equations have no solution: too few joints for a pose, the position beyond the
    reach, or the position reached but never with this orientation; the closest miss found."""
    n = len(chain.q)
    lead = ("no configuration reaches the pose" if n >= 6 else
            f"the arm has {n} joint{'s' if n != 1 else ''}, fewer than the 6 coordinates of a pose: the poses "
            f"it reaches form a {n}-dimensional set, and this one is not in it")
    gap = _position_gap(chain, M, p)
    if gap is None:
        why = ""
    elif gap > 1e-7 * max(1.0, float(np.max(np.abs(p)))):
        why = f"; the position itself is beyond the reach (it stays {gap:.4g} away from it)"
    else:
        why = "; the position alone is reachable, but not with this orientation (it is not attainable there)"
    miss = f" (the closest configuration found misses an entry of the pose by {r.nearest_residual:.3g})" \
        if r.nearest_residual is not None and math.isfinite(r.nearest_residual) else ""
    return lead + why + miss


def _position_gap(chain, M, p):
    """The smallest distance from the frame's origin to p over the configurations (a multi-start
    least-squares search on the 3 position equations), or None."""
    from robosolve.ik.numeric import _lm_batch, lambdify_system, refine, start_points

    boxes = [(-math.pi, math.pi) if j.revolute else
             (tuple(j.limits) if j.limits is not None else (-3.0, 3.0)) for j in chain.joints]
    system = lambdify_system([M[i, 3] - float(p[i]) for i in range(3)], chain.q,
                             [j.revolute for j in chain.joints])
    Q, cost = _lm_batch(system, start_points(boxes, 256))
    best = None
    for i in np.argsort(cost, kind="stable")[:8]:
        q, _ = refine(system, Q[i])
        d = float(np.linalg.norm(system.residual(q[None])[0]))
        best = d if best is None else min(best, d)
    return best


def _verify(res, fk, raw, target, chain):
    rev = [j.revolute for j in chain.joints]
    kept, flags = [], []
    for q, singular in raw:
        qp, err = fk.polish(q, target)
        if err > FK_TOL * max(1.0, float(np.max(np.abs(target)))):
            res.notes.append(f"a candidate solution was dropped: forward kinematics misses the target by {err:.2e}")
            continue
        d = {j.name: (wrap_angle(float(v)) if r else float(v)) for j, v, r in zip(chain.joints, qp, rev)}
        if any(_same(d, e, chain.joints) for e in kept):
            continue
        kept.append(d)
        flags.append(singular)
    order = sort_solutions(list(range(len(kept))), get=lambda i: [kept[i][j.name] for j in chain.joints])
    res.all_solutions = [kept[i] for i in order]
    res.wrist_singular = [bool(flags[i]) for i in order]
    res.joints = chain.joints
    flags = [f is True for f in flags]          # "shoulder": noted where it was found
    if any(flags) and res.method == "three parallel axes":
        n5, n6 = chain.joints[4].name, chain.joints[5].name
        res.notes.append(f"wrist singularity: where sin {n5} = 0 the axes of joints 2, 3, 4 and 6 are parallel "
                         f"and the pose is reached along a continuum; the representatives with {n6} = 0 are given")
    elif any(flags):
        res.notes.append("wrist singularity: the wrist's first and last axes are aligned, only their sum "
                         "(or difference) is determined; the representative with the last wrist angle 0 is given")


def _same(a, b, joints, tol=DEDUPE_TOL):
    return all(abs(wrap_angle(a[j.name] - b[j.name]) if j.revolute else a[j.name] - b[j.name]) < tol
               for j in joints)


def _finish(res: PoseResult, select):
    joints = res.joints
    for d in res.all_solutions:
        broken = in_limits(d, joints)
        if broken:
            res.rejected.append((d, broken))
        else:
            res.solutions.append(d)
    if res.status == "ok" and not res.solutions:
        res.status = "unreachable"
        if res.rejected:
            res.reason = Text("every solution breaks a joint limit: ",
                              Text.join("; ", [Text.join(", ", b) for _, b in res.rejected]))
        else:
            res.reason = res.reason or "the pose is beyond the reach or its orientation is not attainable"
    if not res.solutions:
        return
    if isinstance(select, dict):
        tgt = {j.name: float(select.get(j.name, 0.0)) for j in joints}
        def dist(d):
            return math.sqrt(sum((wrap_angle(d[j.name] - tgt[j.name]) if j.revolute else d[j.name] - tgt[j.name]) ** 2
                                 for j in joints))
        res.selected_index = min(range(len(res.solutions)), key=lambda i: (dist(res.solutions[i]), i))
    else:
        res.selected_index = 0
    res.selected = res.solutions[res.selected_index]


# ---------------------------------------------------------------------------
# steps

def _centre_step(c_t, wc, w, split, names, chain) -> PoseStep:
    c = sp.Matrix([_exact(v) for v in c_t])
    return PoseStep(
        "Kinematic decoupling: the wrist centre",
        f"The axes of the last three joints meet at one point, the wrist centre W (a spherical wrist), "
        f"fixed in the target frame and not moved by the wrist joints. Its position "
        f"${{}}^{{0}}\\vec{{r}}_W = \\vec p + R\\,\\vec c$ depends on the first three joints only "
        f"(frames 0 to {split}), so they are found from W; the last three then give the orientation.",
        [("\\vec c", c), ("{}^{0}\\vec{r}_W", sp.Matrix(wc)), ("{}^{0}\\vec{r}_W", [[float(v)] for v in w])])


def _middle_function(tail, q) -> str:
    """"sine" when the wrist's first and last axes are aligned where the middle angle is 0
    (ZYZ-like: the branches go by the sign of its sine, singular where it vanishes), "cosine"
    when they are aligned at ±π/2 (a roll-pitch-yaw wrist, ZYX-like)."""
    R = sp.lambdify(q, tail, modules=numpy_modules())
    dR = [sp.lambdify(q, tail.diff(x), modules=numpy_modules()) for x in (q[0], q[2])]

    def aligned(middle):
        at = (0.3, middle, -0.7)
        Rt = np.array(R(*at), dtype=float).T
        w = [np.array(d(*at), dtype=float) @ Rt for d in dR]        # each axis, as a skew matrix
        u, v = ([W[2, 1], W[0, 2], W[1, 0]] for W in w)
        return np.linalg.norm(np.cross(u, v)) < 1e-9

    return "cosine" if aligned(math.pi / 2) and not aligned(0.0) else "sine"


def _wrist_step(R3, tail, A, names, tex, singular, Rc=None, middle="sine") -> PoseStep:
    tool = Rc is not None and Rc != sp.eye(3)
    text = ("With the first three joints known, the wrist's rotation is "
            + ("${}^{3}R_{6} = ({}^{0}R_{3})^{T}\\,R\\,R_{t}^{T}$, $R_{t}$ the constant rotation of the target "
               "frame after the last joint's frame, " if tool else "${}^{3}R_{6} = ({}^{0}R_{3})^{T}\\,R$ ")
            + "(written $a_{ij}$ below); equating it to the wrist's "
            "product of rotations gives the last three angles as Euler-like "
            + ("(ZYZ)" if middle == "sine" else "(roll-pitch-yaw)") + " angles: two branches, "
            f"from the sign of the middle angle's {middle}.")
    if singular:
        text += (f" At this pose the middle wrist angle's {middle} is 0 (the wrist singularity): the first and "
                 "last wrist axes are aligned, only their sum is determined.")
    else:
        text += (f" The wrist is singular where the middle wrist angle's {middle} vanishes (first and last axes "
                 "aligned).")
    return PoseStep("Kinematic decoupling: the wrist", text,
                    [("{}^{3}R_{6}(" + ", ".join(names.get(s, str(s)) for s in sorted(tail.free_symbols, key=str)) + ")",
                      tail), ("{}^{3}R_{6}", A)] + ([("R_{t}", Rc)] if tool else []))
