"""The numpy operations of the chain computation (core/chain/forward.py's algebra on floats).

Self-contained (numpy only): robosolve's `NumericChain` (core/chain/algebras.NumpyChainAlgebra adds
the inputs evaluated from a ChainDescription) and the notebook's runtime (render/notebook.py
copies this module and forward.py into report.ipynb) use the same source.
"""

import numpy as np


def rigid_inverse(m):
    """[R, t; 0, 1]⁻¹ = [Rᵀ, −Rᵀ t; 0, 1] of a 4×4 pose."""
    out = np.eye(4)
    out[:3, :3] = m[:3, :3].T
    out[:3, 3] = -m[:3, :3].T @ m[:3, 3]
    return out


class NumpyOperations:
    """identity, zero, products, m a m⁻¹, sums and points on 4×4 float arrays (no normal forms:
    `tidy` and `expand` return their argument)."""

    @staticmethod
    def identity():
        return np.eye(4)

    @staticmethod
    def zero():
        return np.zeros((4, 4))

    @staticmethod
    def compose(a, b):
        return a @ b

    @staticmethod
    def inverse(m):
        return rigid_inverse(m)

    @staticmethod
    def act(m, a):
        return m @ a @ rigid_inverse(m)

    conjugate = act

    @staticmethod
    def add(a, b):
        return a + b

    @staticmethod
    def scale(a, s):
        return a * s

    @staticmethod
    def mul(a, b):
        return a @ b

    @staticmethod
    def tidy(a):
        return a

    @staticmethod
    def expand(a):
        return a

    @staticmethod
    def point(m, p):
        """The first three entries of m p, p homogeneous (4 entries)."""
        return (m @ p)[:3]
