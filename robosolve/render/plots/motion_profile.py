"""Position, velocity and acceleration of every joint against time, switching instants marked.

Data: t (each switching instant twice, once per side), T, switches, joints [{name, label, kind,
q, qd, qdd}].
"""

from __future__ import annotations

from robosolve.render.plots import fixed_layout, save, subplots

COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown")


def _units(joints, order):
    kinds = {j["kind"] for j in joints}
    base = "rad" if kinds == {"revolute"} else "m" if kinds == {"prismatic"} else "rad or m"
    return base + ("", "/s", "/s²")[order]


def mark_switches(ax, switches, T):
    for s in switches:
        ax.axvline(s, color="0.5", ls="--", lw=0.8)
    ax.axvline(0.0, color="0.3", lw=0.8)
    ax.axvline(T, color="0.3", lw=0.8)


def switch_labels(ax, ticks, fontsize: float) -> list[str]:
    """The labels of the switching-instant ticks, a label left blank where it would overlap one
    already kept (close instants: a short acceleration phase, 0.157 s beside 0.333 s): the ends
    0 and T first, then the others from left to right. Widths are estimated from the digits
    (about 0.64 em each in DejaVu Sans), the axes' width from its position in the figure."""
    width_pt = ax.get_position().width * ax.figure.get_figwidth() * 72
    lo, hi = ax.get_xlim()
    labels = [f"{x:.3g}" for x in ticks]
    shown = [""] * len(ticks)
    kept: list[tuple[float, float]] = []            # (centre, half width) in points
    for i in [0, len(ticks) - 1] + list(range(1, len(ticks) - 1)):
        centre = (ticks[i] - lo) / (hi - lo) * width_pt if hi > lo else 0.0
        half = 0.32 * fontsize * len(labels[i]) + 2
        if all(abs(centre - c) >= half + h for c, h in kept):
            kept.append((centre, half))
            shown[i] = labels[i]
    return shown


def draw(spec, path):
    d = spec.data
    t = d["t"]
    fig, axes = subplots(3, 1, figsize=(7.5, 7.5), sharex=True)
    fixed_layout(fig, 3, 1, top=0.7, hgap=0.2)      # the title above the switching-instant ticks
    titles = (("q", "position"), ("qd", "velocity"), ("qdd", "acceleration"))
    for order, (ax, (key, what)) in enumerate(zip(axes, titles)):
        for k, j in enumerate(d["joints"]):
            ax.plot(t, j[key], color=COLOURS[k % len(COLOURS)], lw=1.6, label=f"${j['label']}$")
        mark_switches(ax, d["switches"], d["T"])
        ax.set_ylabel(f"{what} ({_units(d['joints'], order)})")
    axes[0].legend(loc="best")
    axes[0].set_title(spec.title, pad=18)      # above the switching-instant tick labels
    ticks = sorted({0.0, d["T"], *d["switches"]})
    top = axes[0].secondary_xaxis("top")
    top.set_xticks(ticks)
    top.set_xticklabels(switch_labels(axes[0], ticks, fontsize=8), fontsize=8)
    axes[-1].set_xlabel("t (s)")
    save(fig, path)
