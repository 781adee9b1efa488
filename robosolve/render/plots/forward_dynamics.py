"""Forward dynamics: one joint's value (top) and rate (bottom) against time, with its extremes.

Data: t, q, qd, label, rate_label, unit, rate_unit, max, t_max, min, t_min.
"""

from __future__ import annotations

from robosolve.render.plots import figure_number, fixed_layout, plot_or_zero, save, subplots
from robosolve.render.plots.motion_profile import COLOURS


def draw(spec, path):
    d = spec.data
    fig, (ax, axr) = subplots(2, 1, figsize=(8, 5.6), sharex=True)
    fixed_layout(fig, 2, 1, top=0.5, hgap=0.2)
    ax.plot(d["t"], d["q"], color=COLOURS[0], lw=1.5, label=f"${d['label']}(t)$")
    ax.plot([d["t_max"]], [d["max"]], "v", color="0.25", ms=6, label=f"max {figure_number(d['max'], 6)} {d['unit']}")
    ax.plot([d["t_min"]], [d["min"]], "^", color="0.55", ms=6, label=f"min {figure_number(d['min'], 6)} {d['unit']}")
    ax.set_ylabel(f"${d['label']}$ ({d['unit']})")
    ax.legend(loc="best", fontsize=8)
    # a joint at rest (at an equilibrium): a rate of round-off beside the joint's value over the
    # run, drawn as zero, as its value is drawn flat
    duration = d["t"][-1] - d["t"][0]
    rate_scale = max(abs(d["max"]), abs(d["min"])) / duration if duration > 0 else 0.0
    plot_or_zero(axr, d["t"], d["qd"], rate_scale, f"$|{d['rate_label']}|$", d["rate_unit"],
                 color=COLOURS[1 % len(COLOURS)], lw=1.3, label=f"${d['rate_label']}(t)$")
    axr.axhline(0.0, color="0.6", lw=0.6)
    axr.set_ylabel(f"${d['rate_label']}$ ({d['rate_unit']})")
    axr.set_xlabel("t (s)")
    axr.legend(loc="best", fontsize=8)
    fig.suptitle(spec.title)
    save(fig, path)
