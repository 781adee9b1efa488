"""The chain evaluated with numbers: M, W, H of every frame at one configuration.

Only the small local inputs (each frame's pose in its parent, the joints' twists, Ä) are
symbolic, evaluated once; the products, Rivals and Coriolis are the one chain computation
(core/chain/forward.py) over numpy (core/chain/algebras.NumpyChainAlgebra). No simplified expression
built for the report is evaluated (simplifying H costs seconds and a number needs none of
it), every numeric answer exists even when a symbolic product is too large, and this is an
independent route to cross-check the symbolic one.
"""

from __future__ import annotations

import numpy as np

from robosolve.core.chain.algebras import NumpyChainAlgebra, evaluate
from robosolve.core.chain.numpy_algebra import rigid_inverse
from robosolve.core.chain.forward import forward

__all__ = ["NumericChain", "evaluate", "rigid_inverse"]


class NumericChain:
    """M0, W0, H0, L0 and points at the substitutions `subs` (lazy per quantity)."""

    def __init__(self, model, subs: dict):
        self.model = model
        self.subs = subs
        self.data = forward(model.description, NumpyChainAlgebra(model.description, subs))

    def M0(self, frame: str) -> np.ndarray:
        return self.data.M(frame)

    def W0(self, frame: str) -> np.ndarray:
        return self.data.W(frame)

    def H0(self, frame: str) -> np.ndarray:
        return self.data.H(frame)

    def point0(self, name: str) -> np.ndarray:
        return self.data.point(name)

    def L0(self, index: int, frame: str | None = None) -> np.ndarray:
        return self.data.L(index, frame)
