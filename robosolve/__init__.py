"""robosolve: an industrial-robotics exam solver that shows its work.

Importing the package is cheap on purpose: sympy, numpy and matplotlib are
imported by the modules that need them, so `robosolve --help` stays fast.
"""

__version__ = "0.1.0"
