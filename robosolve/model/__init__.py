"""Stage 2 of the pipeline: the symbolic robot built from a validated problem."""
from robosolve.model.chain import RobotModel

__all__ = ["RobotModel"]
