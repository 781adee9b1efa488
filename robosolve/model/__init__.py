"""Stage 2 of the pipeline: the robot built from a validated problem: its description
(description.py), RobotModel (chain.py) and NumericChain (numeric.py), over the one chain
computation of robosolve/core/chain/ (forward.py; sympy, the trig ring or numpy: algebras.py,
numpy_algebra.py)."""
from robosolve.model.chain import RobotModel

__all__ = ["RobotModel"]
