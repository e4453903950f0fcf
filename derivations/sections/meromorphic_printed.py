"""The odd-p bases against the paper's printed forms, and the forms the document prints (sections 5.1, 6.1, 6.2).

Labels: ``pol_sol``, ``gam1``, ``gam2``, ``gam3``, ``poly_F2`` (the printed examples for p = 1 and
p = 3, section 6.2, are in :mod:`derivations.sections.printed_examples`).  Split from
:mod:`derivations.sections.meromorphic`, which certifies the bases; here they are compared with what is
printed (exact identities), written
out in tanh/sech for the document, and tabulated (the coefficients c_j of F1 and of F, Fhat).
"""
from __future__ import annotations

from fractions import Fraction

import flint
import mpmath
import symengine as se
import sympy as sp

from derivations.core import paper
from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.core.common_denominator import polynomial
from derivations.core.errata import erratum
from derivations.core.flint_factor import (
    factor_gaussian,
    factor_multivariate,
    generator_order,
)
from derivations.core.result import DerivationResult
from derivations.core.statement import Statement, ring
from derivations.core.typeset import latex
from derivations.sections.meromorphic_ring import (
    CTX,
    DOMAIN,
    Basis,
    D,
    I,
    X,
    gamma1_numerator,
    hypergeometric_polynomials,
    in_y_squared,
    red,
    third_order_residual,
)


def printed_gam1_numerator(p: int):
    """Printed gam1: the a_k = 4^k x (printed pol_sol coefficients), as a numerator in x (sympy)."""
    xs, ds = sp.symbols("x d")
    total = 0
    for k in range((p - 1) // 2 + 1):
        coefficient = sp.Integer(4) ** k
        for m in range(1, k + 1):
            coefficient *= sp.Rational(2 * m - 1, 2 * m)
        for m in range(k):
            coefficient *= (p * p - (2 * m + 1) ** 2) * ds**2 / ((2 * m + 1) * ds**2 + p * p)
        total += coefficient * (xs**2 + 1) ** (p - 1 - 2 * k) * xs ** (2 * k)
    return (xs**2 - 1) * total


def to_sympy(poly):
    xs, ds = sp.symbols("x d")
    return sp.Add(*(sp.Rational(int(c.p), int(c.q)) * xs ** int(m[0]) * ds ** int(m[1]) * sp.I ** int(m[2])
                    for m, c in zip(poly.monoms(), poly.coeffs())))


def printed_comparisons(log: CertificateLog, result: DerivationResult, proof: Certificate) -> None:
    """gam1, gam2 of Theorem 6.1 as printed, against the derivation (p = 3)."""
    p = 3
    xs, ds = sp.symbols("x d")
    derived = to_sympy(gamma1_numerator(p))
    Den1 = sp.Mul(*[(2 * m + 1) ** 2 * ds**2 + p * p for m in range((p - 1) // 2)])
    from derivations.core.exact import Domain, certify_zero
    c_gam1 = certify_zero(log, "$p = 3$: printed gam1 equals $tanh(t) F1(sech(t)^2)$ (derived)", "gam1",
                          printed_gam1_numerator(p) - derived / Den1, Domain("Q(d)[x]"), expect=Outcome.FAIL)
    F, Fhat = hypergeometric_polynomials(p)
    V1 = red(X * in_y_squared(red(F * Fhat)))
    with stopwatch() as elapsed:
        good = third_order_residual(V1, p, 1).is_zero()
        bad = third_order_residual(V1, p, -1).is_zero()
    c_pair = log.record(Certificate(
        "$p = 3$: $e^(i (p/d) t) x P_p(x^2)/(1+x^2)^p$ (parameters with $+i p$) solves eq:genhipprep", "gam2",
        Statement("exact zero test in ", ring(DOMAIN)), Outcome.PASS if good else Outcome.FAIL, elapsed[0], len(V1)))
    c_pair_bad = log.record(Certificate(
        "$p = 3$: the printed gam2 pairing $e^(-i (p/d) t)$ with the $+i p$ parameters solves eq:genhipprep", "gam2",
        Statement("exact zero test in ", ring(DOMAIN)), Outcome.FAIL if not bad else Outcome.PASS, 0.0, len(V1),
        expected=Outcome.FAIL))
    result.errata.append(erratum(
        paper.GAM1, "corrected", r"\gamma_1^{(1)}=\tanh t\,\mathcal F_1(\operatorname{sech}^2t),\ a_k=4^kc_k",
        "inherits the pol_sol misprints (sign $(-1)^k$, denominators $(2 m+1)^2 d^2 + p^2$)", c_gam1, proof))
    result.errata.append(erratum(
        paper.GAM2, "corrected", r"\gamma_1^{(2)}=\frac{e^{(1+\frac{ip}{d})t}}{(1+e^{2t})^p}\sum_k b_ke^{2kt}"
        r"\ (b_k\text{ from }a=\tfrac{2-p}2+\tfrac{ip}{2d},\ c=\tfrac32+\tfrac{ip}{2d})",
        "the exponent's sign is wrong: the $+i p$ parameters go with $e^(i (p/d) t)$ (as in F_23_pol, "
        "$y^((d+i p)/(2 d))$); gam3 is the complex conjugate", c_pair, c_pair_bad))


def basis_mp(basis: Basis, t, d):
    """Rows gamma^(1..3) from the certified numerators, evaluated with mpmath (x = e^t).

    Real and imaginary parts are compiled separately: a lambdified ``big_int * 1j``
    would be rounded to a Python complex float.
    """
    xs, ds = sp.symbols("x d")
    funcs = getattr(basis, "_mp_funcs", None)
    if funcs is None:
        compile_ = lambda poly, args: [sp.lambdify(args, to_sympy(part), "mpmath")  # noqa: E731
                                       for part in real_imaginary(poly)]
        funcs = [compile_(m, (xs, ds)) for m in basis.real.M + basis.complex_.M]
        funcs += [compile_(basis.scale_real, (ds,)), compile_(basis.k, (ds,))]
        basis._mp_funcs = funcs
    value = lambda pair, *args: mpmath.mpc(pair[0](*args), pair[1](*args))  # noqa: E731
    x = mpmath.exp(t)
    c = mpmath.sqrt(d * d + 1)
    den = (1 + x * x) ** basis.p
    s, k = mpmath.re(value(funcs[6], d)), value(funcs[7], d)
    g1 = [mpmath.re(value(funcs[0], x, d)) / (s * den), mpmath.re(value(funcs[1], x, d)) / (c * s * den),
          mpmath.re(value(funcs[2], x, d)) / (c * s * den)]
    G = [c * value(funcs[3], x, d), value(funcs[4], x, d), value(funcs[5], x, d)]
    phase = mpmath.expjpi(basis.p * t / (d * mpmath.pi))
    G = [phase * v / (k * den) for v in G]
    return [g1, [mpmath.re(v) for v in G], [mpmath.im(v) for v in G]]


TANH, SECH = sp.tanh(sp.Symbol("t")), sp.sech(sp.Symbol("t"))


TS_CTX = flint.fmpq_mpoly_ctx.get(("T", "S", "d"), "lex")


def numerator_to_tanh_sech(numerator, p: int, scale: sp.Expr):
    """``N(x)/(1+x^2)^p * scale`` as a polynomial in tanh t, sech t (degree <= 1 in sech after S^2 = 1 - T^2).

    ``numerator``: N in Q[x, d] (python-flint, the basis ring's variables (x, d, i), free of i);
    ``scale``: a SymPy factor free of x.  With x = e^t, ``x^m/(1+x^2)^p = ((1+T)/2)^(m-p) ... `` gives
    ``2^-p (1+T)^(m-p) S^(2p-m)`` (m >= p) or ``2^-p (1-T)^(p-m) S^m``; the sum is reduced modulo
    S^2 + T^2 - 1 and split as P0 + S P1, all in python-flint; each part is factored by FLINT into SymPy's ``factor`` form.
    """
    T, S, dd = TS_CTX.gens()
    one = TS_CTX.constant(1)
    total = TS_CTX.constant(0)
    for (m, kd, ki), c in zip(numerator.monoms(), numerator.coeffs()):
        if ki:
            raise ValueError("the numerator must be free of i")
        term = c * dd**kd
        total += term * ((1 + T) ** (m - p) * S ** (2 * p - m) if m >= p else (1 - T) ** (p - m) * S**m)
    parts = [TS_CTX.constant(0), TS_CTX.constant(0)]      # P0 + S P1, using S^2 = 1 - T^2
    for (a, b, kd), c in zip(total.monoms(), total.coeffs()):
        parts[b % 2] += c * T**a * dd**kd * (one - T * T) ** (b // 2)
    Tn, Sn, ds = sp.symbols("T S d")
    gens = generator_order({Tn, ds} | sp.sympify(scale).free_symbols)
    ctx = flint.fmpq_mpoly_ctx.get(tuple(str(x) for x in gens), "lex")
    index = {str(x): k for k, x in enumerate(gens)}
    # scale / 2^p as N/D in the same ring (its factors are products of powers of polynomials)
    scale_num, scale_den = (polynomial(se.expand(se.sympify(e)), ctx, index) for e in sp.fraction(scale / 2**p))
    factored = 0
    for key, part in zip((1, Sn), parts):
        if part.is_zero():
            continue
        terms = {}
        for (a, _, kd), c in zip(part.monoms(), part.coeffs()):
            exponents = [0] * len(gens)
            exponents[index["T"]], exponents[index["d"]] = int(a), int(kd)
            terms[tuple(exponents)] = c
        # sympy.factor(part * scale / 2^p), by FLINT (derivations.core.flint_factor: the same expression)
        factored += factor_multivariate(ctx.from_dict(terms) * scale_num, scale_den, gens) * key
    return factored.subs({Tn: TANH, Sn: SECH})


def real_imaginary(poly):
    """(A, B) with poly = A + i B, A and B free of i."""
    A = poly.compose(X, D, CTX.constant(0))
    B = divmod(poly - A, I)[0]
    return A, B


def written_out(basis: Basis) -> list:
    """LaTeX of the rows: gamma^(1), and gamma^(2) + i gamma^(3) = e^{ipt/d} (R + i Q)."""
    cs = sp.Symbol("c")
    p = basis.p
    scale = to_sympy(basis.scale_real)
    first = [numerator_to_tanh_sech(m, p, f / scale) for m, f in zip(basis.real.M, (1, 1 / cs, 1 / cs))]
    kr, ki = real_imaginary(basis.k)
    norm = to_sympy(kr * kr + ki * ki)
    R, Q = [], []
    for m, f in zip(basis.complex_.M, (cs, 1, 1)):
        A, B = real_imaginary(m)
        R.append(numerator_to_tanh_sech(A * kr + B * ki, p, f / norm))
        Q.append(numerator_to_tanh_sech(B * kr - A * ki, p, f / norm))
    phase = r"\tfrac{%d t}{d}" % p if p > 1 else r"\tfrac{t}{d}"
    rows = [(r"\gamma^{(1)}_{%d}" % (k + 1), x) for k, x in enumerate(first)]
    rows.append(r"\gamma^{(2)}=\cos(%s)\,R-\sin(%s)\,Q,\quad \gamma^{(3)}=\sin(%s)\,R+\cos(%s)\,Q" % ((phase,) * 4))
    rows += [(r"%s_{%d}" % (name, k + 1), x) for name, vector in (("R", R), ("Q", Q)) for k, x in enumerate(vector)]
    return rows


def _gaussian_coefficients(poly) -> dict:
    """{k: coefficients (constant first, pairs (real, imaginary) of Fractions) of x^k} of a polynomial in
    (x, d, i) over Q, i^2 = -1."""
    out = {}
    for (kx, kd, ki), c in zip(poly.monoms(), poly.coeffs()):
        value = Fraction(int(c.p), int(c.q)) * (-1 if ki % 4 >= 2 else 1)
        column = out.setdefault(int(kx), {})
        re, im = column.get(int(kd), (Fraction(0), Fraction(0)))
        column[int(kd)] = (re, im + value) if ki % 2 else (re + value, im)
    return {k: [column.get(j, (Fraction(0), Fraction(0))) for j in range(max(column) + 1)] for k, column in out.items()}


def coefficient_tables(options) -> dict:
    """c_j of F1 (odd p <= 15) and the coefficients of F(a+,b;c+;-y), Fhat (odd p <= 7)."""
    from derivations.sections.first_integrals import hypergeometric_coefficient

    ds = sp.Symbol("d")
    f1_rows, f_rows = [], []
    for p in options.odd_p_values():
        if p > 15:
            break
        for j in range(1, (p - 1) // 2 + 1):
            f1_rows.append({"p": p, "j": j, "c": latex(sp.factor(hypergeometric_coefficient(j, p, ds)))})
        if p <= 7:
            F, Fhat = hypergeometric_polynomials(p)
            J = (p - 1) // 2
            den2 = sp.Mul(*[(3 + 2 * j) ** 2 * ds**2 + p * p for j in range(J)])
            # factored over Q(i) (SymPy's factor(..., gaussian=True), the object it gives): every entry
            # splits into linear factors, found by FLINT from its norm (derivations.core.flint_factor)
            den_coefficients = [(Fraction(int(c)), Fraction(0)) for c in sp.Poly(den2, ds).all_coeffs()[::-1]]
            f_by_power, fhat_by_power = _gaussian_coefficients(F), _gaussian_coefficients(Fhat)
            for kk in range(max(max(f_by_power), max(fhat_by_power)) + 1):
                row = {"p": p, "k": kk}
                for name, by_power in (("F", f_by_power), ("Fhat", fhat_by_power)):
                    numerator = by_power.get(kk, [(Fraction(0), Fraction(0))])
                    factored = factor_gaussian(numerator, den_coefficients, ds)
                    if factored is None:   # not a product of linear factors over Q(i): SymPy's general route
                        factored = sp.factor(sum((re + sp.I * im) * ds**j for j, (re, im) in enumerate(numerator))
                                             / den2, gaussian=True)
                    row[name] = latex(factored)
                f_rows.append(row)
    return {"f1": f1_rows, "f": f_rows}


def compare_poly_f2(log: CertificateLog, result: DerivationResult, options) -> None:
    """Coefficients of Fhat (poly_F2): derived, the corrected closed form, and the printed one."""
    from derivations.core.exact import Domain, certify_zero

    xs, ds = sp.symbols("x d")
    good, bad = [], []
    for p in [q for q in options.odd_p_values() if 3 <= q <= 7]:
        F, Fhat = hypergeometric_polynomials(p)
        J = (p - 1) // 2
        den2 = sp.Mul(*[(3 + 2 * j) ** 2 * ds**2 + p * p for j in range(J)])
        Fh = sp.Poly(to_sympy(Fhat), xs)
        a = sp.Rational(2 - p, 2) + sp.I * p / (2 * ds)
        b, c = sp.Rational(1 - p, 2), sp.Rational(3, 2) + sp.I * p / (2 * ds)
        derived, corrected, printed = [], [], []
        for k in range(J + 1):
            f_k = sp.rf(a, k) * sp.rf(b, k) / (sp.rf(c, k) * sp.factorial(k)) * (-1) ** k
            derived.append(Fh.coeff_monomial(xs**k) / den2)
            corrected.append(f_k * (-p) * (ds - sp.I) * ((2 * k + 1) * ds + sp.I * p) / ((p - 2 * k) * ds - sp.I * p))
            printed.append(f_k * (2 * ds * k + ds + p * sp.I) * (4 * ds * k - ds * p + sp.I * p)
                           / (ds * p - 2 * ds * k - sp.I * p))
        good.append(certify_zero(log, f"$p = {p}$: $Fhat_k = -p (d-i)((2k+1)d+i p)/((p-2k)d-i p) F_k$ (from the definition "
                                 "of $Fhat$)", "poly_F2", [u - v for u, v in zip(derived, corrected)], Domain("Q(d)(i)")))
        bad.append(certify_zero(log, f"$p = {p}$: the printed poly_F2 coefficients equal $Fhat_k$", "poly_F2",
                                [u - v for u, v in zip(derived, printed)], Domain("Q(d)(i)"), expect=Outcome.FAIL))
    if good:
        result.errata.append(erratum(
            paper.POLY_F2, "corrected",
            r"\hat F=\sum_k\frac{(a_+)_k(b_+)_k}{(c_+)_kk!}\,\frac{-p(d-i)((2k+1)d+ip)}{(p-2k)d-ip}\,(-y)^k"
            r"\ (\text{conjugate for }a_-,c_-)",
            "the factor $(4 d k - d p + i p)$ should be $-p(d - i)$ (they agree only at $k = 0$); derived from "
            "$Fhat = (d (p-1) y - d - i p) F - 2 d y (y+1) deriv(F, y)$", *good, *bad))
