"""Robotics Toolbox reference of bench/bench_task.py: the same numeric work as
`robosolve solve bench/problems/task-2r-line.yaml`, written as an RTB user would.

    python bench/task_rtb_reference.py            (prints the answers as JSON)

The vertical 2R arm of problems/workspace-2r-line.yaml as a planar DHRobot (its y-z plane is the
robot's x-y plane, gravity along -y): rods m1 = 4 kg (L1 = 0.5 m), m2 = 3 kg (L2 = 0.4 m), a 1 kg
payload at E (merged into link 2), a 5 N force at the middle of link 2, perpendicular to it
(`force: [0, 0, -F]` in frame 2's axes: it turns with the link).
1. the line (0.7, 0.2) -> (0.3, 0.5) m, trapezoidal 0.5 m/s, 2 m/s^2: `ctraj` on 200 samples
   timed by `trapezoidal_func`, `ikine_LM` per sample (started from the previous sample, the
   first from the elbow-up guess), q_dot = J^-1 x_dot with `jacob0` per sample, q_ddot by
   np.gradient; max |q_dot|, max |q_ddot|, min singular value of J;
2. the work-space PD with gravity compensation tau = J^T (Kp e + Kd e_dot) + g(q),
   Kp = 2000, Kd = 100, over 2 s from the line's start at rest: `solve_ivp` (DOP853, the same
   rtol = 1e-10, atol = 1e-12 as robosolve) of M(q) q_ddot = tau + f_ext - rne(q, q_dot, 0) with
   `inertia`, `rne`, `gravload`, `jacob0`; restarted at the timing law's switching instants;
   max |e| and final e on 2001 samples of the dense output.
No plotting.
"""

from __future__ import annotations

import json

import numpy as np
import roboticstoolbox as rtb
from scipy.integrate import solve_ivp
from spatialmath import SE3

L1, L2, m1, m2, m3, F, G = 0.5, 0.4, 4.0, 3.0, 1.0, 5.0, 9.81
A, B = np.array([0.7, 0.2]), np.array([0.3, 0.5])
VMAX, AMAX, KP, KD, DURATION, N = 0.5, 2.0, 2000.0, 100.0, 2.0, 200


def arm():
    # link 2 + payload: mass, centre of mass (from the link's end frame) and inertia about it
    m2p = m2 + m3
    c2 = (m2 * L2 / 2 + m3 * L2) / m2p
    izz2 = m2 * L2 ** 2 / 12 + m2 * (c2 - L2 / 2) ** 2 + m3 * (L2 - c2) ** 2
    izz1 = m1 * L1 ** 2 / 12
    kw = dict(Jm=0, B=0, Tc=[0, 0], G=1)
    links = [rtb.RevoluteDH(a=L1, m=m1, r=[-L1 / 2, 0, 0], I=[0, izz1, izz1, 0, 0, 0], **kw),
             rtb.RevoluteDH(a=L2, m=m2p, r=[-(L2 - c2), 0, 0], I=[0, izz2, izz2, 0, 0, 0], **kw)]
    robot = rtb.DHRobot(links, name="2R", gravity=[0, -G, 0])
    mid = rtb.DHRobot([rtb.RevoluteDH(a=L1), rtb.RevoluteDH(a=L2 / 2)], name="2R-mid")  # where F acts
    return robot, mid


def line(robot):
    L = np.linalg.norm(B - A)
    T = L / VMAX + VMAX / AMAX                     # trapezoidal (L >= v^2/a here)
    prof = rtb.trapezoidal_func(0.0, 1.0, T, VMAX / L)
    t = np.linspace(0, T, N)
    s, sd, _ = prof(t)
    poses = rtb.ctraj(SE3(*A, 0), SE3(*B, 0), s=s)   # s=: the path fraction (t would be re-timed)
    q = np.empty((N, 2))
    guess = np.array([-0.3, 1.3])
    for k, pose in enumerate(poses):
        sol = robot.ikine_LM(pose, q0=guess, mask=[1, 1, 0, 0, 0, 0], tol=1e-12)
        if not sol.success:
            raise SystemExit(f"ikine_LM failed at sample {k}")
        q[k] = guess = sol.q
    xdot = np.outer(sd, (B - A))                   # dx/dt = (b - a) ds/dt, s normalised
    J = np.array([robot.jacob0(qk)[:2] for qk in q])
    qd = np.linalg.solve(J, xdot[..., None])[..., 0]
    qdd = np.gradient(qd, t, axis=0)
    sv = np.linalg.svd(J, compute_uv=False).min()
    return dict(T=T, length=L, start=q[0].tolist(), end=q[-1].tolist(),
                max_joint_velocity=np.abs(qd).max(0).tolist(),
                max_joint_acceleration=np.abs(qdd).max(0).tolist(), min_singular_value=float(sv)), prof, q[0]


def simulate(robot, mid, prof, q0):
    L = np.linalg.norm(B - A)
    T = L / VMAX + VMAX / AMAX

    def desired(t):
        s, sd, _ = prof(min(t, T))
        return A + s * (B - A), (sd if t < T else 0.0) * (B - A)

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        xd, vd = desired(t)
        J = robot.jacob0(q)[:2]
        e, ed = xd - robot.fkine(q).t[:2], vd - J @ qd
        tau = J.T @ (KP * e + KD * ed) + robot.gravload(q)
        Tm = mid.fkine(q)                          # F = 5 N along -y of link 2's frame (a follower force)
        f = mid.jacob0(q)[:2].T @ (-F * Tm.R[:2, 1])
        return np.concatenate([qd, np.linalg.solve(robot.inertia(q), tau + f - robot.rne(q, qd, np.zeros(2)))])

    tb = prof.tb
    breaks = [0.0, tb, T - tb, T, DURATION]
    grid = np.linspace(0, DURATION, 2001)
    y, ts, ys = np.r_[q0, 0.0, 0.0], [], []
    for a, b in zip(breaks[:-1], breaks[1:]):
        tt = grid[(grid >= a) & (grid < b)] if b < DURATION else grid[grid >= a]
        sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-10, atol=1e-12, dense_output=True)
        ts.append(tt), ys.append(sol.sol(tt))
        y = sol.y[:, -1]
    t, Y = np.concatenate(ts), np.concatenate(ys, axis=1)
    x = np.array([robot.fkine(qk).t[:2] for qk in Y[:2].T])
    err = np.array([desired(tk)[0] for tk in t]) - x
    return dict(max_error=np.abs(err).max(0).tolist(), final_error=err[-1].tolist(),
                t_max_error=t[np.abs(err).argmax(0)].tolist())


def main():
    robot, mid = arm()
    answers, prof, q0 = line(robot)
    control = simulate(robot, mid, prof, q0)
    print(json.dumps({"line": answers, "work-space-pd": control}, indent=1))


if __name__ == "__main__":
    main()
