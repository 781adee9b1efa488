"""Test and benchmark fixtures: robots (`robots.py`) and independent references
(`mechanics.py`: the same robots in sympy.physics.mechanics). Not part of the package."""
