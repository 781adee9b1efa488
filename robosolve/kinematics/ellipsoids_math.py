"""Force, velocity and compliance ellipsoids of a Jacobian at one configuration.

docs/course-notes.md#note-ellipsoid-axes and the spec's "Ellipsoids" layout:

* A = J·Jᵀ (J of the chosen task coordinates), eigenvalues νᵢ, *unit* eigenvectors ϑ̂ᵢ;
* force ellipsoid FᵀAF = Kf²: semi-axes (Kf/√νᵢ)·ϑ̂ᵢ;
* velocity ellipsoid VᵀA⁻¹V = Kv²: semi-axes (Kv·√νᵢ)·ϑ̂ᵢ;
* compliance: Ks = J·Kq·Jᵀ (Kq the joint compliances, δq = Kq·τ), semi-axes Ka·κᵢ along
  the unit eigenvectors of Ks;
* condition number = max ν / min ν (= cond(J)²);
* semi-axes sorted by decreasing length; each vector's first component with
  |x| > 1e-9·max|x| is positive; eigenvectors of a repeated eigenvalue are the
  canonical orthonormal basis of the eigenspace (projected e₁, e₂, … then Gram–Schmidt);
* a zero eigenvalue (ν ≤ 1e-12·max ν) gives a degenerate ellipsoid: force semi-axis
  infinite (length and vector ``None``), velocity semi-axis 0, condition number ``None``;
  never a division by zero nor a NaN.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from robosolve.core.simplify import collected_radicals, eigenvalue, radicals, rational
from robosolve.core.opcount import count_ops

__all__ = ["EllipsoidAxes", "EllipsoidResult", "ellipsoids", "eig_sorted", "joint_rates", "exact_values",
           "ZERO_TOL"]

ZERO_TOL = 1e-12      # relative: an eigenvalue below ZERO_TOL * max is zero


@dataclass
class EllipsoidAxes:
    lengths: list            # float or None (infinite), decreasing
    directions: list         # unit vectors (lists), same order
    semi_axes: list          # length * direction, or None when infinite

    def as_dict(self):
        return {"semi_axes": self.semi_axes, "lengths": self.lengths}


@dataclass
class EllipsoidResult:
    A: list
    eigenvalues: list                # ν, ascending
    eigenvectors: list               # unit, same order
    force: EllipsoidAxes
    velocity: EllipsoidAxes
    compliance: EllipsoidAxes
    Ks: list
    compliance_eigenvalues: list     # κ, descending
    condition_number: float | None
    singular: bool
    rank: int
    notes: list = field(default_factory=list)


def _clean(x: float) -> float:
    x = float(x)
    return 0.0 if abs(x) < 1e-15 else x


def _chop(a: np.ndarray, rel: float = 1e-12) -> np.ndarray:
    """Zero the entries below rel·max|a|: rounding noise that would differ between machines."""
    a = np.array(a, dtype=float)
    m = float(np.max(np.abs(a))) if a.size else 0.0
    a[np.abs(a) <= rel * m] = 0.0
    return a


def _orient(v: np.ndarray) -> np.ndarray:
    v = _chop(v)
    m = float(np.max(np.abs(v))) if v.size else 0.0
    for x in v:
        if abs(x) > 1e-9 * m:
            return v if x > 0 else -v
    return v


def _canonical_basis(vectors: np.ndarray) -> np.ndarray:
    """Canonical orthonormal basis of the span of the columns (a repeated eigenvalue)."""
    q, _ = np.linalg.qr(vectors)
    proj = q @ q.T
    basis: list[np.ndarray] = []
    for i in range(proj.shape[0]):
        v = proj[:, i].copy()
        for b in basis:
            v -= np.dot(b, v) * b
        n = np.linalg.norm(v)
        if n > 1e-8:
            basis.append(v / n)
        if len(basis) == vectors.shape[1]:
            break
    return np.column_stack(basis)


def eig_sorted(a, descending: bool = False):
    """Eigenvalues (ascending or descending) and unit eigenvectors (columns) of a symmetric
    matrix, with the canonical choice of sign and of basis for repeated eigenvalues."""
    a = np.asarray(a, dtype=float)
    a = (a + a.T) / 2
    w, v = np.linalg.eigh(a)
    scale = max(1.0, float(np.max(np.abs(w)))) if w.size else 1.0
    w = np.where(np.abs(w) <= ZERO_TOL * scale, 0.0, w)
    # group repeated eigenvalues and make their eigenvectors canonical
    i = 0
    while i < len(w):
        j = i + 1
        while j < len(w) and abs(w[j] - w[i]) <= 1e-9 * scale:
            j += 1
        if j - i > 1:
            v[:, i:j] = _canonical_basis(v[:, i:j])
        i = j
    order = list(range(len(w)))
    if descending:
        order = order[::-1]
    w = w[order]
    v = v[:, order]
    vecs = [_orient(v[:, k]) for k in range(v.shape[1])]
    return [float(x) for x in w], vecs


def _axes(lengths, vectors) -> EllipsoidAxes:
    lens, dirs, semis = [], [], []
    for ln, vec in zip(lengths, vectors):
        dirs.append([_clean(x) for x in vec])
        if ln is None:
            lens.append(None)
            semis.append(None)
        else:
            lens.append(_clean(ln))
            semis.append([_clean(ln * x) for x in vec])
    return EllipsoidAxes(lengths=lens, directions=dirs, semi_axes=semis)


def ellipsoids(j, kf: float = 1.0, kv: float = 1.0, ka: float = 1.0, kq=None) -> EllipsoidResult:
    """All three ellipsoids of a numeric J (m coordinates x n joints) at one configuration."""
    j = np.atleast_2d(np.asarray(j, dtype=float))
    m, n = j.shape
    kq_m = np.eye(n) if kq is None else (np.diag(np.asarray(kq, dtype=float))
                                         if np.ndim(kq) == 1 else np.asarray(kq, dtype=float))
    a = _chop(j @ j.T, 1e-14)
    notes: list[str] = []
    nu, vecs = eig_sorted(a)                        # ascending ν
    numax = max(nu) if nu else 0.0
    rank = sum(1 for x in nu if x > 0)
    singular = rank < m
    # force: Kf/√ν, decreasing length = ascending ν; zero ν → infinite (None)
    f_len = [None if x <= 0 else kf / np.sqrt(x) for x in nu]
    force = _axes(f_len, vecs)
    # velocity: Kv·√ν, decreasing length = descending ν
    v_len = [kv * np.sqrt(max(x, 0.0)) for x in nu[::-1]]
    velocity = _axes(v_len, vecs[::-1])
    # compliance: Ks = J Kq Jᵀ, Ka·κ, descending κ
    ks = _chop(j @ kq_m @ j.T, 1e-14)
    kappa, kvecs = eig_sorted(ks, descending=True)
    compliance = _axes([ka * k for k in kappa], kvecs)
    if singular:
        cond = None
        zero_dirs = [vecs[i] for i, x in enumerate(nu) if x <= 0]
        dirs = "; ".join("(" + ", ".join(f"{_clean(c):.4g}" for c in d) + ")" for d in zero_dirs)
        why = (f"J has more coordinates ({m}) than joints ({n}), so A = J·Jᵀ (rank ≤ {n}) "
               f"always has {m - rank} zero eigenvalue(s)" if m > n and rank == n else
               f"Singular configuration: A = J·Jᵀ has {m - rank} zero eigenvalue(s)")
        notes.append(
            f"{why}. The force "
            f"ellipsoid is unbounded along {dirs} (semi-axis reported as null: the structure "
            "balances any force in that direction with zero joint effort), the velocity and "
            "compliance ellipsoids are flat along it (semi-axis 0), and the condition number "
            "is infinite (reported as null).")
    else:
        cond = float(numax / min(nu)) if nu else None
    if any(k < 0 for k in kappa):
        notes.append("Ks = J·Kq·Jᵀ has a negative eigenvalue: the joint compliances should be "
                     "non-negative.")
    return EllipsoidResult(
        A=[[_clean(x) for x in row] for row in a], eigenvalues=[_clean(x) for x in nu],
        eigenvectors=[[_clean(x) for x in v] for v in vecs],
        force=force, velocity=velocity, compliance=compliance,
        Ks=[[_clean(x) for x in row] for row in ks],
        compliance_eigenvalues=[_clean(x) for x in kappa],
        condition_number=cond, singular=singular, rank=rank, notes=notes)


def joint_rates(j, velocity):
    """q̇ giving the task velocity: exact solve when J is square and regular, otherwise
    the minimum-norm least-squares solution J⁺·v. Returns (q_dot, residual, note)."""
    j = np.atleast_2d(np.asarray(j, dtype=float))
    v = np.asarray(velocity, dtype=float).reshape(-1)
    m, n = j.shape
    sv = np.linalg.svd(j, compute_uv=False)
    tol = ZERO_TOL ** 0.5 * max(1.0, float(sv.max()) if sv.size else 1.0)
    rank = int(np.sum(sv > tol))
    if m == n and rank == n:
        qd = np.linalg.solve(j, v)
        note = None
    else:
        qd = np.linalg.pinv(j, rcond=ZERO_TOL ** 0.5) @ v
        if m < n and rank == m:
            note = (f"J is {m}x{n} (redundant): q̇ = J⁺·v = Jᵀ(J·Jᵀ)⁻¹·v is the solution of "
                    "minimum norm among infinitely many.")
        elif m > n and rank == n:
            note = (f"J is {m}x{n}: more coordinates than joints, q̇ = J⁺·v is the "
                    "least-squares solution.")
        else:
            note = ("J is singular here: q̇ = J⁺·v is the minimum-norm least-squares "
                    "solution.")
    residual = float(np.linalg.norm(j @ qd - v))
    if note and residual > 1e-9 * max(1.0, float(np.linalg.norm(v))):
        note += f" The velocity cannot be reached exactly (residual |J·q̇ − v| = {residual:.6g})."
    return [_clean(x) for x in qd], residual, note


def exact_values(j_exact, kf=1, kv=1, ka=1, kq=None, max_ops: int = 80):
    """Exact eigenvalues and semi-axis lengths when J is exact (numbers, radicals, pi).

    Returns a dict {A, eigenvalues (ascending), force, velocity, compliance (lengths, in the
    layout order), Ks, compliance_eigenvalues, condition_number} of sympy values, or None
    when the eigenvalues are too big to be worth showing (cubic formulas and the like).
    The caller wraps this in its time limit.
    """
    import sympy as sp

    j = sp.Matrix(j_exact)
    m, n = j.shape
    kq_m = sp.eye(n) if kq is None else (sp.diag(*kq) if not isinstance(kq, sp.MatrixBase)
                                         and not isinstance(kq[0], (list, tuple)) else sp.Matrix(kq))
    a = (j * j.T).applyfunc(rational)
    ks = (j * kq_m * j.T).applyfunc(rational)

    def eigs(mat):
        vals = []
        for val, mult in mat.eigenvals().items():
            val = eigenvalue(val)
            if count_ops(val) > max_ops or val.free_symbols:
                return None
            vals += [val] * mult
        return sorted(vals, key=lambda v: (float(sp.re(v.evalf(30))), sp.default_sort_key(v)))

    nu = eigs(a)
    kappa = eigs(ks)
    if nu is None or kappa is None:
        return None
    nice = radicals

    nz = [v for v in nu if v.evalf(30) > sp.Float(ZERO_TOL, 30) * max(1, nu[-1].evalf(30))]
    force = [None if v not in nz else nice(rational(kf) / sp.sqrt(v)) for v in nu]
    velocity = [nice(rational(kv) * sp.sqrt(v)) for v in nu[::-1]]
    compliance = [nice(rational(ka) * k) for k in kappa[::-1]]
    cond = sp.expand(collected_radicals(nu[-1] / nu[0])) if len(nz) == len(nu) else None
    return {"A": a, "eigenvalues": nu, "force": force,
            "velocity": velocity, "compliance": compliance, "Ks": ks,
            "compliance_eigenvalues": kappa[::-1], "condition_number": cond}
