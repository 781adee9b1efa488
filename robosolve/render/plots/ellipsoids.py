"""Figure kind `ellipsoids`: the force, velocity and compliance ellipses (ellipsoids) of
one configuration, each in its own panel, drawn at the end effector over the robot.

`spec.data` (plain numbers, built by robosolve.solvers.ellipsoids):

    dims: 2 or 3
    axis_labels: ["x", "y"(, "z")]     names of the coordinates (plot axes)
    robot: [[[x, y(, z)], ...], ...]  link polylines in the coordinates' space, or null
    end: [x, y(, z)]                   where the ellipses are centred
    panels: [{title, unit, lengths: [float|null], directions: [[...]]}, ...]

The robot is drawn at true scale (m); each ellipse is scaled to fit next to it; its
semi-axes carry a letter past their tips (a, b, c) and the legend gives their true lengths,
units and the drawing scale (a null length is an infinite
semi-axis: the ellipse degenerates into two parallel lines; a zero length flattens it).
Without a robot (coordinates that are not positions) the ellipse is drawn at true scale.
"""

from __future__ import annotations

import math

import numpy as np

COLORS = {"force": "#c0392b", "velocity": "#2471a3", "compliance": "#229954"}


def _fmt(x):
    from robosolve.render.plots import figure_number

    return figure_number(x)


def _scale(panel, robot_size):
    finite = [x for x in panel["lengths"] if x is not None and x > 0]
    if not finite:
        return 1.0
    if robot_size is None:
        return 1.0
    return 0.45 * robot_size / max(finite)


def _robot_extent(robot, end):
    pts = [p for link in (robot or []) for p in link] + [end]
    a = np.array(pts, dtype=float)
    if a.size == 0:
        return None
    span = float(np.max(np.ptp(a, axis=0)))
    return span if span > 1e-9 else None


def _axis_letter(k):
    return "abc"[k] if k < 3 else str(k + 1)


def _semi_axis_label(k, ln, panel):
    return f"{_axis_letter(k)} = " + (_fmt(ln) if ln is not None else "∞") + f" {panel['unit']}"


def _legend(ax, panel, links, finite, s, **where):
    """The semi-axes' lengths (and the drawing scale) in a legend placed where it hides the
    least of the drawing (labels written at the tips overlapped the ellipse and each other)."""
    title = (f"scale: 1 {panel['unit']} = {_fmt(s)} m"
             if links and finite and max(finite) > 0 else None)
    leg = ax.legend(**(where or {"loc": "best"}), fontsize=8, title=title, title_fontsize=8, framealpha=0.9,
                    handlelength=1.5)
    leg.set_zorder(10)


def _placement(spec_data, panel):
    """The ellipse's centre, the robot's links as arrays (none without a robot) and the
    scale that fits the panel's ellipse next to the robot."""
    end = np.array(spec_data["end"], dtype=float)
    robot = spec_data.get("robot")
    links = [np.array(link, dtype=float) for link in robot or []]
    return end, links, _scale(panel, _robot_extent(robot, end) if links else None)


def _draw_2d(ax, spec_data, panel, color):
    end, links, s = _placement(spec_data, panel)
    for a in links:
        ax.plot(a[:, 0], a[:, 1], "-", color="0.35", lw=3, solid_capstyle="round", zorder=2)
        ax.plot(a[:, 0], a[:, 1], "o", color="0.15", ms=4, zorder=3)
    ax.plot(*end, "o", color="k", ms=5, zorder=4)
    lengths, dirs = panel["lengths"], [np.array(d, dtype=float) for d in panel["directions"]]
    finite = [x for x in lengths if x is not None]
    big = (max(finite) if finite else 1.0) * s
    if all(x is not None for x in lengths):
        t = np.linspace(0, 2 * math.pi, 241)
        pts = end[:, None] + s * (lengths[0] * np.outer(dirs[0], np.cos(t))
                                  + lengths[1] * np.outer(dirs[1], np.sin(t)))
        ax.plot(pts[0], pts[1], "-", color=color, lw=2, zorder=5)
    else:
        # infinite semi-axis: the band between two parallel lines
        inf_i = lengths.index(None)
        fin_i = 1 - inf_i
        off = (lengths[fin_i] or 0.0) * s * dirs[fin_i]
        far = 3 * (big if big > 0 else 1.0) * dirs[inf_i]
        for sign in (1, -1):
            a, b = end + sign * off - far, end + sign * off + far
            ax.plot([a[0], b[0]], [a[1], b[1]], "-", color=color, lw=2, zorder=5)
    pad = 0.08 * max(big, _robot_extent(spec_data.get("robot"), end) or 0.0, 1e-9)
    for k, (ln, d) in enumerate(zip(lengths, dirs)):
        reach = (ln * s) if ln is not None else 2 * (big if big > 0 else 1.0)
        style = "-" if ln is not None else "--"
        ax.plot([end[0] - reach * d[0], end[0] + reach * d[0]],
                [end[1] - reach * d[1], end[1] + reach * d[1]], style,
                color=color, lw=1, alpha=0.8, zorder=4, label=_semi_axis_label(k, ln, panel))
        # the axis letter just past the tip, outside the ellipse (the values are in the legend)
        at = end + (reach + pad) * d
        ax.text(at[0], at[1], _axis_letter(k), color=color, fontsize=10, fontweight="bold",
                ha="center", va="center", zorder=6,
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8})
        ax.plot(*at, alpha=0.0)  # keeps the letter inside the data limits
    labels = spec_data["axis_labels"]
    unit_axis = "m" if links else panel["unit"]
    ax.set_xlabel(f"{labels[0]} [{unit_axis}]")
    ax.set_ylabel(f"{labels[1]} [{unit_axis}]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.axhline(0, color="0.6", lw=0.6)
    ax.axvline(0, color="0.6", lw=0.6)
    _legend(ax, panel, links, finite, s)
    ax.set_title(f"{panel['title']} [{panel['unit']}]", fontsize=10)


def _draw_3d(ax, spec_data, panel, color):
    end, links, s = _placement(spec_data, panel)
    for a in links:
        ax.plot(a[:, 0], a[:, 1], a[:, 2], "-o", color="0.35", lw=2.5, ms=3)
    lengths = panel["lengths"]
    dirs = [np.array(d, dtype=float) for d in panel["directions"]]
    finite = [x for x in lengths if x is not None]
    big = (max(finite) if finite else 1.0) * s or 1.0
    eff = [(x * s) if x is not None else 2.5 * big for x in lengths]
    u, v = np.meshgrid(np.linspace(0, 2 * math.pi, 37), np.linspace(0, math.pi, 19))
    xyz = (eff[0] * np.multiply.outer(dirs[0], np.cos(u) * np.sin(v))
           + eff[1] * np.multiply.outer(dirs[1], np.sin(u) * np.sin(v))
           + eff[2] * np.multiply.outer(dirs[2], np.cos(v)))
    ax.plot_wireframe(end[0] + xyz[0], end[1] + xyz[1], end[2] + xyz[2], color=color, lw=0.4,
                      alpha=0.6)
    for k, (ln, d, e) in enumerate(zip(lengths, dirs, eff)):
        a, b = end - e * d, end + e * d
        ax.plot([a[0], b[0]], [a[1], b[1]], [a[2], b[2]], "-" if ln is not None else "--",
                color=color, lw=1.5)
        at = end + 1.12 * e * d
        ax.text(*at, _axis_letter(k), color=color, fontsize=9, fontweight="bold",
                ha="center", va="center")
        ax.plot([], [], "-" if ln is not None else "--", color=color, lw=1.5,
                label=_semi_axis_label(k, ln, panel))
    # a 3-D panel's "best" is its top right, under the title: the empty top left instead
    _legend(ax, panel, links, finite, s, loc="upper left", bbox_to_anchor=(0.0, 0.94))
    labels = spec_data["axis_labels"]
    unit_axis = "m" if links else panel["unit"]
    ax.set_xlabel(f"{labels[0]} [{unit_axis}]")
    ax.set_ylabel(f"{labels[1]} [{unit_axis}]")
    ax.set_zlabel(f"{labels[2]} [{unit_axis}]")
    try:
        ax.set_box_aspect((1, 1, 1))
    except AttributeError:
        pass
    pts = np.concatenate([np.array([p for a in links for p in a] or [end]),
                          (end[:, None] + xyz.reshape(3, -1)).T])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, half = (lo + hi) / 2, max(float(np.max(hi - lo)) / 2, 1e-3)
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_title(f"{panel['title']} [{panel['unit']}]", fontsize=10)


def draw(spec, path):
    from robosolve.render.plots import fixed_layout, new_figure, save

    data = spec.data
    panels = data["panels"]
    dims = data["dims"]
    fig = new_figure((5.2 * len(panels), 5.0))
    for i, panel in enumerate(panels):
        color = COLORS.get(panel.get("key", ""), "C%d" % i)
        if dims == 3:
            ax = fig.add_subplot(1, len(panels), i + 1, projection="3d")
            _draw_3d(ax, data, panel, color)
        else:
            ax = fig.add_subplot(1, len(panels), i + 1)
            _draw_2d(ax, data, panel, color)
    fig.suptitle(spec.title)
    # room for the suptitle over the panel titles, and for semi-axis labels past a panel's edge
    fixed_layout(fig, 1, len(panels), top=0.75, right=0.9, wgap=1.2)
    save(fig, path)
