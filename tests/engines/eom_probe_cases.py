"""Problem generator for probing the equations of motion against Robotics Toolbox (issue 26).

Each case is a plain description (DH rows, joint types, bodies with mass, centre of mass and a
full 3x3 inertia tensor about it, gravity, optional flange payload): `problem_yaml` writes it
as a robosolve problem file, `rtb_twin` builds the same robot as an RTB DHRobot."""

from __future__ import annotations

import numpy as np

NAMES_STD = ("theta", "d", "a", "alpha")
NAMES_MDH = ("alpha", "a", "theta", "d")


def _f(x: float) -> str:
    return repr(float(x))


def _angle(x: float) -> str:
    """±pi/2 written as the exact expression a problem author would write."""
    for k, text in ((1, "pi/2"), (-1, "-pi/2"), (2, "pi"), (0, "0")):
        if abs(x - k * np.pi / 2) < 1e-12:
            return text
    return _f(x)


def random_inertia(rng, scale: float) -> np.ndarray:
    """A physical inertia tensor (principal moments obeying the triangle inequality), rotated."""
    p = rng.uniform(0.3, 1.0, 3) * scale
    p[2] = rng.uniform(abs(p[0] - p[1]) + 0.05 * scale, p[0] + p[1])
    a, b, c = rng.uniform(-np.pi, np.pi, 3)
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    rz = np.array([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rx = np.array([[1, 0, 0], [0, cc, -sc], [0, sc, cc]])
    r = rz @ ry @ rx
    out = r @ np.diag(p) @ r.T
    return np.round((out + out.T) / 2, 6)


def random_case(seed: int, n: int = 6, modified: bool = False, prismatic=(), gravity=None,
                payload: float = 0.0, name: str | None = None) -> dict:
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        a = round(float(rng.uniform(-0.5, 0.5)), 4) if rng.random() < 0.7 else 0.0
        d = round(float(rng.uniform(-0.4, 0.4)), 4) if rng.random() < 0.7 else 0.0
        alpha = float(rng.choice([0, np.pi / 2, -np.pi / 2, round(float(rng.uniform(-3, 3)), 4)]))
        offset = round(float(rng.uniform(-1, 1)), 4) if rng.random() < 0.4 else 0.0
        theta = round(float(rng.uniform(-1, 1)), 4) if (i in prismatic) else 0.0
        rows.append({"a": a, "d": d, "alpha": alpha, "offset": offset, "theta": theta})
    bodies = []
    for i in range(n):
        m = round(float(rng.uniform(0.5, 10)), 3)
        com = np.round(rng.uniform(-0.2, 0.2, 3), 4)
        inertia = random_inertia(rng, rng.uniform(0.005, 0.3))
        bodies.append({"m": m, "com": com, "I": inertia})
    if gravity is None:
        gravity = [0.0, 0.0, -9.81]
    return {"name": name or f"probe-{seed}", "n": n, "modified": modified,
            "prismatic": tuple(prismatic), "rows": rows, "bodies": bodies,
            "gravity": list(map(float, gravity)), "payload": payload}


def problem_yaml(case: dict, at: dict | None = None, extra_questions: str = "",
                 symbolic_params: bool = False) -> str:
    n = case["n"]
    out = ["robosolve: 1", f"name: {case['name']}", "parameters:"]
    gx, gy, gz = case["gravity"]
    out.append("  g: 9.81")
    out.append("joints:")
    for i in range(n):
        kind = "prismatic" if i in case["prismatic"] else "revolute"
        out.append(f"  - {{name: q{i + 1}, type: {kind}}}")
    out.append("dh:")
    out.append(f"  convention: {'modified' if case['modified'] else 'standard'}")
    out.append("  rows:")
    for i, r in enumerate(case["rows"]):
        q = f"q{i + 1}"
        if i in case["prismatic"]:
            theta = _f(r["theta"])
            d = f"{q} + {_f(r['offset'])}" if r["offset"] else q
        else:
            theta = f"{q} + {_f(r['offset'])}" if r["offset"] else q
            d = _f(r["d"])
        out.append(f"    - {{theta: '{theta}', d: '{d}', a: {_f(r['a'])}, alpha: {_angle(r['alpha'])}}}")
    out.append(f"gravity: [{_f(gx)}, {_f(gy)}, {_f(gz)}]")
    out.append("bodies:")
    for i, b in enumerate(case["bodies"]):
        com = ", ".join(_f(v) for v in b["com"])
        inertia = ", ".join("[" + ", ".join(_f(v) for v in row) + "]" for row in b["I"])
        out.append(f"  - {{name: link{i + 1}, frame: \"{i + 1}\", mass: {_f(b['m'])}, com: [{com}],"
                   f" inertia: [{inertia}]}}")
    if case["payload"]:
        out.append(f"  - {{name: payload, frame: \"{n}\", mass: {_f(case['payload'])},"
                   f" point: [0, 0, 0.05]}}")
    if case.get("force"):
        f = case["force"]
        vec = lambda v: "[" + ", ".join(_f(x) for x in v) + "]"
        out.append("forces:")
        out.append(f"  - {{name: push, frame: \"{f['frame']}\", at: {vec(f['at'])}, force: {vec(f['force'])},"
                   f" torque: {vec(f['torque'])}, in: \"{f['in']}\"}}")
    out.append("questions:")
    if at:
        body = ", ".join(f"{k}: {_f(v)}" for k, v in at.items())
        out.append(f"  - {{type: equations_of_motion, at: {{{body}}}}}")
    else:
        out.append("  - {type: equations_of_motion}")
    out.append(extra_questions)
    return "\n".join(out) + "\n"


def rtb_twin(case: dict):
    import roboticstoolbox as rtb
    n = case["n"]
    links = []
    for i, (r, b) in enumerate(zip(case["rows"], case["bodies"])):
        m, com, inertia = b["m"], np.array(b["com"], dtype=float), np.array(b["I"], dtype=float)
        if case["payload"] and i == n - 1:
            # lump the payload (a point at [0, 0, 0.05] of the last frame) into the last link
            mp, p = case["payload"], np.array([0, 0, 0.05])
            total = m + mp
            c = (m * com + mp * p) / total
            def shift(mass, at):
                d = at - c
                return mass * (d @ d * np.eye(3) - np.outer(d, d))
            inertia = inertia + shift(m, com) + shift(mp, p)
            m, com = total, c
        kw = dict(a=r["a"], alpha=r["alpha"], m=m, r=list(com), I=inertia, Jm=0.0, G=1.0, B=0.0,
                  Tc=[0.0, 0.0])
        if i in case["prismatic"]:
            cls = rtb.PrismaticMDH if case["modified"] else rtb.PrismaticDH
            links.append(cls(theta=r["theta"], offset=r["offset"], **kw))
        else:
            cls = rtb.RevoluteMDH if case["modified"] else rtb.RevoluteDH
            links.append(cls(d=r["d"], offset=r["offset"], **kw))
    return rtb.DHRobot(links, gravity=case["gravity"])


def random_state(rng, n: int):
    q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, n))
    return q, qd, qdd


def at_of(q, qd, qdd) -> dict:
    at = {}
    for i in range(len(q)):
        at[f"q{i + 1}"] = q[i]
    for i in range(len(q)):
        at[f"q{i + 1}_dot"] = qd[i]
    for i in range(len(q)):
        at[f"q{i + 1}_ddot"] = qdd[i]
    return at


def external_generalized(case: dict, robot, q) -> np.ndarray:
    """Jᵀ·(F, τ) of the case's force (at a point of the last frame), in frame-0 components:
    what the force adds to the right-hand side M q̈ + c + g = actuators + external."""
    f = case.get("force")
    if not f:
        return np.zeros(case["n"])
    assert f["frame"] == str(case["n"])
    T = robot.fkine(q).A
    R = T[:3, :3]
    J = robot.jacob0(q)
    p = R @ np.asarray(f["at"], float)
    px = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    jv = J[:3] - px @ J[3:]
    rot = R if f["in"] == f["frame"] else np.eye(3)
    F0, T0 = rot @ np.asarray(f["force"], float), rot @ np.asarray(f["torque"], float)
    return jv.T @ F0 + J[3:].T @ T0
