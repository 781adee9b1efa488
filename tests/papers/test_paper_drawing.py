"""The paper's drawing (papers.md "The drawing"): the robot where its forward kinematics puts it
at the reference configuration (frame origins, joints, points against numpy's own products of
DH and elementary matrices), and labels that are legible: in a plane, no label over another
label or over a link, measured with matplotlib's renderer (the drawn text's extent)."""

from __future__ import annotations

import numpy as np
import pytest

from robosolve.load.loader import load_problem_text
from robosolve.model.chain import RobotModel
from robosolve.papers.drawing import paper_figure


def dh(theta, d, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]])


def rz(t):
    return np.array([[np.cos(t), -np.sin(t), 0, 0], [np.sin(t), np.cos(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def tx(x):
    m = np.eye(4)
    m[0, 3] = x
    return m


STANFORD = """\
robosolve: 1
name: stanford
parameters: {d1: 0.412, d2: 0.154, d6: 0.263}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: d3, type: prismatic, limits: [0.1, 1]}
  - {name: q4, type: revolute}
  - {name: q5, type: revolute}
  - {name: q6, type: revolute}
dh:
  convention: standard
  rows:
    - {theta: q1, d: d1, a: 0, alpha: -pi/2}
    - {theta: q2, d: d2, a: 0, alpha: pi/2}
    - {theta: -pi/2, d: d3, a: 0, alpha: 0}
    - {theta: q4, d: 0, a: 0, alpha: -pi/2}
    - {theta: q5, d: 0, a: 0, alpha: pi/2}
    - {theta: q6, d: d6, a: 0, alpha: 0}
questions:
  - {type: position, at: {q1: 0.3, q2: 0.8, d3: 0.5, q4: 0.2, q5: -0.6, q6: 0.4}}
"""


def test_the_drawn_stanford_arm_is_its_forward_kinematics(tmp_path):
    problem = load_problem_text(STANFORD, str(tmp_path / "s.yaml"))
    d = paper_figure(problem, RobotModel(problem)).data
    q1, q2, d3, q4, q5, q6 = 0.3, 0.8, 0.5, 0.2, -0.6, 0.4
    rows = [(q1, 0.412, 0, -np.pi / 2), (q2, 0.154, 0, np.pi / 2), (-np.pi / 2, d3, 0, 0),
            (q4, 0, 0, -np.pi / 2), (q5, 0, 0, np.pi / 2), (q6, 0.263, 0, 0)]
    poses = [np.eye(4)]
    for row in rows:
        poses.append(poses[-1] @ dh(*row))
    origins = {f["name"]: np.array(f["origin"]) for f in d["frames"]}
    for i, m in enumerate(poses):
        assert np.allclose(origins[str(i)], m[:3, 3], atol=1e-12), i
        axes = next(f["axes"] for f in d["frames"] if f["name"] == str(i))
        assert np.allclose(np.array(axes).T, m[:3, :3], atol=1e-12), i
    # joint i+1 turns (or slides) about z_i at the origin of frame i (standard DH)
    for i, j in enumerate(d["joints"]):
        assert np.allclose(j["at"], poses[i][:3, 3], atol=1e-12) and np.allclose(j["axis"], poses[i][:3, 2])
    assert np.allclose(d["points"][0]["at"], poses[6][:3, 3]) and d["plane"] is None


PLANAR = """\
robosolve: 1
name: planar
parameters: {L1: 0.5, L2: 0.3, c: 0.1}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: theta2, type: revolute, limits: [-deg(170), deg(170)]}
frames:
  "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
  tool: {parent: "2", pose: "Tx(c)"}
points:
  G2: {frame: "2", at: [-L2/2, 0, 0]}
forces:
  - {name: Fc, frame: tool, force: [0, -5, 0], in: "0"}
paper: {at: {theta1: pi/3, theta2: pi/2}}
questions:
  - {type: position, frame: tool, at: {theta1: 0, theta2: 0}}
"""


def test_the_drawn_planar_arm_is_its_forward_kinematics(tmp_path):
    problem = load_problem_text(PLANAR, str(tmp_path / "p.yaml"))
    d = paper_figure(problem, RobotModel(problem)).data
    t1, t2 = np.pi / 3, np.pi / 2                     # paper: {at}, not the question's
    m1 = rz(t1) @ tx(0.5)
    m2 = m1 @ rz(t2) @ tx(0.3)
    origins = {f["name"]: np.array(f["origin"]) for f in d["frames"]}
    assert np.allclose(origins["1"], m1[:3, 3]) and np.allclose(origins["2"], m2[:3, 3])
    assert np.allclose(origins["tool"], (m2 @ tx(0.1))[:3, 3])
    assert np.allclose(d["joints"][0]["at"], [0, 0, 0]) and np.allclose(d["joints"][1]["at"], m1[:3, 3])
    points = {p["name"]: p["at"] for p in d["points"]}
    assert np.allclose(points["G2"], (m2 @ [-0.15, 0, 0, 1])[:3])
    assert np.allclose(d["forces"][0]["at"], (m2 @ tx(0.1))[:3, 3]) and np.allclose(d["forces"][0]["direction"], [0, -1, 0])
    assert d["plane"] == (0, 1)


def test_a_configuration_named_by_parameters_is_drawn(tmp_path):
    """`at: {theta1: q1a, theta2: q2a}` — how variants vary a configuration (docs/variants.md): the
    paper had no drawing at all (the joint values stayed symbols); the robot is drawn at the
    parameters' values, as numpy's product of the elementary matrices puts it."""
    from robosolve.papers.workflow import paper_files

    text = (PLANAR.replace("c: 0.1}", "c: 0.1, q1a: pi/6, q2a: q1a + pi/4}").replace("paper: {at: {theta1: pi/3, theta2: pi/2}}\n", "")
            .replace("at: {theta1: 0, theta2: 0}", "at: {theta1: q1a, theta2: q2a}"))
    problem = load_problem_text(text, str(tmp_path / "p.yaml"))
    spec = paper_figure(problem, RobotModel(problem))
    assert spec is not None
    m2 = rz(np.pi / 6) @ tx(0.5) @ rz(np.pi / 6 + np.pi / 4) @ tx(0.3)
    origins = {f["name"]: np.array(f["origin"]) for f in spec.data["frames"]}
    assert np.allclose(origins["2"], m2[:3, 3])
    files = paper_files(problem, "p.yaml")
    assert "figures/robot.png" in files and "](figures/robot.png)" in files["paper.md"].decode()


def _segments_overlap(box, a, b) -> bool:
    """Whether the segment ab (pixels) crosses the box (x0, y0, x1, y1), sampled finely."""
    for s in np.linspace(0, 1, 200):
        x, y = a + s * (b - a)
        if box[0] < x < box[2] and box[1] < y < box[3]:
            return True
    return False


@pytest.mark.parametrize("at", ["{theta1: pi/3, theta2: pi/2}", "{theta1: pi/6, theta2: pi/4}",
                                "{theta1: 0, theta2: 0}"])
def test_labels_cover_no_label_and_no_link(monkeypatch, tmp_path, at):
    """A cramped arm (a tool frame 0.1 from frame 2, a force and a point on the last link): the
    label of θ₂ sat on y₁'s, E's under x₂ (before: each at a fixed offset from its anchor)."""
    from matplotlib.text import Annotation

    from robosolve.render import plots

    problem = load_problem_text(PLANAR.replace("{theta1: pi/3, theta2: pi/2}", at), str(tmp_path / "p.yaml"))
    spec = paper_figure(problem, RobotModel(problem))
    module = __import__("robosolve.render.plots.robot_paper", fromlist=["save"])
    kept = []
    real = module.save
    monkeypatch.setattr(module, "save", lambda fig, path: (kept.append(fig), real(fig, path)))
    plots.draw(spec, tmp_path / "robot.png")
    fig = kept[0]
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    texts = [t for t in fig.findobj(Annotation) if t.get_visible() and t.get_text().strip()]
    boxes = [(t.get_text(), t.get_window_extent(renderer).padded(-1.0)) for t in texts]
    assert len(boxes) >= 12                          # 4 frames × 3 axes, 2 joints, 2 points, 1 force
    for i, (a, ea) in enumerate(boxes):
        for b, eb in boxes[i + 1:]:
            assert not ea.overlaps(eb), (a, b)
    # no scale to read E's coordinates off a drawing made at a question's configuration
    assert not [t.get_text() for t in ax.get_xticklabels() + ax.get_yticklabels() if t.get_text()]
    assert not ax.xaxis.get_gridlines() or not any(g.get_visible() for g in ax.xaxis.get_gridlines())
    links = [np.array([ax.transData.transform((p[0], p[1])) for p in link]) for link in spec.data["links"]]
    for name, e in boxes:
        for link in links:
            for a, b in zip(link[:-1], link[1:]):
                assert not _segments_overlap((e.x0, e.y0, e.x1, e.y1), a, b), (name, at)


GANTRY = """\
robosolve: 1
name: gantry
parameters: {L: 0.25}
joints:
  - {name: x, type: prismatic, limits: [0, 1.2]}
  - {name: phi, type: revolute}
frames:
  "1": {parent: "0", pose: "Tx(x)"}
  "2": {pose: "Rz(phi) Tx(L)"}
forces:
  - {name: W, frame: "2", LOAD}
questions:
  - {type: position, at: {x: 0.5, phi: pi/6}}
"""


@pytest.mark.parametrize("load, turns", [("torque: [0, 0, 2]", "ccw"), ("torque: [0, 0, -2]", "cw"),
                                         ("torque: [2, 0, 0]", None), ("force: [0, 0, 5]", None)])
def test_a_load_normal_to_the_page_is_drawn(monkeypatch, tmp_path, load, turns):
    """A torque about the page's normal is a circular arrow about its point, counter-clockwise
    when it points towards the reader (+z of the x–y page, right-hand rule); a force normal to
    the page a ⊙ (it was an arrow of zero length: nothing but its name); a torque in the page a
    double-headed arrow."""
    from matplotlib.patches import Arc

    from robosolve.render import plots

    problem = load_problem_text(GANTRY.replace("LOAD", load), str(tmp_path / "g.yaml"))
    spec = paper_figure(problem, RobotModel(problem))
    module = __import__("robosolve.render.plots.robot_paper", fromlist=["save"])
    kept = []
    real = module.save
    monkeypatch.setattr(module, "save", lambda fig, path: (kept.append(fig), real(fig, path)))
    plots.draw(spec, tmp_path / "robot.png")
    ax = kept[0].axes[0]
    arcs = [p for p in ax.patches if isinstance(p, Arc)]
    from matplotlib.colors import to_rgb

    purple = [a for a in ax.texts if not a.get_text() and a.arrow_patch is not None
              and np.allclose(a.arrow_patch.get_edgecolor()[:3], to_rgb("tab:purple"))]
    if turns is None:
        assert not arcs
        assert len(purple) == (2 if load.startswith("torque") else 0)      # two heads / a ⊙
        return
    assert len(arcs) == 1 and len(purple) == 1
    centre = np.array(arcs[0].center)
    tail, head = np.array(purple[0].xyann) - centre, np.array(purple[0].xy) - centre
    assert (tail[0] * head[1] - tail[1] * head[0] > 0) == (turns == "ccw")


def test_a_3d_drawing_has_no_scale_either(monkeypatch, tmp_path):
    from robosolve.render import plots

    problem = load_problem_text(STANFORD, str(tmp_path / "s.yaml"))
    module = __import__("robosolve.render.plots.robot_paper", fromlist=["save"])
    kept = []
    real = module.save
    monkeypatch.setattr(module, "save", lambda fig, path: (kept.append(fig), real(fig, path)))
    plots.draw(paper_figure(problem, RobotModel(problem)), tmp_path / "robot.png")
    kept[0].canvas.draw()
    ax = kept[0].axes[0]
    shown = [t.get_text() for axis in (ax.xaxis, ax.yaxis, ax.zaxis) for t in axis.get_ticklabels() if t.get_text()]
    assert not shown
