"""Pure math on sympy matrices: no robot concepts, no I/O."""
