"""The `robosolve` command line: one module per command, and the only place that prints.

`common` holds the typer app, the shared options, printing and the exit; each command module
defines one typer command, registered here in the order `--help` lists them.
"""

from robosolve.cli import batch, check, grade, paper, solve, validate, variants
from robosolve.cli.common import app, main

for _command in (solve.solve, validate.validate, batch.batch, variants.variants, paper.paper, check.check, grade.grade):
    app.command()(_command)

__all__ = ["app", "main"]
