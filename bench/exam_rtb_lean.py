"""A lean Robotics Toolbox script for problems/exam-2r-full.yaml (benchmark reference, issue 26).

The exam's ten questions numerically, written the way a good Robotics Toolbox user would write
them for speed: the toolbox where it is fast (`fkine`, `jacob0`, `jacob0_dot`, `ikine_LM`, the C
`rne` / `inertia` / `gravload`, `rne` on the whole trajectory at once), numpy for the rest
(the follower force through a 2×2 moment-arm formula instead of `fkine_all` per call, the
closed-loop right-hand side from `inertia` and `rne` without `accel`'s extra passes, the
singularity scan on a coarse grid refined by bisection), `solve_ivp` (LSODA, the old script's
tolerances) and three plots with matplotlib (`tight_layout`, no tight bounding box).
bench/exam_rtb_reference.py is the older, slower way (10 s: `fkine_all` and `accel` at every
right-hand-side call, 3 600 `jacob0` calls for the scan); both print the same answers.

    python bench/exam_rtb_lean.py OUT_DIR
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import roboticstoolbox as rtb  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402
from spatialmath import SE3  # noqa: E402

L1, L2, m1, m2, m3, F, g = 0.5, 0.4, 4.0, 3.0, 1.0, 5.0, 9.81


def arm():
    """Vertical 2R about x0, z0 up, as a DH robot (the toolbox's C rne): the base turns the
    DH z axis onto x0 and the links' x axes onto +y0 at q = 0; link 2 carries its rod and
    the payload at E."""
    i1 = m1 * L1**2 / 12
    m23 = m2 + m3
    c2 = (m2 * L2 / 2 + m3 * L2) / m23
    i2 = m2 * L2**2 / 12 + m2 * (c2 - L2 / 2) ** 2 + m3 * (L2 - c2) ** 2
    base = SE3(np.array([[0, 0, 1, 0], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1.0]]))
    return rtb.DHRobot([rtb.RevoluteDH(a=L1, m=m1, r=[-L1 / 2, 0, 0], I=[0, i1, i1]),
                        rtb.RevoluteDH(a=L2, m=m23, r=[c2 - L2, 0, 0], I=[0, i2, i2])],
                       base=base, gravity=[0, 0, -g], name="exam2r")


def force_torques(q):
    """Joint torques of F on the middle of link 2, perpendicular to it: its moment arms about
    the two joints (q may be one configuration or rows of them)."""
    q = np.asarray(q, dtype=float)
    return -F * np.stack([L1 * np.cos(q[..., 1]) + L2 / 2, np.full(q[..., 1].shape, L2 / 2)], axis=-1)


def singular_q2(robot, q1=0.3, n=360):
    """det of the (y, z) Jacobian = 0 in q2 over (-pi, pi]: a coarse scan, then bisection."""
    det = lambda t: np.linalg.det(robot.jacob0([q1, t])[1:3])  # noqa: E731
    step = 2 * np.pi / n
    grid = -np.pi + (np.arange(n) + 0.5) * step
    vals = np.array([det(t) for t in grid])
    roots = []
    for k in np.nonzero(np.sign(vals) != np.sign(np.roll(vals, -1)))[0]:
        a, b, fa = grid[k], grid[k] + step, vals[k]
        for _ in range(50):
            mid = 0.5 * (a + b)
            fm = det(mid)
            a, b, fa = (mid, b, fm) if np.sign(fm) == np.sign(fa) else (a, mid, fa)
        roots.append(0.5 * (a + b))
    return np.angle(np.exp(1j * np.array(roots)))


def bang_bang(q_from, q_to, amax, n=401):
    dist = q_to - q_from
    tf = max(2 * np.sqrt(np.abs(dist) / amax))
    acc = 4 * dist / tf**2
    t = np.linspace(0, tf, n)
    half = (t <= tf / 2)[:, None]
    qt = np.where(half, q_from + 0.5 * acc * t[:, None] ** 2, q_to - 0.5 * acc * (tf - t[:, None]) ** 2)
    qdt = np.where(half, acc * t[:, None], acc * (tf - t[:, None]))
    qddt = np.where(half, acc, -acc)
    return tf, acc, t, qt, qdt, qddt


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    robot = arm()
    q = np.array([np.pi / 6, np.pi / 3])
    qd, qdd = np.array([1, -0.5]), np.array([0, 1.0])
    r = {"M": robot.fkine(q).A}                                         # 1
    j0 = robot.jacob0(q)
    r["v"] = j0 @ qd                                                    # 2
    r["a"] = j0 @ qdd + robot.jacob0_dot(q, qd) @ qd
    jp = j0[1:3]                                                        # 3: (y, z) of E
    r["det"] = np.linalg.det(jp)
    r["singular"] = singular_q2(robot)
    r["com_J"] = [robot.jacob0(q, end=robot.links[k]) for k in (0, 1)]
    r["statics"] = -jp.T @ np.array([0, -20])                           # 4
    r["weight"] = robot.gravload(q)
    u, s, _vt = np.linalg.svd(jp)                                       # 5
    r["ellipses"] = (u, s, 1 / s, s**2)
    r["rates"] = np.linalg.solve(jp, [0, 0.5])
    target = SE3.Trans(0, 0.6, 0.3)                                     # 6
    mask = [1, 1, 1, 0, 0, 0]
    r["ik"] = [robot.ikine_LM(target, q0=q0, mask=mask).q for q0 in ([0.5, 1], [1, -1])]
    q_from, q_to = np.zeros(2), np.array([np.pi / 2, -np.pi / 3])       # 7: bang-bang, synced
    tf, acc, t, qt, qdt, qddt = bang_bang(q_from, q_to, np.array([2.0, 3.0]))
    r["eom"] = (robot.inertia(q), robot.rne(q, qd, np.zeros(2), gravity=[0, 0, 0]),  # 8
                robot.gravload(q), robot.rne(q, qd, qdd) - force_torques(q))
    tau = robot.rne(qt, qdt, qddt) - force_torques(qt)                  # 9
    kp = 5000.0                                                         # 10: tau = Kp e

    def desired(time):
        k = min(max(time, 0), tf)
        return q_from + 0.5 * acc * k**2 if k <= tf / 2 else q_to - 0.5 * acc * (tf - k) ** 2

    def rhs(time, x):
        qq, vv = x[:2], x[2:]
        torque = kp * (desired(time) - qq) + force_torques(qq)
        return np.concatenate([vv, np.linalg.solve(robot.inertia(qq), torque - robot.rne(qq, vv, np.zeros(2)))])

    sim = solve_ivp(rhs, (0, tf + 0.5), np.zeros(4), method="LSODA", rtol=1e-6, atol=1e-9, dense_output=True)
    ts = np.linspace(0, tf + 0.5, 801)
    xs = sim.sol(ts)[:2].T
    err = np.array([desired(k) for k in ts]) - xs
    for name, ys, ylabels, series in (("profile", [qt, qdt, qddt], ["q [rad]", "q̇ [rad/s]", "q̈ [rad/s²]"], t),
                                      ("torques", [tau], ["τ [N·m]"], t),
                                      ("tracking", [xs, err], ["q [rad]", "e [rad]"], ts)):
        fig, axes = plt.subplots(len(ys), 1, figsize=(7, 2.4 * len(ys)), squeeze=False)
        for ax, y, lab in zip(axes[:, 0], ys, ylabels):
            ax.plot(series, y[:, 0], label="joint 1")
            ax.plot(series, y[:, 1], label="joint 2")
            ax.set_xlabel("t [s]")
            ax.set_ylabel(lab)
            ax.legend()
            ax.grid(True)
        axes[0, 0].set_title(f"exam 2R: {name}")
        fig.tight_layout()
        fig.savefig(out / f"{name}.png", dpi=100)
        plt.close(fig)
    brief = {k: r[k] for k in ("det", "singular", "statics", "weight", "rates", "ik")}
    brief["C"] = r["eom"][3]
    brief["max_error"] = np.abs(err).max(axis=0)
    print({k: np.round(np.asarray(v, dtype=float), 6).tolist() for k, v in brief.items()})


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/exam-rtb-lean"))
