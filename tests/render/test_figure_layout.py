"""Nothing a figure writes is clipped (issue 22): every title, label and annotation of the
joint-torque figure lies inside the figure, and each peak's "peak … at t = …" inside its panel,
wherever the peak falls in the run and however long its numbers are. Measured on matplotlib's
own renderer (the text's window extent against the figure's and the axes' boxes)."""

from __future__ import annotations

import numpy as np
import pytest

from robosolve.core.prose import Num, Text
from robosolve.solvers.base import FigureSpec


def drawn(monkeypatch, kind, spec, tmp_path):
    """Draw `spec` with the plot module of `kind`; the Figure it saved (and the PNG on disk)."""
    import importlib

    from robosolve.render import plots

    module = importlib.import_module(f"robosolve.render.plots.{kind}")
    figures = []
    real = module.save

    def keep(fig, path):
        figures.append(fig)
        real(fig, path)

    monkeypatch.setattr(module, "save", keep)
    plots.draw(spec, tmp_path / f"{spec.name}.png")
    return figures[0]


def clipped(fig) -> list[str]:
    """What `fig` draws outside itself (its tight box: only what is drawn, the ticks in view
    included), and the annotations outside their axes."""
    from matplotlib.text import Annotation, Text as MplText

    renderer = fig.canvas.get_renderer()
    out = []
    tight = fig.get_tightbbox(renderer)                  # inches
    w, h = fig.get_size_inches()
    if tight.x0 < -0.01 or tight.y0 < -0.01 or tight.x1 > w + 0.01 or tight.y1 > h + 0.01:
        box = fig.bbox
        outside = [t.get_text() for t in fig.findobj(MplText) if t.get_visible() and t.get_text().strip()
                   and box.x0 <= t.get_window_extent(renderer).x1 and t.get_window_extent(renderer).x0 <= box.x1
                   and not box.contains(*t.get_window_extent(renderer).p0)]
        out.append(f"outside the figure: the drawing spans {tuple(round(x, 2) for x in tight.bounds)} "
                   f"of (0, 0, {w:g}, {h:g}) {outside}")
    for t in fig.findobj(Annotation):
        if not t.get_visible() or not t.get_text().strip() or t.axes is None:
            continue
        e, a = t.get_window_extent(renderer), t.axes.get_window_extent(renderer)
        if e.x0 < a.x0 or e.x1 > a.x1 or e.y0 < a.y0 or e.y1 > a.y1:
            out.append(f"outside its panel: {t.get_text()!r} {e.bounds} not in {a.bounds}")
    return out


def torques_spec(T, peaks, values):
    t = list(np.linspace(0.0, T, len(values[0])))
    acts = [{"name": f"C{k + 1}", "label": f"C_{{{k + 1}}}", "unit": "N·m", "values": list(v),
             "peak": p, "t_peak": tp} for k, (v, (p, tp)) in enumerate(zip(values, peaks))]
    return FigureSpec("torques", "joint_torques", Text("Actuators along the profile (T = ", Num(T), " s)"),
                      {"t": t, "T": T, "switches": [T / 2], "actuators": acts})


CASES = {
    # peak near the end, at the top of the panel (the text goes left and below)
    "late": (1.77857, lambda s: 40 * s ** 3, 1.0),
    # peak at the very start
    "early": (2.0, lambda s: 50 * (1 - s) ** 2 - 10, 0.0),
    # peak in the middle, long numbers (-123456.789 N·m at t = 1234.5678 s)
    "middle-long": (2469.1356, lambda s: -123456.789 * np.sin(np.pi * s), 0.5),
    # a negative peak late, near the bottom (the text goes left and above)
    "late-negative": (0.3, lambda s: -7.123456 * s ** 4 + 0.1, 1.0),
    # just past the middle
    "just-past-middle": (1.0, lambda s: 3 * np.exp(-80 * (s - 0.51) ** 2), 0.51),
}


@pytest.mark.parametrize("case", list(CASES))
def test_joint_torque_texts_are_inside_the_figure_and_their_panels(monkeypatch, tmp_path, case):
    T, f, where = CASES[case]
    s = np.linspace(0.0, 1.0, 201)
    first = f(s)
    k = int(round(where * 200))
    second = 0.3 * first[::-1]
    j = int(np.argmax(np.abs(second)))
    spec = torques_spec(T, [(float(first[k]), where * T), (float(second[j]), float(s[j] * T))], [first, second])
    fig = drawn(monkeypatch, "joint_torques", spec, tmp_path)
    assert clipped(fig) == []


def test_the_check_sees_a_clipped_text(monkeypatch, tmp_path):
    """The measure can fail: a title pushed off the figure is found."""
    T, f, where = CASES["late"]
    s = np.linspace(0.0, 1.0, 201)
    spec = torques_spec(T, [(float(f(s)[-1]), T)], [f(s)])
    fig = drawn(monkeypatch, "joint_torques", spec, tmp_path)
    fig.axes[0].title.set_position((1.4, 1.0))
    assert any("outside the figure" in c for c in clipped(fig))
    fig.axes[0].texts[0].set_position((400, 0))
    assert any("outside its panel" in c for c in clipped(fig))


# -- the paper's drawing: long frame and force names stay inside the figure -------------------

LONG_NAMES = """\
robosolve: 1
name: longnames
parameters: {{L: 1, F: 3}}
joints:
  - {{name: q1, type: revolute}}
  - {{name: q2, type: revolute}}
  - {{name: q3, type: {third}}}
frames:
  "the frame of the upper arm, named at length $\\\\frac{{$ by a hostile teacher": {{parent: "0", pose: "Rz(q1) Tx(L)"}}
  endeffectorframewithaverylongidentifiername: {{pose: "Rz(q2) Tx(L)"}}
  "3": {{pose: "{pose3}"}}
forces:
  - {{name: "a force with a long, long, long name that goes on", frame: "3", at: [0, 0, 0], force: [0, -F, 0]}}
questions:
  - {{type: position, at: {{q1: 0.3, q2: 0.4, q3: 0.2}}}}
"""


@pytest.mark.parametrize("third,pose3", [("revolute", "Rz(q3) Tx(L)"), ("revolute", "Rx(q3) Tz(L)")],
                         ids=["plane", "3-D"])
def test_long_names_stay_inside_the_paper_drawing(monkeypatch, tmp_path, third, pose3):
    from robosolve.load.loader import load_problem_text
    from robosolve.model import RobotModel
    from robosolve.papers.drawing import paper_figure

    problem = load_problem_text(LONG_NAMES.format(third=third, pose3=pose3), "p.yaml")
    spec = paper_figure(problem, RobotModel(problem))
    assert bool(spec.data["plane"]) == (pose3.startswith("Rz"))
    fig = drawn(monkeypatch, "robot_paper", spec, tmp_path)
    from matplotlib.text import Annotation

    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    texts = [t for t in fig.findobj(Annotation) if t.get_visible() and t.get_text().strip()]
    assert any("…" in t.get_text() for t in texts)                  # the long names are cut
    outside = [(t.get_text(), t.get_window_extent(renderer).bounds) for t in texts
               if t.get_window_extent(renderer).x0 < box.x0 - 1 or t.get_window_extent(renderer).x1 > box.x1 + 1]
    assert not outside


def _profile_spec(T, switches):
    t = sorted({*np.linspace(0.0, T, 50), *switches})
    joint = {"name": "q1", "label": "q_1", "kind": "revolute", "q": [0.0] * len(t), "qd": [0.0] * len(t),
             "qdd": [0.0] * len(t)}
    return FigureSpec("profile", "motion_profile", "Synchronized trapezoidal profile",
                      {"t": t, "T": T, "switches": list(switches), "joints": [joint]})


@pytest.mark.parametrize("T, switches", [
    (3.3333333, [0.1571, 0.3333333, 3.0, 3.1762]),      # two short phases at each end
    (1.0, [0.5]),
    (2.0, [0.001, 0.002, 1.0, 1.998, 1.999]),
    # a synchronized trapezoid of three joints: 0.208, 0.292 and 0.4 s; 1.25, 1.358 and 1.442 s
    (1.65, [0.2083333, 0.2916667, 0.4, 1.25, 1.3583333, 1.4416667]),
    (123456.7, [0.5, 61728.35, 123456.2]),                   # long numbers at the right end
])
def test_every_switching_instant_is_labelled_without_overlap(monkeypatch, tmp_path, T, switches):
    # measured on matplotlib's renderer: every switching instant (and 0, T) has its label above the
    # first panel, centred on it; labels never overlap one another or the title, all inside the figure
    fig = drawn(monkeypatch, "motion_profile", _profile_spec(T, switches), tmp_path)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    labels = [t for t in ax.texts if t.get_text()]
    instants = sorted({0.0, T, *switches})
    assert sorted(float(lab.get_position()[0]) for lab in labels) == instants
    for lab in labels:
        assert float(lab.get_text()) == pytest.approx(lab.get_position()[0], rel=5e-3, abs=5e-4)
    assert len({lab.get_text() for lab in labels}) == len(labels)    # close instants told apart
    boxes = [lab.get_window_extent(renderer) for lab in labels]
    for lab, box in zip(labels, boxes):
        x = ax.transData.transform((lab.get_position()[0], 0))[0]
        assert box.x0 < x < box.x1                                   # over its own instant
        assert box.y0 >= ax.get_window_extent(renderer).y1            # above the panel
    for i, a in enumerate(boxes):
        assert not a.overlaps(ax.title.get_window_extent(renderer)), labels[i].get_text()
        for j in range(i + 1, len(boxes)):
            assert not a.overlaps(boxes[j]), (labels[i].get_text(), labels[j].get_text())
    assert clipped(fig) == []


def test_the_peak_text_does_not_hide_the_curve(monkeypatch, tmp_path):
    # a force rising to its peak at T with a jump just before (a prismatic joint's F along a
    # trapezoidal profile): the usual place, left of and below the marker, lies on the curve; the
    # text must sit where its white box hides none of the curve's points (measured on the renderer)
    T = 2.3
    s = np.linspace(0.0, 1.0, 401)
    f = np.where(s < 0.87, -11 + 25 * s, 13 + 1.6 * (s - 0.87) / 0.13)
    spec = torques_spec(T, [(float(f[-1]), T)], [f])
    fig = drawn(monkeypatch, "joint_torques", spec, tmp_path)
    ax = fig.axes[0]
    renderer = fig.canvas.get_renderer()
    box = ax.texts[0].get_window_extent(renderer)
    points = ax.transData.transform(np.column_stack([s * T, f]))
    under = (points[:, 0] >= box.x0) & (points[:, 0] <= box.x1) & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1)
    assert not under.any()
    assert clipped(fig) == []
