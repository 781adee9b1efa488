"""Closed-loop tracking: each joint's actual trajectory over its desired profile (left) and the
error e = q_d - q (right), one row per joint.

Data: t, T, duration, switches, joints [{name, label, unit, q, q_desired, error}]; optional
error_title (a work-space error: x_d - x).
"""

from __future__ import annotations

from robosolve.render.plots import plot_or_zero, save, time_panels
from robosolve.render.plots.motion_profile import COLOURS


def _marks(ax, d):
    for s in d["switches"]:
        ax.axvline(s, color="0.5", ls="--", lw=0.8)
    if d["T"] < d["duration"]:
        ax.axvline(d["T"], color="0.3", lw=0.8)


def _error_panel(ax, t, j, colour):
    """The error against time; round-off relative to the coordinate's values (computed torque
    started on the reference: zero in exact arithmetic) is drawn as the zero line."""
    scale = max(abs(x) for x in [*j["q"], *j["q_desired"], 0.0])
    plot_or_zero(ax, t, j["error"], scale, "$|e|$", j["unit"], color=colour, lw=1.2)
    ax.axhline(0.0, color="0.6", lw=0.6)


def draw(spec, path):
    d = spec.data
    js = d["joints"]
    # suptitle above the panel titles
    # the gap holds the error column's tick labels (an error of a few mrad: −0.0035, seven
    # characters) and its axis label, clear of the trajectory column
    fig, axes = time_panels(len(js), 2, width=10, row_height=2.6, top=0.75, wgap=1.1)
    for k, j in enumerate(js):
        c = COLOURS[k % len(COLOURS)]
        unit = f" ({j['unit']})" if j["unit"] else ""      # none for a coordinate of mixed units
        ax = axes[k, 0]
        ax.plot(d["t"], j["q_desired"], color="0.2", ls="--", lw=1.4, label="desired")
        ax.plot(d["t"], j["q"], color=c, lw=1.4, label="actual")
        _marks(ax, d)
        ax.set_ylabel(f"${j['label']}${unit}")
        ax.legend(loc="best", fontsize=8)
        ax = axes[k, 1]
        _error_panel(ax, d["t"], j, c)
        _marks(ax, d)
        ax.set_ylabel(f"$e_{{{j['label']}}}${unit}")
    axes[0, 0].set_title("trajectory")
    axes[0, 1].set_title(d.get("error_title", "error $e = q_d - q$"))
    for ax in axes[-1]:
        ax.set_xlabel("t (s)")
    fig.suptitle(spec.title)
    save(fig, path)
