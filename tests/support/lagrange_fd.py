"""A numeric Lagrange reference for serial robots: finite differences on Robotics Toolbox's
forward kinematics only (its `fkine_all`, which the tests check against robosolve's own
poses), never on its dynamics. (Robotics Toolbox's `inertia`/`rne` are wrong for modified-DH
prismatic joints: an asymmetric mass matrix.)

M(q) = Σ mᵢ Jvᵢᵀ Jvᵢ + Jωᵢᵀ Rᵢ Iᵢ Rᵢᵀ Jωᵢ (Jacobians of the centres of mass by central
differences), c = Ṁ q̇ − ½ ∂(q̇ᵀ M q̇)/∂q, g = ∂U/∂q, τ = M q̈ + c + g.
"""

from __future__ import annotations

import numpy as np


class FiniteDifferenceLagrange:
    def __init__(self, robot, gravity=(0.0, 0.0, -9.81)):
        self.robot = robot
        self.n = robot.n
        self.gravity = np.asarray(gravity, dtype=float)

    def _poses(self, q):
        poses = self.robot.fkine_all(q)
        return [poses[i + 1].A for i in range(self.n)]

    def _com_jacobians(self, q, i, h=1e-6):
        com = np.append(self.robot.links[i].r, 1.0)
        pose = self._poses(q)[i]
        jv, jw = np.zeros((3, self.n)), np.zeros((3, self.n))
        for j in range(self.n):
            e = np.zeros(self.n)
            e[j] = h
            plus, minus = self._poses(q + e)[i], self._poses(q - e)[i]
            jv[:, j] = ((plus @ com)[:3] - (minus @ com)[:3]) / (2 * h)
            w = (plus[:3, :3] - minus[:3, :3]) / (2 * h) @ pose[:3, :3].T
            jw[:, j] = [w[2, 1], w[0, 2], w[1, 0]]
        return jv, jw, pose[:3, :3]

    def mass_matrix(self, q):
        q = np.asarray(q, dtype=float)
        out = np.zeros((self.n, self.n))
        for i, link in enumerate(self.robot.links):
            jv, jw, r = self._com_jacobians(q, i)
            out += link.m * jv.T @ jv + jw.T @ r @ link.I @ r.T @ jw
        return out

    def potential(self, q):
        poses = self._poses(q)
        return sum(-link.m * self.gravity @ (poses[i] @ np.append(link.r, 1.0))[:3]
                   for i, link in enumerate(self.robot.links))

    def torques(self, q, qd, qdd, h=1e-4):
        q, qd, qdd = (np.asarray(x, dtype=float) for x in (q, qd, qdd))
        steps = h * np.eye(self.n)
        dm = [(self.mass_matrix(q + s) - self.mass_matrix(q - s)) / (2 * h) for s in steps]
        m_dot = sum(dm[k] * qd[k] for k in range(self.n))
        c = m_dot @ qd - 0.5 * np.array([qd @ d @ qd for d in dm])
        g = np.array([(self.potential(q + s) - self.potential(q - s)) / (2 * h) for s in steps])
        return self.mass_matrix(q) @ qdd + c + g
