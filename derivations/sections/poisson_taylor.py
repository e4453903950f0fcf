"""High-precision integration of the Poisson equations from t = -oo to t = +oo (mpmath).

An independent numerical route for the scattering angle (paper section 5.1,
Theorem 5.4, boundary condition ``ss``) that uses neither the 3F2 lemma
``gam_0`` nor the monodromy proposition: only ``eq:whole`` with
``omega = u tanh t + v sech t`` (``omegas``, ``eq:o12``).

Method
------
1. *The ends.*  In ``x = e^t`` the Poisson equations read
   ``x dgamma/dx = gamma x omega(x)`` with ``omega = (u (x^2-1) + 2 v x)/(x^2+1)``,
   a regular singular point at ``x = 0`` with exponents ``0, +-i|u|``.  The
   solution with exponent 0 and ``gamma(0) = g0`` (the steady rotation's
   axis) is a power series with radius 1 (the poles ``x = +-i``, i.e.
   ``t = +-i pi/2``); its coefficients follow from
   ``k gamma_k - gamma_k x omega_0 = sum_{j>=1} gamma_{k-j} x omega_j``
   (a 3x3 solve per k, never singular: ``k != +-i|u|``).  At ``t = +oo`` the
   same with ``xi = e^-t``: ``xi dgamma/dxi = -gamma x omega``.
2. *The middle.*  Taylor steps in ``t`` of ``gamma' = gamma x omega``, with
   the Taylor coefficients of ``tanh`` and ``sech`` from ``T' = S^2``,
   ``S' = -T S``; steps of at most 1/4 (the poles are pi/2 away) and at most
   8/|u| (the rotation: terms up to e^8, well inside the
   15 guard digits), summed until three consecutive terms are below the
   tolerance.
3. *The angle.*  Solutions of ``eq:whole`` are rotated rigidly, so
   ``<gamma(t), phi(t)>`` is constant for two solutions; with ``gamma`` the
   ``ss`` solution and ``phi(+oo) = u/|u|``, its value is the component of
   ``gamma(+oo)`` along the limit axis.

This is evidence at the working precision (no error enclosure); the number
of digits is checked against the closed form by the caller.
"""
from __future__ import annotations

import mpmath
from mpmath.libmp import fzero
from mpmath.libmp import mpf_add as add
from mpmath.libmp import mpf_mul as mul
from mpmath.libmp import mpf_mul_int as mul_int
from mpmath.libmp import mpf_neg as neg
from mpmath.libmp import mpf_sub as sub


def _raw(value):
    """The raw (sign, mantissa, exponent, bits) of an mpf, as mpmath's own operators would see it."""
    return mpmath.mpf(value)._mpf_


def _cross_sum(pairs, scale, prec: int, rnd: str) -> list:
    """``sum scale * (g x (w1, w2, 0))`` over the (g, w) pairs of raw mpf values, as mpf: operation for operation
    what ``r0 += scale * (-g2 * w1)`` etc. do on mpf (``r0 += -g2 * w1`` for ``scale=None``), so the same
    roundings and the same bits, without an mpf object per operation."""
    r0 = r1 = r2 = fzero
    for g_, w_ in pairs:
        t0 = mul(neg(g_[2], prec, rnd), w_[1], prec, rnd)
        t1 = mul(g_[2], w_[0], prec, rnd)
        t2 = sub(mul(g_[0], w_[1], prec, rnd), mul(g_[1], w_[0], prec, rnd), prec, rnd)
        if scale is not None:
            t0, t1, t2 = mul_int(t0, scale, prec, rnd), mul_int(t1, scale, prec, rnd), mul_int(t2, scale, prec, rnd)
        r0, r1, r2 = add(r0, t0, prec, rnd), add(r1, t1, prec, rnd), add(r2, t2, prec, rnd)
    return [mpmath.mp.make_mpf(r) for r in (r0, r1, r2)]


def cross(g, w):
    """g x (w1, w2, 0)."""
    return [-g[2] * w[1], g[2] * w[0], g[0] * w[1] - g[1] * w[0]]


def limit_series(u, v, g0, at_plus: bool, terms: int):
    """Coefficients of the exponent-0 solution at t = -oo (``at_plus=False``) or +oo."""
    s = -1 if at_plus else 1
    uu = [-c for c in u] if at_plus else list(u)
    inv = [((-1) ** (k // 2) if k % 2 == 0 else 0) for k in range(terms + 1)]  # 1/(1+x^2)
    w = []
    for k in range(terms + 1):
        shifted2 = inv[k - 2] if k >= 2 else 0
        shifted1 = inv[k - 1] if k >= 1 else 0
        w.append([uu[i] * (shifted2 - inv[k]) + 2 * v[i] * shifted1 for i in range(2)])
    coeffs = [[mpmath.mpf(c) for c in g0]]
    w0 = w[0]
    prec, rnd = mpmath.mp._prec_rounding
    raw_w = [[_raw(c) for c in wj] for wj in w]
    raw = [[c._mpf_ for c in coeffs[0]]]
    for k in range(1, terms + 1):
        rhs = _cross_sum(((raw[k - j], raw_w[j]) for j in range(1, k + 1)), s, prec, rnd)   # sum_j s gamma_(k-j) x w_j
        M = mpmath.matrix([[k, 0, s * w0[1]], [0, k, -s * w0[0]], [-s * w0[1], s * w0[0], k]])
        coeffs.append(list(mpmath.lu_solve(M, mpmath.matrix(rhs))))
        raw.append([c._mpf_ for c in coeffs[-1]])
    return coeffs


def eval_series(coeffs, x):
    out = [mpmath.mpf(0)] * 3
    power = mpmath.mpf(1)
    for g in coeffs:
        out = [out[i] + g[i] * power for i in range(3)]
        power *= x
    return out


def taylor_step(g, t0, h, u, v, tol):
    """gamma(t0 + h) from gamma(t0) by one Taylor series of gamma' = gamma x (u tanh + v sech)."""
    T, S, G = [mpmath.tanh(t0)], [mpmath.sech(t0)], [list(g)]
    W = []     # omega's Taylor coefficients, each computed once (the same operations as inline: same digits)
    total, power, n, small = list(g), mpmath.mpf(1), 0, 0
    prec, rnd = mpmath.mp._prec_rounding
    raw_g, raw_w = [[_raw(c) for c in g]], []
    while small < 3:
        W.append([u[i] * T[n] + v[i] * S[n] for i in range(2)])
        raw_w.append([c._mpf_ for c in W[-1]])
        acc = _cross_sum(((raw_g[j], raw_w[n - j]) for j in range(n + 1)), None, prec, rnd)   # sum_j G_j x W_(n-j)
        T.append(mpmath.fsum(S[j] * S[n - j] for j in range(n + 1)) / (n + 1))
        S.append(-mpmath.fsum(T[j] * S[n - j] for j in range(n + 1)) / (n + 1))
        G.append([a / (n + 1) for a in acc])
        raw_g.append([c._mpf_ for c in G[-1]])
        n += 1
        power *= h
        term = [c * power for c in G[-1]]
        total = [total[i] + term[i] for i in range(3)]
        small = small + 1 if max(abs(c) for c in term) < tol else 0
        if n > 5000:
            raise ArithmeticError(f"Taylor series at t = {t0} did not converge")
    return total


def propagate(g, t0, t1, u, v, tol):
    """gamma(t1) from gamma(t0) by Taylor steps (see the module docstring for the step bound)."""
    rate = max(abs(c) for c in list(u) + list(v))
    hmax = min(mpmath.mpf(1) / 4, 8 / rate) if rate else mpmath.mpf(1) / 4
    steps = max(1, int(mpmath.ceil(abs(t1 - t0) / hmax)))
    h = (t1 - t0) / steps
    t = t0
    for _ in range(steps):
        g = taylor_step(g, t, h, u, v, tol)
        t += h
    return g


def ss_through(u, v, dps: int):
    """(gamma(0), <gamma(+oo), u/|u|>) for the ss solution gamma(-oo) = -u/|u| (mpmath, ``dps`` digits).

    ``u`` and ``v`` are real pairs (mpmath numbers) with ``omega = u tanh t + v sech t``.
    """
    with mpmath.workdps(dps + 15):
        norm = mpmath.sqrt(u[0] ** 2 + u[1] ** 2)
        axis = [u[0] / norm, u[1] / norm, mpmath.mpf(0)]
        tol = mpmath.mpf(10) ** (-dps - 8)
        terms = int((dps + 10) * 2.4) + 10  # e^-1 per term at t = -1: 2.3 terms per digit
        x = mpmath.exp(-1)
        start = eval_series(limit_series(u, v, [-c for c in axis], False, terms), x)
        end = eval_series(limit_series(u, v, axis, True, terms), x)
        g0 = propagate(start, mpmath.mpf(-1), mpmath.mpf(0), u, v, tol)
        g1 = propagate(g0, mpmath.mpf(0), mpmath.mpf(1), u, v, tol)
        along = mpmath.fsum(g1[i] * end[i] for i in range(3))
        return [+c for c in g0], +along
