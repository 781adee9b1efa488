"""The dynamics engine's plain inputs (frames, joints, bodies, loads) and its symbolic result.

No dependency on the rest of robosolve: the model bridge (`dynamics/bridge.py`) builds
these from a `RobotModel`, the engine (`engine.py`) consumes them, `numeric.py` turns a
`Dynamics` into numbers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import sympy as sp

__all__ = ["FrameSpec", "JointSpec", "BodySpec", "LoadSpec", "Dynamics"]


@dataclass(frozen=True)
class FrameSpec:
    """A frame of the chain.

    ``local`` is its pose in its parent, the 4x4 sympy matrix ``ᵖM_name`` of the course,
    a function of the joints that move it (the base frame has no FrameSpec).
    """

    name: str
    parent: str
    local: sp.Matrix


@dataclass(frozen=True)
class JointSpec:
    """A generalized coordinate q with the symbols of q̇ and q̈ and of its actuator's action
    (a torque for a revolute joint, a force for a prismatic one)."""

    name: str
    q: sp.Symbol
    qd: sp.Symbol
    qdd: sp.Symbol
    actuator: sp.Symbol
    kind: str = "revolute"  # or "prismatic"


@dataclass(frozen=True)
class BodySpec:
    """A rigid body fixed in ``frame``.

    ``J`` is its pseudo-inertia in that frame, the symmetric 4x4 ∫ P Pᵀ dm whose [4, 4]
    entry is the mass.
    """

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


class _PerJoint:
    """A read-only attribute of `Dynamics`: one symbol of each joint, in joint order."""

    def __init__(self, attribute: str):
        self.attribute = attribute

    def __get__(self, dynamics, owner=None) -> list[sp.Symbol]:
        if dynamics is None:
            return self
        return [getattr(j, self.attribute) for j in dynamics.joints]


class Dynamics:
    """The equations of motion M(q) q'' + c(q, q') + g(q) = actuators + external.

    ``mass_matrix``, ``velocity_terms``, ``gravity_terms``, ``external_forces``,
    ``kinetic_energy``, ``potential_energy`` are sympy objects; each may instead be given as
    a function in ``builders`` (name -> zero-argument callable), called on first use: a big
    robot's expressions are then built only when a reader asks for them (the equations of
    motion question of a 7-joint arm reads the engine's polynomials directly).
    """

    FIELDS = ("mass_matrix", "velocity_terms", "gravity_terms", "external_forces",
              "kinetic_energy", "potential_energy")

    def __init__(self, joints: list[JointSpec], mass_matrix=None, velocity_terms=None,
                 gravity_terms=None, external_forces=None, kinetic_energy=None,
                 potential_energy=None, engine: Any = None, builders: dict | None = None):
        self.joints = joints
        self.engine = engine  # the DynamicsEngine (intermediate matrices)
        self._builders = dict(builders or {})
        given = dict(mass_matrix=mass_matrix, velocity_terms=velocity_terms,
                     gravity_terms=gravity_terms, external_forces=external_forces,
                     kinetic_energy=kinetic_energy, potential_energy=potential_energy)
        for name, value in given.items():
            if value is not None or name not in self._builders:
                setattr(self, name, value)

    def __getattr__(self, name):
        # only called for an attribute not set yet: a lazily built field
        builders = self.__dict__.get("_builders", {})
        if name in builders:
            value = builders.pop(name)()
            setattr(self, name, value)
            return value
        raise AttributeError(name)

    def __repr__(self) -> str:
        return f"Dynamics({len(self.joints)} joints)"

    # the joints' symbols, in joint order
    q = _PerJoint("q")
    qd = _PerJoint("qd")
    qdd = _PerJoint("qdd")
    actuators = _PerJoint("actuator")

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
