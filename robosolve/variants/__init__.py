"""Individualized variants of a problem (spec variants.md).

The `variants:` section itself is validated by the loader (robosolve/load/variants.py) into
a `VariantSpec` on the Problem (varied parameters with exact value sets, `require`); here:

- `draw`: the draw of variant k from (seed, k) with a stable hash, the grid, distinctness;
- `require`: cheap numeric checks of the conditions (inequalities, `reachable`, `nonsingular`);
- `naming`: roster ids -> folder names;
- `workflow`: the `robosolve variants` command (draw, write problem.yaml, solve, variants.csv).
"""
