"""The polynomial first integral F3 = P1 g1 + P2 g2 + P3 g3 for odd p (Theorem 6.2, corrected; ``eq:p1``, ``eq:p23``).

``core`` is the generated module's ``_integral_core``: the shared recipe ``suslov.recipes.integrals``,
certified by the build in exact arithmetic for every p in ``INTEGRAL_PS``.  Here it is run in
python-flint rationals for a rational d (exact coefficients), rounded once to float64 with a power-of-two
scale (no overflow at large p), and evaluated by Horner's rule in the ratio of modulus <= 1
(``suslov.kernel.horner.combination``); the mpmath twin sums the exact coefficients at ``dps`` digits.
"""
from __future__ import annotations

import functools
from fractions import Fraction

import flint
import mpmath
import numpy as np

from suslov.kernel import horner
from suslov.kernel.display import MPValue
from suslov.kernel.scalars import like_ufunc
from suslov.kernel.validate import mp_dps, mp_real, odd_p, rational, real_array
from suslov.recipes.rings import IntegralRing, homogeneous_coefficients

__all__ = ["CACHE_SIZE", "integral_p", "exact_coefficients", "float_coefficients", "first_integral_coefficients",
           "first_integral", "first_integral_mp"]

# per-(p, d) tables kept for repeated calls on one body; bounded so that sweeps over many bodies are not
CACHE_SIZE = 1024
WHY_ODD = "even p: the Poisson equations are not Liouville-integrable, no polynomial integral"


def integral_p(p, ps) -> int:
    return odd_p(p, ps, WHY_ODD)


@functools.lru_cache(maxsize=256)
def _cached_coefficients(core, p: int, d: Fraction) -> dict:
    # the recipe in python-flint rationals (fmpq), returned as Fractions: Python's Fraction spent its
    # time in gcds of large integers (0.8 s per d at p = 201, 0.1 s with fmpq); the mpmath twin asks once per point
    numerators = core(p, IntegralRing(flint.fmpq(d.numerator, d.denominator)))
    if not numerators.exact:
        raise ArithmeticError(f"p={p}: omega1 does not divide the numerator of P2 (the certified recipe says it does)")
    scales = {"P1": numerators.Den, "P2": numerators.K**2 * numerators.Den, "P3": numerators.K * numerators.Den}
    polys = {"P1": numerators.P1t, "P2": numerators.M2, "P3": numerators.M3}
    out = {}
    for name in polys:
        values = (flint.fmpq(v) / flint.fmpq(scales[name]) for v in homogeneous_coefficients(polys[name], p))
        out[name] = tuple(Fraction(int(v.p), int(v.q)) for v in values)
    return out


def exact_coefficients(core, p: int, d: Fraction) -> dict:
    """``{name: [a_k]}`` (fresh lists: callers may keep or change them), cached per (p, d)."""
    return {name: list(values) for name, values in _cached_coefficients(core, p, d).items()}


def first_integral_coefficients(core, ps, p, d) -> dict:
    return exact_coefficients(core, integral_p(p, ps), rational("d", d, positive=True))


@functools.lru_cache(maxsize=CACHE_SIZE)
def float_coefficients(core, p: int, d: float) -> tuple[np.ndarray, int]:
    """(3, p+1) coefficients of P1, P2, P3 over 2^E, correctly rounded to float64, and E (cached per (p, d)).

    Exact from the float d; E is the binary exponent of the largest, so every scaled coefficient
    is at most 1 in modulus and none overflows (they reach 1e340 at p = 201, d = 50) or falls
    below the normal range unless it is 2^-1000 times smaller than the largest.
    """
    exact = exact_coefficients(core, p, Fraction(d))
    rows = [exact[name] for name in ("P1", "P2", "P3")]
    top = max((abs(v) for row in rows for v in row), default=Fraction(1)) or Fraction(1)
    E = top.numerator.bit_length() - top.denominator.bit_length() + 1   # top / 2^E in (1/4, 1)
    two_E = Fraction(2) ** E
    return np.array([[float(v / two_E) for v in row] for row in rows]), E


@like_ufunc
def first_integral(core, ps, p, d, omega1, omega2, gamma1, gamma2, gamma3) -> np.ndarray | np.float64:
    """F3 in float64 (see the generated ``first_integral`` for the formula and its error bound)."""
    p = integral_p(p, ps)
    names = ("d", "omega1", "omega2", "gamma1", "gamma2", "gamma3")
    d, w1, w2, g1, g2, g3 = np.broadcast_arrays(
        *(real_array(n, v, positive=(n == "d")) for n, v in zip(names, (d, omega1, omega2, gamma1, gamma2, gamma3))))
    shape = d.shape
    d, w1, w2 = d.ravel(), w1.ravel(), w2.ravel()
    g = np.stack([g1.ravel(), g2.ravel(), g3.ravel()])
    s = np.maximum(np.abs(w1), np.abs(w2))
    # s^p as m^p 2^(p e), m in [1/2, 1): m^p >= 2^-p is a normal float for every certified p, so
    # neither s^p nor the coefficients' scale 2^E over- or underflows before the one final ldexp
    mantissa, exponent = np.frexp(s)
    value = np.empty(d.shape)
    single = d.size and np.all(d == d[0])
    for dv in ((d[0],) if single else np.unique(d)):
        mask = slice(None) if single else d == dv
        coefficients, E = float_coefficients(core, p, float(dv))
        value[mask] = horner.combination(coefficients, w1[mask], w2[mask], g[:, mask]) * mantissa[mask] ** p
        exponents = p * exponent[mask].astype(np.int64) + E
        with np.errstate(over="ignore"):   # an overflow is reported below, with its point
            value[mask] = np.ldexp(value[mask], np.clip(exponents, -4000, 4000))   # beyond +-4000: 0 or inf anyway
    if not np.all(np.isfinite(value)):
        where = int(np.flatnonzero(~np.isfinite(value))[0])
        point = f"p={p}, d={float(d[where])!r}, omega=({float(w1[where])!r}, {float(w2[where])!r})"
        raise ValueError(f"first_integral overflows float64 at {point}: |F3| beyond 1.8e308; use first_integral_mp")
    return value.reshape(shape)


def first_integral_mp(core, ps, p, d, omega1, omega2, gamma1, gamma2, gamma3, dps):
    dps = mp_dps(dps)
    p = integral_p(p, ps)
    exact = exact_coefficients(core, p, rational("d", d, positive=True))
    with mpmath.workdps(dps):
        w1, w2, g1, g2, g3 = (mp_real(n, v) for n, v in zip(("omega1", "omega2", "gamma1", "gamma2", "gamma3"),
                                                          (omega1, omega2, gamma1, gamma2, gamma3)))
        total = mpmath.mpf(0)
        for name, g in zip(("P1", "P2", "P3"), (g1, g2, g3)):
            total += g * mpmath.fsum(mpmath.mpf(a.numerator) / a.denominator * w1 ** (p - k) * w2**k
                                     for k, a in enumerate(exact[name]))
        return MPValue(+total, dps)
