"""Joint motion against time: positions, rates and accelerations (three panels, one line per joint).

Data: t, T, switches, joints [{label, unit, q, qd, qdd}].
"""

from __future__ import annotations

from robosolve.render.plots import save, time_panels
from robosolve.render.plots.motion_profile import COLOURS


def draw(spec, path):
    d = spec.data
    fig, axes = time_panels(3, 1, width=8, row_height=2.4, top=0.55, hgap=0.3)
    units = sorted({j["unit"] for j in d["joints"]})
    u = "/".join(units)
    rows = (("q", f"position ({u})"), ("qd", f"rate ({u}/s)"), ("qdd", f"acceleration ({u}/s²)"))
    for r, (key, ylabel) in enumerate(rows):
        ax = axes[r, 0]
        for k, j in enumerate(d["joints"]):
            ax.plot(d["t"], j[key], color=COLOURS[k % len(COLOURS)], lw=1.4, label=f"${j['label']}$")
        for s in d["switches"]:
            ax.axvline(s, color="0.5", ls="--", lw=0.8)
        ax.axhline(0.0, color="0.7", lw=0.6)
        ax.set_ylabel(ylabel)
        ax.legend(loc="best", fontsize=8)
    axes[-1, 0].set_xlabel("t (s)")
    fig.suptitle(spec.title)
    save(fig, path)
