"""The real orthonormal basis of Poisson solutions for odd p (Theorem 6.1, corrected; ``eq:gam3``, ``asymp``).

``core`` is the generated module's ``_basis_core`` (the shared recipe ``suslov.recipes.basis``,
certified for every p in ``BASIS_PS``) and ``sigma`` its ``_BASIS_SIGMA``.  Method:

1. *Ball series.*  The recipe runs in python-flint ball arithmetic from the exact binary d; the
   numerators are normalised by their certified limits at x = 0 and converted to trigonometric
   polynomials in th = 2 arctan(e^-t) (``suslov.kernel.fourier``); the precision is doubled until
   every ball is narrower than the radius asked for, so each midpoint is within it of the exact
   coefficient (a rigorous bound).
2. *Float path.*  Midpoints within 1e-17, evaluated by ``suslov.kernel.trig_series``; the phase
   (p/d) t reduced in double-double arithmetic (``suslov.kernel.phase``) below ``PHASE_LIMIT`` and
   enclosed in python-flint balls beyond (:func:`careful_phase`).  The error bound the docstring
   states is proven over both branches by ``derivations.proofs.basis_proof``.
3. *mp twin.*  Midpoints within 10^-(dps+10), summed in mpmath at dps + 10 digits; the phase (p/d) t
   with k more digits when it is about 10^k (:func:`phase_digits`; t and d are read with them too).
   The sums call mpmath's ``libmp`` functions that its ``mpf`` operators and ``fsum`` call, with the
   same arguments in the same order (``mpf_mul_int`` for k th, ``mpf_cos_sin`` for cos and sin, which
   ``mpf_cos`` and ``mpf_sin`` each return half of, ``mpf_mul``, ``mpf_add``, ``mpf_sum``): the values are
   bit for bit those of ``fsum(alpha[k] * cos(k th) + beta[k] * sin(k th))``, without an ``mpf`` object
   per intermediate and with one argument reduction per k instead of two.  Why: the round trip calls
   the twin 34 times per p (``check_gamma_basis``); a call with its series cached took 8.4 ms at
   p = 201 (3.8 ms at p = 101), now 3.7 ms (1.8 ms), one core, dps = 40; the whole check is timed
   old against new in ``bench/bench_gamma_basis_checks.py``.
"""
from __future__ import annotations

import functools
from fractions import Fraction

import flint
import mpmath
import numpy as np
from mpmath.libmp import mpf_add, mpf_cos_sin, mpf_mul, mpf_mul_int, mpf_sum

from suslov.kernel import fourier, phase, trig_series
from suslov.kernel.contexts import FLOAT
from suslov.kernel.validate import DPS_RANGE, mp_dps, mp_real, odd_p, real_array
from suslov.recipes.rings import AcbBasisRing

from .integrals import CACHE_SIZE

__all__ = ["basis_p", "careful_phase", "gamma_basis", "gamma_basis_mp", "series_float"]

WHY_ODD = "closed-form meromorphic solutions exist for odd p only"


def basis_p(p, ps) -> int:
    return odd_p(p, ps, WHY_ODD)


def _arb_of(value) -> flint.arb:
    """A ball containing a float or an mpf exactly (the precision set holds its mantissa).

    An mpf is read from its raw mantissa and exponent: ``mpmath.mpf(value)`` would round it to
    mpmath's current precision, which is the caller's, not the ``dps`` asked for.
    """
    if isinstance(value, mpmath.mpf):
        man, exp = value.man_exp
        return flint.arb(int(man)) * flint.arb(2) ** int(exp)
    exact = Fraction(float(value))
    return flint.arb(flint.fmpq(exact.numerator, exact.denominator))


def _mpf_of(exact) -> mpmath.mpf:
    """An arb with radius 0 (a ball's midpoint or radius) as the same binary number in mpmath, exactly
    (``make_mpf``: ``mpmath.mpf((man, exp))`` would round to mpmath's current precision)."""
    man, exp = exact.man_exp()
    return mpmath.mp.make_mpf(mpmath.libmp.from_man_exp(int(man), int(exp)))


def series_balls(core, p: int, d, radius: mpmath.mpf, bits: int):
    """Ball coefficients of the basis rows' trigonometric series, every radius <= ``radius``.

    Returns (alpha, beta) as ``acb_mat``, rows gamma^(1)_1..3 then G_1..3 (V scaled), columns k = 0..p.
    """
    while True:
        with flint.ctx.workprec(bits):
            ring = AcbBasisRing(_arb_of(d))
            c = (ring.d**2 + 1).sqrt()
            real, cplx = core(p, ring)
            real_lists = [m.coeffs() for m in real.M]
            complex_lists = [m.coeffs() for m in cplx.M]
            s, k = -real_lists[0][0], complex_lists[1][0]  # certified: gamma1 -> -1 and V2 -> 1 at x = 0
            rows = [[v / (f * s) for v in comp] for comp, f in zip(real_lists, (1, c, c))]
            rows += [[f * v / k for v in comp] for comp, f in zip(complex_lists, (c, 1, 1))]
            alpha, beta = fourier.to_fourier_acb(rows, p)
            # compared as mpf: a float radius such as 10^-(dps+10) would underflow to 0 beyond dps ~ 300
            parts = (part for m in (alpha, beta) for v in m.entries() for part in (v.real, v.imag))
            if all(_mpf_of(part.rad()) <= radius for part in parts):
                return alpha, beta
        bits *= 2


def _series_midpoints(core, p: int, d, radius: mpmath.mpf, bits: int, convert) -> list:
    """``convert``-ed ball midpoints, nested [row][component][re/im][cos/sin][k] (row 0: gamma^(1), 1: G)."""
    alpha, beta = series_balls(core, p, d, radius, bits)
    return [[[[[convert(getattr(matrix[3 * row + comp, k], part).mid()) for k in range(p + 1)]
               for matrix in (alpha, beta)] for part in ("real", "imag")] for comp in range(3)] for row in range(2)]


@functools.lru_cache(maxsize=CACHE_SIZE)
def _series_mp(core, p: int, d, dps: int) -> list:
    """mpf coefficients within 10^-(dps+10) of the exact ones, cached per (p, d, dps) (an mpf key compares
    exact values: two d that agree to the caller's precision are still two d)."""
    radius = mpmath.mpf(10) ** -(dps + 10)
    return _series_midpoints(core, p, d, radius, int(3.33 * (dps + 10)) + 12 * p, _mpf_of)


@functools.lru_cache(maxsize=CACHE_SIZE)
def series_float(core, p: int, d: float) -> np.ndarray:
    """float64 coefficients (shape (2, 3, 2, 2, p+1): row, component, re/im, cos/sin, k), cached per (p, d).

    Each is its ball's midpoint with radius <= 1e-17 (from 64 + 12p bits), so within 1e-17 + half an
    ulp of the exact value (a rigorous bound).
    """
    return np.array(_series_midpoints(core, p, d, mpmath.mpf(1e-17), 64 + 12 * p, float))


FAR_RADIUS = 2.0**-70     # radius of the far phase's cos and sin balls before rounding to float64

_make_mpf = mpmath.mp.make_mpf     # gamma_basis_mp: an mpf from libmp's tuple, as mpmath.fsum returns it


def careful_phase(p: int, d: float, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos, sin of (p/d) t for phases beyond ``phase.PHASE_LIMIT``: the exact rational p t/d (t and d are binary
    numbers) enclosed in python-flint balls at 64 bits plus its size, the precision doubled until both radii are
    below ``FAR_RADIUS``, then rounded to float64: within one ulp plus 2^-70 of the exact values, whatever the
    phase (a rigorous bound, used by the proof of the docstring's bound)."""
    cos_out, sin_out = np.empty(t.shape), np.empty(t.shape)
    d_exact = flint.fmpq(*Fraction(float(d)).as_integer_ratio())
    for index, tv in np.ndenumerate(t):
        angle = flint.fmpq(p) * flint.fmpq(*Fraction(float(tv)).as_integer_ratio()) / d_exact
        bits = 64 + max(0, int(abs(angle.p)).bit_length() - int(angle.q).bit_length() + 1)
        while True:
            with flint.ctx.workprec(bits):
                sin_ball, cos_ball = flint.arb(angle).sin_cos()
            if cos_ball.rad() < FAR_RADIUS and sin_ball.rad() < FAR_RADIUS:
                break
            bits *= 2
        cos_out[index], sin_out[index] = float(cos_ball.mid()), float(sin_ball.mid())
    return cos_out, sin_out


@functools.lru_cache(maxsize=CACHE_SIZE)
def _series_matrix(core, p: int, d: float) -> np.ndarray:
    """(2(p+1), 9) coefficients for trig_series: gamma^(1) (3 columns), Re V (3), Im V (3)."""
    c = series_float(core, p, d)
    columns = [c[0, j, 0] for j in range(3)] + [c[1, j, 0] for j in range(3)] + [c[1, j, 1] for j in range(3)]
    return np.ascontiguousarray(np.stack([np.concatenate(col) for col in columns], axis=1))


def _one_d(core, sigma, t: np.ndarray, p: int, d: float) -> np.ndarray:
    t = np.ravel(t)
    T, S = FLOAT.tanh_sech(t)
    values = trig_series.evaluate(T, S, _series_matrix(core, p, d))  # rows: gamma^(1) (3), Re V (3), Im V (3)
    with np.errstate(over="ignore", invalid="ignore"):   # p t/d beyond float64: careful_phase below
        cphi, sphi = phase.phase_cos_sin(p, d, t)
        # also where the split of p/d overflowed (d = 1e-300: p/d ~ 3e300 gave NaN even at t = 0)
        far = (np.abs(p * t / d) >= phase.PHASE_LIMIT) | ~np.isfinite(cphi) | ~np.isfinite(sphi)
    if far.any():
        cphi[far], sphi[far] = careful_phase(p, d, t[far])
    out = np.empty((t.size, 3, 3))
    sign = -sigma[p]
    for j in range(3):
        re, im = values[3 + j], values[6 + j]
        out[:, 0, j] = values[j]
        out[:, 1, j] = cphi * re - sphi * im
        out[:, 2, j] = sign * (sphi * re + cphi * im)
    return out


def gamma_basis(core, sigma, ps, t, p, d) -> np.ndarray:
    """Rows gamma^(1..3) at t, shape ``broadcast(t, d).shape + (3, 3)`` (see the generated docstring)."""
    p = basis_p(p, ps)
    t, d = np.broadcast_arrays(real_array("t", t), real_array("d", d, positive=True))
    out = np.empty(t.shape + (3, 3))
    if d.size == 1 or np.all(d == d.flat[0]):
        return _one_d(core, sigma, t, p, float(d.flat[0])).reshape(t.shape + (3, 3))
    for dv in np.unique(d):
        mask = d == dv
        out[mask] = _one_d(core, sigma, t[mask], p, float(dv))
    return out


def phase_digits(p: int, t, d, dps: int) -> int:
    """Digits the phase (p/d) t needs beyond ``dps + 10``: its decimal exponent (0 below 1).

    The mp twin multiplies by cos and sin of the phase, so its absolute error must be 10^-(dps+10);
    a phase of size 10^k needs k more digits in t, d and the product (issue 38: at dps = 15 and
    |p t/d| = 1e27 the phase had no correct digit).  Beyond ``DPS_RANGE``'s limit: ValueError naming the
    digits it would take.
    """
    size = abs(p * t / d)
    extra = max(0, int(mpmath.ceil(mpmath.log10(size)))) if size > 1 else 0
    if dps + 10 + extra > DPS_RANGE[1]:
        raise ValueError(f"t={mpmath.nstr(t, 5)}, d={mpmath.nstr(d, 5)}: the phase p t/d ~ {mpmath.nstr(size, 3)} "
                         f"needs {dps + 10 + extra} working digits for dps={dps} (limit {DPS_RANGE[1]}); ask "
                         f"for dps <= {DPS_RANGE[1] - 10 - extra} or a smaller |p t/d|")
    return extra


def gamma_basis_mp(core, sigma, ps, t, p, d, dps):
    """The mpmath twin: a 3x3 ``mpmath.matrix`` at ``dps`` digits (scalars t, d)."""
    dps = mp_dps(dps)
    p = basis_p(p, ps)
    with mpmath.workdps(dps):
        t_in, d_in = t, d
        t = mp_real("t", t)
        d = mp_real("d", d, positive=True)
    extra = phase_digits(p, t, d, dps)
    if extra:   # read t and d again with the digits the phase p t/d needs (a decimal string is not rounded to dps)
        with mpmath.workdps(dps + extra):
            t, d = mp_real("t", t_in), mp_real("d", d_in, positive=True)
    rows = _series_mp(core, p, d, max(dps, 40))
    with mpmath.workdps(dps + 10):
        th = 2 * mpmath.atan(mpmath.exp(-t))
        # cos k th, sin k th once for the 15 series of this call (each was recomputing them); mpmath's own libmp
        # operations called directly (module docstring, 3.), bit for bit: k * th is mpf_mul_int, and mpmath.cos,
        # mpmath.sin are the two halves of mpf_cos_sin (one argument reduction instead of two)
        prec, rnd = mpmath.mp._prec_rounding
        th_ = th._mpf_
        cos_sin = [mpf_cos_sin(mpf_mul_int(th_, k, prec, rnd), prec, rnd) for k in range(p + 1)]
        cosines, sines = [c for c, _ in cos_sin], [s for _, s in cos_sin]

        def series(part):
            # mpmath.fsum(alpha[k] * cosines[k] + beta[k] * sines[k] for k ...): the same products, sums and final
            # mpf_sum, without an mpf object per intermediate
            alpha, beta = part
            return _make_mpf(mpf_sum([mpf_add(mpf_mul(a._mpf_, c, prec, rnd), mpf_mul(b._mpf_, s, prec, rnd), prec, rnd)
                                     for a, b, c, s in zip(alpha, beta, cosines, sines)], prec, rnd))

        out = mpmath.matrix(3, 3)
        with mpmath.workdps(dps + 10 + extra):   # the phase to 10^-(dps+10) absolute, whatever its size
            phase_mp = p * t / d
            cphi, sphi = mpmath.cos(phase_mp), mpmath.sin(phase_mp)
        cphi, sphi = +cphi, +sphi
        for j in range(3):
            out[0, j] = series(rows[0][j][0])
            re, im = series(rows[1][j][0]), series(rows[1][j][1])
            out[1, j] = cphi * re - sphi * im
            out[2, j] = -sigma[p] * (sphi * re + cphi * im)
    with mpmath.workdps(dps):
        return +out
