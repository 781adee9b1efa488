"""The `jacobian` question's singular configurations on robots not among the bundled problems
(issue 26), through the whole pipeline (results.json), against Robotics Toolbox's `jacob0` of
the same DH table and numpy's SVD (tests/support/singular_probe.py): every reported condition
met at random configurations makes J lose rank (soundness), and rank-deficient configurations
found independently (a least-squares solve of the reference's maximal minors) each satisfy a
reported condition (completeness). The cases are ones the random probe found wrong, kept."""

import math

import numpy as np
import pytest

from tests.support.singular_probe import PI2, Case, Row, check_answer, reference, satisfies, solve_case

pytest.importorskip("roboticstoolbox")


def _conditions(ans):
    conds = ans["symbolic"].get("singularities")
    assert conds is not None, ans.get("notes")
    return conds


def test_negative_tool_offset_keeps_both_roots_of_the_offset_angle():
    """A 4R arm (position of a tool point, 3×4) whose tool offset dt is negative: the factor
    a4·sin q4 + dt·cos q4 has two roots, -atan(dt/a4) and -acos(-a4/√(a4²+dt²)); substituting the
    acos root brought |dt| into the other minors (sin(acos x) = √(1−x²)), the factoring could not
    split them, and the family q3 = ±π/2 of that root was lost (an equation in |dt| instead)."""
    case = Case("probe-arm4-3", "arm4", [
        Row("R", a=0.1018, d=-0.1802, alpha=0.0), Row("R", a=0.2652, d=-0.454, alpha=PI2),
        Row("R", alpha=-PI2), Row("R", a=0.211, alpha=-PI2)], tool=-0.2227, geometric=False,
        at=[0.426, -0.143, 1.366, -2.348])
    ans = solve_case(case)
    conds = _conditions(ans)
    # the lost family, checked singular by the reference
    r = math.hypot(0.211, -0.2227)
    q = np.array([0.3, -1.1, -PI2, -math.acos(-0.211 / r)])
    sv = np.linalg.svd(reference(case)(q), compute_uv=False)
    assert sv[-1] < 1e-12 * sv[0]
    assert any(satisfies(c, case, q) for c in conds), conds
    assert all(isinstance(c, dict) for c in conds), [c for c in conds if not isinstance(c, dict)]
    assert check_answer(case, ans, np.random.default_rng(3), starts=25) == []
