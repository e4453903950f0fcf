"""Angular velocity: omega of the case I13 = 0 (paper ``omegas``) and of any body (``eq:o12``).

The formulas themselves are the emitted ``_omega`` and ``_omega_general`` of the generated module
(functions of a number context); here: argument validation, broadcasting, and the mpmath twins'
precision handling.
"""
from __future__ import annotations

import mpmath
import numpy as np

from suslov.kernel import finite
from suslov.kernel.contexts import FLOAT, MP
from suslov.kernel.display import MPValue
from suslov.kernel.scalars import like_ufunc
from suslov.kernel.validate import mp_dps, mp_real, real_array

__all__ = ["full", "tensor_arrays", "branch_sign", "omega", "omega_mp", "omega_general", "omega_general_mp"]

EQUILIBRIUM = "I13=0 and I23=0: the constraint axis is a principal axis, every motion is an equilibrium"


def full(values, shape) -> np.ndarray:
    """A writable float64 array of the broadcast shape (a fresh result is returned as it is)."""
    values = np.asarray(values, dtype=float)
    return values if values.shape == shape else np.array(np.broadcast_to(values, shape))


def tensor_arrays(I11, I22, I13, I23):
    """Validated float arrays of the four tensor entries (I11, I22 > 0; not I13 = I23 = 0)."""
    I11, I22 = real_array("I11", I11, positive=True), real_array("I22", I22, positive=True)
    I13, I23 = real_array("I13", I13), real_array("I23", I23)
    if np.any((I13 == 0) & (I23 == 0)):
        raise ValueError(EQUILIBRIUM)
    return I11, I22, I13, I23


def branch_sign(branch) -> int:
    if isinstance(branch, bool) or branch not in (1, -1):
        raise ValueError(f"branch={branch!r}: must be +1 or -1 (the sign of r = +-sqrt(I11 I22))")
    return int(branch)


@like_ufunc
def omega(emitted, t, p, d) -> tuple[np.ndarray, np.ndarray]:
    """``emitted(FLOAT, t, p, d)`` on validated, broadcast arrays (scalar parameters stay scalars)."""
    t, p, d = real_array("t", t), real_array("p", p, nonzero=True), real_array("d", d, positive=True)
    shape = np.broadcast_shapes(t.shape, p.shape, d.shape)
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        w1, w2 = emitted(FLOAT, t, p, d)
    # p/d beyond float64 (or inf * 0): those entries again in mpmath, or a ValueError naming t, p, d
    w1, w2 = finite.repair("omega", (full(w1, shape), full(w2, shape)), ("t", "p", "d"), (t, p, d),
                           lambda *x: emitted(MP, *x))
    return w1, w2


def omega_mp(emitted, t, p, d, dps) -> tuple:
    dps = mp_dps(dps)
    with mpmath.workdps(dps):
        t, p, d = mp_real("t", t), mp_real("p", p, nonzero=True), mp_real("d", d, positive=True)
        w1, w2 = emitted(MP, t, p, d)
        return MPValue(+w1, dps), MPValue(+w2, dps)


@like_ufunc
def omega_general(emitted, t, I11, I22, I13, I23, branch) -> tuple[np.ndarray, np.ndarray]:
    t = real_array("t", t)
    I11, I22, I13, I23 = tensor_arrays(I11, I22, I13, I23)
    shape = np.broadcast_shapes(t.shape, I11.shape, I22.shape, I13.shape, I23.shape)
    # the coefficients of omega are homogeneous of degree 0 in the entries: scaled to at most 1 first, a
    # tensor of size 1e-300 or 1e200 gives the same finite omega (its products overflowed to NaN)
    given = (t, I11, I22, I13, I23)
    size = np.maximum(np.maximum(I11, I22), np.maximum(np.abs(I13), np.abs(I23)))
    I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / size
    sign = branch_sign(branch)
    with np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore"):
        r = sign * np.sqrt(I11 * I22)
        w1, w2 = emitted(FLOAT, t, I11, I22, I13, I23, r)
    # entries spanning more than float64's range (scaled products underflow to 0/0): mpmath, or a
    # ValueError naming the arguments (omega itself beyond float64: |I11, I22| / |I13, I23| > 1e308)
    w1, w2 = finite.repair("omega_general", (full(w1, shape), full(w2, shape)), ("t", "I11", "I22", "I13", "I23"),
                           given, lambda t, a, b, c, e: emitted(MP, t, a, b, c, e,
                                                                                   sign * mpmath.sqrt(a * b)))
    return w1, w2


def omega_general_mp(emitted, t, I11, I22, I13, I23, branch, dps) -> tuple:
    dps = mp_dps(dps)
    with mpmath.workdps(dps):
        t = mp_real("t", t)
        I11, I22 = mp_real("I11", I11, positive=True), mp_real("I22", I22, positive=True)
        I13, I23 = mp_real("I13", I13), mp_real("I23", I23)
        if I13 == 0 and I23 == 0:
            raise ValueError(EQUILIBRIUM)
        r = branch_sign(branch) * mpmath.sqrt(I11 * I22)
        w1, w2 = emitted(MP, t, I11, I22, I13, I23, r)
        return MPValue(+w1, dps), MPValue(+w2, dps)
