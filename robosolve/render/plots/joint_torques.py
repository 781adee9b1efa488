"""Every actuator against time along the profile: jumps at the switching instants, peaks marked.

Data: t (each switching instant twice, once per side), T, switches, actuators [{name, label,
unit, values, peak, t_peak}].
"""

from __future__ import annotations

import numpy as np

from robosolve.render.plots import figure_number, save, time_panels
from robosolve.render.plots.motion_profile import COLOURS, mark_switches


def draw(spec, path):
    d = spec.data
    acts = d["actuators"]
    fig, axes = time_panels(len(acts), width=7.5, row_height=2.4, top=0.4)
    for k, (ax, a) in enumerate(zip(axes[:, 0], acts)):
        ax.plot(d["t"], a["values"], color=COLOURS[k % len(COLOURS)], lw=1.6)
        mark_switches(ax, d["switches"], d["T"])
        ax.axhline(0.0, color="0.6", lw=0.6)
        ax.plot([a["t_peak"]], [a["peak"]], "o", color="k", ms=5)
        note = ax.annotate(f"peak {figure_number(a['peak'])} {a['unit']} at t = {figure_number(a['t_peak'])} s",
                           (a["t_peak"], a["peak"]), xytext=(8, -12), textcoords="offset points", fontsize=8,
                           bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85))
        ax.set_ylabel(f"${a['label']}$ ({a['unit']})")
        _place(ax, note, d["t"], a["values"], right=a["t_peak"] > d["T"] / 2, above=a["peak"] <= 0)
    axes[0, 0].set_title(spec.title)
    axes[-1, 0].set_xlabel("t (s)")
    save(fig, path)


def _place(ax, note, ts, values, right: bool, above: bool) -> None:
    """Put the peak's text beside its marker where it stays inside the panel and hides the
    fewest points of the curve (its white box would cover them): either side of the marker, at
    a few heights, the usual place first (to the left of a late peak, below a positive one);
    measured on the renderer (the layout is fixed, so the positions are final)."""
    renderer = ax.figure.canvas.get_renderer()
    points = ax.transData.transform(np.column_stack([np.asarray(ts, float), np.asarray(values, float)]))
    panel = ax.get_window_extent(renderer)
    # the usual offset first, then the other side vertically, then a line further away each time
    ups, downs = [6 + 14 * k for k in range(6)], [-12 - 14 * k for k in range(6)]
    rises = [v for pair in zip(*((ups, downs) if above else (downs, ups))) for v in pair]
    sides = [(left_of, dy) for left_of in (right, not right) for dy in rises]
    best = None
    for rank, (left_of, dy) in enumerate(sides):
        note.xyann = (-8 if left_of else 8, dy)
        note.set_horizontalalignment("right" if left_of else "left")
        box = note.get_window_extent(renderer)
        inside = panel.x0 <= box.x0 and box.x1 <= panel.x1 and panel.y0 <= box.y0 and box.y1 <= panel.y1
        hidden = int(np.count_nonzero((points[:, 0] >= box.x0) & (points[:, 0] <= box.x1)
                                      & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1)))
        score = (not inside, hidden, rank)
        if best is None or score < best[0]:
            best = (score, note.xyann, note.get_horizontalalignment())
    note.xyann = best[1]
    note.set_horizontalalignment(best[2])
