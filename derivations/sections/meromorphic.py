"""Meromorphic solutions for odd p: F1, F2, F3 and the orthonormal basis (sections 5.1, 6.1).

Labels: ``pol_sol``, ``F_23_splitted``, ``abc``, ``poly_F``, ``poly_F2``,
``F_23_pol``, ``gam1``, ``gam2``, ``gam3`` (Theorem 6.1), ``eq:gam3``,
``asymp``, and the printed examples for p = 1 and p = 3 (section 6.2).

Representation
--------------
With ``x = e^t`` every solution is ``e^{i r t} N(x) / (1 + x^2)^p`` with a
polynomial numerator ``N`` of degree <= 2p (r = 0 or r = p/d).  Components are
kept in the *c-free* scaling ``(g1, c g2, c g3)``, ``c = sqrt(d^2+1)``, in which
the Poisson equations with ``omega = ((p/d) tanh t, -(p/d) c sech t)`` have
rational coefficients:

    g1' = a S g3~,  g2~' = w1 g3~,  g3~' = -a (d^2+1) S g1 - w1 g2~,   a = p/d.

Construction (per odd p, exact in ``Q[x, d, i]/(i^2+1)`` with python-flint):

* gamma^(1): ``g1 = tanh t F1(sech^2 t)``, i.e. numerator
  ``N1 = (x^2 - 1) sum_j c_j 4^j x^{2j} (1+x^2)^{p-1-2j}`` with the derived
  coefficients of ``derivations.sections.first_integrals`` (denominators cleared).
* the complex solution: ``g1 = e^{+i (p/d) t} x P(x^2)/(1+x^2)^p``, ``P = F Fhat``
  with ``F = 2F1(a+, b; c+; -y)``, ``a+ = (2-p)/2 + ip/(2d)``, ``b = (1-p)/2``,
  ``c+ = 3/2 + ip/(2d)`` and ``Fhat = [d(p-1)y - d - ip] F - 2d y(y+1) F'``
  (``abc``, ``poly_F``, ``F_23_splitted``).  The parameters with ``+ip`` go with
  ``e^{+i(p/d)t}``: the printed ``gam2`` pairs them with ``e^{-i(p/d)t}``, which
  is not a solution (certified below).
* the other components from ``eq:gam3`` in exact form: ``g3~ = D g1 (1+x^2)/(2 a x)``
  and ``g2~ = (c w2 g1 - D g3~)/w1`` (``D = d/dt = x d/dx``); the divisions by
  ``x`` and by ``x^2 - 1`` (which vanishes at t = 0, the removable singularity of
  the printed ``eq:gam3``) are exact polynomial divisions, certified.

Certificates per odd p: Poisson equations (exact numerator identities), unit
norm of gamma^(1), ``V.V = 0`` and ``V.conj(V) = 2|k|^2`` for the complex
solution normalised by ``k = lim_{t->-oo} V2``, orthogonality, the limits
(``asymp``), the orientation, and F1 solving ``eq:genhip``.  Orthonormality is certified for
p <= KEEP_BASES by expanding the four products (exact zero tests) and beyond by conservation: the
c-free Poisson matrix is real and skew for ``M = diag(d^2+1, 1, 1)`` (certified once), so the
M-product of two certified solutions is constant in t; for ``|gamma^(1)|^2`` and ``V.conj(V)`` the
constant is the exact value at x = 0, and ``V.V``, ``gamma^(1).V`` carry ``e^(2iat)``, ``e^(iat)``
(a = p/d != 0), which has no limit as t -> -oo, so their constants are 0.  Measured: 7.4 s -> 0.03 s
for this certificate at p = 51, where the expanded products were 95% of the per-p cost.  The real basis is
``gamma^(2) + i sigma gamma^(3) = Gamma`` with ``sigma`` chosen so that the matrix
of rows gamma^(1), gamma^(2), gamma^(3) has determinant +1.

Where each odd p is certified
-----------------------------
* p <= KEEP_BASES (15): here, in the main process (:func:`certify_p`: :func:`construct`, then
  :func:`certify_numerators`); these Basis objects feed the printed comparisons (p = 1, 3; section 6.2) and the
  written-out formulas, and the round trip compares the emitted core with them, polynomial by polynomial.
* p > KEEP_BASES: here only ``pol_sol`` (:func:`genhip_check`, in workers) and, once for every p,
  ``sigma = -1`` (:func:`sigma_certificate`, label ``asymp``: the recipe's own ``complete`` run with p and d
  symbolic on ``g1 = x P(x^2)`` gives ``V3(0) = -i V2(0)``, an exact zero test); the module is emitted with
  that sigma, and the bases are left pending (``exports["pending"]``).  The round trip
  (:func:`derivations.output.roundtrip.per_p_checks`) then certifies the numerators the *emitted* module
  computes (``_basis_core(p, BASIS_RING)``) with the same :func:`certify_numerators`: eq:gam3, F_23_pol,
  eq:ps, gam1-gam3 (by conservation) and asymp, which also requires the numerators' sigma to be the emitted
  one; the certificates are recorded as this derivation's and the rows of the basis table
  (``templates/basis_tables.tex.j2``) are completed from them (:func:`complete_row`) before the documents are
  rendered.  What the module computes is what is certified, and each basis is built once: before, a worker
  built and certified it here and sent its :func:`numerators_digest`, and the round trip built it again
  and compared digests.  A build that emits no module (``--only`` without the module's derivations, or
  without an output) certifies the pending bases from the recipe instead (:func:`certify_pending`).

Cost at large p (one core, p = 201, ``bench/bench_basis_construct.py``): the construction (the recipe on
``BASIS_RING``, whose ``mul_red`` forms ``F * Fhat`` by one Kronecker-packed univariate product: see
``suslov/recipes/flint_rings.py``) 4.6 s -> 3.0 s, the third-order and Poisson zero tests in coordinates
(:func:`poisson_hold`, ``meromorphic_ring.third_order_holds``) 3.5 s -> 2.2 s, the orthonormality
certificate (products of the values at x = 0 by ``mul_red``) 0.6 s -> 0.1 s, :func:`numerators_digest`
(the same bytes) 1.2 s -> 1.0 s.  Certifying the emitted core in the round trip instead of a second
construction saves, per p, one construction and both digests (the build's times: ``docs/benchmarks.md``).
Since then the recipe's exact routes (``suslov/recipes/basis.py``: the construction 3.27 s -> 2.68 s at p = 201),
the complex solution's first numerator split into its i-coordinates once for the third-order and Poisson tests
(it was split three times: 35 ms each at p = 201), and the limits at t -> +oo read from the leading terms only
(:func:`_coefficient_x`): at p = 201 the third-order test 0.85 s -> 0.71 s, orthonormality and limits 0.16 s ->
0.10 s, the round trip's whole ``per_p_checks`` 8.35 s -> 7.67 s (shared 2-core AMD EPYC, medians of 4 fresh
processes per route; ``bench/results/basis_roundtrip.md``).
"""
from __future__ import annotations

import hashlib
from array import array
from itertools import chain, repeat
from operator import attrgetter

import sympy as sp
from flint import fmpz

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    CertificationFailure,
    Outcome,
    stopwatch,
)
from derivations.core.differential import t
from derivations.core.exact import Domain, certify_zero
from derivations.core.result import DerivationResult
from derivations.core.statement import Statement, ring
from derivations.core.symbols import d
from derivations.sections.meromorphic_printed import (
    coefficient_tables,
    compare_poly_f2,
    printed_comparisons,
    written_out,
)
from derivations.sections.meromorphic_ring import (  # noqa: F401  (re-exported: the ring helpers the tests and roundtrip use)
    CTX,
    DD,
    DOMAIN,
    I2,
    ONE,
    RING,
    ZCTX,
    ZD,
    ZV,
    Basis,
    D,
    DD_split,
    I,
    X,
    at_x,
    conj,
    gamma1_numerator,
    hypergeometric_polynomials,
    in_y_squared,
    red,
    split_i,
    third_order_holds,
    third_order_residual,
)
from derivations.sections.meromorphic_sigma import (  # noqa: F401 (sigma_values: tests)
    SIGMA,
    sigma_certificate,
    sigma_values,
)
from derivations.sections.printed_examples import compare_printed_examples
from suslov.recipes import basis as recipe
from suslov.recipes.basis import Solution
from suslov.recipes.integrals import e_coefficient

NAME = "meromorphic"
TITLE = "Meromorphic solutions for odd $p$ and the orthonormal basis (sections 5.1, 6.1)"
REQUIRES = ("hypergeometric",)

def poisson_residuals(sol: Solution) -> list:
    """The c-free Poisson equations, numerators times d (zero iff solved)."""
    M1, M2, M3 = sol.M
    p, r = sol.p, sol.rate
    return [red(DD(M1, p, r) - 2 * p * X * M3),
            red(DD(M2, p, r) - p * (X**2 - 1) * M3),
            red(DD(M3, p, r) + 2 * p * (D**2 + 1) * X * M1 + p * (X**2 - 1) * M2)]


def poisson_hold(sol: Solution, first: tuple | None = None, parts: tuple | None = None) -> bool:
    """``all(r.is_zero() for r in poisson_residuals(sol))``, in coordinates (``derivations.sections.meromorphic_ring``):
    each equation ``A = B`` tested as the equality of the two sides' real and imaginary coordinates.
    ``first``: ``DD_split(split_i(M1), p, rate)`` when the caller has it already, ``parts`` likewise ``split_i(M1)``."""
    p, r = sol.p, sol.rate
    M1, M2, M3 = (split_i(m) if n or parts is None else parts for n, m in enumerate(sol.M))
    D1 = DD_split(M1, p, r) if first is None else first
    if not all(a == 2 * p * X * b for a, b in zip(D1, M3)):
        return False
    if not all(a == p * (X**2 - 1) * b for a, b in zip(DD_split(M2, p, r), M3)):
        return False
    return all(a + 2 * p * (D**2 + 1) * X * b == -p * (X**2 - 1) * c for a, b, c in zip(DD_split(M3, p, r), M1, M2))


def metric_dot(A: list, B: list):
    """(d^2+1) A1 B1 + A2 B2 + A3 B3 (the Euclidean product of (A1, A2/c, A3/c) times c^2), reduced modulo i^2 + 1.

    Each product by the ring's ``mul_red`` (packed into univariate products when large; red is linear and
    d^2 + 1 is free of i, so this is the same polynomial as ``red`` of the whole sum)."""
    return (D**2 + 1) * RING.mul_red(A[0], B[0]) + RING.mul_red(A[1], B[1]) + RING.mul_red(A[2], B[2])


def conservation_certificate(log: CertificateLog) -> Certificate:
    """The c-free Poisson system ``G' = A(t) G`` of :func:`poisson_residuals` is skew for the metric of
    :func:`metric_dot`: ``A^T M + M A = 0`` with ``M = diag(d^2+1, 1, 1)``, and A is real.

    So for two solutions ``d/dt (G_a^T M G_b) = G_a^T (A^T M + M A) G_b = 0``: every metric product
    of two solutions is constant in t, and the complex conjugate of a solution is a solution.
    """
    a, S, w1 = sp.symbols("a S w1", real=True)
    dd = sp.Symbol("d", positive=True)
    A = sp.Matrix([[0, 0, a * S], [0, 0, w1], [-a * (dd**2 + 1) * S, -w1, 0]])
    G = sp.diag(dd**2 + 1, 1, 1)
    return certify_zero(log, "the $c$-free Poisson matrix $A(t)$ ($deriv(g1, t) = a S g3$, $deriv(g2, t) = w1 g3$, $deriv(g3, t) = -a (d^2+1) S g1 - w1 g2$) "
                        "is real and skew for $M = diag(d^2+1, 1, 1)$: $A^T M + M A = 0$, so $M$-products of two "
                        "solutions are constant in $t$", "eq:ps", list(A.T * G + G * A), Domain("Q(a,d,S,w1)"))


def construct(p: int) -> tuple[Solution, Solution]:
    """The shared recipe ``suslov.recipes.basis.construct`` in Q[x, d, i]/(i^2+1)."""
    return recipe.construct(p, RING)


def certify_p(log: CertificateLog, p: int, direct: bool | None = None) -> Basis:
    """The certificates of one odd p's basis, constructed here (:func:`construct`, the shared recipe): see
    :func:`certify_numerators`; the construction's time is counted in the first certificate's, as before."""
    with stopwatch() as elapsed:
        real, cplx = construct(p)
    return certify_numerators(log, p, real, cplx, direct, seconds=elapsed[0])


def certify_numerators(log: CertificateLog, p: int, real: Solution, cplx: Solution, direct: bool | None = None,
                       sigma: int | None = None, seconds: float = 0.0, origin: str = "") -> Basis:
    """The certificates of one odd p's basis on the numerators ``real``, ``cplx`` (see the module docstring):
    exact division (eq:gam3), the third-order equation (F_23_pol), the Poisson equations (eq:ps),
    orthonormality (gam1, gam2, gam3) and the limits (asymp), in this order.

    The numerators are those of :func:`construct` (p <= KEEP_BASES, and builds that emit no module) or of the
    emitted module's ``_basis_core(p, BASIS_RING)`` (the round trip, :func:`derivations.output.roundtrip.per_p_checks`,
    for every p > KEEP_BASES: what the module computes is what is certified).  Orthonormality is certified
    ``direct``-ly (the four product identities expanded, exact zero tests; the default for p <= KEEP_BASES) or
    by conservation (the default beyond: the products of two solutions of a G-skew linear system are constant
    in t, see :func:`conservation_certificate`; 50 times cheaper at p = 51, where the expanded products
    dominate the whole per-p cost).  ``sigma``: the value the build derived and emitted before these
    numerators were certified (:func:`sigma_certificate`); asymp then also requires the numerators' sigma to
    be that one (None: either sign).  ``seconds``: the construction's time, counted in the first certificate;
    ``origin``: where the numerators come from, said in the first certificate's detail and in any failure's.
    """
    direct = p <= KEEP_BASES if direct is None else direct
    certs = []

    def detail(ok: bool, text: str = "") -> str:
        # the origin of the numerators on a failure (the first certificate says it always)
        if ok or not origin:
            return text
        return f"{text}; on {origin}" if text else origin

    with stopwatch() as elapsed:
        ok_div = bool(getattr(real, "divisions_exact", False) and getattr(cplx, "divisions_exact", False))
    certs.append(log.record(Certificate(
        f"$p = {p}$: the components from eq:gam3 are polynomials over $(1+x^2)^p$: exact division by $x$ and $x^2-1$ "
        "(no removable singularity at $t = 0$)", "eq:gam3", Statement("exact division in ", ring(DOMAIN)),
        Outcome.PASS if ok_div else Outcome.FAIL, seconds + elapsed[0], sum(len(m) for m in real.M + cplx.M),
        origin if ok_div else detail(False))))
    with stopwatch() as elapsed:
        # in coordinates (meromorphic_ring); the residual itself only to report its size when it is not zero
        parts = split_i(cplx.M[0])   # split once for both tests (80k terms at p = 201)
        first = DD_split(parts, p, 1)
        ok = third_order_holds(cplx.M[0], p, 1, first, parts)
        size = 0 if ok else len(third_order_residual(cplx.M[0], p, 1))
    certs.append(log.record(Certificate(
        f"$p = {p}$: $g1 = e^(i (p/d) t) x P_p(x^2)/(1+x^2)^p = sqrt(z-1) F2(z)$ (F_23_pol) solves eq:genhipprep; with the "
        "certified reduction to eq:genhip, $F2$ and its conjugate $F3$ solve eq:genhip", "F_23_pol",
        Statement("exact zero test in ", ring(DOMAIN)), Outcome.PASS if ok else Outcome.FAIL, elapsed[0], size,
        detail(ok))))
    with stopwatch() as elapsed:
        ok = poisson_hold(real) and poisson_hold(cplx, first, parts)   # first = DD(M1) of the complex solution
        size = 0 if ok else sum(len(r) for r in poisson_residuals(real) + poisson_residuals(cplx))
    certs.append(c_poisson := log.record(Certificate(
        f"$p = {p}$: $gammaI$ and the complex solution $e^(i(p/d)t) V$ solve the Poisson equations eq:ps with $omega$ "
        "from omegas", "eq:ps", Statement("exact zero test in ", ring(DOMAIN)), Outcome.PASS if ok else Outcome.FAIL, elapsed[0],
        size, detail(ok, "6 numerator identities"))))

    with stopwatch() as elapsed:
        K = 2 * p * p  # M = (2p^2 N1, M2, p M3), N1 over Den1
        Den1 = ONE
        for m in range((p - 1) // 2):
            Den1 *= (2 * m + 1) ** 2 * D**2 + p * p
        scale_real = K * Den1
        k = at_x(cplx.M[1], 0)
        V = cplx.M
        unit_target = 2 * RING.mul_red(k, conj(k))
        if direct:
            Vbar = [conj(v) for v in V]
            norm = metric_dot(real.M, real.M) - (D**2 + 1) * (scale_real * (1 + X**2) ** p) ** 2
            isotropic = metric_dot(V, V)
            unit = metric_dot(V, Vbar) - unit_target * (1 + X**2) ** (2 * p)
            orthogonal = metric_dot(real.M, V)
            ok = norm.is_zero() and isotropic.is_zero() and unit.is_zero() and orthogonal.is_zero()
            size = len(norm) + len(isotropic) + len(unit) + len(orthogonal)
        else:
            # conserved products (see conservation_certificate): the rate-0 constants are the values at
            # x = 0; V.V and gamma^(1).V carry e^(2iat), e^(iat) and vanish without any evaluation
            real0, V0 = ([at_x(c, 0) for c in vector] for vector in (real.M, V))
            Vbar0 = [conj(v) for v in V0]
            ok = (c_poisson.outcome is Outcome.PASS
                  and (metric_dot(real0, real0) - (D**2 + 1) * scale_real**2).is_zero()
                  and (metric_dot(V0, Vbar0) - unit_target).is_zero())
            size = 2
    method = (Statement("exact zero test in ", ring(DOMAIN)) if direct else
              "conservation: the certified Poisson solutions (this $p$) have constant $G$-products ($G$-skew system, "
              "certified once); rate-0 constants from exact values at $x = 0$, products carrying $e^(i k a t)$ with $k$ "
              "non-zero are zero (a non-zero constant would make $e^(i k a t)$ converge as $t$ tends to $-oo$)")
    certs.append(log.record(Certificate(
        f"$p = {p}$: $abs(gammaI) = 1$, $inner(V, V) = 0$, $abs(V)^2 = 2 abs(k)^2$, $inner(gammaI, V) = 0$: $gammaI$, Re and Im of $V/k$ orthonormal",
        "gam1, gam2, gam3", method, Outcome.PASS if ok else Outcome.FAIL, elapsed[0], size,
        detail(ok, "4 identities"))))

    with stopwatch() as elapsed:
        v3 = at_x(cplx.M[2], 0)
        found = 1 if red(v3 - I * k).is_zero() else (-1 if red(v3 + I * k).is_zero() else 0)
        lim_minus = [at_x(m, 0) for m in real.M]
        top = 2 * p
        lim_plus = [_coefficient_x(m, top) for m in real.M]
        ok = (found != 0 and not k.is_zero() and (lim_minus[0] + scale_real).is_zero() and lim_minus[1].is_zero()
              and lim_minus[2].is_zero() and (lim_plus[0] - scale_real).is_zero() and lim_plus[1].is_zero()
              and lim_plus[2].is_zero() and at_x(cplx.M[0], 0).is_zero())
        ok_sigma = sigma is None or found == sigma
    certs.append(log.record(Certificate(
        f"$p = {p}$: $gammaI$ tends to $(-1,0,0)$ as $t$ tends to $-oo$ and to $(1,0,0)$ as $t$ tends to $oo$; $V/k$ tends to "
        f"$(0, 1, {'' if found > 0 else '-'}i)$ as $t$ tends to $-oo$", "asymp", Statement("exact evaluation in ", ring(DOMAIN)),
        Outcome.PASS if ok and ok_sigma else Outcome.FAIL, elapsed[0], 0,
        detail(ok and ok_sigma, "" if ok_sigma else f"$sigma = {found}$ from the numerators, ${sigma}$ derived and emitted"))))
    return Basis(p, real, cplx, k, scale_real, found, certs)


def _coefficient_x(poly, degree: int):
    """Coefficient of x^degree as a polynomial in (d, i).

    The terms are stored in lex order, x first and descending: those with x^degree follow those with a higher power
    and precede every lower one, so the scan stops there (at p = 201 the limits read 100 terms of each numerator,
    not 20,000)."""
    total = CTX.constant(0)
    for n in range(len(poly)):
        monomial = poly.monomial(n)
        if monomial[0] < degree:
            break
        if monomial[0] == degree:
            total += poly.coefficient(n) * D ** monomial[1] * I ** monomial[2]
    return total


def genhip_check(log: CertificateLog, p: int) -> Certificate:
    """F1(z) = sum c_j z^j solves eq:genhip (fraction-free, times 8 d^2)."""
    with stopwatch() as elapsed:
        J = (p - 1) // 2
        u = ZCTX.constant(0)
        for j in range(J + 1):
            tail = ZCTX.constant(1)
            for m in range(j, J):
                tail *= (2 * m + 1) ** 2 * ZD**2 + p * p
            u += e_coefficient(j, p) * ZD ** (2 * j) * tail * ZV**j
        d1 = u.derivative("z")
        d2 = d1.derivative("z")
        d3 = d2.derivative("z")
        lhs = (8 * ZD**2 * ZV**2 * (1 - ZV) * d3 + 4 * ZD**2 * (4 - 9 * ZV) * ZV * d2
               + (2 * (ZD**2 + p * p) + 2 * ZD**2 * (p * p - 13) * ZV) * d1 + ZD**2 * (p * p - 1) * u)
    return log.record(Certificate(
        f"$p = {p}$: the terminating series $F1(z)$ (pol_sol, derived coefficients) solves eq:genhip",
        "pol_sol", "exact zero test in $Z[z,d]$ (`python-flint`; times $8 d^2$ and the coefficients' common denominator)",
        Outcome.PASS if lhs.is_zero() else Outcome.FAIL, elapsed[0], len(u)))


# the conditions of the written-out bases (printed with them, and in the formula catalog)
HYPOTHESES = (r"$I_{13}=0$, with $p$, $d$ of section 4: $I_{11}=I_{22}(d^2+1)$, $I_{23}=-I_{22}d/p$",
              r"$d>0$, $c=\sqrt{d^2+1}$",
              r"$\omega=\big(\tfrac pd\tanh t,\,-\tfrac pd\,c\operatorname{sech}t\big)$",
              r"$t$ real")


def basis_expr(written: list, p: int) -> sp.Tuple:
    """The written-out basis (:func:`written_out`'s rows, the expressions the document prints) as SymPy for the
    formula catalog: ``Eq(gammakj, ...)`` for the component j of gamma^(k), in t and d (the project's symbols),
    ``c = sqrt(d^2+1)`` substituted and ``gamma^(2) + i gamma^(3) = e^(i p t/d) (R + i Q)`` written out."""
    plain = {sp.Symbol("c"): sp.sqrt(d**2 + 1), sp.Symbol("d"): d, sp.Symbol("t"): t}
    values = {lhs: value.xreplace(plain) for lhs, value in (row for row in written if isinstance(row, tuple))}
    first = [values[rf"\gamma^{{(1)}}_{{{k}}}"] for k in (1, 2, 3)]
    R, Q = ([values[f"{name}_{{{k}}}"] for k in (1, 2, 3)] for name in ("R", "Q"))
    phase = p * t / d
    second = [sp.cos(phase) * a - sp.sin(phase) * b for a, b in zip(R, Q)]
    third = [sp.sin(phase) * a + sp.cos(phase) * b for a, b in zip(R, Q)]
    return sp.Tuple(*[sp.Eq(sp.Symbol(f"gamma{k}{j}"), value, evaluate=False)
                      for k, vector in enumerate((first, second, third), 1) for j, value in enumerate(vector, 1)])


KEEP_BASES = 15   # bases up to this p are built in the main process and kept (printed examples, tables); beyond,
#                   the round trip certifies the emitted core's (or certify_pending the recipe's, without a module)
DIGEST_CHUNK = 2048   # coefficients per hashed piece of text (256 to 16384 measured within 10% of each other)
_NUMERATOR, _DENOMINATOR = attrgetter("p"), attrgetter("q")


def numerators_digest(real_M: list, complex_M: list) -> str:
    """SHA-256 of the six numerators' terms: the fingerprint by which a worker process running the round trip's
    float-path check of a kept basis (p <= KEEP_BASES, certified in the main process) takes the emitted core's
    numerators as the certified ones (``roundtrip.float_check``; shipping the polynomials is what it avoids: at
    p = 101 they print as 31 MB in decimal).  The bases beyond KEEP_BASES need no fingerprint: the round trip
    certifies the emitted core's numerators themselves (see the module docstring).

    Per numerator: its number of terms and its exponent vectors as 64-bit integers in python-flint's term
    order (the count first, so the fixed-width exponents cannot run into the printed text), then its
    coefficients as python-flint prints them in base 16 (``fmpz.str(16)``, numerator and denominator).
    Base 16, not decimal: flint prints a binary integer in base 16 in linear time, and the decimal
    conversion of the 2500-bit coefficients at p = 201 was two thirds of the fingerprint's 2.3 s.  Term
    by term, not ``str(poly)``: python-flint 0.9's printing of a whole mpoly does not free its buffer
    (measured: 32 MB kept per call at p = 101, 250 MB per p near 200 in a worker).

    The same bytes, produced faster: the numerators printed through ``map`` (no Python-level loop) and
    hashed in chunks of :data:`DIGEST_CHUNK` (joined with the same commas; the text of a chunk is still in
    the cache when it is encoded and hashed, where one 65 MB string per numerator went through memory
    three times), and the denominators, all 1 for the basis numerators, written as ``1,1,...,1`` once
    that is checked (``list.count`` in C) instead of printed one by one.  Measured at p = 201: 1.2-1.35 s
    -> 0.9-1.05 s (``bench/results/basis_construct.md``; what is left is the text itself: 223 MB of hex
    printed, encoded and hashed)."""
    digest = hashlib.sha256()
    for poly in list(real_M) + list(complex_M):
        digest.update(array("q", [len(poly), *chain.from_iterable(poly.monoms())]).tobytes())
        coefficients = poly.coeffs()
        numerators = list(map(_NUMERATOR, coefficients))
        for start in range(0, len(numerators), DIGEST_CHUNK):
            if start:
                digest.update(b",")
            digest.update(",".join(map(fmpz.str, numerators[start:start + DIGEST_CHUNK], repeat(16))).encode())
        digest.update(b"/")
        denominators = list(map(_DENOMINATOR, coefficients))
        if denominators.count(1) == len(denominators):
            digest.update(b",".join([b"1"] * len(denominators)))
        else:
            digest.update(",".join(map(fmpz.str, denominators, repeat(16))).encode())
        digest.update(b";")
    return digest.hexdigest()


def basis_for_p(p: int, sigma: int | None = SIGMA) -> dict:
    """The basis of one odd p constructed and certified in a worker (:func:`certify_p`, with the derived
    ``sigma``): the route of a build that emits no module (``--only`` without the module's derivations, or
    without an output), where no round trip certifies the emitted core (:func:`certify_pending`).

    Returns plain data (python-flint objects do not pickle): the certificates (keys left to the main log,
    which records them in p order) and the numerators' term counts.  A certificate with an unexpected outcome
    is returned too, not raised: the main log raises when it records it, exactly as a serial build would.
    """
    private = CertificateLog(derivation=NAME)
    terms = []
    try:
        with stopwatch() as elapsed:
            real, cplx = construct(p)
        certify_numerators(private, p, real, cplx, sigma=sigma, seconds=elapsed[0])
        terms = [len(m) for m in real.M + cplx.M]
    except CertificationFailure:
        pass
    return {"certificates": private.handed_over(), "terms": terms}


def genhip_for_p(p: int) -> list:
    """:func:`genhip_check` of one odd p in a worker: its certificate, key left to the main log."""
    private = CertificateLog(derivation=NAME)
    try:
        genhip_check(private, p)
    except CertificationFailure:
        pass
    return private.handed_over()


def complete_row(result: DerivationResult, p: int, keys: list, terms: list) -> None:
    """The row of a p > KEEP_BASES (``result.exports["rows"]``: its genhip certificate so far) completed with the
    keys of its basis certificates, once recorded (by the round trip on the emitted core, or :func:`certify_pending`),
    and the numerators' term counts; p is no longer pending."""
    row = next(r for r in result.exports["rows"] if r["p"] == p)
    row["certificates"] = row["certificates"] + list(keys)
    row["terms"] = list(terms)
    result.exports["pending"] = [q for q in result.exports["pending"] if q != p]


def certify_pending(log: CertificateLog, result: DerivationResult) -> list:
    """The bases still pending (p > KEEP_BASES; ``result.exports["pending"]``) constructed and certified from the
    recipe in workers (:func:`basis_for_p`), recorded in p order as this derivation's, their rows completed: for a
    build that runs no round trip.  A build that emits the module leaves them to the round trip, which certifies
    the emitted core's numerators instead (:func:`derivations.output.roundtrip.certify_module`)."""
    pending = list(result.exports.get("pending", ()))
    certs = []
    with log.section(NAME):
        for p, outcome in zip(pending, log.map_per_p("bases", pending, basis_for_p)):
            recorded = [log.record(c) for c in outcome["certificates"]]   # raises at a failed one
            certs += recorded
            complete_row(result, p, [c.key for c in recorded], outcome["terms"])
    return certs


def run(log: CertificateLog, options, hyper_result) -> DerivationResult:
    result = DerivationResult(NAME)
    rows = []
    bases, objects = {}, {}
    odd = options.odd_p_values()

    def kept_bases():
        # p <= KEEP_BASES in this process (their Basis objects feed the printed comparisons), while the
        # workers check genhip for the rest; recorded before them, in p order, so the log is the same either way
        compare_poly_f2(log, result, options)
        conservation_certificate(log)
        for p in log.per_p("bases", [q for q in odd if q <= KEEP_BASES]):
            c_f1 = genhip_check(log, p)
            basis = bases[p] = certify_p(log, p)
            objects[p] = (basis.real.M, basis.complex_.M)
            rows.append({"p": p, "sigma": basis.sigma,
                         "certificates": [c_f1.key] + [c.key for c in basis.certificates],
                         "terms": [len(m) for m in basis.real.M + basis.complex_.M]})

    later = [q for q in odd if q > KEEP_BASES]

    def kept_then_sigma():
        kept_bases()
        if later:   # the sigma the module is emitted with, for every p beyond the kept ones (the round trip confirms it)
            sigma_certificate(log)

    # beyond KEEP_BASES only genhip here: the bases themselves are certified on the numerators the emitted module
    # computes, in the round trip (or by certify_pending when no module is emitted), which completes these rows
    for p, certs in zip(later, log.map_per_p("bases", later, genhip_for_p, meanwhile=kept_then_sigma)):
        keys = [log.record(c).key for c in certs]   # raises at a failed one, as in serial
        rows.append({"p": p, "sigma": SIGMA, "certificates": keys, "terms": []})
    if 3 in bases:
        printed_comparisons(log, result, bases[3].certificates[2])
    compare_printed_examples(log, result, bases)
    # the catalog gets the written-out bases of the formulas below; no per-p family (catalog_family): writing out
    # every kept basis (p <= 15) costs 2.1 s (measured; 0.8 s for p = 15 alone), over the catalog's budget
    for p, basis in sorted(bases.items()):
        if p > 3:
            continue
        written = written_out(basis)
        result.formula(f"basis{p}", "gam1, gam2, gam3, eq:gam3", f"Orthonormal basis for $p={p}$ ($c=\\sqrt{{d^2+1}}$)",
                       written,
                       *[c for c in log.certificates if c.key in rows[(p - 1) // 2]["certificates"]],
                       expr=basis_expr(written, p), hypotheses=[*HYPOTHESES, f"$p={p}$"])
    result.exports.update(objects=objects, pending=list(later), bases=bases, rows=rows, sigma={r["p"]: r["sigma"] for r in rows}, tables=coefficient_tables(options))
    return result
