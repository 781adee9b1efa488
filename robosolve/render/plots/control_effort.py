"""Closed-loop actuator effort against time, one panel per actuator.

Data: t, T, duration, switches, actuators [{name, label, unit, values, external}]
(external: the generalized external force on the joint, or None when zero).
"""

from __future__ import annotations

from robosolve.render.plots import save, time_panels
from robosolve.render.plots.control_tracking import _marks
from robosolve.render.plots.motion_profile import COLOURS


def draw(spec, path):
    d = spec.data
    acts = d["actuators"]
    fig, axes = time_panels(len(acts), width=7.5, row_height=2.3, top=0.5)
    for k, (ax, a) in enumerate(zip(axes[:, 0], acts)):
        ax.plot(d["t"], a["values"], color=COLOURS[k % len(COLOURS)], lw=1.2,
                label=f"actuator ${a['label']}$")
        if a.get("external") is not None:      # the loads the actuator works with or against
            ax.plot(d["t"], a["external"], color="0.25", ls="--", lw=1.1,
                    label="external (generalized) force $f_{ext}$")
        ax.axhline(0.0, color="0.6", lw=0.6)
        _marks(ax, d)
        extra = ", $f_{ext}$" if a.get("external") is not None else ""
        ax.set_ylabel(f"${a['label']}${extra} ({a['unit']})")
        ax.legend(loc="best", fontsize=8)
    fig.suptitle(spec.title)
    axes[-1, 0].set_xlabel("t (s)")
    save(fig, path)
