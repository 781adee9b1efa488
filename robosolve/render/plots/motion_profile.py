"""Position, velocity and acceleration of every joint against time, switching instants marked.

Data: t (each switching instant twice, once per side), T, switches, joints [{name, label, kind,
q, qd, qdd}].
"""

from __future__ import annotations

from robosolve.render.plots import figure_number, fixed_layout, save, settle_layout, subplots

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


# the switching instants' labels above the first panel: their size and the step between rows
# (points); the figure's top margin with one row (inches)
LABEL_SIZE = 8
ROW_STEP = 10
TOP = 0.7


def label_rows(ax, ticks, labels) -> list[int]:
    """The row of each switching instant's label above `ax` (0 nearest it): each label goes to
    the lowest row where it clears the labels already there (close instants: a short
    acceleration phase, 0.208 s beside 0.295 s), the ends 0 and T first, then the others from
    left to right. Widths are measured on the renderer, positions at the panel's width."""
    from matplotlib.font_manager import FontProperties

    renderer = ax.figure.canvas.get_renderer()
    font = FontProperties(size=LABEL_SIZE)
    gap = 3 * ax.figure.dpi / 72                            # pixels between neighbours
    kept: list[list[tuple[float, float]]] = []              # per row: (x0, x1), pixels
    rows = [0] * len(ticks)
    for i in dict.fromkeys([0, len(ticks) - 1, *range(1, len(ticks) - 1)]):
        width = renderer.get_text_width_height_descent(labels[i], font, ismath=False)[0]
        centre = ax.transData.transform((ticks[i], 0.0))[0]
        x0, x1 = centre - width / 2 - gap, centre + width / 2 + gap
        row = next((r for r, spans in enumerate(kept) if all(x1 <= a or b <= x0 for a, b in spans)),
                   len(kept))
        if row == len(kept):
            kept.append([])
        kept[row].append((x0, x1))
        rows[i] = row
    return rows


def _settled_rows(fig, ax, ticks, labels) -> list[int]:
    """`label_rows` at the figure's final layout: more rows need a larger top margin, which
    changes the panels' heights (and maybe their tick labels, and so the margins)."""
    for _ in range(3):
        settle_layout(fig)
        rows = label_rows(ax, ticks, labels)
        top = TOP + max(rows) * ROW_STEP / 72
        if fig.robosolve_layout["top"] == top:
            return rows
        fixed_layout(fig, **dict(fig.robosolve_layout, top=top))
    settle_layout(fig)
    return label_rows(ax, ticks, labels)


def instant_labels(ticks) -> list[str]:
    """The instants written with three significant digits, or as many more (up to six) as tell
    close ones apart (1.998 and 1.999 beside T = 2, not three 2s)."""
    for digits in range(3, 7):
        labels = [figure_number(x, digits) for x in ticks]
        if len(set(labels)) == len(labels):
            break
    return labels


def mark_switch_times(ax, ticks, title) -> None:
    """Every switching instant (and 0, T) written above `ax`, in staggered rows where close
    instants would overlap, a tick at each; the title above the rows."""
    from matplotlib.transforms import offset_copy

    labels = instant_labels(ticks)
    rows = _settled_rows(ax.figure, ax, ticks, labels)
    top = ax.secondary_xaxis("top")
    top.set_xticks(ticks)
    top.set_xticklabels([""] * len(ticks))
    for x, label, row in zip(ticks, labels, rows):
        above = offset_copy(ax.get_xaxis_transform(), fig=ax.figure, y=7 + row * ROW_STEP, units="points")
        ax.text(x, 1.0, label, transform=above, ha="center", va="bottom", fontsize=LABEL_SIZE)
    ax.set_title(title, pad=18 + max(rows) * ROW_STEP)


def draw(spec, path):
    d = spec.data
    t = d["t"]
    fig, axes = subplots(3, 1, figsize=(7.5, 7.5), sharex=True)
    fixed_layout(fig, 3, 1, top=TOP, hgap=0.2)      # the title above the switching-instant labels
    titles = (("q", "position"), ("qd", "velocity"), ("qdd", "acceleration"))
    for order, (ax, (key, what)) in enumerate(zip(axes, titles)):
        for k, j in enumerate(d["joints"]):
            ax.plot(t, j[key], color=COLOURS[k % len(COLOURS)], lw=1.6, label=f"${j['label']}$")
        mark_switches(ax, d["switches"], d["T"])
        ax.set_ylabel(f"{what} ({_units(d['joints'], order)})")
    axes[0].legend(loc="best")
    axes[-1].set_xlabel("t (s)")
    mark_switch_times(axes[0], sorted({0.0, d["T"], *d["switches"]}), spec.title)
    save(fig, path)
