"""⁰J = M₀ⱼ ʲJ M₀ⱼᵀ for the report: past the count the report shows a matrix within, the
entries not yet compacted keep their canonical forms (no expansion: a 3R arm with twists of
pi/4 and pi/6 and decimal inertias spent seconds an entry, 10 of its 19 s, expanding products
it never shows; two joints here keep the test short).
The entries are checked against numpy's product of the DH poses at random configurations."""

import numpy as np
import sympy as sp

import robosolve.core.simplify as simplify
from robosolve.dynamics.engine import DynamicsEngine
from robosolve.dynamics.types import BodySpec, FrameSpec, JointSpec

TWISTS = (sp.pi / 4, sp.pi / 6)
OFFSETS = ((0.2, 0.3), (0, 0.25))    # (d, a) of each row


def _dh(theta, d, a, alpha, lib):
    ct, st, ca, sa = lib.cos(theta), lib.sin(theta), lib.cos(alpha), lib.sin(alpha)
    rows = [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st], [0, sa, ca, d], [0, 0, 0, 1]]
    return sp.Matrix(rows) if lib is sp else np.array(rows, dtype=float)


def _pseudo_inertia(m, c, inertia):
    """J from the mass, centre of mass and inertia tensor about it (spec §3)."""
    c, inertia = np.array(c), np.array(inertia)
    second = np.trace(inertia) / 2 * np.eye(3) - inertia + m * np.outer(c, c)
    J = np.zeros((4, 4))
    J[:3, :3], J[:3, 3], J[3, :3], J[3, 3] = second, m * c, m * c, m
    return J


J3 = _pseudo_inertia(1.5, [0.04, -0.03, 0.02], [[0.031, 0.002, -0.001], [0.002, 0.027, 0.003], [-0.001, 0.003, 0.044]])


def _engine():
    qs = sp.symbols("q1:3", real=True)
    joints = [JointSpec(f"q{i + 1}", q, sp.Symbol(f"q{i + 1}_dot"), sp.Symbol(f"q{i + 1}_ddot"),
                        sp.Symbol(f"C{i + 1}")) for i, q in enumerate(qs)]
    frames = [FrameSpec(str(i + 1), str(i), _dh(q, sp.Float(d), sp.Float(a), al, sp))
              for i, (q, (d, a), al) in enumerate(zip(qs, OFFSETS, TWISTS))]
    body = BodySpec("link2", "2", sp.Matrix([[sp.Float(x) for x in row] for row in J3]))
    return DynamicsEngine(frames, joints, [body], [0, 0, -sp.Float(9.81)]), body, qs


def _numeric_J0(q):
    M = np.eye(4)
    for qi, (d, a), al in zip(q, OFFSETS, TWISTS):
        M = M @ _dh(qi, d, a, float(al), np)
    return M @ J3 @ M.T


def test_long_congruence_stops_expanding_and_keeps_the_values(monkeypatch):
    expanded = []
    real = simplify.congruence_entry
    monkeypatch.setattr(simplify, "congruence_entry", lambda c, p: expanded.append(1) or real(c, p))
    eng, body, qs = _engine()
    shown = eng.J0(body, 400)
    # expanded until the entries done count more than 400 operations, no further
    counts = np.cumsum([simplify.count_ops(e) for e in shown])
    assert 1 <= len(expanded) < 16
    assert len(expanded) == 1 + np.argmax(counts > 400)
    rng = np.random.default_rng(3)
    f = sp.lambdify(qs, shown, "numpy")
    for q in rng.uniform(-np.pi, np.pi, (4, 2)):
        assert np.allclose(np.array(f(*q), dtype=float), _numeric_J0(q), rtol=1e-10, atol=1e-12)
