"""gamma(t) of every body from Gauss's 2F1, not by integration (issue 44): the public routine.

Every solution of the Poisson equations ``gamma' = gamma x omega``, ``omega = u tanh t + v sech t`` (paper eq:whole,
eq:o12; rate 1, paper frame) is quadratic in 2F1 functions (``derivations/sections/gauss.py``):
``S(gamma(t)) = Phi(t) X0 Phi(t)^-1`` with ``S(w) = -(i/2)(w1 sigma3 + w2 sigma1 + w3 sigma2)`` and ``Phi`` the unitary
fundamental matrix of the spinor lift built from Gauss's basis at infinity,
``z^-e (z^(kappa/2) (1-z)^(mu/2)) 2F1(e, e-C+1; e-e'+1; 1/z)``, e = A, B, ``z = (1 + i sinh t)/2``.  The formulas,
the branches and the normalisation: :mod:`suslov.kernel.gauss_gamma_mp` (mpmath, any precision); the float64
vectorised evaluation of the same closed form: :mod:`suslov.kernel.gauss_gamma_float`.  The simulator's
``gauss_2f1`` route (:mod:`suslov.simulator.engine`) calls the float64 one and checks every run.

>>> g = gamma_gauss(1.0, "5/4", 1, "3/10", "-1/2", gamma0=(0, 0, 1), dps=20)
>>> abs(sum(x * x for x in g) - 1) < 1e-19
True
>>> import numpy as np
>>> G = gamma_gauss(np.linspace(-3, 3, 7), 2, 1, 0, "-1/2")      # p = 2, d = 1 (I13 = 0), the ss solution
>>> G.shape, bool(np.all(np.abs(np.linalg.norm(G, axis=-1) - 1) < 1e-14))
((7, 3), True)
"""
from __future__ import annotations

import mpmath
import numpy as np

from suslov.kernel.gauss_gamma_float import solve
from suslov.kernel.gauss_gamma_mp import GUARD_DIGITS, body_uv, solve_mp
from suslov.kernel.validate import mp_dps

__all__ = ["gamma_gauss", "gamma_gauss_uv"]


def gamma_gauss_uv(t, u, v, gamma0=None, t0=0, dps=None):
    """gamma(t) for ``omega = u tanh t + v sech t`` (rate-1 time, paper frame): ``gamma0`` at ``t0``, or the ss
    solution (``gamma(-oo) = -u/|u|``) when ``gamma0`` is None or "ss".

    ``dps`` None: float64 (:func:`suslov.kernel.gauss_gamma_float.solve`, vectorised), an array of shape
    ``np.shape(t) + (3,)``.  ``dps`` an int: mpmath at that many digits (:func:`suslov.kernel.gauss_gamma_mp.solve_mp`),
    a tuple of three mpf for a scalar ``t``, a list of such tuples for a sequence.
    """
    ss = gamma0 is None or (isinstance(gamma0, str) and gamma0 == "ss")
    if isinstance(gamma0, str) and not ss:
        raise ValueError(f"gamma0={gamma0!r}: a vector, None or 'ss'")
    if dps is None:
        times = np.asarray(t, dtype=float)
        initial = "ss" if ss else np.asarray(gamma0, dtype=float)
        values = solve(u, v, times.ravel(), initial, float(t0)).values[:, 0, :]
        return values.reshape(times.shape + (3,))
    dps = mp_dps(dps)
    scalar = np.ndim(t) == 0
    out = solve_mp(u, v, [t] if scalar else list(t), None if ss else gamma0, t0, dps)
    return out[0] if scalar else out


def gamma_gauss(t, I11, I22, I13, I23, gamma0=None, t0=0, dps=None):
    """gamma(t) of the body (I11, I22, I13, I23) (paper frame: I12 = 0, a = e3) from Gauss's 2F1.

    Rate-1 time t (``omega = u tanh t + v sech t``: ``omega_general`` with branch +1), ``gamma0`` at ``t0`` or the
    ss solution (``gamma0`` None or "ss").  ``dps`` None: float64, vectorised over ``t`` (shape ``np.shape(t) + (3,)``);
    an int: mpmath at that many digits (module docstring of :func:`gamma_gauss_uv`).  Entries: ints, floats,
    Fractions, mpf or decimal / "a/b" strings (:func:`suslov.kernel.validate.mp_real`).  Accuracy measured against
    mpmath's Taylor integration at higher precision: ``dps`` digits up to the last one or two; float64 about 1e-15
    absolute at moderate |t| (``docs/simulator.md``).
    """
    digits = 30 if dps is None else mp_dps(dps)
    with mpmath.workdps(digits + GUARD_DIGITS):
        u, v = body_uv(I11, I22, I13, I23)
    return gamma_gauss_uv(t, u, v, gamma0, t0, dps)
