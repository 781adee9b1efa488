"""The one time symbol of robosolve: `t` in a problem file (forces in time, actuator laws), the
motion profiles' time, the simulations' time. A real symbol (sympy: Symbol('t') and
Symbol('t', real=True) are different symbols, so an expression built with one is constant in
the other): everything that makes or substitutes time uses TIME."""

import sympy as sp

__all__ = ["TIME"]

TIME = sp.Symbol("t", real=True)
