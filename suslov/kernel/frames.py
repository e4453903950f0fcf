"""The paper's body frame for a numeric inertia tensor (section 2).

The constraint vector is a = e3.  Rotating about e3 keeps a and can make I12 = 0; the
paper's frame also has I11 >= I22 and det I = 1.  :func:`canonical_frame` finds that
rotation and validates the tensor with messages that say what is wrong.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["canonical_frame", "rotation_about_e3"]


def rotation_about_e3(theta: float) -> np.ndarray:
    """The rotation by ``theta`` about e3 (columns: the new axes in the old frame)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def canonical_frame(I) -> tuple[np.ndarray, tuple[float, float, float, float]]:
    """Validate a numeric inertia tensor (constraint axis a = e3) and find the paper's frame.

    Returns ``(R, (I11, I22, I13, I23))``: ``R`` is a rotation about e3 whose columns are
    the new axes in the given frame (a vector ``v`` has new coordinates ``R.T @ v``), and
    the entries are those of ``det I = 1`` in the new frame, where I12 = 0 and I11 >= I22.
    Raises ValueError naming what is wrong (shape, NaN/inf, asymmetry, not positive
    definite, a an eigenvector of I).

    >>> R, (I11, I22, I13, I23) = canonical_frame([[2, 0, 0], [0, 1, 0.5], [0, 0.5, 1]])
    >>> round(I13, 12), I11 >= I22
    (0.0, True)
    """
    try:
        raw = np.asarray(I)
        if np.iscomplexobj(raw):
            raise ValueError(f"I: complex entries are not accepted (dtype {raw.dtype}); an inertia tensor is real")
        M = np.array(raw, dtype=float)
    except (TypeError, ValueError) as error:
        if "complex" in str(error):
            raise
        raise ValueError(f"I={I!r}: must be a 3x3 array of real numbers") from None
    if M.shape != (3, 3):
        raise ValueError(f"I has shape {M.shape}: must be 3x3")
    if not np.all(np.isfinite(M)):
        raise ValueError("I contains NaN or inf")
    scale = np.max(np.abs(M))
    if scale == 0:
        raise ValueError("I is zero: not positive definite")
    # every answer is scale-invariant (det I = 1 below): scaled to entries of order 1 first, so that
    # 1e-300 * I or 1e103 * I neither underflows nor overflows in det, eigvalsh or the tests below
    M, scale = M / scale, 1.0
    if np.max(np.abs(M - M.T)) > 1e-12 * scale:
        raise ValueError(f"I is not symmetric (max |I - I^T| = {np.max(np.abs(M - M.T)):.3g})")
    M = (M + M.T) / 2
    try:   # Cholesky decides graded tensors (eigenvalues 1 and 1e-300) that eigvalsh rounds to <= 0
        np.linalg.cholesky(M)
    except np.linalg.LinAlgError:
        raise ValueError(f"I is not positive definite (smallest eigenvalue {np.linalg.eigvalsh(M)[0]:.6g})") from None
    # det I = 1 through the logarithm of the determinant: entries spanning 1e-300..1e300 have a det that
    # underflows to 0 (then inf/NaN everywhere) although its cube root is an ordinary number
    det = np.linalg.det(M)
    if det > 1e-290:   # the ordinary case, bit for bit as before
        M = M / det ** (1.0 / 3.0)
    else:
        sign, log_det = np.linalg.slogdet(M)
        if sign <= 0 or not np.isfinite(log_det):
            raise ValueError(f"I is not positive definite (det of I/max|I| has sign {sign:g}, log {log_det:.6g})")
        with np.errstate(over="ignore", invalid="ignore"):
            M = M * math.exp(-log_det / 3.0) if -log_det / 3.0 < 709.0 else M * np.inf
    if not np.all(np.isfinite(M)):
        raise ValueError("I: its eigenvalues span too many orders of magnitude (det(I/max|I|) below 1e-920); "
                         "I / det(I)^(1/3) is beyond float64's range")
    R = rotation_about_e3(0.5 * math.atan2(2 * M[0, 1], M[0, 0] - M[1, 1]))
    M = R.T @ M @ R
    I11, I22, I13, I23 = M[0, 0], M[1, 1], M[0, 2], M[1, 2]
    if math.hypot(I13, I23) <= 1e-12 * np.max(np.abs(M)):
        raise ValueError("a = (0, 0, 1) is an eigenvector of I (I13 = I23 = 0): every motion is an equilibrium")
    return R, (float(I11), float(I22), float(I13), float(I23))
