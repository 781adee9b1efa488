"""The one chain computation (pinocchio's Data): `forward(description, algebra)` (forward.py)
over sympy, the trig ring or numpy (algebras.py, numpy_algebra.py). Pure math: it imports only
core, errors, numpy and sympy, so that the model, the engines and the notebook share it."""
