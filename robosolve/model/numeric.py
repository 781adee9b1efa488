"""The chain evaluated with numbers: M, W, H of every frame at one configuration.

Only the small local poses M (each frame in its parent) and their raw, unsimplified
derivatives are symbolic; W = Mdot M^-1, H = Mddot M^-1, L = dM/dq M^-1, the products,
Rivals and Coriolis are done in numpy. No simplified expression built for the report is
evaluated (simplifying H costs seconds and a number needs none of it), every numeric
answer exists even when a symbolic product is too large, and this is an independent
route to cross-check the symbolic one.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.errors import MissingValues


def evaluate(obj, subs) -> np.ndarray:
    """A small sympy matrix (a local pose, a factor) as floats at `subs`."""
    return _num(obj, subs)


def _num(obj, subs) -> np.ndarray:
    m = sp.Matrix(obj).xreplace(subs).evalf(17)
    missing = sorted(s.name for s in m.free_symbols)
    if missing:
        raise MissingValues(missing)
    return np.array(m.tolist(), dtype=float)


def rigid_inverse(m: np.ndarray) -> np.ndarray:
    out = np.eye(4)
    out[:3, :3] = m[:3, :3].T
    out[:3, 3] = -m[:3, :3].T @ m[:3, 3]
    return out


class NumericChain:
    """M0, W0, H0 of each frame at the substitutions `subs` (lazy per quantity)."""

    def __init__(self, model, subs: dict):
        self.model = model
        self.subs = subs
        self._m = {"0": np.eye(4)}
        self._w = {"0": np.zeros((4, 4))}
        self._h = {"0": np.zeros((4, 4))}

    def M0(self, frame: str) -> np.ndarray:
        if frame not in self._m:
            parent = self.model.frames[frame].parent
            self._m[frame] = self.M0(parent) @ self._local(frame)
        return self._m[frame]

    def _local(self, frame: str, order: int = 0) -> np.ndarray:
        """M (order 0), Mdot (1) or Mddot (2) of the frame in its parent, as numbers."""
        key = ("local", frame, order)
        if key not in self._m:
            self._m[key] = _num(self.model.local_derivative(frame, order), self.subs)
        return self._m[key]

    def _relative(self, frame: str, order: int) -> np.ndarray:
        """W (order 1) or H (order 2) of the frame relative to its parent, in the parent."""
        return self._local(frame, order) @ rigid_inverse(self._local(frame))

    def _moved(self, frame: str, a: np.ndarray) -> np.ndarray:
        mp = self.M0(self.model.frames[frame].parent)
        return mp @ a @ rigid_inverse(mp)

    def W0(self, frame: str) -> np.ndarray:
        if frame not in self._w:
            parent = self.model.frames[frame].parent
            self._w[frame] = self.W0(parent) + self._moved(frame, self._relative(frame, 1))
        return self._w[frame]

    def H0(self, frame: str) -> np.ndarray:
        if frame not in self._h:
            parent = self.model.frames[frame].parent
            w_rel = self._moved(frame, self._relative(frame, 1))
            h_rel = self._moved(frame, self._relative(frame, 2))
            self._h[frame] = self.H0(parent) + 2 * self.W0(parent) @ w_rel + h_rel
        return self._h[frame]

    def point0(self, name: str) -> np.ndarray:
        frame, at = self.model.point_local(name)
        p = _num(sp.Matrix([*at, 1]), self.subs)[:, 0]
        return (self.M0(frame) @ p)[:3]

    def L0(self, index: int, frame: str | None = None) -> np.ndarray:
        model = self.model
        frame = frame or model.joint_frame(index)
        total = np.zeros((4, 4))
        for f in model.chain(frame):
            if index in model.joints_in(f):
                m = model.M_local(f)
                dm = _num(m.diff(model.joints[index].symbol), self.subs)
                total += self._moved(f, dm @ rigid_inverse(self._local(f)))
        return total
