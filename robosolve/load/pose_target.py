"""The pose target of an inverse-kinematics question (spec: the row of a pose target).

``target: {pose: M}`` (4x4, last row 0 0 0 1) or ``target: {position: [x, y, z], R: 3x3 | zyz: [φ, θ, ψ]
| rpy: [roll, pitch, yaw]}``. A given rotation must be orthonormal with determinant 1 within 1e-3:
entries rounded by hand are projected onto the nearest rotation (polar decomposition) with a note,
exact entries are kept exact, further off is an input error.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from robosolve.core.transforms import nearest_rotation, rot_x, rot_y, rot_z, rotation_defect
from robosolve.load.expressions import degrees_hint

POSE_KEYS = ("pose", "position", "R", "zyz", "rpy")
ORIENTATION_KEYS = ("R", "zyz", "rpy")
POSITION = POSE_KEYS[1]      # the key `position` (a word, not the question type)
ROTATION_TOL = 1e-3


@dataclass
class PoseTarget:
    R: sp.Matrix                # 3x3, of parameters (exact where given exact)
    p: sp.Matrix                # 3x1
    given: str                  # "pose", "R", "zyz" or "rpy"
    angles: tuple | None = None # the zyz / rpy angles as given
    note: str | None = None     # the projection onto the nearest rotation, when done


def is_pose_target(value) -> bool:
    return isinstance(value, dict) and any(k in value for k in POSE_KEYS)


def v_pose_target(ql, path, value, q):
    """A pose target (see the module docstring), or None after reporting the mistake."""
    chk = ql.chk
    if not chk.mapping(path, value, POSE_KEYS):
        return None
    given = [k for k in ORIENTATION_KEYS if k in value]
    if "pose" in value:
        if q.point_given:
            chk.error(path + ("pose",), "a `pose` is the pose of a frame: it cannot go with `point` "
                      "(give `position` and `R`, `zyz` or `rpy` for a point)")
            return None
        if given or POSITION in value:
            chk.error(path, "the target is given twice: `pose` already holds the position and the "
                      f"orientation (remove {', '.join('`' + k + '`' for k in given + ([POSITION] if POSITION in value else []))})")
            return None
        return _pose(ql, path + ("pose",), value["pose"])
    if len(given) > 1:
        chk.error(path, f"the orientation is given twice ({' and '.join('`' + k + '`' for k in given)}): keep one")
        return None
    if not given or POSITION not in value:
        # a key whose did-you-mean was already reported (`postion`) is not missing a second time
        missing = [] if POSITION in value or chk.misspelt(value, POSITION, POSE_KEYS) else ["`position`"]
        if not given and not any(chk.misspelt(value, k, POSE_KEYS) for k in ORIENTATION_KEYS):
            missing.append("`R`, `zyz` or `rpy`")
        if missing:
            chk.error(path, "a pose target needs `position` and one orientation (`R`, `zyz` or `rpy`): "
                      f"{' and '.join(missing)} missing")
        return None
    p = chk.vector(path + (POSITION,), value[POSITION], ql.params_ns, length=3)
    key = given[0]
    if key == "R":
        R = chk.matrix(path + ("R",), value["R"], ql.params_ns, shapes=((3, 3),))
        if R is None or p is None:
            return None
        return _checked(ql, path + ("R",), R, p, "R")
    a = chk.vector(path + (key,), value[key], ql.params_ns, length=3)
    if a is None or p is None:
        return None
    _degrees_warning(chk, path + (key,), list(a), value[key])
    if key == "zyz":
        R = (rot_z(a[0]) * rot_y(a[1]) * rot_z(a[2]))[:3, :3]
    else:
        R = (rot_z(a[2]) * rot_y(a[1]) * rot_x(a[0]))[:3, :3]
    return PoseTarget(R, p, key, tuple(a))


def _degrees_warning(chk, path, angles, raw) -> None:
    """One warning for angles that read like degrees (rpy: [30, 45, 60] is read in radians, as a
    DH twist or an Rz() of a pose is), with the list as it would be written in degrees."""
    hinted = [degrees_hint(a) is not None for a in angles]
    if not any(hinted):
        return
    shown = [f"{float(a):g}" if h else str(r) for a, r, h in zip(angles, raw, hinted)]   # as written
    meant = [f"deg({t})" if h else t for t, h in zip(shown, hinted)]
    chk.warn(path, f"[{', '.join(shown)}] are angles in radians (beyond a full turn); if degrees were "
             f"meant, write [{', '.join(meant)}]")


def _pose(ql, path, value):
    chk = ql.chk
    M = chk.matrix(path, value, ql.params_ns, shapes=((4, 4),))
    if M is None:
        return None
    last = [chk.number_value(M[3, j]) for j in range(4)]
    if any(v is not None and abs(v - w) > 1e-12 for v, w in zip(last, (0, 0, 0, 1))):
        chk.error(path + (3,), "the last row of a pose must be 0 0 0 1")
        return None
    return _checked(ql, path, M[:3, :3], M[:3, 3], "pose")


def _checked(ql, path, R, p, given):
    """The rotation checked (orthonormal, det 1 within 1e-3) and projected when rounded by hand."""
    vals = [ql.chk.number_value(v) for v in R]
    if any(v is None for v in vals):
        return PoseTarget(R, p, given)       # checked when solved, with the values then known
    err, det = rotation_defect(vals)
    what = "the rotation of the pose" if given == "pose" else "R"
    if det <= 0 or err > ROTATION_TOL or abs(det - 1) > ROTATION_TOL:
        ql.chk.error(path, f"{what} is not a rotation: RᵀR differs from I by {err:.3g} and det R = {det:.6g} "
                     f"(orthonormal with determinant 1 within {ROTATION_TOL:g} is required)")
        return None
    if err < 1e-12 and abs(det - 1) < 1e-12:
        return PoseTarget(R, p, given)
    note = (f"{what} is orthonormal only to {err:.2g} (entries rounded by hand): it is replaced by the "
            "nearest rotation (polar decomposition, R = U·Vᵀ from its SVD)")
    return PoseTarget(nearest_rotation(vals), p, given, note=note)
