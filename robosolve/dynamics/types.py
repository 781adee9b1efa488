"""The dynamics engine's plain inputs (frames, joints, bodies, loads) and its symbolic result.

No dependency on the rest of robosolve: the model bridge (`dynamics/model.py`) builds
these from a `RobotModel`, the engine (`engine.py`) consumes them, `numeric.py` turns a
`Dynamics` into numbers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Sequence

import sympy as sp

__all__ = ["FrameSpec", "JointSpec", "BodySpec", "LoadSpec", "Dynamics"]


@dataclass(frozen=True)
class FrameSpec:
    """A frame: its parent and its local pose ``M_parent,name`` (4x4 sympy)."""

    name: str
    parent: str
    local: sp.Matrix


@dataclass(frozen=True)
class JointSpec:
    """A generalized coordinate with its derivatives and its actuator symbol."""

    name: str
    q: sp.Symbol
    qd: sp.Symbol
    qdd: sp.Symbol
    actuator: sp.Symbol
    kind: str = "revolute"  # or "prismatic"


@dataclass(frozen=True)
class BodySpec:
    """A rigid body fixed in ``frame`` with pseudo-inertia ``J`` (4x4) in that frame."""

    name: str
    frame: str
    J: sp.Matrix


@dataclass(frozen=True)
class LoadSpec:
    """An external action on the body of ``frame``.

    ``force`` and ``torque`` are 3-vectors (or None) with components in frame ``in_frame``
    (default: ``frame``); ``point`` is the application point in ``frame`` coordinates.
    """

    name: str
    frame: str
    force: Sequence | None = None
    point: Sequence | None = None
    torque: Sequence | None = None
    in_frame: str | None = None


@dataclass
class Dynamics:
    """The equations of motion M(q) q'' + c(q, q') + g(q) = actuators + external."""

    joints: list[JointSpec]
    mass_matrix: sp.Matrix
    velocity_terms: sp.Matrix
    gravity_terms: sp.Matrix
    external_forces: sp.Matrix
    kinetic_energy: dict[str, Any]
    potential_energy: dict[str, Any]
    engine: Any = field(repr=False, default=None)  # the DynamicsEngine (intermediate matrices)

    @property
    def q(self) -> list[sp.Symbol]:
        return [j.q for j in self.joints]

    @property
    def qd(self) -> list[sp.Symbol]:
        return [j.qd for j in self.joints]

    @property
    def qdd(self) -> list[sp.Symbol]:
        return [j.qdd for j in self.joints]

    @property
    def actuators(self) -> list[sp.Symbol]:
        return [j.actuator for j in self.joints]

    @property
    def generalized_forces(self) -> sp.Matrix:
        """f_i = actuator_i + external_i (course-notes#note-lagrange)."""
        return sp.Matrix(self.actuators) + self.external_forces

    def lhs(self) -> sp.Matrix:
        """M(q) q'' + c + g, the left-hand side d/dt dL/dq' - dL/dq."""
        return self.mass_matrix * sp.Matrix(self.qdd) + self.velocity_terms + self.gravity_terms

    def equations(self) -> list[sp.Eq]:
        lhs = self.lhs()
        f = self.generalized_forces
        return [sp.Eq(lhs[i], f[i], evaluate=False) for i in range(len(self.joints))]

    def actuator_expressions(self) -> sp.Matrix:
        """Actuator values needed: M q'' + c + g - external (inverse dynamics)."""
        return self.lhs() - self.external_forces
