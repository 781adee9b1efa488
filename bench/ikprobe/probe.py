"""Throwaway probe of the pose IK on robots robosolve has not seen (issue 26).

Generates problem YAML files (random standard / modified DH arms of several families, targets in
every form), runs `python -m robosolve solve`, and checks each answer against an independent
reference: numpy forward kinematics of the DH table, and a 500-start batched Levenberg-Marquardt
search on the 12 pose equations (deduplicated, wrapped, within the limits).

    python bench/ikprobe/probe.py [--seed S] [--n N] [--family F] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field

import numpy as np

PI = math.pi


# ---------------------------------------------------------------------------
# numpy kinematics

def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def tr(x, y, z):
    m = np.eye(4)
    m[:3, 3] = (x, y, z)
    return m


@dataclass
class Link:
    kind: str          # R | P
    theta: float       # offset (R) or constant (P)
    d: float           # constant (R) or offset (P)
    a: float
    alpha: float


@dataclass
class Robot:
    name: str
    conv: str                          # standard | modified
    links: list
    limits: list = field(default_factory=list)   # per joint: None or (lo, hi)
    tool: np.ndarray | None = None     # extra frame after the last (a constant pose)
    family: str = ""

    @property
    def n(self):
        return len(self.links)

    def fk(self, q, upto=None, tool=True):
        M = np.eye(4)
        for L, v in list(zip(self.links, q))[:upto]:
            th = L.theta + v if L.kind == "R" else L.theta
            d = L.d if L.kind == "R" else L.d + v
            if self.conv == "standard":
                M = M @ rz(th) @ tr(0, 0, d) @ tr(L.a, 0, 0) @ rx(L.alpha)
            else:
                M = M @ rx(L.alpha) @ tr(L.a, 0, 0) @ rz(th) @ tr(0, 0, d)
        if tool and self.tool is not None and upto is None:
            M = M @ self.tool
        return M


# batched FK for the reference search

def _rz_b(t):
    c, s = np.cos(t), np.sin(t)
    N = t.shape[0]
    m = np.zeros((N, 4, 4))
    m[:, 0, 0], m[:, 0, 1], m[:, 1, 0], m[:, 1, 1] = c, -s, s, c
    m[:, 2, 2] = m[:, 3, 3] = 1
    return m


def _tz_b(d):
    N = d.shape[0]
    m = np.tile(np.eye(4), (N, 1, 1))
    m[:, 2, 3] = d
    return m


def fk_batch(robot, Q):
    N = Q.shape[0]
    M = np.tile(np.eye(4), (N, 1, 1))
    for k, L in enumerate(robot.links):
        v = Q[:, k]
        th = L.theta + v if L.kind == "R" else np.full(N, L.theta)
        d = np.full(N, L.d) if L.kind == "R" else L.d + v
        A, B = tr(L.a, 0, 0) @ rx(L.alpha), rx(L.alpha) @ tr(L.a, 0, 0)
        if robot.conv == "standard":
            M = M @ _rz_b(th) @ _tz_b(d) @ A
        else:
            M = M @ B @ _rz_b(th) @ _tz_b(d)
    if robot.tool is not None:
        M = M @ robot.tool
    return M


def wrap(a):
    return PI - np.mod(PI - np.asarray(a, dtype=float), 2 * PI)


def in_limits(robot, q):
    for k, L in enumerate(robot.links):
        lim = robot.limits[k] if robot.limits else None
        if L.kind == "R":
            lo, hi = lim if lim else (-PI, PI)
            v = q[k]
            if not any(lo - 1e-9 <= v + 2 * PI * m <= hi + 1e-9 for m in range(-3, 4)):
                return False
        elif lim and not (lim[0] - 1e-9 <= q[k] <= lim[1] + 1e-9):
            return False
    return True


def reference(robot, T, point_c=None, starts=500, seed=0):
    """Every solution the multi-start LM finds: list of q (wrapped), within the limits."""
    rng = np.random.default_rng(seed)
    n = robot.n
    lo, hi = [], []
    for k, L in enumerate(robot.links):
        lim = robot.limits[k] if robot.limits else None
        if L.kind == "R":
            lo.append(-PI), hi.append(PI)
        else:
            a, b = lim if lim else (-2.0, 2.0)
            w = b - a
            lo.append(a - 0.2 * w), hi.append(b + 0.2 * w)
    Q = rng.uniform(lo, hi, size=(starts, n))
    tgt = T[:3, :4].reshape(-1)
    scale = np.array([1.0] * 9 + [1.0] * 3)

    def res(Q):
        M = fk_batch(robot, Q)
        if point_c is not None:
            M = M.copy()
            M[:, :3, 3] = M[:, :3, 3] + np.einsum("nij,j->ni", M[:, :3, :3], point_c)
        return (M[:, :3, :4].reshape(len(Q), 12) - tgt) * scale

    lam = np.full(starts, 1e-2)
    r = res(Q)
    cost = (r ** 2).sum(1)
    for it in range(200):
        J = np.empty((starts, 12, n))
        h = 1e-7
        for k in range(n):
            Qh = Q.copy()
            Qh[:, k] += h
            J[:, :, k] = (res(Qh) - r) / h
        A = np.einsum("nmi,nmj->nij", J, J)
        g = np.einsum("nmi,nm->ni", J, r)
        Ad = A + lam[:, None, None] * np.eye(n)[None]
        step = -np.linalg.solve(Ad, g[:, :, None])[:, :, 0]
        nrm = np.linalg.norm(step, axis=1)
        big = nrm > 0.5
        step[big] *= (0.5 / nrm[big])[:, None]
        Qn = Q + step
        rn = res(Qn)
        cn = (rn ** 2).sum(1)
        ok = cn < cost
        Q = np.where(ok[:, None], Qn, Q)
        r = np.where(ok[:, None], rn, r)
        cost = np.where(ok, cn, cost)
        lam = np.where(ok, np.maximum(lam / 3, 1e-12), np.minimum(lam * 5, 1e8))
    sols = []
    best = float(np.sqrt(cost.min()))
    for i in np.argsort(cost):
        if cost[i] > 1e-16:
            break
        q = Q[i].copy()
        # Newton polish
        for _ in range(20):
            rr = res(q[None])[0]
            Jq = np.empty((12, n))
            for k in range(n):
                qh = q.copy()
                qh[k] += 1e-7
                Jq[:, k] = (res(qh[None])[0] - rr) / 1e-7
            q = q + np.linalg.lstsq(Jq, -rr, rcond=1e-12)[0]
        if np.max(np.abs(res(q[None])[0])) > 1e-9:
            continue
        qw = np.array([wrap(v) if L.kind == "R" else v for v, L in zip(q, robot.links)])
        if any(close(qw, s, robot) for s in sols):
            continue
        sols.append(qw)
    inside = [s for s in sols if in_limits(robot, s)]
    return inside, sols, best


def close(a, b, robot, tol=1e-5):
    for x, y, L in zip(a, b, robot.links):
        d = abs(x - y)
        if L.kind == "R":
            d = min(d, 2 * PI - d)
        if d > tol:
            return False
    return True


# ---------------------------------------------------------------------------
# YAML

def f(v):
    return repr(float(v))


def yaml_of(robot, question, name):
    lines = ["robosolve: 1", f"name: {name}", "joints:"]
    for k, L in enumerate(robot.links):
        t = "revolute" if L.kind == "R" else "prismatic"
        lim = robot.limits[k] if robot.limits else None
        ls = f", limits: [{f(lim[0])}, {f(lim[1])}]" if lim else ""
        lines.append(f"  - {{name: q{k + 1}, type: {t}{ls}}}")
    lines += ["dh:", f"  convention: {robot.conv}", "  rows:"]
    for k, L in enumerate(robot.links):
        qn = f"q{k + 1}"
        if L.kind == "R":
            th = qn if L.theta == 0 else f"{qn} + {f(L.theta)}"
            d = f(L.d)
        else:
            th = f(L.theta)
            d = qn if L.d == 0 else f"{qn} + {f(L.d)}"
        lines.append(f"    - {{theta: '{th}', d: '{d}', a: {f(L.a)}, alpha: {f(L.alpha)}}}")
    if robot.tool is not None:
        lines.append("frames:")
        M = robot.tool
        rows = ", ".join("[" + ", ".join(f(x) for x in M[i]) + "]" for i in range(4))
        lines.append(f"  \"t\": {{parent: \"{robot.n}\", matrix: [{rows}]}}")
    if question.get("points"):
        lines.append("points:")
        for pn, (fr, c) in question["points"].items():
            lines.append(f"  {pn}: {{frame: \"{fr}\", at: [{', '.join(f(x) for x in c)}]}}")
    lines.append("questions:")
    lines.append("  - " + question["yaml"])
    return "\n".join(lines) + "\n"


def target_yaml(T, form, rng):
    R, p = T[:3, :3], T[:3, 3]
    pos = "[" + ", ".join(f(x) for x in p) + "]"
    if form == "pose":
        return "{pose: [" + ", ".join("[" + ", ".join(f(x) for x in T[i]) + "]" for i in range(4)) + "]}"
    if form == "R":
        return "{position: " + pos + ", R: [" + ", ".join("[" + ", ".join(f(x) for x in R[i]) + "]" for i in range(3)) + "]}"
    if form == "zyz":
        th = math.atan2(math.hypot(R[0, 2], R[1, 2]), R[2, 2])
        phi = math.atan2(R[1, 2], R[0, 2])
        psi = math.atan2(R[2, 1], -R[2, 0])
        return "{position: " + pos + f", zyz: [{f(phi)}, {f(th)}, {f(psi)}]}}"
    if form == "rpy":
        pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
        yaw = math.atan2(R[1, 0], R[0, 0])
        roll = math.atan2(R[2, 1], R[2, 2])
        return "{position: " + pos + f", rpy: [{f(roll)}, {f(pitch)}, {f(yaw)}]}}"
    raise ValueError(form)


def R_of_form(T, form):
    """The rotation robosolve sees for the target written in `form` (ZYZ/RPY round trip)."""
    R = T[:3, :3]
    if form == "zyz":
        th = math.atan2(math.hypot(R[0, 2], R[1, 2]), R[2, 2])
        phi = math.atan2(R[1, 2], R[0, 2])
        psi = math.atan2(R[2, 1], -R[2, 0])
        return (rz(phi) @ _ry(th) @ rz(psi))[:3, :3]
    if form == "rpy":
        pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
        yaw = math.atan2(R[1, 0], R[0, 0])
        roll = math.atan2(R[2, 1], R[2, 2])
        return (rz(yaw) @ _ry(pitch) @ rx(roll))[:3, :3]
    return R


def _ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1.0]])


# ---------------------------------------------------------------------------
# families

def sgn(rng):
    return float(rng.choice([-1, 1]))


def puma_like(rng, conv):
    """Spherical wrist: PUMA / KUKA / ABB-like, offsets a1, a2, a3, d2, d4, d6, twist signs."""
    a1 = float(rng.choice([0.0, rng.uniform(0.05, 0.4)]))
    d1 = float(rng.choice([0.0, rng.uniform(0.2, 0.8)]))
    a2 = rng.uniform(0.3, 0.9)
    d2 = float(rng.choice([0.0, rng.uniform(-0.2, 0.2)]))
    a3 = float(rng.choice([0.0, rng.uniform(-0.1, 0.1)]))
    d4 = rng.uniform(0.3, 0.9)
    d6 = float(rng.choice([0.0, rng.uniform(0.05, 0.25)]))
    s = [sgn(rng) for _ in range(5)]
    if conv == "standard":
        links = [Link("R", 0, d1, a1, s[0] * PI / 2), Link("R", 0, d2, a2, 0), Link("R", 0, 0, a3, s[1] * PI / 2),
                 Link("R", 0, d4, 0, s[2] * PI / 2), Link("R", 0, 0, 0, s[3] * PI / 2), Link("R", 0, d6, 0, 0)]
    else:
        links = [Link("R", 0, d1, 0, 0), Link("R", 0, d2, a1, s[0] * PI / 2), Link("R", 0, 0, a2, 0),
                 Link("R", 0, d4, a3, s[1] * PI / 2), Link("R", 0, 0, 0, s[2] * PI / 2),
                 Link("R", 0, d6, 0, s[3] * PI / 2)]
    if rng.uniform() < 0.3:
        links[1].theta = -PI / 2       # an offset in theta2 (KUKA / ABB-like)
    return Robot(f"puma-{conv[:3]}", conv, links, family="puma")


UR_DATA = {"ur3": (0.1519, -0.24365, -0.21325, 0.11235, 0.08535, 0.0819),
           "ur5": (0.089159, -0.425, -0.39225, 0.10915, 0.09465, 0.0823),
           "ur10": (0.1273, -0.612, -0.5723, 0.163941, 0.1157, 0.0922)}


def ur_like(rng, which=None, conv="standard"):
    if which:
        d1, a2, a3, d4, d5, d6 = UR_DATA[which]
    else:
        d1, a2, a3 = rng.uniform(0.05, 0.3), sgn(rng) * rng.uniform(0.2, 0.7), sgn(rng) * rng.uniform(0.2, 0.6)
        d4, d5, d6 = rng.uniform(0.05, 0.2) * sgn(rng), rng.uniform(0.05, 0.15), rng.uniform(0.0, 0.15)
    if conv == "standard":
        links = [Link("R", 0, d1, 0, PI / 2), Link("R", 0, 0, a2, 0), Link("R", 0, 0, a3, 0),
                 Link("R", 0, d4, 0, PI / 2), Link("R", 0, d5, 0, -PI / 2), Link("R", 0, d6, 0, 0)]
    else:
        links = [Link("R", 0, d1, 0, 0), Link("R", 0, 0, 0, PI / 2), Link("R", 0, 0, a2, 0),
                 Link("R", 0, d4, a3, 0), Link("R", 0, d5, 0, PI / 2), Link("R", 0, d6, 0, -PI / 2)]
    return Robot(f"ur-{which or 'rand'}-{conv[:3]}", conv, links, family="ur")


def stanford(rng):
    d1, d2, d6 = rng.uniform(0.2, 0.6), rng.uniform(0.05, 0.25), rng.uniform(0.0, 0.3)
    links = [Link("R", 0, d1, 0, -PI / 2), Link("R", 0, d2, 0, PI / 2), Link("P", 0, 0, 0, 0),
             Link("R", 0, 0, 0, -PI / 2), Link("R", 0, 0, 0, PI / 2), Link("R", 0, d6, 0, 0)]
    r = Robot("stanford", "standard", links, family="stanford")
    r.limits = [None, None, (0.1, 1.2), None, None, None]
    return r


def random_arm(rng, n):
    links = []
    for k in range(n):
        links.append(Link("R", 0, float(rng.choice([0, rng.uniform(-0.3, 0.3)])), rng.uniform(0, 0.5),
                          float(rng.choice([0, PI / 2, -PI / 2, rng.uniform(-PI, PI)]))))
    return Robot(f"rand{n}r", "standard", links, family=f"rand{n}")


# ---------------------------------------------------------------------------
# cases

@dataclass
class Case:
    name: str
    robot: Robot
    T: np.ndarray            # pose of the target frame (or the frame of the point)
    q0: np.ndarray | None
    form: str
    point_c: np.ndarray | None = None
    expect_closed: bool = False
    expect_unreachable: bool = False
    singular: bool = False
    note: str = ""


def rand_q(rng, robot):
    q = rng.uniform(-PI, PI, robot.n)
    for k, L in enumerate(robot.links):
        if L.kind == "P":
            lo, hi = robot.limits[k]
            q[k] = rng.uniform(lo + 0.05, hi - 0.05)
    return q


def make_cases(seed, n_each, families):
    rng = np.random.default_rng(seed)
    out = []
    forms = ["pose", "R", "zyz", "rpy"]
    for i in range(n_each):
        for fam in families:
            if fam == "puma":
                rob = puma_like(rng, str(rng.choice(["standard", "modified"])))
                closed = True
            elif fam == "ur":
                which = [None, None, "ur3", "ur10", "ur5"][i % 5]
                rob = ur_like(rng, which, "standard" if i % 3 else "modified")
                closed = True
            elif fam == "stanford":
                rob = stanford(rng)
                closed = True
            elif fam == "rand6":
                rob = random_arm(rng, 6)
                closed = False
            elif fam in ("rand5", "rand4"):
                rob = random_arm(rng, int(fam[-1]))
                closed = False
            q0 = rand_q(rng, rob)
            sub = rng.uniform()
            form = forms[(i + len(out)) % 4]
            name = f"{fam}-{seed}-{i}"
            T = rob.fk(q0)
            c = Case(name, rob, T, q0, form, expect_closed=closed)
            if fam in ("puma", "ur") and sub < 0.15:
                q0[4] = 0.0                     # wrist singularity
                c.T, c.singular = rob.fk(q0), True
            elif fam in ("puma", "ur", "stanford") and sub < 0.25:
                # joint limits excluding some solutions
                lo = rng.uniform(-2.5, -0.5)
                rob.limits = rob.limits or [None] * rob.n
                k = int(rng.integers(0, 3))
                rob.limits[k] = (min(lo, q0[k] - 0.1), q0[k] + 0.3)
                c.note = f"limits on q{k + 1}"
            elif fam in ("puma", "ur") and sub < 0.33:
                # beyond reach
                T = T.copy()
                T[:3, 3] *= 6.0
                c.T, c.q0, c.expect_unreachable = T, None, True
            elif fam in ("rand5", "rand4") and sub < 0.5:
                # a random pose: unreachable (orientation or position)
                Rr = rz(rng.uniform(-3, 3)) @ rx(rng.uniform(-3, 3)) @ rz(rng.uniform(-3, 3))
                T = Rr.copy()
                T[:3, 3] = rob.fk(rand_q(rng, rob))[:3, 3]
                c.T, c.q0, c.expect_unreachable = T, None, True
            elif fam in ("puma",) and sub < 0.45:
                rob.tool = tr(0.0, 0.0, rng.uniform(0.05, 0.2)) @ rx(rng.uniform(-1, 1))
                c.T = rob.fk(q0)
                c.note = "tool frame (the last frame), target on frame 6"
                c.T = rob.fk(q0, tool=False)
                c.frame = str(rob.n)
            elif fam in ("puma", "ur") and sub < 0.55:
                c.point_c = rng.uniform(-0.1, 0.1, 3)
                c.note = "point target"
            out.append(c)
    return out


def question_of(c: Case, rng):
    form = c.form
    T = c.T.copy()
    pts = {}
    extra = ""
    if c.point_c is not None:
        # target: the point's position and the frame's orientation
        if form == "pose":
            form = "R"
        T[:3, 3] = T[:3, :3] @ c.point_c + T[:3, 3]
        pts["P"] = (str(c.robot.n), c.point_c)
        extra = ", point: P"
    frame = getattr(c, "frame", None)
    if frame:
        extra += f", frame: \"{frame}\""
    c.form = form
    y = "{type: inverse_kinematics, target: " + target_yaml(T, form, rng) + extra + "}"
    return {"yaml": y, "points": pts}


def run(c: Case, workdir, rng):
    q = question_of(c, rng)
    text = yaml_of(c.robot, q, c.name)
    path = os.path.join(workdir, c.name + ".yaml")
    open(path, "w").write(text)
    out = os.path.join(workdir, "out-" + c.name)
    p = subprocess.run([sys.executable, "-m", "robosolve", "solve", path, "--out", out],
                       capture_output=True, text=True, timeout=900)
    problems = []
    if p.returncode != 0:
        return [f"exit {p.returncode}: {p.stderr[-800:]}"], None, path
    ans = json.load(open(os.path.join(out, "results.json")))["answers"]["inverse_kinematics"]
    if "error" in ans:
        return [f"error: {ans['error']}"], ans, path
    sols = ans["numeric"].get("solutions", [])
    chk = _checked_robot(c)
    names = [f"q{k + 1}" for k in range(chk.n)]
    # the rotation robosolve was given (zyz/rpy round trip)
    Rg = R_of_form(c.T, c.form)
    Tg = c.T.copy()
    Tg[:3, :3] = Rg
    qs = []
    for s in sols:
        qv = np.array([s.get(n, 0.0) for n in names])
        qs.append(qv)
        M = chk.fk(qv)
        if c.point_c is not None:
            M = M.copy()
            M[:3, 3] = M[:3, 3] + M[:3, :3] @ c.point_c
            Tg2 = Tg.copy()
            Tg2[:3, 3] = c.T[:3, 3] + c.T[:3, :3] @ c.point_c
            err = np.max(np.abs(M[:3, :4] - Tg2[:3, :4]))
        else:
            err = np.max(np.abs(M[:3, :4] - Tg[:3, :4]))
        if err > 1e-9:
            problems.append(f"solution {s} misses by {err:.2e}")
        if not in_limits(chk, qv):
            problems.append(f"solution {s} outside the limits")
        for k, L in enumerate(chk.links):
            if L.kind == "R" and not (-PI < qv[k] <= PI):
                problems.append(f"solution {s} not wrapped")
    # sorted
    for a, b in zip(qs, qs[1:]):
        for x, y in zip(a, b):
            if abs(x - y) > 1e-9:
                if x > y:
                    problems.append("not sorted")
                break
    un = ans.get("unreachable", False)
    if c.expect_unreachable and not un:
        problems.append(f"expected unreachable, got {len(sols)} solutions")
    if un and not ans.get("reason"):
        problems.append("unreachable without reason")
    if c.q0 is not None:
        q0w = np.array([wrap(v) if L.kind == "R" else v for v, L in zip(c.q0, chk.links)])
        if in_limits(chk, q0w) and not c.singular and not any(close(q0w, s, chk, 1e-6) for s in qs):
            problems.append(f"q0 {np.round(q0w, 6).tolist()} not among the solutions")
    if c.expect_closed and not un and not c.singular and "closed_form" not in ans.get("symbolic", {}):
        problems.append("no closed form")
    # reference count
    Tref = Tg.copy()
    # the frame's pose is fixed by a point target too (same orientation, origin p - R c)
    inside, allref, best = reference(chk, Tref)
    if not c.singular:
        extra_ref = [r for r in inside if not any(close(r, s, chk, 1e-5) for s in qs)]
        if extra_ref:
            problems.append(f"reference finds {len(inside)} in limits, robosolve {len(qs)}; missing "
                            f"{[np.round(r, 5).tolist() for r in extra_ref]}")
        if len(inside) < len(qs):
            problems.append(f"(info) robosolve {len(qs)} > reference {len(inside)}")
    if un and inside:
        problems.append(f"unreachable but the reference finds {len(inside)}")
    return problems, ans, path


def _checked_robot(c):
    """The chain up to the question's frame (no tool when the frame is given)."""
    import copy
    if not getattr(c, "frame", None):
        return c.robot
    r2 = copy.copy(c.robot)
    r2.tool = None
    k = int(c.frame)
    r2.links = c.robot.links[:k]
    r2.limits = c.robot.limits[:k] if c.robot.limits else []
    return r2


def _no_tool(r):
    import copy
    r2 = copy.copy(r)
    r2.tool = None
    return r2


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--n", type=int, default=2)
    ap.add_argument("--family", default="puma,ur,stanford,rand6,rand5,rand4")
    ap.add_argument("--keep", default=None)
    ap.add_argument("--only", default=None)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed + 1000)
    workdir = a.keep or tempfile.mkdtemp(prefix="ikprobe-")
    os.makedirs(workdir, exist_ok=True)
    cases = special_cases() if a.family == "special" else make_cases(a.seed, a.n, a.family.split(","))
    bad = 0
    for c in cases:
        if a.only and a.only != c.name:
            continue
        probs, ans, path = run(c, workdir, rng)
        nsol = len(ans["numeric"].get("solutions", [])) if ans and "numeric" in ans else "-"
        meth = ""
        if ans:
            meth = "closed" if "closed_form" in ans.get("symbolic", {}) else "numeric"
            if ans.get("unreachable"):
                meth += " UNREACH(" + str(ans.get("reason"))[:70] + ")"
        flag = "OK " if not [p for p in probs if not p.startswith("(info)")] else "BAD"
        bad += flag == "BAD"
        print(f"{flag} {c.name:18s} {c.robot.name:14s} {c.form:4s} {c.note or ('singular' if c.singular else ''):22s} "
              f"n={nsol} {meth}", flush=True)
        for p_ in probs:
            print("      ", p_, flush=True)
        if probs:
            print("       file:", path, flush=True)
    print("bad", bad, "of", len(cases), "workdir", workdir)



def special_cases():
    """Hand-made cases: singular poses, a frame in the middle of the chain, datasheet arms."""
    from scipy.optimize import brentq
    out = []
    # UR5 at the wrist singularity q5 = 0 and at q5 = pi
    for k, q5 in enumerate((0.0, PI)):
        rob = ur_like(None, "ur5")
        q0 = np.array([0.4, -1.1, 1.3, -0.8, q5, 0.5])
        out.append(Case(f"ur5-wrist-sing-{k}", rob, rob.fk(q0), q0, "pose", singular=True, note="q5 = %g" % q5))
    # PUMA-like without a shoulder offset, the wrist centre on the axis of joint 1
    links = [Link("R", 0, 0.6, 0, PI / 2), Link("R", 0, 0, 0.43, 0), Link("R", 0, 0, 0, PI / 2),
             Link("R", 0, 0.43, 0, -PI / 2), Link("R", 0, 0, 0, PI / 2), Link("R", 0, 0.1, 0, 0)]
    rob = Robot("puma-noofs", "standard", links, family="puma")
    q2 = 0.9
    fr = lambda q3: rob.fk([0.3, q2, q3, 0, 0, 0], upto=4)[0, 3] ** 2 + rob.fk([0.3, q2, q3, 0, 0, 0], upto=4)[1, 3] ** 2
    rad = lambda q3: math.copysign(math.sqrt(fr(q3)), rob.fk([0, q2, q3, 0, 0, 0], upto=4)[0, 3])
    q3 = brentq(rad, 0.0, 3.1) if rad(0.0) * rad(3.1) < 0 else brentq(rad, -3.1, 0.0)
    q0 = np.array([0.3, q2, q3, 0.7, -0.9, 1.2])
    out.append(Case("puma-shoulder-sing", rob, rob.fk(q0), q0, "pose", singular=True, note="wrist centre on axis 1"))
    # a frame in the middle of the chain: frame 3 and frame 5 of a PUMA-like arm
    rng = np.random.default_rng(5)
    for fr_ in (3, 5):
        rob = puma_like(rng, "standard")
        q0 = rand_q(rng, rob)
        c = Case(f"puma-frame{fr_}", rob, rob.fk(q0, upto=fr_), q0, "R", note=f"frame {fr_}")
        c.frame = str(fr_)
        c.sub = fr_
        out.append(c)
        T = rob.fk(q0, upto=fr_) @ rx(0.3)
        c = Case(f"puma-frame{fr_}-unreach", rob, T, None, "R", expect_unreachable=True, note=f"frame {fr_}")
        c.frame = str(fr_)
        c.sub = fr_
        out.append(c)
    # datasheet UR arms with datasheet limits [-2pi, 2pi]
    for which in ("ur3", "ur10"):
        rob = ur_like(None, which)
        rob.limits = [(-2 * PI, 2 * PI)] * 6
        q0 = np.array([2.5, -0.6, 2.0, -2.9, 1.7, -3.0])
        out.append(Case(f"{which}-datasheet", rob, rob.fk(q0), q0, "rpy", expect_closed=True))
    return out


if __name__ == "__main__":
    main()
