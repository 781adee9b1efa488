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


# -- a coordinate that stays constant (an arc in the plane z = 0.4, started on the path) ---------

def constant_spec(noise):
    """Three task coordinates; E_z is 0.4 plus `noise` (integration noise of the run: 1e-13 m)
    and its error that noise; E_x moves, with an error of a few mm."""
    t = np.linspace(0.0, 1.5, 151)
    wiggle = np.sin(40 * t) * np.exp(-((t - 0.7) / 0.2) ** 2)
    x_desired = 0.45 - 0.15 * np.clip(t / 1.2, 0, 1)
    x_error = 3e-3 * np.sin(np.pi * np.clip(t / 1.2, 0, 1))
    z_desired = np.full_like(t, 0.4)
    joints = [{"name": "E.x", "label": "E_x", "unit": "m", "q": list(x_desired - x_error),
               "q_desired": list(x_desired), "error": list(x_error)},
              {"name": "E.z", "label": "E_z", "unit": "m", "q": list(z_desired - noise * wiggle),
               "q_desired": list(z_desired), "error": list(noise * wiggle)}]
    return FigureSpec("task", "control_tracking", Text("task_computed_torque control"),
                      {"t": list(t), "T": 1.2, "duration": 1.5, "switches": [], "joints": joints,
                       "error_title": "error $e = x_d - x$"})


def shown(fig, ax):
    """What the panel writes on its y axis: its tick labels and offset text."""
    fig.canvas.draw()
    lo, hi = sorted(ax.get_ylim())
    plain = str.maketrans("", "", "${}")
    ticks = [t.get_text().replace("\\mathdefault", "").translate(plain) for t in ax.get_yticklabels()
             if lo <= t.get_position()[1] <= hi]
    return ticks, ax.yaxis.get_offset_text().get_text()


def test_a_constant_coordinate_is_drawn_flat_with_plain_ticks(monkeypatch, tmp_path):
    fig = drawn(monkeypatch, "control_tracking", constant_spec(2e-13), tmp_path)
    axes = fig.axes
    z_panel, z_error = axes[2], axes[3]           # rows: E_x, E_z; columns: trajectory, error
    ticks, offset = shown(fig, z_panel)
    assert offset == ""
    assert all("×" not in t and len(t) <= 5 for t in ticks) and any(float(t) == 0.4 for t in ticks)
    lo, hi = z_panel.get_ylim()
    assert hi - lo > 1e-3                         # the noise is far below a pixel
    ticks, offset = shown(fig, z_error)
    assert offset == "" and all("×" not in t for t in ticks)
    assert any("round-off" in t.get_text() for t in z_error.texts)
    # the moving coordinate and its mm error are drawn as they are
    assert not any("round-off" in t.get_text() for t in axes[1].texts)
    assert max(abs(v) for v in axes[1].get_ylim()) < 1e-2
    assert label_overlaps(fig) == []
    assert clipped(fig) == []


def test_a_small_real_change_is_not_flattened(monkeypatch, tmp_path):
    # 2e-8 m about 0.4 m (5e-8 of it): more than round-off, drawn as it is
    fig = drawn(monkeypatch, "control_tracking", constant_spec(2e-8), tmp_path)
    lo, hi = fig.axes[2].get_ylim()
    assert hi - lo < 1e-6
    assert not any("round-off" in t.get_text() for t in fig.axes[3].texts)
    # its offset text (×10⁻⁸+4×10⁻¹) clear of the panel above and of that panel's tick marks
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    tick_marks = fig.axes[0].xaxis.get_major_ticks()[0].tick1line.get_markersize() * fig.dpi / 72
    for below, above in ((fig.axes[2], fig.axes[0]), (fig.axes[3], fig.axes[1])):
        offset = below.yaxis.get_offset_text()
        assert offset.get_text()
        assert offset.get_window_extent(renderer).y1 + tick_marks < above.get_window_extent(renderer).y0
    assert clipped(fig) == []


def test_a_joint_at_rest_is_drawn_flat_and_its_rate_zero(monkeypatch, tmp_path):
    # forward dynamics from an equilibrium (hanging at −π/2): the run's value and rate are its
    # integration noise (1e-13 rad, 1e-12 rad/s); both panels flat with plain ticks
    from tests.render.test_long_tick_labels import T, forward_dynamics_spec

    fig = drawn(monkeypatch, "forward_dynamics", forward_dynamics_spec(-np.pi / 2 + 1e-13 * np.sin(19 * T)), tmp_path)
    value, rate = fig.axes
    for ax in (value, rate):
        ticks, offset = shown(fig, ax)
        assert offset == "" and all("×" not in t and len(t) <= 6 for t in ticks)
    assert any(float(t.replace("−", "-")) == 0 for t in shown(fig, rate)[0])
    assert any("round-off" in t.get_text() for t in rate.texts)
    assert clipped(fig) == []
