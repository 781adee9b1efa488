"""Individualized variants of a problem (spec variants.md).

- `section`: the `variants:` section of a problem file, validated by the loader into a
  `VariantSpec` (varied parameters with their exact value sets, `require` conditions);
- `draw`: the draw of variant k from (seed, k) with a stable hash, the grid, distinctness;
- `require`: cheap numeric checks of the conditions (inequalities, `reachable`, `nonsingular`);
- `naming`: roster ids -> folder names;
- `workflow`: the `robosolve variants` command (draw, write problem.yaml, solve, variants.csv).
"""
