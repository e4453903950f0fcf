"""Rational functions of x = e^t as trigonometric polynomials in th = 2 arctan(e^-t).

With x = cot(th/2): x^m / (1+x^2)^p = cos^m(th/2) sin^(2p-m)(th/2), a trigonometric
polynomial of degree p in th (m + n = 2p even).  Writing cos and sin of th/2 through
e^{+-i th/2} and expanding both binomials gives its Fourier coefficients

    F_k = (-i)^n / 4^p * sum_{a+b=p-k} C(m, a) C(n, b) (-1)^b,   k = -p..p,  n = 2p - m,

real for even n (a cosine series) and imaginary for odd n (a sine series).  The integer
matrices are exact and cached per p; :func:`to_fourier_acb` applies them to ball
coefficients (python-flint ``acb``) at any precision.  The basis of Poisson solutions is
evaluated in this form: its coefficients are bounded, there is no cancellation for
large p and no overflow for any t.

The ball matrices C/4^p, S/4^p are exact (dyadic entries, radius 0) at every precision of at least
their entries' bit length (:func:`exact_bits`, 2p + 2 or less), so they are built once per p
(:func:`_exact_matrices`: ``fmpz_mat`` -> ``acb_mat``, times the exact 2^-2p, checked exact) and shared by
every precision from there up; each entry is the same ball the former per-(p, precision) route made
(``acb(v) / 4^p``, kept in :func:`_matrices_acb` for lower precisions), so the products, and every
series built from them, are bit for bit those of before.  Why: a round trip at p builds the series at
three precisions (64 + 12p bits for ``gamma_basis``, and for ``gamma_basis_mp`` at 40 and 50 digits),
and each per-precision build of the two 403 x 202 matrices took 0.2-0.3 s at p = 201 (one core), 0.6 s
of ``check_gamma_basis``'s 3.9 s; now 0.14 s once per p.  The products themselves (``acb_mat`` in C,
``acb_dot`` per entry, exact zeros skipped) are 55 ms per series at p = 201 and are left as they are:
their balls are what the checks certify.  Measured old against new in
``bench/bench_gamma_basis_checks.py``.
"""
from __future__ import annotations

from functools import cache
from math import comb

__all__ = ["fourier_matrices", "to_fourier_acb"]


@cache
def fourier_matrices(p: int) -> tuple[tuple[tuple[int, ...], ...], tuple[tuple[int, ...], ...]]:
    """Integer (C, S): x^m/(1+x^2)^p = (sum_k C[m][k] cos k th + S[m][k] sin k th) / 4^p.

    The sum over a + b = p - k is the coefficient of w^(p-k) in (1+w)^m (1-w)^n; those
    polynomials are produced for m = 0..2p by P_(m+1) = P_m (1+w)/(1-w) (an exact division:
    a running sum), O(p^2) integer operations in all.
    """
    C = [[0] * (p + 1) for _ in range(2 * p + 1)]
    S = [[0] * (p + 1) for _ in range(2 * p + 1)]
    P = [comb(2 * p, j) * (-1) ** j for j in range(2 * p + 1)]  # (1-w)^(2p): m = 0
    for m in range(2 * p + 1):
        n = 2 * p - m
        unit = (-1) ** (n // 2) if n % 2 == 0 else (-1) ** ((n + 1) // 2)  # (-i)^n = unit or unit * i
        for k in range(p + 1):
            weight = 1 if k == 0 else 2
            if n % 2 == 0:
                C[m][k] = weight * unit * P[p - k]
            else:  # F_k = i unit total: weight Re(F_k e^{ik th}) = -weight unit total sin k th
                S[m][k] = -weight * unit * P[p - k]
        times = [P[j] + (P[j - 1] if j else 0) for j in range(len(P))]  # (1+w) P, the top term dropped:
        running, P = 0, []                                             # it cancels in the division
        for value in times:
            running += value
            P.append(running)
    return tuple(map(tuple, C)), tuple(map(tuple, S))


@cache
def _matrices_acb(p: int, prec: int):
    """(C/4^p, S/4^p) as ``acb_mat`` at ``prec``, entry by entry (each ``acb(v) / 4^p`` rounded to ``prec``):
    the route below :func:`exact_bits`, where an entry may be rounded."""
    import flint

    C, S = fourier_matrices(p)
    scale = 4**p
    rows = 2 * p + 1
    return (flint.acb_mat(rows, p + 1, [flint.acb(v) / scale for row in C for v in row]),
            flint.acb_mat(rows, p + 1, [flint.acb(v) / scale for row in S for v in row]))


@cache
def exact_bits(p: int) -> int:
    """The largest bit length of an entry of C, S: from this precision up every v / 4^p (a division by a
    power of two) is exact, in :func:`_matrices_acb` and in :func:`_exact_matrices` alike."""
    C, S = fourier_matrices(p)
    return max(abs(v).bit_length() for matrix in (C, S) for row in matrix for v in row)


@cache
def _exact_matrices(p: int):
    """(C/4^p, S/4^p) as exact ``acb_mat``, for every precision >= :func:`exact_bits` (one build per p).

    Built in C (``fmpz_mat`` -> ``acb_mat``, times 2^-2p) at a precision holding every entry, and checked
    exact (``M == M.mid()`` holds only for balls of radius 0): the same balls as :func:`_matrices_acb`."""
    import flint

    C, S = fourier_matrices(p)
    rows = 2 * p + 1
    with flint.ctx.workprec(exact_bits(p) + 64):
        scale = flint.arb(2) ** (-2 * p)
        matrices = tuple(flint.acb_mat(flint.fmpz_mat(rows, p + 1, [v for row in M for v in row])) * scale
                         for M in (C, S))
        if not all(M == M.mid() for M in matrices):
            raise ArithmeticError("_exact_matrices: an entry of C/4^p or S/4^p is not exact")
    return matrices


def to_fourier_acb(numerators: list, p: int):
    """(alpha, beta) as ``acb_mat`` (one row per numerator) of numerator(x)/(1+x^2)^p, k = 0..p.

    ``numerators`` are lists of ``acb`` coefficients (low to high, at most 2p+1); the products
    with the exact integer matrices are done in ball arithmetic at ``flint.ctx.prec``.
    """
    import flint

    size = 2 * p + 1
    # ball arithmetic cannot cancel a leading term exactly: beyond degree 2p (the certified bound) every
    # coefficient must be a ball that contains 0, and is dropped
    if any(0 not in v for n in numerators for v in list(n)[size:]):
        raise ArithmeticError("to_fourier_acb: a numerator exceeds degree 2p (increase the precision)")
    rows = [list(n)[:size] + [flint.acb(0)] * (size - len(n)) for n in numerators]
    N = flint.acb_mat(len(rows), size, [v for row in rows for v in row])
    prec = flint.ctx.prec
    C, S = _exact_matrices(p) if prec >= exact_bits(p) else _matrices_acb(p, prec)
    return N * C, N * S
