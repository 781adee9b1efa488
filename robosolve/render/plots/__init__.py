"""Figures. `draw(spec, path)` dispatches to the module named by `spec.kind`.

matplotlib is imported here only, and only when a figure is drawn; pyplot never is: a
`matplotlib.figure.Figure` is drawn by the Agg canvas directly (`new_figure`), which skips
pyplot's import, its figure manager and the bookkeeping of open figures.

Drawing is kept cheap (issue 15): every figure gets a fixed layout, margins in inches set by
`fixed_layout` for what its kind draws (titles, tick labels, axis labels), instead of
constrained / tight layout or `bbox_inches="tight"`, which measure every text's extent in
extra draw passes (they were most of the figures' time); PNGs are written with zlib level 1
(same bytes for the same input, about half the encoding time of the default level 6).

Before a figure is written (`save`, `settle_layout`), two things are settled that its kind cannot know in advance:
a panel whose values are one constant to round-off is drawn flat with plain ticks
(`flat_when_constant`), and the margins and gaps are widened where a panel's axes need more than
the fixed layout gave them (`fit_margins`: tick labels like −1.57175, small motions about a large
value, and the axis label left of them). Only the axes' own texts are measured (the axis' tick
labels and label, which matplotlib caches for the draw that follows), not the whole figure.
"""

from __future__ import annotations

import gc
import importlib
import math

_RC = {
    "figure.dpi": 100, "savefig.dpi": 100, "font.size": 10, "axes.grid": True,
    "grid.alpha": 0.3, "svg.hashsalt": "robosolve",
    # titles at a fixed height: the automatic one measures the top axis' tick labels on every
    # draw; a figure with tick labels on top (a motion profile) gives its title a larger pad
    "axes.titley": 1.0,
    # values from 1e4 up, or below 1e-4, are written with a ×10ⁿ above the axis (tick labels
    # can still be long: −1.57175, a small motion about a large value; `fit_margins` makes room)
    "axes.formatter.limits": (-4, 4), "axes.formatter.use_mathtext": True,
}
PNG_OPTIONS = {"compress_level": 1}


def _import_matplotlib():
    """Import the parts of matplotlib the figures use, without building the property tables
    of its docstrings.

    While matplotlib's modules are imported, every Artist subclass formats the table of its
    settable properties into the docstring of its `set` method (`matplotlib.artist.kwdoc`, also
    used for the `%(Line2D:kwdoc)s` substitutions in the Axes methods' docstrings): a quarter
    of matplotlib's import time, for text only `help()` shows. It is skipped while importing
    (the docstrings lose the table; nothing that draws reads them) and restored afterwards; if
    matplotlib was imported already, or changes how it builds those docstrings, this is just
    the ordinary import."""
    import sys

    if "matplotlib.figure" not in sys.modules:
        import matplotlib.artist as artist

        kwdoc = getattr(artist, "kwdoc", None)
        if callable(kwdoc):
            artist.kwdoc = lambda _artist: ""
            try:
                import matplotlib.figure  # noqa: F401
                from matplotlib.backends import backend_agg  # noqa: F401
            finally:
                artist.kwdoc = kwdoc
    import matplotlib

    return matplotlib


def setup():
    """matplotlib with the figures' rc settings (applied once per process): the module."""
    matplotlib = _import_matplotlib()

    if matplotlib.rcParams["savefig.dpi"] != _RC["savefig.dpi"] or \
            matplotlib.rcParams["svg.hashsalt"] != "robosolve":
        matplotlib.rcParams.update(_RC)
    return matplotlib


def new_figure(figsize):
    """An empty Figure on an Agg canvas (no pyplot)."""
    setup()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)
    return fig


def subplots(nrows=1, ncols=1, *, figsize, **kwargs):
    """`pyplot.subplots` without pyplot: (fig, axes)."""
    fig = new_figure(figsize)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def fixed_layout(fig, nrows=1, ncols=1, *, left=0.85, right=0.2, top=0.45, bottom=0.55,
                 hgap=0.25, wgap=0.3):
    """Place the subplot grid with margins and gaps given in inches (no text is measured here;
    `fit_margins` widens them at `save` if the axes' texts need more).

    left/bottom hold tick labels and axis labels, top the title(s), hgap/wgap what sits
    between panels (tick labels, a panel's axis label or title)."""
    fig.robosolve_layout = dict(nrows=nrows, ncols=ncols, left=left, right=right, top=top,
                                bottom=bottom, hgap=hgap, wgap=wgap)
    w, h = fig.get_size_inches()
    axes_w = (w - left - right - (ncols - 1) * wgap) / ncols
    axes_h = (h - top - bottom - (nrows - 1) * hgap) / nrows
    fig.subplots_adjust(left=left / w, right=1 - right / w, bottom=bottom / h, top=1 - top / h,
                        wspace=wgap / axes_w, hspace=hgap / axes_h)


# a text's clearance from the figure's edge or from the next panel (inches)
TEXT_CLEARANCE = 0.06


def matplotlib_rc(key):
    return setup().rcParams[key]


def _reach(fig, layout) -> dict:
    """How far (inches) the 2-D panels' axes draw beyond their boxes, measured on the renderer:
    {"left", "right": per column; "above", "below": per row} (tick labels, offset texts, labels)."""
    renderer = fig.canvas.get_renderer()
    reach = {"left": [0.0] * layout["ncols"], "right": [0.0] * layout["ncols"],
             "above": [0.0] * layout["nrows"], "below": [0.0] * layout["nrows"]}
    for ax in fig.axes:
        spec = ax.get_subplotspec()
        if spec is None or ax.name != "rectilinear" or not ax.axison:
            continue
        box = ax.get_window_extent(renderer)
        for axis in (ax.xaxis, ax.yaxis):
            drawn = axis.get_tightbbox(renderer)
            if drawn is None:
                continue
            for side, at, beyond in (("left", spec.colspan.start, box.x0 - drawn.x0),
                                     ("right", spec.colspan.stop - 1, drawn.x1 - box.x1),
                                     ("above", spec.rowspan.start, drawn.y1 - box.y1),
                                     ("below", spec.rowspan.stop - 1, box.y0 - drawn.y0)):
                reach[side][at] = max(reach[side][at], beyond / fig.dpi)
    return reach


def _relayout(fig, layout, wanted) -> dict:
    if wanted != layout:
        fixed_layout(fig, **wanted)
    return wanted


def fit_margins(fig) -> bool:
    """Widen the gaps between rows, then the left and right margins and the gaps between
    columns, of a `fixed_layout` figure where its 2-D panels' axes draw further than the layout
    gave them (`_reach`): an offset text (×10⁻⁸+4×10⁻¹) above a panel, the y axis' tick labels
    (−1.57175) and label left of it. The rows first: their heights decide the y ticks, which
    the columns' widths do not change. Nothing is ever narrowed. Whether the layout changed."""
    layout = getattr(fig, "robosolve_layout", None)
    if layout is None:
        return False
    reach = _reach(fig, layout)
    # below a panel, its x tick marks at least (they point out, into the gap)
    ticks = matplotlib_rc("xtick.major.size") / 72 if matplotlib_rc("xtick.direction") == "out" else 0.0
    rows = [max(reach["below"][r - 1], ticks) + reach["above"][r] + TEXT_CLEARANCE
            for r in range(1, layout["nrows"])]
    settled = _relayout(fig, layout, dict(layout, hgap=max([layout["hgap"], *rows])))
    if settled != layout:
        reach = _reach(fig, settled)
    columns = [reach["right"][c - 1] + reach["left"][c] + TEXT_CLEARANCE for c in range(1, layout["ncols"])]
    settled = _relayout(fig, settled, dict(settled, wgap=max([settled["wgap"], *columns]),
                                           left=max(settled["left"], reach["left"][0] + TEXT_CLEARANCE),
                                           right=max(settled["right"], reach["right"][-1] + TEXT_CLEARANCE)))
    return settled != layout


# a spread of values below this fraction of their size is round-off (or integration noise), not
# a change: the values are one constant (the solvers' threshold for an error that is noise)
ROUNDOFF = 1e-9


def is_roundoff(spread: float, scale: float) -> bool:
    """Whether `spread` is round-off relative to values of size `scale`."""
    return math.isfinite(spread) and abs(spread) <= ROUNDOFF * abs(scale)


def plot_or_zero(ax, t, values, scale, note, unit, **style):
    """Plot `values` against `t`; values that are all round-off relative to `scale` (a tracking
    error that is zero in exact arithmetic, the rate of a joint at rest) are drawn as the zero
    line, with `note` (what is bounded) and their bound in `unit` written in the panel, not as 10⁻¹² noise under a ×10ⁿ."""
    largest = max((abs(v) for v in values), default=0.0)
    if largest > 0 and is_roundoff(largest, scale):
        ax.plot(t, [0.0] * len(t), **style)
        ax.text(0.5, 0.75, f"zero to round-off: {note} ≤ {figure_number(largest, 2)} {unit}", transform=ax.transAxes,
                ha="center", va="center", fontsize=8, color="0.25", bbox=dict(fc="white", ec="none", alpha=0.85))
    else:
        ax.plot(t, values, **style)


def flat_when_constant(ax) -> None:
    """A panel whose data are one constant to round-off (a coordinate that stays in its plane):
    its y range is the one matplotlib gives an exact constant, so the values are drawn as a flat
    line with plain ticks instead of their noise under a ×10⁻¹³+4×10⁻¹ offset. Panels scaled
    by hand, with equal aspect or a log scale are left as they are."""
    if ax.name != "rectilinear" or not ax.get_autoscaley_on() or ax.get_yscale() != "linear" \
            or ax.get_aspect() != "auto":
        return
    lo, hi = ax.dataLim.intervaly
    if not (math.isfinite(lo) and math.isfinite(hi)) or hi <= lo or \
            not is_roundoff(hi - lo, max(abs(lo), abs(hi))):
        return
    centre = (lo + hi) / 2
    ax.set_ylim(*ax.yaxis.get_major_locator().nonsingular(centre, centre))


def one_3d_box(width, height):
    """A figure holding one 3-D axes: (fig, ax). Axes3D draws its labels inside its box, so
    the margins are thin but for the title."""
    fig = new_figure((width, height))
    ax = fig.add_subplot(projection="3d")
    fixed_layout(fig, left=0.1, right=0.1, top=0.4, bottom=0.1)
    return fig, ax


_SUPERSCRIPTS = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def figure_number(x: float, digits: int = 4) -> str:
    """A number written in a figure: `digits` significant digits, plain from 0.001 to below 10⁶
    (123457, 1235, 0.0123), else as 1.235×10⁻⁹; the minus sign of the tick labels (−)."""
    x = float(x)
    if x == 0 or not math.isfinite(x):
        return "0" if x == 0 else str(x)
    exponent = math.floor(math.log10(abs(x)))
    if -3 <= exponent < 6:
        places = max(0, digits - 1 - exponent)
        shown = f"{x:.{places}f}"
        if "." in shown:
            shown = shown.rstrip("0").rstrip(".")
    else:
        mantissa = f"{x / 10 ** exponent:.{digits - 1}f}".rstrip("0").rstrip(".")
        if mantissa in ("10", "-10"):                 # 9.9996 rounded up
            mantissa, exponent = mantissa[:-1], exponent + 1
        shown = f"{mantissa}×10{str(exponent).translate(_SUPERSCRIPTS)}"
    return shown.replace("-", "−", 1) if shown.startswith("-") else shown


def time_panels(rows, cols=1, *, width, row_height, top, hgap=0.2, wgap=0.3):
    """A figure of rows x cols panels against one time axis (shared x), laid out by
    `fixed_layout`: (fig, axes as a rows x cols array)."""
    fig, axes = subplots(rows, cols, figsize=(width, row_height * rows + 0.8), sharex=True,
                         squeeze=False)
    fixed_layout(fig, rows, cols, top=top, hgap=hgap, wgap=wgap)
    return fig, axes


def settle_layout(fig) -> None:
    """Its constant panels flat, its margins fitted to its axes' texts (idempotent: `save` runs
    it; a kind that places texts by the final panel widths runs it first)."""
    for ax in fig.axes:
        flat_when_constant(ax)
    fit_margins(fig)


def save(fig, path):
    """Write `fig` as a PNG, its layout settled (`settle_layout`)."""
    settle_layout(fig)
    fig.savefig(path, metadata={"Software": None}, pil_kwargs=dict(PNG_OPTIONS))


def draw(spec, path) -> None:
    """Draw one FigureSpec into a PNG file at `path`."""
    from dataclasses import replace

    from robosolve.render.numbers import text

    module = importlib.import_module(f"robosolve.render.plots.{spec.kind}")
    setup()
    # no cyclic garbage collection while a figure is built and drawn: matplotlib allocates tens
    # of thousands of objects per figure, which set off collections of the whole heap (after a
    # solve, mostly sympy's expressions: 0.3 s a pass); the figure's own cycles are collected
    # at the next ordinary collection after it is written
    collecting = gc.isenabled()
    gc.disable()
    try:
        module.draw(replace(spec, title=text(spec.title), data=_formatted(spec.data)), path)
    finally:
        if collecting:
            gc.enable()


def _formatted(v):
    """The figure's data with prose (`Text`, `Num`: labels, titles) formatted."""
    from robosolve.core.prose import Num, Text
    from robosolve.render.numbers import text

    if isinstance(v, (Num, Text)):
        return text(v)
    if isinstance(v, dict):
        return {k: _formatted(x) for k, x in v.items()}
    if isinstance(v, list):
        if all(type(x) is float for x in v):    # samples: nothing to format
            return v
        return [_formatted(x) for x in v]
    return v
