"""The closed-loop tracking figure (p_control): the error column's axis labels stay clear of the
trajectory column, whatever the errors' tick labels (an error of a few mrad is ticked as
−0.0035: seven characters). Measured on matplotlib's renderer, as test_figure_layout does."""

from __future__ import annotations

import numpy as np
import pytest

from robosolve.core.prose import Text
from robosolve.solvers.base import FigureSpec
from tests.render.test_figure_layout import clipped, drawn


def tracking_spec(errors):
    t = np.linspace(0.0, 1.2, 121)
    joints = []
    for k, (lo, hi) in enumerate(errors):
        error = lo + (hi - lo) * np.sin(np.pi * t / 2.4) ** 2
        q_desired = -2.0 + 0.5 * t
        joints.append({"name": f"q{k + 1}", "label": f"q_{{{k + 1}}}", "unit": "rad", "q": list(q_desired - error),
                       "q_desired": list(q_desired), "error": list(error)})
    return FigureSpec("tracking", "control_tracking", Text("pd control: actual vs desired, and the error"),
                      {"t": list(t), "T": 1.2, "duration": 1.2, "switches": [0.27, 0.94], "joints": joints})


def label_overlaps(fig):
    """The axis labels and offset texts drawn over another panel."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        for text in (ax.yaxis.label, ax.yaxis.get_offset_text()):
            if not text.get_visible() or not text.get_text().strip():
                continue
            box = text.get_window_extent(renderer)
            out += [text.get_text() for other in fig.axes
                    if other is not ax and box.overlaps(other.get_window_extent(renderer))]
    return out


@pytest.mark.parametrize("errors", [
    [(0.0, -0.0035), (0.0, 0.0125)],          # ticks −0.0035, 0.0125: 7 and 6 characters
    [(0.0, -0.0019), (0.0, -0.05)],           # −0.0015 beside −0.06
    [(0.0, 0.3), (0.0, -2e-5)],               # a ×10⁻⁵ above the axis
])
def test_error_labels_stay_clear_of_the_trajectory_panels(monkeypatch, tmp_path, errors):
    fig = drawn(monkeypatch, "control_tracking", tracking_spec(errors), tmp_path)
    assert label_overlaps(fig) == []
    assert clipped(fig) == []
