"""Every actuator against time along the profile: jumps at the switching instants, peaks marked.

Data: t (each switching instant twice, once per side), T, switches, actuators [{name, label,
unit, values, peak, t_peak}].
"""

from __future__ import annotations

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
        # to the left of a peak in the second half of the run: the text stays inside the axes
        right = a["t_peak"] > d["T"] / 2
        ax.annotate(f"peak {figure_number(a['peak'])} {a['unit']} at t = {figure_number(a['t_peak'])} s",
                    (a["t_peak"], a["peak"]),
                    textcoords="offset points", xytext=(-8 if right else 8, -12 if a["peak"] > 0 else 6),
                    ha="right" if right else "left", fontsize=8,
                    bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85))
        ax.set_ylabel(f"${a['label']}$ ({a['unit']})")
    axes[0, 0].set_title(spec.title)
    axes[-1, 0].set_xlabel("t (s)")
    save(fig, path)
