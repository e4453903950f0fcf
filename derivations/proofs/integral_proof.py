"""Proof of ``first_integral``'s float64 error bound (issue 34; Theorem 6.2, ``eq:p1``, ``eq:p23``).

``suslov.runtime.integrals.first_integral`` evaluates ``F3 = sum_i g_i P_i(w1, w2)`` as

* ``a~_ik = fl(a_ik / 2^E)``: the exact coefficients of the float d over the power of two of the largest
  (every ``|a~_ik| <= 1``, the largest in (1/4, 1)), correctly rounded (relative u, absolute 2^-1075 where
  one falls below the normal range);
* ``c_k = (a~_0k g_0 + a~_1k g_1) + a~_2k g_2`` (elementwise NumPy, in that order, so that the bits do not
  depend on the CPU as a BLAS product's do; the magnitude bound below is the same for every order, and an
  FMA would only drop a rounding);
* Horner ``h = c_n; h = h r + c_k`` in ``r = fl(small/big)``, ``|r| <= 1`` (correctly rounded: relative u
  plus 2^-1074 where it underflows), the coefficients reversed where ``|w2| > |w1|``, times ``sign(big)``
  (exact);
* times ``m^p`` (``s = m 2^e``, m in [1/2, 1), ``np.frexp`` exact; ``m ** p`` by libm's pow, within 4 ulp,
  ``>= 2^-p`` normal), then ``ldexp(., p e + E)``: exact unless the result is subnormal (then within 2^-1075).

The walk below runs these operations on :class:`derivations.proofs.float_bounds.FE` values and reads the
*magnitude form* ``|computed - exact| <= w M + aw``: ``M = m^p sum_i |g_i| sum_k |a~_ik| |r|^k`` is the sum of
the moduli of the expanded terms, and ``w`` (Higham's bound for sums and products, no cancellation penalty)
does not depend on the values: one box (coefficients and g in [-1, 1], r in [-1, 1]) proves it for every d,
omega and gamma.  The absolute part ``aw`` (underflows inside the scaled sum, in units of 2^(p e + E)) is
covered by the relative slack wherever ``sum_j |g_j| sum_k |a_jk| >= 2^-600 max |a_jk|`` (stated domain),
since then ``M >= 2^(-p-602)``.  The proven bound is ``B u s^p sum_j |g_j| sum_k |a_jk| + 5e-324``.
"""
from __future__ import annotations

import math

import numpy as np
from flint import arb, ctx

from derivations.proofs.float_bounds import ETA, FE, LIBM_REL, U, BoundFailure
from derivations.proofs.float_proofs import PREC, Proof, _in_u, box

DOMAIN_LOG2 = 600                 # the stated domain: sum_j |g_j| sum_k |a_jk| >= 2^-600 max |a_jk|
STATED_PER_DEGREE = 2e-15         # first_integral's docstring: 2e-15 (p + 1) s^p sum |g| sum |a| + 5e-324


def stated(p: int) -> float:
    return STATED_PER_DEGREE * (p + 1)


def ratio(small, big):
    """``horner.combination``'s r = small/big, one correctly rounded quotient."""
    return small / big


def walk(p: int, coefficient, g, small, big, power):
    """The operations of ``horner.combination`` and ``integrals.first_integral`` after the coefficients:
    ``coefficient(i, k)`` is a~_ik in the order of the branch (reversed where |w2| > |w1|), ``g`` the three
    gamma, ``small``/``big`` the omega of smaller/larger modulus, ``power`` m^p; generic in the number type
    (FE for the proof, float for the bit check)."""
    r = ratio(small, big)
    c = [(coefficient(0, k) * g[0] + coefficient(1, k) * g[1]) + coefficient(2, k) * g[2] for k in range(p + 1)]
    h = c[p]
    for k in range(p - 1, -1, -1):
        h = h * r
        h = h + c[k]
    return h * power


def prove_first_integral(p: int) -> Proof:
    with ctx.workprec(PREC):
        unit = box(-1.0, 1.0)
        # distinct objects: the walk must not take a~_0k g_0 for a square
        coefficients = [[FE(unit, U + ETA, U, ETA) for _ in range(p + 1)] for _ in range(3)]
        g = [FE(unit) for _ in range(3)]
        # omega scaled to |big| in [1, 2], |small| <= |big| (the quotient's relative bound does not depend on the scale)
        small, big = FE(unit), FE(box(1.0, 2.0))
        power = FE(box(2.0**-p, 1.0), LIBM_REL, LIBM_REL, 0)
        out = walk(p, lambda i, k: coefficients[i][k], g, small, big, power)
        w, aw = out.w, out.aw
        # the walk's sum of |terms| is the stated M: over the box, 3 (p + 1) terms of modulus <= 1 (a walk
        # that adds terms of its own, a constant added and taken away, is not the stated sum); 2^-20 for the
        # radii of the unit balls
        if not out.m <= 3 * (p + 1) * (1 + arb(2) ** -20):
            raise BoundFailure(f"first_integral p={p}: the walk's terms sum to {out.m}, beyond the stated "
                               f"{3 * (p + 1)}")
        # M >= m^p max|a~| (sum|g| sum|a|)/max|a| >= 2^-p 2^-2 2^-600 on the domain: aw within the slack
        floor = arb(2) ** -(p + 2 + DOMAIN_LOG2)
        if not aw < (arb(stated(p)) - w) * floor:
            raise BoundFailure(f"first_integral p={p}: absolute part {aw} beyond the slack on the domain")
    bound_u = math.ceil(_in_u(w))
    return Proof("first_integral", bound_u, 1,
                 f"$p = {p}$, every $d > 0$, $omega$ and $gamma$ with $abs(g_j) <= 1$ and "
                 f"$Sum(abs(g_j) Sum(abs(a_jk), (k, 0, p)), (j, 1, 3))$ at least $2^(-{DOMAIN_LOG2})$ times $A$, "
                 "$A$ the largest "
                 "$abs(a_jk)$",
                 f"the computed $F3$ is within ${bound_u} u s^p Sum(abs(g_j) Sum(abs(a_jk), (k, 0, p)), (j, 1, 3)) + "
                 "5e-324$ of the exact one")


def replica(module, p: int, d: float, w1: float, w2: float, g) -> float:
    """The analysed operation sequence in float64 (Python floats, the three-term sums in one order), for the
    bit-for-bit check against the public function."""
    from suslov.runtime.integrals import float_coefficients

    coefficients, E = float_coefficients(module._integral_core, p, float(d))
    first = abs(w1) >= abs(w2)
    big, small = (w1, w2) if first else (w2, w1)
    if big == 0:
        return 0.0
    mantissa, exponent = math.frexp(max(abs(w1), abs(w2)))
    rows = coefficients if first else coefficients[:, ::-1]
    power = float((np.array([mantissa]) ** p)[0])          # the array power of the runtime (libm pow)
    value = walk(p, lambda i, k: float(rows[i][k]), [float(x) for x in g], small, big, power)
    # the runtime multiplies by sign(big) before m^p: exact, and rounding is symmetric, so the bits agree
    try:
        return math.ldexp(value, p * exponent + E) * math.copysign(1.0, big)
    except OverflowError:   # the public function's contract there: ValueError, which the check reads as inf
        return math.inf


CLAIM = ("$p = {p}$: `first_integral` `float64` within $2e-15 (p + 1) s^p Sum(abs(g_j) Sum(abs(a_jk), (k, 0, p)), "
         "(j, 1, 3)) + 5e-324$ of the exact $F3$ ($s = Max(abs(w1), abs(w2))$, $a_jk$ the coefficients of "
         "$P_j$, $A$ the largest $abs(a_jk)$) where $abs(g_j) <= 1$ and $Sum(abs(g_j) Sum(abs(a_jk), (k, 0, p)), "
         "(j, 1, 3))$ is at least $2^(-600)$ times $A$, or `ValueError` where the computed value overflows `float64`")


def model_points(p: int):
    """Fixed points for the bit-for-bit check: both Horner branches, omega from 1e-300 to 1e3, unit gamma."""
    rng = np.random.default_rng(1300 + p)
    points = []
    for d in (0.5, 1e-2, 50.0, 0.37):
        for scale in (1e-300, 1e-3, 1.0, 20.0, 1e3):
            for _ in range(4):
                w1, w2 = (float(v) * scale for v in rng.uniform(-1, 1, 2))
                g = rng.normal(size=3)
                points.append((d, w1, w2, g / np.linalg.norm(g)))
        points.append((d, 1.5, 0.0, np.array([0.0, 0.0, 1.0])))
        points.append((d, 0.0, -2.5, np.array([0.6, -0.8, 0.0])))
    return points


def certificate(log, module, p: int):
    """Prove the bound for p, check that the public function gives the analysed sequence's bits, record it."""
    from derivations.core.certificates import Certificate, Outcome, stopwatch
    from derivations.proofs.float_proofs import METHOD, method

    with stopwatch() as elapsed:
        try:
            proof = prove_first_integral(p)
            ok = proof.bound <= stated(p)
            detail = (f"{proof.statement}, ${proof.bound_u} u = {proof.bound:.3g}$, at most ${stated(p):g}$" if ok
                      else f"proven only: {proof.statement}, ${proof.bound:.3g}$, above ${stated(p):g}$")
            points = model_points(p)
            differing = 0
            with np.errstate(under="ignore"):
                for d, w1, w2, g in points:
                    try:
                        public = float(module.first_integral(p, d, w1, w2, *g))
                    except ValueError:
                        public = math.inf
                    if public != replica(module, p, d, w1, w2, g):
                        differing += 1
            detail += (f"; the public function gives the analysed sequence's bits at {len(points)} points" if not differing
                       else f"; the public function differs from the analysed sequence at {differing} points")
            ok = ok and not differing
            # one box: the magnitude form's w does not depend on the values
            method_text, boxes = method(proof).replace("over 1 boxes", "over 1 box"), proof.boxes
        except BoundFailure as failure:
            ok, detail, boxes, method_text = False, f"no bound: {failure}", 0, METHOD.format(n="?")
    return log.record(Certificate(CLAIM.format(p=p), "round trip", method_text, Outcome.PASS if ok else Outcome.FAIL,
                                  elapsed[0], boxes, detail))
