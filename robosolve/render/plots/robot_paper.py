"""The robot of an exam paper, drawn like a textbook figure (papers.md "The drawing").

Data (papers/drawing.py): frames [{name, label, origin, axes}], links, points [{name, at}],
joints [{label, at, revolute}], forces [{label, at, direction, kind}], gravity (a unit
vector or None), plane (the two axes of frame 0 the robot moves in, or None: 3-D).
2-D: the in-plane axes of each frame as arrows labelled x₁, y₁; an axis normal to the
page as ⊙ (towards the reader) or ⊗ (away); a force as an arrow, a torque as a double-headed
arrow, or about the page's normal as a circular arrow (counter-clockwise when it points towards
the reader), a force normal to the page as ⊙ / ⊗. Frames sharing an origin get longer axes.
Labels are placed once the limits are fixed, each beside its anchor where it covers no label
placed before, no link, arrow or marker (`_place_labels_2d`; in 3-D, `_place_labels`: no label).
"""

from __future__ import annotations

import numpy as np

from robosolve.render.plots import fixed_layout, one_3d_box, save, subplots
from robosolve.render.plots.robot import extent

AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")
LINK = "0.3"
FORCE = "tab:purple"
NAMES = "xyz"


def _scales(frames, size, base=0.16):
    """Axis length of each frame: longer for each earlier frame at (nearly) the same origin."""
    out, seen = [], []
    for f in frames:
        o = np.array(f["origin"], dtype=float)
        k = sum(1 for p in seen if np.linalg.norm(p - o) < 0.05 * size)
        out.append(base * size * (1 + 0.6 * k))
        seen.append(o)
    return out


def _shared(frames, size):
    """For each frame, how many earlier frames share its origin."""
    out, seen = [], []
    for f in frames:
        o = np.array(f["origin"], dtype=float)
        out.append(sum(1 for p in seen if np.linalg.norm(p - o) < 0.05 * size))
        seen.append(o)
    return out


def _points_2d(d, h, v):
    pts = [[0.0, 0.0]]
    for link in d["links"]:
        pts += [[p[h], p[v]] for p in link]
    pts += [[p["at"][h], p["at"][v]] for p in d["points"]]
    return np.array(pts, dtype=float)


def _draw_2d(ax, d, size) -> tuple[list, list]:
    """The robot in the plane, without its labels; returns (labels, obstacles): each label
    (anchor xy, text, colour, points, weight, preferred side) placed later by `_place_labels_2d`
    once the limits are fixed, and what a label must not cover (segments and markers, in data
    coordinates with their half-widths in points)."""
    h, v = d["plane"]
    normal = 3 - h - v
    labels, segments, markers = [], [], []
    for link in d["links"]:
        a = np.array(link, dtype=float)
        ax.plot(a[:, h], a[:, v], "-", color=LINK, lw=4, solid_capstyle="round", zorder=2)
        segments += [((p[h], p[v]), (q[h], q[v]), 3.5) for p, q in zip(a[:-1], a[1:])]
    for j in d["joints"]:
        x, y = j["at"][h], j["at"][v]
        ax.plot([x], [y], "o" if j["revolute"] else "s", ms=9, mfc="white", mec=LINK, mew=2, zorder=3)
        markers.append(((x, y), 5.5))
        labels.append(((x, y), j["label"], "0.1", 12, "normal", "NW"))
    for f, s, k in zip(d["frames"], _scales(d["frames"], size), _shared(d["frames"], size)):
        o = np.array(f["origin"], dtype=float)
        for c, axis in enumerate(f["axes"]):
            a = np.array(axis, dtype=float)
            label = f["axis_labels"][c]
            if abs(a[normal]) > 0.9:          # normal to the page: ⊙ / ⊗
                towards = a[normal] > 0 if (h, v) != (0, 2) else a[normal] < 0
                ax.plot([o[h]], [o[v]], "o", ms=7, mfc="white", mec=AXIS_COLOURS[c], mew=1.2, zorder=4)
                ax.plot([o[h]], [o[v]], "." if towards else "x", ms=5 if towards else 4,
                        color=AXIS_COLOURS[c], zorder=5)
                markers.append(((o[h], o[v]), 4.5))
                labels.append(((o[h], o[v]), label, AXIS_COLOURS[c], 10, "normal", "SE"))
                continue
            tip = o + a * s
            ax.annotate("", xy=(tip[h], tip[v]), xytext=(o[h], o[v]),
                        arrowprops=dict(arrowstyle="-|>", color=AXIS_COLOURS[c], lw=1.3), zorder=4)
            segments.append(((o[h], o[v]), (tip[h], tip[v]), 1.5))
            labels.append(((tip[h], tip[v]), label, AXIS_COLOURS[c], 10, "normal", _side(a[h], a[v])))
    for p in d["points"]:
        x, y = p["at"][h], p["at"][v]
        ax.plot([x], [y], "s", ms=6, color="tab:orange", zorder=5)
        markers.append(((x, y), 3.5))
        labels.append(((x, y), p["name"], "tab:orange", 12, "bold", "NE"))
    for f in d["forces"]:
        _load_2d(ax, f, (h, v), size, labels, segments)
    # no scale: a drawing at a question's configuration must not let coordinates be read off it
    ax.set_xticks([])
    ax.set_yticks([])
    ax.grid(False)
    ax.set_xlabel(f"{NAMES[h]}₀")
    ax.set_ylabel(f"{NAMES[v]}₀")
    return labels, (segments, markers)


def _load_2d(ax, f, plane, size, labels, segments) -> None:
    """A force or torque in the plane: an arrow (two heads for a torque); one normal to the page:
    a torque as a circular arrow about its point (counter-clockwise when it points towards the
    reader), a force as ⊙ (towards the reader) or ⊗ (away)."""
    from matplotlib.patches import Arc

    h, v = plane
    o, u = np.array(f["at"]), np.array(f["direction"]) * 0.3 * size
    if np.hypot(u[h], u[v]) > 0.2 * 0.3 * size:
        for reach in _heads(f):               # a moment: two heads at the tip, as textbooks draw it
            ax.annotate("", xy=(o[h] + reach * u[h], o[v] + reach * u[v]), xytext=(o[h], o[v]),
                        arrowprops=dict(arrowstyle="-|>", color=FORCE, lw=2.2), zorder=6)
        segments.append(((o[h], o[v]), (o[h] + u[h], o[v] + u[v]), 2.0))
        labels.append(((o[h] + u[h], o[v] + u[v]), f["label"], FORCE, 12, "normal", _side(u[h], u[v])))
        return
    normal = 3 - h - v
    towards = (u[normal] > 0) != ((h, v) == (0, 2))     # the page's normal towards the reader
    r = 0.12 * size
    if f.get("kind") != "torque":
        ax.plot([o[h]], [o[v]], "o", ms=11, mfc="white", mec=FORCE, mew=1.8, zorder=6)
        ax.plot([o[h]], [o[v]], "." if towards else "x", ms=7, color=FORCE, mew=1.8, zorder=7)
        labels.append(((o[h] + 0.04 * size, o[v] + 0.04 * size), f["label"], FORCE, 12, "normal", "NE"))
        return
    ax.add_patch(Arc((o[h], o[v]), 2 * r, 2 * r, theta1=30, theta2=300, color=FORCE, lw=2.2, zorder=6))
    ends = (290, 300) if towards else (40, 30)          # the head at the end it turns towards
    a, b = (o[[h, v]] + r * np.array([np.cos(np.radians(t)), np.sin(np.radians(t))]) for t in ends)
    ax.annotate("", xy=tuple(b), xytext=tuple(a), arrowprops=dict(arrowstyle="-|>", color=FORCE, lw=2.2),
                zorder=6)
    ring = [o[[h, v]] + r * np.array([np.cos(t), np.sin(t)]) for t in np.radians(np.arange(30, 301, 30))]
    segments += [(tuple(p), tuple(q), 2.0) for p, q in zip(ring[:-1], ring[1:])]
    labels.append((tuple(o[[h, v]] + r * np.array([0.7, 0.7])), f["label"], FORCE, 12, "normal", "NE"))


def _heads(force) -> tuple:
    """Where the arrowheads of a load go along its arrow: one at the tip for a force, two for a
    torque (the double-headed arrow of a moment vector)."""
    return (1.0, 0.84) if force.get("kind") == "torque" else (1.0,)


def _side(dx, dy) -> str:
    """The side of an arrow's tip its label goes first: beyond the tip, away from the shaft."""
    return ("N" if dy > 0 else "S") + ("E" if dx >= 0 else "W") if abs(dy) > 0.3 * abs(dx) else \
        ("E" if dx >= 0 else "W")


# where a label's box goes around its anchor, by side, nearest first; the gaps (points) tried
SIDES = ("NE", "NW", "SE", "SW", "E", "W", "N", "S")
GAPS = (3.0, 8.0, 14.0, 22.0)


def _box(px, py, side, gap, w, h):
    """The box (x0, y0, x1, y1) in points of a w × h label on `side` of (px, py)."""
    x0 = {"E": px + gap, "W": px - gap - w}.get(side[-1], px - w / 2)
    y0 = {"N": py + gap, "S": py - gap - h}.get(side[0], py - h / 2)
    return (x0, y0, x0 + w, y0 + h)


def _hits_segment(box, a, b, half) -> bool:
    """Whether the segment ab (points), widened by `half`, meets the box."""
    x0, y0, x1, y1 = box[0] - half, box[1] - half, box[2] + half, box[3] + half
    (ax_, ay), (bx, by) = a, b
    if max(ax_, bx) < x0 or min(ax_, bx) > x1 or max(ay, by) < y0 or min(ay, by) > y1:
        return False
    t0, t1 = 0.0, 1.0                        # Liang–Barsky clipping of the segment by the box
    for p, q in ((-(bx - ax_), ax_ - x0), (bx - ax_, x1 - ax_), (-(by - ay), ay - y0), (by - ay, y1 - ay)):
        if p == 0:
            if q < 0:
                return False
            continue
        r = q / p
        if p < 0:
            t0 = max(t0, r)
        else:
            t1 = min(t1, r)
        if t0 > t1:
            return False
    return True


def _conflicts(box, placed, segments, markers, bounds) -> float:
    """How bad a label's box is: over another label, over a drawn segment or marker, outside."""
    bad = 0.0
    bad += 10 * sum(1 for b in placed if box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3])
    bad += 3 * sum(1 for a, b, half in segments if _hits_segment(box, a, b, half))
    bad += 3 * sum(1 for (x, y), r in markers
                   if box[0] - r < x < box[2] + r and box[1] - r < y < box[3] + r)
    if box[0] < bounds[0] or box[1] < bounds[1] or box[2] > bounds[2] or box[3] > bounds[3]:
        bad += 20
    return bad


def _place_labels_2d(ax, labels, obstacles, reserved=()) -> list:
    """Each label beside its anchor where it covers no label placed before, no link, axis or
    force arrow and no marker (its preferred side first, then the others, nearest first); where
    every place covers something, the least bad. Sizes are estimated from the characters.
    Returns the annotations."""
    to_points = 72 / ax.figure.dpi

    def pts(xy):
        return tuple(ax.transData.transform(xy) * to_points)

    segments = [(pts(a), pts(b), half) for a, b, half in obstacles[0]]
    markers = [(pts(xy), r) for xy, r in obstacles[1]]
    lo, hi = ax.transAxes.transform((0, 0)) * to_points, ax.transAxes.transform((1, 1)) * to_points
    bounds = (lo[0] + 2, lo[1] + 2, hi[0] - 2, hi[1] - 2)        # inside the drawing's frame
    placed, out = list(reserved), []
    for xy, text, colour, points, weight, side in labels:
        px, py = pts(xy)
        w, h = _width(text, points), points * 1.25
        order = [side] + [s for s in SIDES if s != side]
        best = None
        for gap in GAPS:
            for s in order:
                box = _box(px, py, s, gap, w, h)
                score = _conflicts(box, placed, segments, markers, bounds)
                if best is None or score < best[0]:
                    best = (score, box)
                if score == 0:
                    break
            if best[0] == 0:
                break
        box = best[1]
        placed.append(box)
        out.append(ax.annotate(text, xy, xytext=(box[0] - px, box[1] - py + 0.2 * points),
                               textcoords="offset points", fontsize=points, color=colour, weight=weight,
                               ha="left", va="baseline", zorder=8, annotation_clip=False))
    return out


def _frame_limits(ax, d, size, box, extra=(0.0, 0.0)):
    """Limits around the drawing with equal scales on both axes of the `box` (inches); `extra`
    widens the range to the left and right (room for long labels)."""
    h, v = d["plane"]
    pts = _points_2d(d, h, v)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.35 * size
    lo, hi = lo - pad, hi + pad
    lo[0] -= extra[0]
    hi[0] += extra[1]
    span = hi - lo
    per_inch = max(span[0] / box[0], span[1] / box[1])
    centre = (lo + hi) / 2
    ax.set_xlim(centre[0] - per_inch * box[0] / 2, centre[0] + per_inch * box[0] / 2)
    ax.set_ylim(centre[1] - per_inch * box[1] / 2, centre[1] + per_inch * box[1] / 2)


def _label_overflow(ax) -> tuple[float, float]:
    """How far (points) the labels run past the drawing's left and right edges, their widths
    estimated from their characters (no text is measured)."""
    to_points = 72 / ax.figure.dpi
    x_left, x_right = (ax.transAxes.transform((0, 0))[0] * to_points, ax.transAxes.transform((1, 1))[0] * to_points)
    left = right = 0.0
    for ann in ax.texts:
        if not hasattr(ann, "xyann") or not ann.get_text():
            continue
        px = ax.transData.transform(ann.xy)[0] * to_points
        x0 = px + ann.xyann[0]
        right = max(right, x0 + _width(ann.get_text(), ann.get_fontsize()) - (x_right - 2))
        left = max(left, x_left + 2 - x0)
    return left, right


def _keep_inside_2d(ax, d, size, box, labels, obstacles, reserved) -> None:
    """Place the labels, and widen the drawing's horizontal range until no label runs past its
    edges (a long frame or force name near the edge), placing them again; the scales stay equal."""
    extra = [0.0, 0.0]
    for _ in range(5):
        placed = _place_labels_2d(ax, labels, obstacles, reserved)
        left, right = _label_overflow(ax)
        if left <= 0 and right <= 0:
            return
        for ann in placed:
            ann.remove()
        per_point = (ax.get_xlim()[1] - ax.get_xlim()[0]) / (box[0] * 72)
        extra[0] += max(left, 0) * per_point * 1.05
        extra[1] += max(right, 0) * per_point * 1.05
        _frame_limits(ax, d, size, box, extra)
    _place_labels_2d(ax, labels, obstacles, reserved)


GRAVITY_AXES = [0.86, 0.68, 0.08, 0.12]      # where the gravity arrow is drawn (figure fraction)


def _gravity_box(fig, d) -> list:
    """The place (points) of the gravity arrow, which no label may cover."""
    if d.get("gravity") is None:
        return []
    w, h = fig.get_figwidth() * 72, fig.get_figheight() * 72
    x, y, bw, bh = GRAVITY_AXES
    return [((x - 0.02) * w, (y - 0.01) * h, (x + bw + 0.02) * w, (y + bh + 0.01) * h)]


def _gravity_2d(fig, d):
    g = d.get("gravity")
    if g is None:
        return
    h, v = d["plane"]
    gh, gv = g[h], g[v]
    if abs(gh) + abs(gv) < 1e-9:
        fig.text(0.93, 0.78, "g ⊥ page", fontsize=10, ha="right")
        return
    ax = fig.add_axes(GRAVITY_AXES)
    ax.set_axis_off()
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    n = np.hypot(gh, gv)
    ax.annotate("", xy=(0.8 * gh / n, 0.8 * gv / n), xytext=(-0.8 * gh / n, -0.8 * gv / n),
                arrowprops=dict(arrowstyle="-|>", color="0.15", lw=2))
    ax.text(0.25, 0.0, "$g$", fontsize=13)


def _draw_3d(ax, d, size) -> list:
    """The robot in 3-D; returns its labels [(xyz, text, colour, size, weight)], placed later
    by `_place_labels` (once the view is fixed) so that they do not overlap."""
    labels = []
    for link in d["links"]:
        a = np.array(link, dtype=float)
        ax.plot(a[:, 0], a[:, 1], a[:, 2], "-", color=LINK, lw=4)
    for j in d["joints"]:
        x, y, z = j["at"]
        ax.scatter([x], [y], [z], s=50, facecolors="white", edgecolors=LINK, linewidths=2,
                   depthshade=False, marker="o" if j["revolute"] else "s")
        labels.append((j["at"], j["label"], "0.1", 12, "normal"))
    for f, s in zip(d["frames"], _scales(d["frames"], size, 0.1)):
        o = np.array(f["origin"], dtype=float)
        for c, axis in enumerate(f["axes"]):
            tip = o + np.array(axis, dtype=float) * s
            ax.plot([o[0], tip[0]], [o[1], tip[1]], [o[2], tip[2]], color=AXIS_COLOURS[c], lw=1.4)
            labels.append((tip, f["axis_labels"][c], AXIS_COLOURS[c], 9, "normal"))
    for p in d["points"]:
        ax.scatter(*[[x] for x in p["at"]], s=30, color="tab:orange", marker="s", depthshade=False)
        labels.append((p["at"], p["name"], "tab:orange", 12, "bold"))
    for f in d["forces"]:
        o, u = np.array(f["at"]), np.array(f["direction"]) * 0.3 * size
        for reach in _heads(f):               # a moment: two heads at the tip
            ax.quiver(*o, *(reach * u), color=FORCE, lw=2, arrow_length_ratio=0.25 / reach)
        labels.append((o + u, f["label"], FORCE, 12, "normal"))
    g = d.get("gravity")
    if g is not None:
        a = np.array([1.0, 1.0, 1.0]) * 0.45 * size
        ax.quiver(*a, *(np.array(g) * 0.3 * size), color="0.15", lw=2, arrow_length_ratio=0.3)
        labels.append((a + np.array(g) * 0.3 * size, "$g$", "0.15", 12, "normal"))
    return labels


# offsets (points) tried in turn for a label, nearest first
OFFSETS = [(4, 3), (4, -11), (-12, 3), (-12, -11), (4, 13), (-12, 13), (14, -3), (-22, -3),
           (4, -21), (-12, -21), (4, 23), (18, 9), (-26, 9), (18, -15), (-26, -15)]


def _width(text: str, points: float) -> float:
    shown = text.replace("\\mathrm", "").replace("$", "").replace("{", "").replace("}", "")
    shown = shown.replace("\\", "").replace("_", "")
    shown = shown.replace("theta", "θ")
    return max(len(shown), 1) * points * 0.6


def _place_labels(ax, labels) -> None:
    """Each label at the first offset from its anchor where it overlaps no label placed before."""
    from mpl_toolkits.mplot3d import proj3d

    m = ax.get_proj()
    fig_width = ax.figure.get_figwidth() * 72
    boxes = []
    for xyz, text, colour, points, weight in labels:
        x2, y2, _ = proj3d.proj_transform(*[float(v) for v in xyz], m)
        px, py = ax.transData.transform((x2, y2)) * 72 / ax.figure.dpi      # in points
        w, h = _width(text, points), points * 1.1
        offsets = [o for o in OFFSETS if 4 <= px + o[0] and px + o[0] + w <= fig_width - 4] or OFFSETS
        for dx, dy in offsets:
            box = (px + dx, py + dy, px + dx + w, py + dy + h)
            if not any(box[0] < b[2] and b[0] < box[2] and box[1] < b[3] and b[1] < box[3] for b in boxes):
                break
        else:
            dx, dy = offsets[0]
            box = (px + dx, py + dy, px + dx + w, py + dy + h)
        boxes.append(box)
        ax.annotate(text, (x2, y2), xytext=(dx, dy), textcoords="offset points", fontsize=points,
                    color=colour, weight=weight, annotation_clip=False, zorder=20,
                    bbox=dict(boxstyle="square,pad=0.05", fc="white", ec="none", alpha=0.75))


def _equal_3d(ax, d, size):
    pts = [[0.0, 0.0, 0.0]] + [p for link in d["links"] for p in link] + [p["at"] for p in d["points"]]
    a = np.array(pts, dtype=float)
    centre = (a.max(axis=0) + a.min(axis=0)) / 2
    half = max(size / 2 * 1.3, 1e-3)
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):      # no scale to read coordinates off (see _draw_2d)
        axis.set_ticklabels([])
    ax.set_xlabel("x₀")
    ax.set_ylabel("y₀")
    ax.set_zlabel("z₀")


def draw(spec, path):
    d = spec.data
    size = extent([d])
    if d.get("plane"):
        fig, ax = subplots(figsize=(6.4, 5.6))
        fixed_layout(fig, left=0.8, right=0.25, top=0.95, bottom=0.6)
        labels, obstacles = _draw_2d(ax, d, size)
        box = (6.4 - 0.8 - 0.25, 5.6 - 0.95 - 0.6)
        _frame_limits(ax, d, size, box)
        _keep_inside_2d(ax, d, size, box, labels, obstacles, _gravity_box(fig, d))
        _gravity_2d(fig, d)
        ax.set_title(spec.title, fontsize=11)
    else:
        fig, ax = one_3d_box(6.4, 6.2)
        labels = _draw_3d(ax, d, size)
        _equal_3d(ax, d, size)
        ax.view_init(elev=22, azim=-55)
        _place_labels(ax, labels)
        fig.suptitle(spec.title, fontsize=11)
    save(fig, path)
