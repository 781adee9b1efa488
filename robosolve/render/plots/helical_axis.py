"""The helical axis of a displacement with the reference, initial and final frames.

Data: frames [{name, origin, axes (x, y, z columns)}] (reference, initial,
final), axis {u, point} or None (identity), alpha, h, case. A pure
translation is drawn as an arrow from the initial to the final origin.
"""

from __future__ import annotations

import numpy as np

from robosolve.core.prose import name_plot
from robosolve.render.plots import figure_number, one_3d_box, save

AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")
FRAME_STYLE = {"initial": ("-", 1.0), "final": ("--", 1.0)}


def draw(spec, path):
    d = spec.data
    fig, ax = one_3d_box(7, 6.5)
    origins = np.array([f["origin"] for f in d["frames"]], dtype=float)
    span = float(np.max(np.ptp(origins, axis=0))) if len(origins) > 1 else 1.0
    scale = max(span, 1e-3) * 0.25 if span > 0 else 0.5
    pts = [o for o in origins]
    labels: dict = {}  # frames drawn at the same origin share one label ("0 = initial")
    for fr in d["frames"]:
        key = tuple(np.round(np.array(fr["origin"], dtype=float), 9))
        labels[key] = (labels[key] + " = " if key in labels else "") + fr["name"]
    for key, text in labels.items():
        ax.text(*key, f" {name_plot(text)}", fontsize=9)
    for k, fr in enumerate(d["frames"]):
        o = np.array(fr["origin"], dtype=float)
        style, lw = FRAME_STYLE.get(fr["name"], (":", 0.8))
        for c, colour in enumerate(AXIS_COLOURS):
            e = o + scale * np.array(fr["axes"][c], dtype=float)
            ax.plot([o[0], e[0]], [o[1], e[1]], [o[2], e[2]], style, color=colour, lw=2 * lw)
            pts.append(e)
    axis = d.get("axis")
    if axis is not None and axis.get("point") is not None:
        p = np.array(axis["point"], dtype=float)
        u = np.array(axis["u"], dtype=float)
        centre = origins.mean(axis=0)
        t0 = float(u @ (centre - p))
        half = max(span, 1.0) * 0.9
        a, b = p + (t0 - half) * u, p + (t0 + half) * u
        ax.plot([a[0], b[0]], [a[1], b[1]], [a[2], b[2]], "-", color="black", lw=1.8,
                label=f"helical axis: α = {figure_number(d['alpha'])} rad, h = {figure_number(d['h'])}")
        ax.quiver(*p, *(u * scale * 1.5), color="black", arrow_length_ratio=0.25)
        ax.scatter(*p, color="black", s=25, depthshade=False, label="P* (nearest the origin)")
        pts += [a, b, p]
    elif axis is not None:  # pure translation
        o1, o2 = origins[1], origins[2]
        ax.quiver(*o1, *(o2 - o1), color="black", arrow_length_ratio=0.1,
                  label=f"pure translation: h = {figure_number(d['h'])}")
    _equal(ax, np.array(pts, dtype=float))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    fig.suptitle(spec.title, fontsize=10)      # above the 3-D box and the legend
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="upper left", fontsize=8)
    save(fig, path)


def _equal(ax, a):
    centre = (a.max(axis=0) + a.min(axis=0)) / 2
    half = max(float(np.max(a.max(axis=0) - a.min(axis=0))) / 2 * 1.1, 1e-3)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
