"""The numpy namespace for sympy.lambdify, without `from numpy import *`.

`lambdify(..., modules="numpy")` runs `from numpy import *`, which imports numpy.f2py,
numpy.testing, numpy.ma, numpy.random, ... (numpy 2 lists its submodules in `__all__`):
0.15-0.2 s of every process that evaluates a formula with numpy. Passing the numpy module
itself gives lambdify the same printer (NumPyPrinter: `numpy` is among the modules) and the
same functions (numpy's namespace), so the generated code and its values are the same.
"""

from __future__ import annotations

import numpy


def numpy_modules() -> list:
    """`modules=` for sympy.lambdify: numpy's own namespace."""
    return [numpy]
