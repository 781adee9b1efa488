"""Public interface of the dynamics engine (used by `equations_of_motion`, `joint_torques`,
the control solvers and the benchmark).

Inputs are plain sympy objects (no dependency on the loader):

* ``frames``: a list of :class:`FrameSpec` (name, parent, local 4x4 pose ``M_parent,frame``),
  parents listed before children; frame ``"0"`` is the fixed base and is never listed;
* ``joints``: a list of :class:`JointSpec` (q, q_dot, q_ddot symbols and the actuator symbol);
  a joint symbol may appear in the local pose of any frame (usually exactly one);
* ``bodies``: a list of :class:`BodySpec` (name, frame, pseudo-inertia J in that frame);
* ``gravity``: the gravity vector in frame 0;
* ``loads``: a list of :class:`LoadSpec` (external forces / torques on a frame, with the
  frame of their components).

``derive_dynamics(...)`` returns a :class:`Dynamics` with

* ``mass_matrix`` (n x n), ``velocity_terms`` (n x 1), ``gravity_terms`` (n x 1),
* ``external_forces`` (n x 1): generalized forces of the external loads,
* ``actuators``: actuator symbols in joint order; for a chain f_i = actuator_i + external_i,
* ``kinetic_energy`` / ``potential_energy``: dict body -> expression,
* ``numeric(subs) -> NumericDynamics`` with numpy functions ``mass(q)``,
  ``velocity_terms(q, qd)``, ``gravity(q)``, ``external(q)``,
  ``actuators(q, qd, qdd)`` (lambdified with cse), and ``numeric_dynamics(...)`` for the
  numeric-only path (no symbolic M; big robots).

From a problem's RobotModel (what solvers use; one derivation per model, cached):

    from robosolve.dynamics.model import dynamics_for, numeric_for
    dyn = dynamics_for(model)            # Dynamics; raises SymbolicTimeout past 90 s
    nd, note = numeric_for(model, subs)  # NumericDynamics from parameter values; falls back
                                         # to the numeric-only path (note says so)
    nd.actuators(q, qd, qdd), nd.forward(q, qd, tau), nd.mass(q), nd.gravity(q) ...

`subs` must give every parameter the equations use (null parameters -> ValueError naming
them); joint symbols in it are ignored. Actuator order = joint order; for a chain
f_i = actuator_i + external_i.

Conventions: spec §3 and docs/course-notes.md (Dynamics) (see ``robosolve/dynamics/engine.py``).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable, Mapping, Sequence

import sympy as sp

__all__ = [
    "FrameSpec", "JointSpec", "BodySpec", "LoadSpec", "Dynamics", "NumericDynamics",
    "derive_dynamics", "numeric_dynamics",
]


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

    def numeric(self, subs: Mapping) -> "NumericDynamics":
        from robosolve.dynamics.numeric import lambdify_dynamics

        return lambdify_dynamics(self, subs)


@dataclass
class NumericDynamics:
    """numpy callables: mass(q), velocity_terms(q, qd), gravity(q), external(q),
    actuators(q, qd, qdd). Arguments are sequences in joint order; results numpy arrays."""

    n: int
    mass: Callable
    velocity_terms: Callable
    gravity: Callable
    external: Callable
    note: str = ""
    actuators_fn: Callable | None = field(repr=False, default=None)

    def actuators(self, q, qd, qdd):
        """Actuator values needed: M q'' + c + g - external."""
        import numpy as np

        if self.actuators_fn is not None:
            return self.actuators_fn(q, qd, qdd)
        return (self.mass(q) @ np.asarray(qdd, dtype=float) + self.velocity_terms(q, qd)
                + self.gravity(q) - self.external(q))

    def forward(self, q, qd, tau):
        """Joint accelerations for actuator values tau (free simulation, control)."""
        import numpy as np

        rhs = np.asarray(tau, dtype=float) + self.external(q) - self.velocity_terms(q, qd) \
            - self.gravity(q)
        return np.linalg.solve(self.mass(q), rhs)


def derive_dynamics(frames, joints, bodies, gravity, loads=(), *, simplify: bool = True,
                    subs: Mapping | None = None) -> Dynamics:
    """Symbolic equations of motion by the course's matrix method (see engine.py).

    ``subs`` (optional) substitutes parameter values into the inputs first (numeric
    parameters give much smaller expressions for big robots).
    """
    from robosolve.dynamics.engine import DynamicsEngine

    eng = DynamicsEngine(frames, joints, bodies, gravity, loads, simplify=simplify, subs=subs)
    return eng.dynamics()


def numeric_dynamics(frames, joints, bodies, gravity, loads=(), *,
                     subs: Mapping | None = None) -> NumericDynamics:
    """Numeric-only path (no symbolic M): for robots too big for the symbolic derivation."""
    from robosolve.dynamics.numeric import numeric_from_engine
    from robosolve.dynamics.engine import DynamicsEngine

    eng = DynamicsEngine(frames, joints, bodies, gravity, loads, simplify=False, subs=subs)
    return numeric_from_engine(eng)
