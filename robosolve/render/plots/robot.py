"""The robot drawn at a configuration: links, frames (x red, y green, z blue), points.

Data (from solvers.common.robot_drawing): frames [{name, origin, axes}], links
[[p0, p1, ...]], points [{name, at}], optional highlight (a point name).
Other figure kinds reuse `draw_robot_3d` and `equal_3d` on their own axes.
"""

from __future__ import annotations

import numpy as np

from robosolve.core.prose import name_plot
from robosolve.render.plots import one_3d_box, save

AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")


def _all_points(drawings) -> np.ndarray:
    pts = [[0.0, 0.0, 0.0]]
    for d in drawings:
        for link in d["links"]:
            pts += link
        pts += [p["at"] for p in d["points"]]
    return np.array(pts, dtype=float)


def extent(drawings) -> float:
    a = _all_points(drawings)
    span = float(np.max(a.max(axis=0) - a.min(axis=0)))
    return span if span > 1e-9 else 1.0


def polylines(links) -> list[np.ndarray]:
    """The links as few polylines as draw the same: a link that starts where the previous one
    ends continues its line (a serial chain is one line, one artist instead of one per link;
    matplotlib's cost is per artist, and a joint's marker is drawn once instead of twice).
    For drawings without frames (ik_solutions): see `draw_robot_3d`."""
    lines: list[list] = []
    for link in links:
        if lines and len(link) and list(lines[-1][-1]) == list(link[0]):
            lines[-1].extend(link[1:])
        else:
            lines.append(list(link))
    return [np.array(line, dtype=float) for line in lines]


def draw_robot_3d(ax, d, colour="0.25", label=None, frames=True, scale=None, alpha=1.0):
    scale = scale or 0.12 * extent([d])
    # one artist per link, not `polylines`: Axes3D orders artists by depth, and one line for the
    # whole arm would be drawn over (hide) the frames' axes that lie along it
    for k, link in enumerate(d["links"]):
        a = np.array(link, dtype=float)
        ax.plot(a[:, 0], a[:, 1], a[:, 2], "-o", color=colour, lw=3, ms=4, alpha=alpha,
                label=label if k == 0 else None)
    if frames:
        for f in d["frames"]:
            o = np.array(f["origin"], dtype=float)
            for c, axis in enumerate(f["axes"]):
                v = np.array(axis, dtype=float) * scale
                ax.plot([o[0], o[0] + v[0]], [o[1], o[1] + v[1]], [o[2], o[2] + v[2]],
                        color=AXIS_COLOURS[c], lw=1.2, alpha=alpha)
            ax.text(o[0], o[1], o[2], f" {name_plot(f['name'])}", fontsize=8, color="0.3")
    for p in d["points"]:
        x, y, z = p["at"]
        hl = p["name"] == d.get("highlight")
        ax.scatter([x], [y], [z], color="tab:orange" if hl else "0.4", s=40 if hl else 12,
                   depthshade=False, zorder=5)
        ax.text(x, y, z, f"  {p['name']}", fontsize=9, color="tab:orange" if hl else "0.3")


def equal_3d(ax, drawings):
    a = _all_points(drawings)
    centre = (a.max(axis=0) + a.min(axis=0)) / 2
    half = max(extent(drawings) / 2 * 1.15, 1e-3)
    ax.set_xlim(centre[0] - half, centre[0] + half)
    ax.set_ylim(centre[1] - half, centre[1] + half)
    ax.set_zlim(centre[2] - half, centre[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x0 [m]")
    ax.set_ylabel("y0 [m]")
    ax.set_zlabel("z0 [m]")


def draw(spec, path):
    d = spec.data
    fig, ax = one_3d_box(6.5, 6)
    draw_robot_3d(ax, d, label="links")
    equal_3d(ax, [d])
    ax.view_init(elev=25, azim=-60)
    fig.suptitle(spec.title)      # above the 3-D box and the legend (Axes3D lowers axes titles)
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color="0.25", lw=3, marker="o", label="links")]
    handles += [Line2D([], [], color=c, lw=1.2, label=f"{n} axis") for c, n in zip(AXIS_COLOURS, "xyz")]
    ax.legend(handles=handles, loc="upper left", fontsize=8)
    save(fig, path)
