"""Public interface of the dynamics engine (used by the solvers of the
dynamics question types and the benchmark).

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
* ``numeric.lambdify_dynamics(dyn, subs) -> NumericDynamics`` with numpy functions ``mass(q)``,
  ``velocity_terms(q, qd)``, ``gravity(q)``, ``external(q)``,
  ``actuators(q, qd, qdd)`` (lambdified with cse), and ``numeric_dynamics(...)`` for the
  numeric-only path (no symbolic M; big robots).

From a problem's RobotModel (what solvers use; one derivation per model, cached):

    from robosolve.dynamics.bridge import dynamics_for, numeric_for
    dyn = dynamics_for(model)            # Dynamics; raises SymbolicTimeout past 90 s
    nd, note = numeric_for(model, subs)  # NumericDynamics from parameter values; falls back
                                         # to the numeric-only path (note says so)
    nd.actuators(q, qd, qdd), nd.forward(q, qd, tau), nd.mass(q), nd.gravity(q) ...

`subs` must give every parameter the equations use (null parameters -> ValueError naming
them); joint symbols in it are ignored. Actuator order = joint order; for a chain
f_i = actuator_i + external_i.

Conventions: spec §3 and docs/course-notes.md, Dynamics (see ``robosolve/dynamics/engine.py``).
"""

from __future__ import annotations

from typing import Mapping

from robosolve.dynamics.engine import DynamicsEngine
from robosolve.dynamics.numeric import NumericDynamics, numeric_from_engine
from robosolve.dynamics.types import BodySpec, Dynamics, FrameSpec, JointSpec, LoadSpec

__all__ = [
    "FrameSpec", "JointSpec", "BodySpec", "LoadSpec", "Dynamics", "NumericDynamics",
    "derive_dynamics", "numeric_dynamics",
]


def derive_dynamics(frames, joints, bodies, gravity, loads=(), *, simplify: bool = True,
                    subs: Mapping | None = None) -> Dynamics:
    """Symbolic equations of motion by the course's matrix method (see engine.py).

    ``subs`` (optional) substitutes parameter values into the inputs first (numeric
    parameters give much smaller expressions for big robots).
    """
    eng = DynamicsEngine(frames, joints, bodies, gravity, loads, simplify=simplify, subs=subs)
    return eng.dynamics()


def numeric_dynamics(frames, joints, bodies, gravity, loads=(), *,
                     subs: Mapping | None = None) -> NumericDynamics:
    """Numeric-only path (no symbolic M): for robots too big for the symbolic derivation."""
    from robosolve.dynamics.numeric import numeric_from_engine
    eng = DynamicsEngine(frames, joints, bodies, gravity, loads, simplify=False, subs=subs)
    return numeric_from_engine(eng)
