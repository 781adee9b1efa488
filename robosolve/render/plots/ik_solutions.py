"""Every inverse-kinematics solution overlaid, labelled, with the target marked.

Data: drawings (list of `robot` drawings, one per solution), labels, rejected
(flags: drawn dashed), selected (index among the accepted ones or None),
target {name, at, given} or None. A robot whose links all lie in one
horizontal plane is drawn from above (x0, y0); otherwise in 3-D.
"""

from __future__ import annotations

import numpy as np

from robosolve.render.plots import fixed_layout, one_3d_box, save, subplots
from robosolve.render.plots.robot import equal_3d, polylines

COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
           "tab:pink", "tab:olive", "tab:cyan", "tab:gray", "navy", "maroon")


def _planar(drawings) -> bool:
    zs = [p[2] for d in drawings for link in d["links"] for p in link]
    return bool(zs) and (max(zs) - min(zs)) < 1e-9


def draw(spec, path):
    d = spec.data
    drawings, labels, rejected = d["drawings"], d["labels"], d["rejected"]
    target = d.get("target")
    planar = _planar(drawings)
    if planar:
        fig, ax = subplots(figsize=(6.5, 6))
        fixed_layout(fig, top=0.4)
    else:
        fig, ax = one_3d_box(7, 6.5)
    for k, (drw, lab, rej) in enumerate(zip(drawings, labels, rejected)):
        colour = COLOURS[k % len(COLOURS)]
        style = "--" if rej else "-"
        for i, a in enumerate(polylines(drw["links"])):
            kw = dict(color=colour, lw=2.5, ms=4, alpha=0.55 if rej else 0.9, label=lab if i == 0 else None)
            if planar:
                ax.plot(a[:, 0], a[:, 1], style + "o", **kw)
            else:
                ax.plot(a[:, 0], a[:, 1], a[:, 2], style + "o", **kw)
    if target is not None:
        x, y, z = target["at"]
        if planar:
            ax.plot([x], [y], marker="*", ms=16, color="black", ls="none", label=f"target {target['name']}")
        else:
            ax.scatter([x], [y], [z], marker="*", s=180, color="black", depthshade=False,
                       label=f"target {target['name']}")
    if planar:
        pts = np.array([p for drw in drawings for link in drw["links"] for p in link] + [[0, 0, 0]], float)
        if target is not None:
            pts = np.vstack([pts, np.array(target["at"], float)])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        c = (lo + hi) / 2
        half = max(float(np.max(hi - lo)) / 2 * 1.15, 1e-3)
        ax.set_xlim(c[0] - half, c[0] + half)
        ax.set_ylim(c[1] - half, c[1] + half)
        ax.set_aspect("equal")
        ax.set_xlabel("x0 [m]")
        ax.set_ylabel("y0 [m]")
    else:
        equal_3d(ax, drawings)
        ax.view_init(elev=25, azim=-60)
    if planar:
        ax.set_title(spec.title)
    else:
        fig.suptitle(spec.title)      # above the 3-D box and the legend (Axes3D lowers axes titles)
    ax.legend(loc="upper left", fontsize=7)
    save(fig, path)
