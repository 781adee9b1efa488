"""A work-space path: the point's trace in frame 0 and the arm drawn at start, middle and end.

Data: trace [[x, y, z], ...], poses [{label, drawing}], point.
"""

from __future__ import annotations

import numpy as np

from robosolve.render.plots import one_3d_box, save
from robosolve.render.plots.robot import draw_robot_3d, equal_3d

SHADES = ("tab:blue", "0.45", "tab:red")


def draw(spec, path):
    from robosolve.render.plots import _formatted

    d = spec.data
    fig, ax = one_3d_box(6.5, 6)
    tr = np.array(d["trace"], dtype=float).reshape(-1, 3)
    drawings = [p["drawing"] for p in d["poses"]]
    for k, p in enumerate(d["poses"]):
        draw_robot_3d(ax, p["drawing"], colour=SHADES[k % len(SHADES)], label=f"arm at {_formatted(p['label'])}",
                      frames=False, alpha=0.85)
    if tr.size:
        ax.plot(tr[:, 0], tr[:, 1], tr[:, 2], color="tab:green", lw=2.2, label=f"path of {d['point']}")
        drawings = drawings + [{"links": [tr.tolist()], "frames": [], "points": []}]
    if drawings:
        equal_3d(ax, drawings)
    ax.view_init(elev=25, azim=-60)
    ax.legend(loc="upper left", fontsize=8)
    fig.suptitle(spec.title)
    save(fig, path)
