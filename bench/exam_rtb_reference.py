"""The numeric toolbox's way of doing problems/exam-2r-full.yaml (benchmark reference).

What a user writes instead of robosolve: Robotics Toolbox for Python + scipy + matplotlib,
the exam's ten questions numerically (no symbolic answer, no derivation), with 3 PNG plots
(profile, torques, closed-loop tracking). Timed as a whole process by bench/exam_vs_rtb.py.

    python bench/exam_rtb_reference.py OUT_DIR
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import roboticstoolbox as rtb  # noqa: E402
from roboticstoolbox import ET, Link  # noqa: E402
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


def force_torques(robot, q):
    """Joint torques of the force F on the middle of link 2, perpendicular to it
    ((0, 0, -F) in the course's frame 2): tau_i = (z_i x (p - o_i)) . f."""
    frames = robot.fkine_all(q)
    axis = frames[0].R[:, 2]
    link = frames[2].R[:, 0]
    p = frames[2].t - L2 / 2 * link
    f = -F * np.cross(axis, link)
    return np.array([np.cross(axis, p - frames[i].t) @ f for i in (0, 1)])


def main(out: Path):
    out.mkdir(parents=True, exist_ok=True)
    robot = arm()
    q = np.array([np.pi / 6, np.pi / 3])
    qd, qdd = np.array([1, -0.5]), np.array([0, 1.0])
    results = {}
    results["M"] = robot.fkine(q).A                                     # 1
    j0 = robot.jacob0(q)
    results["v"] = j0 @ qd                                              # 2
    results["a"] = j0 @ qdd + robot.jacob0_dot(q, qd) @ qd
    jp = j0[1:3]                                                        # 3: (y, z) of E
    results["det"] = np.linalg.det(jp)
    step = 2 * np.pi / 3600                            # a scan of (-pi, pi] for det = 0
    grid = np.arange(3600) * step - np.pi + step / 2
    dets = np.array([np.linalg.det(robot.jacob0([0.3, t])[1:3]) for t in grid])
    change = np.nonzero(np.sign(dets) != np.sign(np.roll(dets, -1)))[0]
    results["singular"] = np.angle(np.exp(1j * (grid[change] + step / 2)))
    results["com_J"] = [robot.jacob0(q, end=robot.links[k]) for k in (0, 1)]
    results["statics"] = -jp.T @ np.array([0, -20])                     # 4
    results["weight"] = robot.gravload(q)
    u, s, vt = np.linalg.svd(jp)                                        # 5
    results["ellipses"] = (u, s, 1 / s, s**2)
    results["rates"] = np.linalg.solve(jp, [0, 0.5])
    target = SE3.Trans(0, 0.6, 0.3)                                     # 6
    mask = [1, 1, 1, 0, 0, 0]
    sols = [robot.ikine_LM(target, q0=q0, mask=mask) for q0 in ([0.5, 1], [1, -1])]
    results["ik"] = [s.q for s in sols]
    q_from, q_to = np.zeros(2), np.array([np.pi / 2, -np.pi / 3])       # 7: bang-bang, synced
    dist, amax = q_to - q_from, np.array([2.0, 3.0])
    tf = max(2 * np.sqrt(np.abs(dist) / amax))
    acc = 4 * dist / tf**2
    t = np.linspace(0, tf, 401)
    half = t <= tf / 2
    qt = np.where(half[:, None], q_from + 0.5 * acc * t[:, None] ** 2,
                  q_to - 0.5 * acc * (tf - t[:, None]) ** 2)
    qdt = np.where(half[:, None], acc * t[:, None], acc * (tf - t[:, None]))
    qddt = np.where(half[:, None], acc, -acc)
    results["eom"] = (robot.inertia(q), robot.rne(q, qd, np.zeros(2), gravity=[0, 0, 0]), robot.gravload(q),  # 8
                      robot.rne(q, qd, qdd) - force_torques(robot, q))
    tau = robot.rne(qt, qdt, qddt) - np.array([force_torques(robot, a) for a in qt])  # 9
    kp = 5000.0                                                         # 10: tau = Kp e

    def desired(time):
        k = min(max(time, 0), tf)
        if k <= tf / 2:
            return q_from + 0.5 * acc * k**2
        return q_to - 0.5 * acc * (tf - k) ** 2

    def rhs(time, x):
        qq, vv = x[:2], x[2:]
        torque = kp * (desired(time) - qq) + force_torques(robot, qq)
        return np.concatenate([vv, robot.accel(qq, vv, torque)])

    sim = solve_ivp(rhs, (0, tf + 0.5), np.zeros(4), method="LSODA", rtol=1e-6, atol=1e-9,
                    dense_output=True)
    ts = np.linspace(0, tf + 0.5, 801)
    xs = sim.sol(ts)
    for name, ys, ylabel, series in (
        ("profile", [qt, qdt, qddt], ["q [rad]", "q̇ [rad/s]", "q̈ [rad/s²]"], t),
        ("torques", [tau], ["τ [N·m]"], t),
        ("tracking", [xs[:2].T, (np.array([desired(k) for k in ts]) - xs[:2].T)],
         ["q [rad]", "e [rad]"], ts),
    ):
        fig, axes = plt.subplots(len(ys), 1, figsize=(7, 2.4 * len(ys)), squeeze=False)
        for ax, y, lab in zip(axes[:, 0], ys, ylabel):
            ax.plot(series, y[:, 0], label="joint 1")
            ax.plot(series, y[:, 1], label="joint 2")
            ax.set_xlabel("t [s]")
            ax.set_ylabel(lab)
            ax.legend()
            ax.grid(True)
        axes[0, 0].set_title(f"exam 2R: {name}")
        fig.savefig(out / f"{name}.png", dpi=110, bbox_inches="tight")
        plt.close(fig)
    brief = {k: results[k] for k in ("det", "singular", "statics", "weight", "rates", "ik")}
    brief["C"] = results["eom"][3]
    brief["max_error"] = np.abs(np.array([desired(k) for k in ts]) - xs[:2].T).max(axis=0)
    print({k: np.round(np.asarray(v, dtype=float), 6).tolist() for k, v in brief.items()})


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "/tmp/exam-rtb"))
