"""Degrees of freedom of a mechanism (seed §1.1.3, docs/course-notes.md#note-mobility).

Gruebler (planar):   n = 3 (m - 1) - 2 c1 - c2
Kutzbach (spatial):  n = 6 (m - 1) - 5 c1 - 4 c2 - 3 c3

m counts the bodies including the fixed base; c_k is the number of joints that
leave k degrees of freedom between the two bodies they connect (a revolute or
prismatic joint is a c1, a universal joint a c2 in space, a spherical joint a
c3; in the plane a pin-in-slot or a rolling-with-slipping contact is a c2).

The count is a necessary estimate: n <= 0 means the mechanism is a structure
(n = 0, statically determinate) or over-constrained (n < 0), unless special
geometry (parallel axes, ...) adds mobility the formula cannot see.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["Mobility", "mobility", "gruebler", "kutzbach"]


@dataclass(frozen=True)
class Mobility:
    """Result of a mobility count.

    ``formula`` is the general formula, ``substituted`` the same with the
    numbers in, ``terms`` the signed contributions (free motion of the moving
    bodies first, then the constraint of each joint class).
    """

    space: str                    # "planar" or "spatial"
    dof: int
    bodies: int                   # m, base included
    joints: dict                  # {1: c1, 2: c2, 3: c3}
    formula: str
    substituted: str
    terms: list                   # [(label, value), ...]
    status: str                   # "mechanism", "structure" or "overconstrained"
    notes: list = field(default_factory=list)


def _check_count(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{name} must be a whole number, got {value!r}")
    if value < 0:
        raise ValueError(f"{name} must not be negative, got {value}")
    return value


def mobility(bodies: int, joints_1dof: int = 0, joints_2dof: int = 0, joints_3dof: int = 0,
             space: str = "planar") -> Mobility:
    """Degrees of freedom by Gruebler (``space="planar"``) or Kutzbach (``"spatial"``)."""
    m = _check_count("bodies", bodies)
    c1 = _check_count("joints_1dof", joints_1dof)
    c2 = _check_count("joints_2dof", joints_2dof)
    c3 = _check_count("joints_3dof", joints_3dof)
    if m < 1:
        raise ValueError("bodies must count at least the base (m >= 1)")
    if space == "planar":
        if c3:
            raise ValueError("joints_3dof is for spatial mechanisms only (a planar joint leaves at most 2 DOF)")
        lam = 3
        weights = {1: 2, 2: 1}
        formula = "n = 3(m - 1) - 2 c1 - c2"
        substituted = f"n = 3({m} - 1) - 2·{c1} - {c2}"
    elif space == "spatial":
        lam = 6
        weights = {1: 5, 2: 4, 3: 3}
        formula = "n = 6(m - 1) - 5 c1 - 4 c2 - 3 c3"
        substituted = f"n = 6({m} - 1) - 5·{c1} - 4·{c2} - 3·{c3}"
    else:
        raise ValueError(f"space must be 'planar' or 'spatial', got {space!r}")
    counts = {1: c1, 2: c2, 3: c3}
    terms = [(f"{m - 1} moving bodies × {lam} DOF", lam * (m - 1))]
    for k, w in weights.items():
        if counts[k]:
            terms.append((f"{counts[k]} joints with {k} DOF × {w} constraints", -w * counts[k]))
    n = sum(v for _, v in terms)
    notes = []
    if n > 0:
        status = "mechanism"
    elif n == 0:
        status = "structure"
        notes.append("n = 0: the bodies cannot move (a statically determinate structure), "
                     "unless special geometry gives them mobility")
    else:
        status = "overconstrained"
        notes.append(f"n = {n} < 0: over-constrained (a hyperstatic structure, {-n} redundant "
                     "constraints); it can move only thanks to special geometry")
    joints = {1: c1, 2: c2} if space == "planar" else counts
    return Mobility(space, n, m, joints, formula, substituted, terms, status, notes)


def gruebler(bodies: int, joints_1dof: int = 0, joints_2dof: int = 0) -> Mobility:
    """Planar count n = 3(m - 1) - 2 c1 - c2."""
    return mobility(bodies, joints_1dof, joints_2dof, 0, "planar")


def kutzbach(bodies: int, joints_1dof: int = 0, joints_2dof: int = 0, joints_3dof: int = 0) -> Mobility:
    """Spatial count n = 6(m - 1) - 5 c1 - 4 c2 - 3 c3."""
    return mobility(bodies, joints_1dof, joints_2dof, joints_3dof, "spatial")
