"""Equations of motion by the course's matrix method (see engine.py and api.py)."""

from robosolve.dynamics.api import (  # noqa: F401
    BodySpec, Dynamics, FrameSpec, JointSpec, LoadSpec, NumericDynamics, derive_dynamics,
    numeric_dynamics,
)

__all__ = ["BodySpec", "Dynamics", "FrameSpec", "JointSpec", "LoadSpec", "NumericDynamics",
           "derive_dynamics", "numeric_dynamics"]
