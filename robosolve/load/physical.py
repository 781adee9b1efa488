"""Whether a body's mass distribution can exist: the checks of an inertia tensor and of a
pseudo-inertia matrix, on their numeric values (the loader skips them while a value is unknown).

- An inertia tensor I about the centre of mass must be positive semi-definite (principal
  moments ≥ 0): otherwise M(q) can lose its sign. A rigid body also meets the triangle
  inequalities (each principal moment at most the sum of the other two), but published data
  sets lump the rotor inertia of a link's motor into the link (the PUMA 560 of Armstrong,
  Khatib and Burdick, problems/puma560-dynamics.yaml, breaks them twice); that does not harm
  M(q), which stays positive definite, so `inertia_issue(..., triangle=False)` (the loader's
  call) accepts it, and `triangle=True` checks them too. The loader warns of a broken one
  (`triangle_issue`, with why it can still be right): the report and the CLI say it.
- A pseudo-inertia matrix J = ∫ [r; 1][r; 1]ᵀ dm is physical exactly when it is positive
  semi-definite (its [4,4] entry, the mass, then non-negative): that one condition contains the
  triangle inequalities of the inertia about the centre of mass.
"""

from __future__ import annotations

import numpy as np

TOLERANCE = 1e-9          # relative to the largest entry: round-off in the given values


def _fmt(x: float) -> str:
    return f"{x:.6g}"


def _min_eig(m: np.ndarray) -> float:
    return float(np.linalg.eigvalsh((m + m.T) / 2).min())


def _moments(values):
    """(scale, eigenvalues, names, the moments shown, the principal moments' words)."""
    inertia = np.asarray(values, dtype=float)
    scale = max(float(np.abs(inertia).max()), 1e-300)
    moments = np.linalg.eigvalsh(inertia)
    diagonal = not np.any(inertia - np.diag(np.diag(inertia)))
    names = ("Ixx", "Iyy", "Izz") if diagonal else ("I1", "I2", "I3")
    shown = np.diag(inertia) if diagonal else moments
    where = "" if diagonal else f" (principal moments {', '.join(_fmt(m) for m in moments)})"
    return scale, moments, names, shown, where


def inertia_issue(values, triangle: bool = True) -> str | None:
    """Why the 3x3 inertia tensor `values` (floats) cannot be a body's, or None."""
    scale, moments, names, shown, where = _moments(values)
    if moments.min() < -TOLERANCE * scale:
        neg = [n for n, m in zip(names, shown) if m < -TOLERANCE * scale]
        return ("the inertia tensor is not positive semi-definite" + where
                + (f": {', '.join(neg)} < 0" if neg else "") + "; no body has it")
    broken = triangle_issue(values) if triangle else None
    return broken + "; no body has it" if broken else None


def triangle_issue(values) -> str | None:
    """The first triangle inequality (each principal moment at most the sum of the other two)
    that the 3x3 inertia tensor `values` breaks, in words, or None."""
    scale, _, names, shown, where = _moments(values)
    for k in range(3):
        i, j = [n for n in range(3) if n != k]
        if shown[i] + shown[j] < shown[k] - TOLERANCE * scale:
            return (f"the inertia tensor breaks the triangle inequality {names[i]} + {names[j]} ≥ "
                    f"{names[k]} ({_fmt(shown[i])} + {_fmt(shown[j])} < {_fmt(shown[k])}){where}")
    return None


LUMPED_ROTOR = ("no rigid body alone has it, but a link that carries its motor's rotor inertia "
                "(lumped in, as published data sets do) can; accepted: the tensor is positive "
                "semi-definite, so M(q) keeps its sign")


def pseudo_inertia_issue(values) -> str | None:
    """Why the 4x4 pseudo-inertia matrix `values` (floats) cannot be a body's, or None."""
    j = np.asarray(values, dtype=float)
    scale = max(float(np.abs(j).max()), 1e-300)
    if j[3, 3] < -TOLERANCE * scale:
        return f"the mass (the [4,4] entry) is negative ({_fmt(j[3, 3])})"
    low = _min_eig(j)
    if low < -TOLERANCE * scale:
        return (f"the pseudo-inertia matrix is not positive semi-definite (smallest eigenvalue "
                f"{_fmt(low)}): no body has it (J = ∫ [r; 1][r; 1]ᵀ dm; e.g. a second moment "
                "∫x² dm below m·x_G², or an inertia breaking the triangle inequalities)")
    return None
