"""Stage 2 of the pipeline: the robot built from a validated problem: its description
(description.py), the one chain computation (forward.py) over sympy, the trig ring or numpy
(algebras.py, numpy_algebra.py), RobotModel (chain.py) and NumericChain (numeric.py)."""
from robosolve.model.chain import RobotModel

__all__ = ["RobotModel"]
