"""Homogeneous transforms (4x4 rototranslation matrices M) on sympy.

Notation (docs/course-notes.md#note-frame-notation): ``M_ij`` is the pose of frame j in frame i, so
``P_i = M_ij * P_j`` for homogeneous points and ``M_0j = M_01 * M_12 * ...``.
Every function accepts sympy expressions or plain numbers and returns an
explicit ``sympy.Matrix``.
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "rot_x", "rot_y", "rot_z", "trans_x", "trans_y", "trans_z", "translation",
    "ELEMENTARY", "dh_standard", "dh_modified", "rigid_inverse", "skew", "vex",
    "rotation_part", "translation_part", "homogeneous", "is_rototranslation",
]


def rot_x(a) -> sp.Matrix:
    """Rx(a): rotation by angle a about the x axis."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def rot_y(a) -> sp.Matrix:
    """Ry(a): rotation by angle a about the y axis."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, 0, s, 0], [0, 1, 0, 0], [-s, 0, c, 0], [0, 0, 0, 1]])


def rot_z(a) -> sp.Matrix:
    """Rz(a): rotation by angle a about the z axis."""
    c, s = sp.cos(a), sp.sin(a)
    return sp.Matrix([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def translation(x=0, y=0, z=0) -> sp.Matrix:
    """Pure translation by (x, y, z)."""
    return sp.Matrix([[1, 0, 0, x], [0, 1, 0, y], [0, 0, 1, z], [0, 0, 0, 1]])


def trans_x(d) -> sp.Matrix:
    return translation(d, 0, 0)


def trans_y(d) -> sp.Matrix:
    return translation(0, d, 0)


def trans_z(d) -> sp.Matrix:
    return translation(0, 0, d)


# The elementary motions of a `pose:` string, by name.
ELEMENTARY = {
    "Tx": trans_x, "Ty": trans_y, "Tz": trans_z,
    "Rx": rot_x, "Ry": rot_y, "Rz": rot_z,
}


def dh_standard(theta, d, a, alpha) -> sp.Matrix:
    """Standard DH: Rz(theta) Tz(d) Tx(a) Rx(alpha) (course-notes#note-dh-order)."""
    ct, st = sp.cos(theta), sp.sin(theta)
    ca, sa = sp.cos(alpha), sp.sin(alpha)
    return sp.Matrix([
        [ct, -st * ca, st * sa, a * ct],
        [st, ct * ca, -ct * sa, a * st],
        [0, sa, ca, d],
        [0, 0, 0, 1],
    ])


def dh_modified(alpha, a, theta, d) -> sp.Matrix:
    """Modified (Craig) DH: Rx(alpha) Tx(a) Rz(theta) Tz(d)."""
    ct, st = sp.cos(theta), sp.sin(theta)
    ca, sa = sp.cos(alpha), sp.sin(alpha)
    return sp.Matrix([
        [ct, -st, 0, a],
        [st * ca, ct * ca, -sa, -sa * d],
        [st * sa, ct * sa, ca, ca * d],
        [0, 0, 0, 1],
    ])


def rotation_part(m: sp.Matrix) -> sp.Matrix:
    return m[:3, :3]


def translation_part(m: sp.Matrix) -> sp.Matrix:
    return m[:3, 3]


def homogeneous(r: sp.Matrix, t) -> sp.Matrix:
    """[R t; 0 0 0 1] from a 3x3 rotation and a 3-vector."""
    out = sp.eye(4)
    out[:3, :3] = r
    out[:3, 3] = sp.Matrix(t)
    return out


def rigid_inverse(m: sp.Matrix) -> sp.Matrix:
    """Inverse of a rototranslation: [R^T, -R^T t; 0 0 0 1] (course-notes#note-inverse-pose)."""
    rt = m[:3, :3].T
    return homogeneous(rt, -rt * m[:3, 3])


def skew(v) -> sp.Matrix:
    """[v]: the 3x3 skew-symmetric matrix with [v] w = v x w."""
    x, y, z = v
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def vex(s: sp.Matrix) -> sp.Matrix:
    """The vector v of a skew-symmetric matrix [v] (inverse of `skew`)."""
    return sp.Matrix([s[2, 1], s[0, 2], s[1, 0]])


def is_rototranslation(m, tol: float = 1e-9) -> bool:
    """True when a numeric 4x4 matrix is a proper rigid transform."""
    import numpy as np

    a = np.array(m, dtype=float)
    if a.shape != (4, 4):
        return False
    r = a[:3, :3]
    return (
        np.allclose(r.T @ r, np.eye(3), atol=tol * 1e3)
        and abs(np.linalg.det(r) - 1.0) < tol * 1e3
        and np.allclose(a[3], [0, 0, 0, 1], atol=tol)
    )


def rotation_defect(r) -> tuple[float, float]:
    """(max |RᵀR − I|, det R) of a numeric 3x3 block: how far entries rounded by hand (0.707
    for cos 45°) leave it from a rotation."""
    import numpy as np

    a = np.array(r, dtype=float).reshape(3, 3)
    return float(np.max(np.abs(a.T @ a - np.eye(3)))), float(np.linalg.det(a))


def nearest_rotation(r) -> sp.Matrix:
    """The rotation nearest a numeric 3x3 block (polar decomposition: R = U·Vᵀ from its SVD),
    its entries as 15-digit Floats: what robosolve reads for a rotation rounded by hand."""
    import numpy as np

    u, _, vt = np.linalg.svd(np.array(r, dtype=float).reshape(3, 3))
    return sp.Matrix(3, 3, [sp.Float(float(v), 15) for v in (u @ vt).reshape(9)])
