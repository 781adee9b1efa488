"""Figures. `draw(spec, path)` dispatches to the module named by `spec.kind`.

matplotlib is imported here only (Agg backend), and only when a figure is drawn.
"""

from __future__ import annotations

import importlib


def setup():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({
        "figure.dpi": 100, "savefig.dpi": 110, "font.size": 10, "axes.grid": True,
        "grid.alpha": 0.3, "svg.hashsalt": "robosolve",
    })
    return plt


def save(fig, path):
    fig.savefig(path, metadata={"Software": None}, bbox_inches="tight")
    import matplotlib.pyplot as plt

    plt.close(fig)


def draw(spec, path) -> None:
    """Draw one FigureSpec into a PNG file at `path`."""
    from dataclasses import replace

    from robosolve.render.numbers import text

    module = importlib.import_module(f"robosolve.render.plots.{spec.kind}")
    setup()
    module.draw(replace(spec, title=text(spec.title), data=_formatted(spec.data)), path)


def _formatted(v):
    """The figure's data with prose (`Text`, `Num`: labels, titles) formatted."""
    from robosolve.core.prose import Num, Text
    from robosolve.render.numbers import text

    if isinstance(v, (Num, Text)):
        return text(v)
    if isinstance(v, dict):
        return {k: _formatted(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_formatted(x) for x in v]
    return v
