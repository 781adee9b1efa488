"""Long tick labels never push an axis label off the figure or onto the next panel: a small
motion about a large value is ticked −1.57175 (eight characters), more than the fixed left margin
or the gap between columns holds. `save` measures the axes' texts and widens the margins
(`fit_margins`). Measured on matplotlib's renderer, as test_figure_layout does."""

from __future__ import annotations

import numpy as np
import pytest

from robosolve.core.prose import Text
from robosolve.solvers.base import FigureSpec
from tests.render.test_figure_layout import clipped, drawn
from tests.render.test_tracking_layout import label_overlaps

T = np.linspace(0.0, 0.5, 201)
# −1.5707963 plus a motion of a few 1e-4 rad: ticks −1.57025 … −1.57150
WOBBLE = -1.5707963 + 4e-4 * np.sin(19 * T) - 3e-4 * T
# a panel that also draws its zero line (an effort, an error), of about a mrad: ticks −0.00125
SMALL = 3e-4 - 1.5e-3 * np.sin(np.pi * T / 0.5) ** 2


def forward_dynamics_spec(q):
    qd = list(np.gradient(q, T))
    k_max, k_min = int(np.argmax(q)), int(np.argmin(q))
    return FigureSpec("fd", "forward_dynamics", Text("$q_{1}(t)$ with $C_{1} = 0$"),
                      {"t": list(T), "q": list(q), "qd": qd, "label": "q_{1}", "rate_label": "\\dot{q}_{1}",
                       "unit": "rad", "rate_unit": "rad/s", "max": float(q[k_max]), "t_max": float(T[k_max]),
                       "min": float(q[k_min]), "t_min": float(T[k_min])})


def joint_motion_spec(q):
    joints = [{"label": "q_{1}", "unit": "rad", "q": list(q), "qd": list(np.gradient(q, T)),
               "qdd": list(np.gradient(np.gradient(q, T), T))}]
    return FigureSpec("joints", "joint_motion", Text("Joint motion"),
                      {"t": list(T), "T": 0.5, "switches": [0.25], "joints": joints})


def effort_spec(values):
    acts = [{"name": "C1", "label": "C_{1}", "unit": "N·m", "values": list(values), "external": None}]
    return FigureSpec("effort", "control_effort", Text("pd control: actuator effort"),
                      {"t": list(T), "T": 0.5, "duration": 0.5, "switches": [0.25], "actuators": acts})


def tracking_spec(q):
    q_desired = np.full_like(q, -1.5707963)
    joints = [{"name": "q1", "label": "q_{1}", "unit": "rad", "q": list(q), "q_desired": list(q_desired),
               "error": list(q_desired - q)},
              {"name": "q2", "label": "q_{2}", "unit": "rad", "q": list(q + 3.0 - SMALL),
               "q_desired": list(q_desired + 3.0), "error": list(SMALL)}]    # the error column ticked −0.00125
    return FigureSpec("tracking", "control_tracking", Text("pd control: actual vs desired, and the error"),
                      {"t": list(T), "T": 0.5, "duration": 0.5, "switches": [0.25], "joints": joints})


def ylabels_inside(fig):
    """The y axis labels that are drawn, each inside the figure (left edge at x >= 0)."""
    renderer = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        if ax.name == "rectilinear" and ax.yaxis.label.get_text():
            box = ax.yaxis.label.get_window_extent(renderer)
            out.append(box.x0 >= 0 and box.x1 <= fig.bbox.x1)
    return out


@pytest.mark.parametrize("kind,spec", [
    ("forward_dynamics", forward_dynamics_spec(WOBBLE)),
    ("joint_motion", joint_motion_spec(WOBBLE)),
    ("control_effort", effort_spec(SMALL)),
    ("control_tracking", tracking_spec(WOBBLE)),
], ids=["forward_dynamics", "joint_motion", "control_effort", "control_tracking"])
def test_long_tick_labels_keep_the_axis_labels_inside(monkeypatch, tmp_path, kind, spec):
    fig = drawn(monkeypatch, kind, spec, tmp_path)
    fig.canvas.draw()
    longest = max(len(t.get_text()) for ax in fig.axes for t in ax.get_yticklabels())
    assert longest >= 8                                   # the case: ticks like −1.57025
    labels = ylabels_inside(fig)
    assert labels and all(labels)
    assert clipped(fig) == []
    assert label_overlaps(fig) == []


def test_short_tick_labels_keep_the_fixed_layout(monkeypatch, tmp_path):
    """Margins are only ever widened: a figure with short ticks keeps the layout it was given."""
    fig = drawn(monkeypatch, "forward_dynamics", forward_dynamics_spec(0.3 * np.sin(5 * T)), tmp_path)
    assert fig.subplotpars.left == pytest.approx(0.85 / fig.get_figwidth())
