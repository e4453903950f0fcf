"""The Frobenius logarithm obstruction of ``y'' = r(w) y`` at a double pole, exactly in Q(m).

Used by :mod:`derivations.sections.galois` for the Conjecture of paper section 5.2 (labels ``eq:rlin``,
``eq:Q``, ``eq:Deltai``): is there a logarithm at the singular points s1, s2 (exponent
difference ``Delta = p``) and s3, s4 (``Delta = 2``) for every d > 0?

Method
------
At a double pole ``w = s`` write ``r = sum_k r_k zeta^(k-2)`` (``zeta = w - s``, ``r_k`` in Q(m)).
The Frobenius series ``y = zeta^mu sum_k y_k zeta^k`` from the smaller exponent
``mu = (1 - Delta)/2`` satisfies ``beta_k y_k = sum_{j=1}^{k} r_j y_{k-j}`` with
``beta_k = (mu+k)(mu+k-1) - r_0``, which vanishes at ``k = Delta``; there the right-hand side,
the *obstruction* ``sum_{j=1}^{Delta} r_j y_{Delta-j}``, must be zero for a solution without a
logarithm.  It is an element of Q(m); zero (as a rational function) means no logarithm for every
m, non-zero means a logarithm for all but finitely many m.

1. The first ``r_k`` are computed as reduced fractions (python-flint ``fmpq_poly`` numerator
   and denominator, gcd after every step) from the Taylor coefficients of the numerator and of
   the denominator with the double root removed.
2. A *clearing factor* ``E`` in Q[m] is read off the factored denominators of the first
   ``PROBE`` coefficients: every irreducible factor f with multiplicity e in den(r_j) gets
   exponent ``max_j ceil(e / j)``.  Then ``T_j = r_j E^j`` follow from the Taylor recursion times
   E^j by exact divisions by the leading coefficient (a remainder means E does not clear that
   order, and the reduced fractions of step 1 are used for every order instead: never assumed).
3. ``Y_k = y_k E^k`` then obeys ``beta_k Y_k = sum_j T_j Y_{k-j}``, a recursion in Q[m] without
   any gcd, and ``E^Delta * obstruction = sum_j T_j Y_{Delta-j}``.  E is non-zero, so the
   obstruction is zero exactly when this polynomial is.
4. The convolutions ``sum_j T_j Y_{k-j}`` are not summed term by term (k products of two long
   polynomials for each k, Delta^2/2 in all): ``sum T_j zeta^j`` is the rational series
   ``a(E zeta)/b(E zeta)`` of the shifted numerator and rest, so the convolutions obey a recursion
   with len(a) + len(b) terms (:func:`_convolutions`).  The same polynomials, exactly: at p = 201
   the decision at s1 takes 0.7 s instead of 4.2 s.

Why this and not a fraction-free recursion with the full leading coefficient ``b0``: for the
Suslov reduced form ``den(r_k) = (m-1)^2 (m+1)^k`` (up to constants), so ``E = m^2 - 1``, degree
2 per step, where the powers of ``b0`` (degree 14 in m) gave polynomials of degree 28p - 1.  At
p = 101 the decision takes about 2 s instead of about 80 s (``bench/bench_build.py``).
"""
from __future__ import annotations

import flint

ZERO = flint.fmpq_poly([])
ONE = flint.fmpq_poly([1])


def taylor_shift(coeffs: list, point, zero=ZERO, terms: int | None = None) -> list:
    """Coefficients (low to high, in zeta) of ``sum c_k w^k`` at ``w = point + zeta`` (synthetic division).

    Any ring: ``zero`` is its zero (python-flint ``fmpq_poly`` by default, a SymPy domain's elsewhere).
    ``terms``: only the first ones (each pass of the division yields the next; the first is Horner's value).
    """
    coeffs, out = list(coeffs[::-1]), []
    while coeffs and (terms is None or len(out) < terms):
        acc, quotient = zero, []
        for c in coeffs:
            acc = acc * point + c
            quotient.append(acc)
        out.append(quotient.pop())
        coeffs = quotient
    return out


def _reduced(num, den) -> tuple:
    if num.is_zero():
        return ZERO, ONE
    g = num.gcd(den)
    num, den = num / g, den / g
    lead = den.leading_coefficient()
    return num / lead, den / lead


def laurent_fractions(num: list, rest: list, point, order: int) -> list[tuple]:
    """``[(n_k, d_k)]``, ``r_k = n_k/d_k`` reduced, k = 0..order, for ``r = num / ((w - point)^2 rest)``.

    ``num``, ``rest``: coefficient lists (low to high in w) of ``fmpq_poly`` in m; ``point`` an
    ``fmpq_poly`` (a constant or a polynomial in m).
    """
    a = taylor_shift(num, point) + [ZERO] * (order + 1)
    b = taylor_shift(rest, point)
    if b[0].is_zero():
        raise ArithmeticError("the pole is not double: the rest of the denominator vanishes at the point")
    out = []
    for k in range(order + 1):
        n, d = a[k], ONE
        for j in range(1, min(k, len(b) - 1) + 1):
            rn, rd = out[k - j]
            n, d = n * rd - b[j] * rn * d, d * rd
        out.append(_reduced(n, d * b[0]))
    return out


def clearing_factor(fractions: list) -> object:
    """The least ``E`` (product of irreducible factors) with ``den(r_j) | E^j`` for every j >= 1."""
    exponents = {}
    for j, (_, den) in enumerate(fractions[1:], start=1):
        for factor, multiplicity in den.factor()[1]:
            key = str(factor)
            need = -(-multiplicity // j)
            if need > exponents.get(key, (None, 0))[1]:
                exponents[key] = (factor, need)
    E = ONE
    for _, (factor, need) in sorted(exponents.items()):
        E *= factor**need
    return E


PROBE = 12   # terms computed as reduced fractions to find the clearing factor


def cleared_coefficients(num: list, rest: list, point, order: int) -> tuple[list, object]:
    """``([T_0, ..., T_order], E)`` with ``T_k = r_k E^k`` in Q[m], by exact divisions only.

    E is the :func:`clearing_factor` of the first ``PROBE`` coefficients (reduced fractions, cheap
    at low order).  Multiplying the Taylor recursion ``b0 r_k = a_k - sum_j b_j r_{k-j}`` by E^k gives
    ``b0 T_k = a_k E^k - sum_j b_j E^j T_{k-j}``: when each right-hand side is divisible by b0 the
    quotients are exactly the T_k (the recursion determines them uniquely), with no gcd.  If a
    division leaves a remainder, E does not clear that order and every r_k is computed as a reduced
    fraction instead (slower, same result).
    """
    probe = laurent_fractions(num, rest, point, min(order, PROBE))
    E = clearing_factor(probe)
    a = taylor_shift(num, point) + [ZERO] * (order + 1)
    b = taylor_shift(rest, point)
    powers = [ONE]
    for _ in range(max(order, len(b))):
        powers.append(powers[-1] * E)
    T = []
    for k in range(order + 1):
        rhs = a[k] * powers[k]
        for j in range(1, min(k, len(b) - 1) + 1):
            rhs -= b[j] * powers[j] * T[k - j]
        quotient, remainder = divmod(rhs, b[0])
        if not remainder.is_zero():
            return _cleared_from_fractions(laurent_fractions(num, rest, point, order))
        T.append(quotient)
    return T, E


def _cleared_from_fractions(fractions: list) -> tuple[list, object]:
    E = clearing_factor(fractions)
    T, power = [], ONE
    for k, (n, d) in enumerate(fractions):
        quotient, remainder = divmod(n * power, d)
        if not remainder.is_zero():
            raise ArithmeticError(f"the clearing factor does not clear r_{k}")
        T.append(quotient)
        power = power * E
    return T, E


def log_obstruction(num: list, rest: list, point, delta: int) -> tuple[bool, object, object]:
    """``(r0_ok, P, E)``: whether ``r_0 = (delta^2 - 1)/4`` and ``P = E^delta * obstruction`` in Q[m].

    ``P`` is zero exactly when the local solutions at the point have no logarithm for every m.
    The convolutions ``C_k = sum_{j=1}^{k} T_j Y_{k-j}`` come from :func:`_convolutions`, a recursion of
    fixed length, not from the k products of the sum.
    """
    T, E = cleared_coefficients(num, rest, point, delta)
    r0 = flint.fmpq(delta * delta - 1, 4)
    r0_ok = T[0] == r0
    mu = flint.fmpq(1 - delta, 2)
    a, b = taylor_shift(num, point), taylor_shift(rest, point)
    convolutions = _convolutions(a, b, E, T[0], lambda k, C_k: C_k / ((mu + k) * (mu + k - 1) - r0), delta)
    return r0_ok, convolutions[delta], E


def _convolutions(a: list, b: list, E, T0, next_Y, order: int) -> list:
    """``[C_0, ..., C_order]``, ``C_k = sum_{j=1}^{k} T_j Y_{k-j}``, with ``Y_0 = 1`` and ``Y_k = next_Y(k, C_k)``.

    ``T_j = r_j E^j`` are the coefficients of ``R(E zeta)``, where ``R = a/b`` is the Laurent series of
    the potential (``b R = a`` as power series in zeta).  So ``S = T Y`` (the full convolution,
    ``S_k = T_0 Y_k + C_k``) satisfies ``b(E zeta) S = a(E zeta) Y``, and with ``b_0 T_0 = a_0``:

        ``b_0 C_k = sum_{j>=1} a_j E^j Y_{k-j} - sum_{j>=1} b_j E^j S_{k-j}``,

    len(a) + len(b) products per k instead of k (at p = 201: 20 instead of up to 200, each of a short
    polynomial by a long one, not of two long ones).  The T_j, Y_k and hence C_k are polynomials in m
    (E clears the denominators, see :func:`cleared_coefficients`), so the division by b_0 is exact; a
    remainder raises ArithmeticError rather than being dropped.
    """
    top = max(len(a), len(b))
    power, aE, bE = ONE, [ZERO] * top, [ZERO] * top
    for j in range(1, top):
        power = power * E
        aE[j] = a[j] * power if j < len(a) else ZERO
        bE[j] = b[j] * power if j < len(b) else ZERO
    Y, S, C = [ONE], [T0], [ZERO]
    for k in range(1, order + 1):
        rhs = ZERO
        for j in range(1, min(k, top - 1) + 1):
            rhs += aE[j] * Y[k - j] - bE[j] * S[k - j]
        C_k, remainder = divmod(rhs, b[0])
        if not remainder.is_zero():
            raise ArithmeticError(f"the convolution of order {k} is not a polynomial: E does not clear it")
        C.append(C_k)
        if k < order:
            Y.append(next_Y(k, C_k))
            S.append(T0 * Y[k] + C_k)
    return C
