"""Differential Galois analysis and the logarithm conjecture (paper section 5.2).

Labels: ``eq:ui``, ``eq:gi``, ``eq:rig``, ``eq:ABC``, ``eq:r2``, ``eq:lin``,
``eq:2rzedu``, ``eq:rlin`` (P = sum p_i z^i), ``eq:Q``, ``eq:Deltai``, the
Conjecture of section 5.2 and Proposition 5.8.

Method
------
1. *Riccati form.*  On the sphere |gamma| = 1 (extension ``g3^2 = 1 - g1^2 - g2^2``)
   ``u1 = (g3 + 1)/(g1 - i g2)`` solves ``u' = A + B u + C u^2`` with the printed
   A, B, C (omega3 = 0, so B = 0); certified exactly.  ``u = -w'/(C w)`` turns it
   into ``w'' - B1 w' - A1 w = 0`` with ``A1 = -A C``, ``B1 = B + C'/C`` (a jet
   identity).
2. *In z = e^t* (the section's z, not sech^2 t): ``w'' + p(z) w' + q(z) w = 0`` with
   ``p = (1 - B1)/z``, ``q = -A1/z^2``, derived from ``omegas`` and compared
   with the printed p(z), q(z); then ``r = p'/2 + p^2/4 - q = P/Q`` (eq:rlin),
   compared with the printed ``p_0 ... p_8`` and ``Q``.
3. *Singular points and exponent differences*: ``Q`` vanishes at s0 = 0,
   s1,2 = +-i, s3,4 = -i(c +- d); at a double pole ``r ~ rho0/(z-s)^2`` the
   exponent difference satisfies ``Delta^2 = 1 + 4 rho0`` (also at infinity).
4. *Logarithms.*  With the rational parametrisation ``c = (m^2+1)/(2m)``,
   ``d = (m^2-1)/(2m)`` (m > 1 covers every d > 0) all singular points lie in
   ``Q(m)(i)``: s3 = -i m, s4 = -i/m.  In ``w = -i z`` the reduced form ``y_ww = -r(i w) y`` is
   real (certified) with s1..s4 at w = 1, -1, -m, -1/m.  At a singular point with integer
   ``Delta = n`` the Frobenius recursion from the smaller exponent ``(1-n)/2`` is obstructed at
   step n by ``sum_{j=1}^{n} r_j y_{n-j}`` (``r = sum r_j zeta^(j-2)``); zero means no logarithm.
   :mod:`derivations.sections.local_obstruction` computes it exactly in Q(m) (python-flint ``fmpq_poly``,
   denominators cleared by the least E with $den(r_j)$ divides $E^j$, here m^2 - 1) for s1 and s3 and the
   p of the build's range ``galois_pmax = max(40, pmax)`` that :func:`derivations.core.options.cross_check_p_values`
   selects: every p <= ``cross_check_pmax`` (101 by default, ``--cross-check-pmax``), above it p = 150, 151,
   200, 201, ... (0 or 1 mod 50) and the largest even and the largest odd p <= galois_pmax.  That is sound
   because the table is a cross-check: :mod:`derivations.sections.pole_theorem` proves the conjecture for every
   p and every d > 0 (s1, s2 logarithmic exactly for even p, s3, s4 never); the sample keeps both parities at
   the top of the range, and the title, the hypotheses and the note name the p that ran.  s2 follows from s1
   by the certified symmetry (w, m) -> (-w, -m), s4 from s3 by m -> 1/m.  Choice measured: the earlier
   fraction-free recursion in Q(i)[m] with powers of the leading coefficient (m-degree 28p - 1) took about
   80 s at p = 101 and p^3.7 growth; this one takes about 2 s there.
5. *Proposition 5.8*: for even p, every choice of local exponents compatible
   with the logarithmic points gives ``deg R = -sum rho_i < 0``: enumerated.
"""
from __future__ import annotations

import functools
import itertools
from fractions import Fraction

import flint
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
from derivations.core.exact import Domain, Extension, cancelled, certify_zero
from derivations.core.options import checked_words, dense_prefix
from derivations.core.result import DerivationResult
from derivations.core.differential import t
from derivations.core.symbols import d as d_symbol
from derivations.core.symbols import g1, g2, g3, p, w1, w2
from derivations.core.typeset import latex
from derivations.sections.local_obstruction import log_obstruction

NAME = "galois"
TITLE = "Differential Galois analysis and logarithms at the singular points (section 5.2)"
REQUIRES = ("special_case",)
# The conjecture is decided for p <= max(pmax, GALOIS_PMAX) (every p up to the build's cross_check_pmax, a sample
# above it: derivations.core.options.cross_check_p_values); the whole range p <= 40 costs about a second.
GALOIS_PMAX = 40

z = sp.Symbol("z")
cc = sp.Symbol("c", positive=True)
m = sp.Symbol("m", positive=True)
SPHERE = Extension(g3, 1 - g1**2 - g2**2, "|gamma| = 1")
SPHERE_DOMAIN = Domain("Q(omega)(gamma1,gamma2)[gamma3,i]/(gamma1^2 + gamma2^2 + gamma3^2 - 1, i^2+1)", (SPHERE,))
ZC = Domain("Q(c,p)(z)[i]")


def riccati_coefficients():
    A = (w2 - sp.I * w1) / 2
    C = (w2 + sp.I * w1) / 2
    return A, sp.Integer(0), C


@functools.cache   # run and reduced_form both ask: the Polys are built once
def derived_pqr():
    """p(z), q(z) of eq:2rzedu (expressions) and the numerator N of r = N/Q (a polynomial).

    From omegas with t = log z: w1 = a (z^2-1)/(z^2+1), w2 = -2 a c z/(z^2+1), a^2 = p^2/(c^2-1).
    C = a L/(2(z^2+1)) with L = i(z^2-1) - 2 c z, so B1 = z C'/C = z L'/L - 2z^2/(z^2+1) and
    p = (1 - B1)/z = A_p/D_p with D_p = z (z^2+1) L; q = -A1/z^2 = (w1^2 + w2^2)/(4 z^2).
    With Q = 4 (c^2-1) D_p^2:  N = 2(c^2-1)(A_p' D_p - A_p D_p') + (c^2-1) A_p^2 - p^2 ((z^2-1)^2 + 4c^2z^2) L^2.
    """
    L = sp.I * (z**2 - 1) - 2 * cc * z
    dL = sp.diff(L, z)
    A_p = sp.expand((z**2 + 1) * L + 2 * z**2 * L - z * (z**2 + 1) * dL)
    D_p = sp.expand(z * (z**2 + 1) * L)
    pz = A_p / D_p
    qz = p**2 / (cc**2 - 1) * ((z**2 - 1) ** 2 + 4 * cc**2 * z**2) / (4 * z**2 * (z**2 + 1) ** 2)
    N = (2 * (cc**2 - 1) * (sp.diff(A_p, z) * D_p - A_p * sp.diff(D_p, z)) + (cc**2 - 1) * A_p**2
         - p**2 * ((z**2 - 1) ** 2 + 4 * cc**2 * z**2) * L**2)
    return pz, qz, sp.Poly(N, z, cc, p, domain=sp.QQ_I), sp.Poly(4 * (cc**2 - 1) * D_p**2, z, cc, p, domain=sp.QQ_I)


def printed_pq():
    pz = (z**2 * (z**2 + 4 * sp.I * cc * z - 4) - 1) / (z * (z**2 + 1) * (z**2 + 2 * sp.I * cc * z - 1))
    qz = p**2 / (4 * (cc**2 - 1)) / z**2 + p**2 / (z**2 + 1) ** 2
    return pz, qz


def printed_PQ():
    d2 = cc**2 - 1
    coeffs = {0: d2 + p**2, 8: d2 + p**2, 7: 4 * sp.I * cc * (2 * d2 + p**2), 2: -4 * (4 * d2 + p**2),
              6: -4 * (4 * d2 + p**2), 5: 4 * sp.I * cc * ((4 * p**2 - 2) * d2 + p**2),
              4: -2 * ((-8 * d2 + 8 * (d2 + 2) * p**2 + 1) * d2 + 5 * p**2)}
    coeffs[1] = coeffs[7].subs(sp.I, -sp.I)  # p_1^* = p_7
    coeffs[3] = coeffs[5].subs(sp.I, -sp.I)  # p_3^* = p_5
    P = sum(v * z**k for k, v in coeffs.items())
    Q = 4 * (cc**2 - 1) * z**2 * (z**2 + 1) ** 2 * (2 * cc * z - sp.I * (z**2 - 1)) ** 2
    return P, Q


def _homogeneous_value(poly: sp.Poly, u, v):
    """``v^D poly(u/v)`` (D = degree in z) for ``u``, ``v`` in the Poly's coefficient ring, by Horner's rule."""
    coefficients = list(poly.rep.to_list())      # high to low, elements of the coefficient ring
    value, power = coefficients[0], poly.domain.one
    for c in coefficients[1:]:
        power = power * v
        value = value * u + c * power
    return value


def leading_coefficient_at_double_pole(num: sp.Poly, den: sp.Poly, point):
    """``r_0 = lim (z - point)^2 num/den`` where ``point`` is a double root of ``den``: ``num(point) / c2`` with
    ``c2 = den''(point)/2``, an element of the coefficient ring's fraction field (raises if the root is not double).

    ``num``, ``den``: Polys in z over a polynomial ring (``QQ_I[m, p]``); ``point = u/v`` with u, v in that ring.
    Everything is evaluated in the ring, homogeneously (``v^D f(u/v)``), and divided once in the field: no gcd
    per step (the synthetic division in ``QQ_I(m, p)`` took 0.3 s of the cold build under cProfile, 0.04 s here).
    """
    ring = num.domain
    u, v = (ring.from_sympy(part) for part in sp.fraction(sp.sympify(point)))
    den1 = den.diff()
    c0, c1, c2 = (_homogeneous_value(f, u, v) for f in (den, den1, den1.diff()))
    if c0 or c1 or not c2:
        raise ArithmeticError(f"z = {point} is not a double root")
    field = ring.get_field()
    # num(point) = N / v^deg(num), c2 = C2 / (2 v^(deg(den) - 2))
    return (field.convert_from(2 * _homogeneous_value(num, u, v) * v ** (den.degree() - 2), ring)
            / field.convert_from(c2 * v ** num.degree(), ring))


POINTS = {"s0": sp.Integer(0), "s1": sp.I, "s2": -sp.I, "s3": -sp.I * m, "s4": -sp.I / m}


@functools.cache
def reduced_form():
    """``(num_e, den_e)``: r = num_e/den_e in the parametrisation c = (m^2+1)/(2m) (expressions in z, m, p)."""
    _, _, N, Qd = derived_pqr()
    c_m = (m**2 + 1) / (2 * m)
    return (sp.expand(N.as_expr().xreplace({cc: c_m}) * (2 * m) ** 10),
            sp.expand(Qd.as_expr().xreplace({cc: c_m}) * (2 * m) ** 10))


w = sp.Symbol("w")
# s2 follows from s1 by (w, m) -> (-w, -m) and s4 from s3 by m -> 1/m, both certified in run
POINTS_W = {"s1": sp.Integer(1), "s3": -m}


@functools.cache
def rotated_form():
    """``(num_w, den_w)``: ``-r(i w) = num_w/den_w``, polynomials in w, m, p with rational coefficients.

    ``z = i w`` turns ``y_zz = r(z) y`` into ``y_ww = -r(i w) y`` (logarithms are preserved: the local
    solutions correspond one to one), and the reduced form becomes real: no Gaussian arithmetic.
    """
    num_e, den_e = reduced_form()
    return sp.expand(-num_e.xreplace({z: sp.I * w})), sp.expand(den_e.xreplace({z: sp.I * w}))


def _m_poly(expr) -> flint.fmpq_poly:
    """A SymPy polynomial in m with rational coefficients as a python-flint ``fmpq_poly``."""
    coeffs = sp.Poly(expr, m).all_coeffs()[::-1] if expr != 0 else []
    return flint.fmpq_poly([flint.fmpq(int(sp.Rational(c).p), int(sp.Rational(c).q)) for c in coeffs])


_WMP = flint.fmpq_mpoly_ctx.get(("w", "m", "p"), "lex")


def _by_power_of_w(poly) -> dict:
    """``{j: {k: coefficient of w^j p^k as an fmpq_poly in m}}`` of an ``fmpq_mpoly`` in (w, m, p)."""
    out: dict = {}
    for (j, i, k), c in zip(poly.monoms(), poly.coeffs()):
        out.setdefault(int(j), {}).setdefault(int(k), {})[int(i)] = c
    return {j: {k: flint.fmpq_poly([terms.get(i, 0) for i in range(max(terms) + 1)]) for k, terms in by_p.items()}
            for j, by_p in out.items()}


@functools.cache
def _obstruction_data():
    """The p-independent flint data of the per-p decision (built once per process).

    ``rt(w) = num_w/den_w`` read into python-flint (symengine's expansion, the shared polynomial reader),
    ``den_w`` divided by ``(w - point)^2`` exactly there (a remainder raises): no SymPy ``cancel``."""
    index = {"w": 0, "m": 1, "p": 2}
    num_w, den_w = (polynomial(se.expand(se.sympify(e)), _WMP, index) for e in rotated_form())
    numerator = _by_power_of_w(num_w)
    numerator = [numerator.get(j, {}) for j in range(num_w.degrees()[0] + 1)]
    gw, gm, _ = _WMP.gens()
    rests = {}
    for name, pt in (("s1", _WMP.constant(1)), ("s3", -gm)):
        rest, remainder = divmod(den_w, (gw - pt) ** 2)
        if not remainder.is_zero():
            raise ArithmeticError(f"{name}: (w - point)^2 does not divide the denominator")
        by_w = _by_power_of_w(rest)
        rests[name] = [by_w.get(j, {}).get(0, flint.fmpq_poly([])) for j in range(rest.degrees()[0] + 1)]
        if any(k for by_p in by_w.values() for k in by_p):
            raise ArithmeticError("the denominator depends on p")
    return numerator, rests, {name: _m_poly(pt) for name, pt in POINTS_W.items()}


def decide_logarithms(p_value: int) -> tuple[dict, float]:
    """Per-p work (run in a worker): ``({s1..s4: "log" | "no log"}, seconds)`` for ``y'' = r y``.

    The obstruction polynomial of :func:`derivations.sections.local_obstruction.log_obstruction` at w = 1
    (s1, Delta = p) and w = -m (s3, Delta = 2); s2 and s4 by the certified symmetries.  Raises
    ArithmeticError if a point is not a double pole with r_0 = (Delta^2 - 1)/4.
    """
    numerator, rests, points = _obstruction_data()
    verdict = {}
    with stopwatch() as elapsed:
        num_p = [sum((poly * p_value**k for k, poly in coefficient.items()), flint.fmpq_poly([]))
                 for coefficient in numerator]
        for name, delta in (("s1", p_value), ("s3", 2)):
            r0_ok, obstruction, _ = log_obstruction(num_p, rests[name], points[name], delta)
            if not r0_ok:
                raise ArithmeticError(f"p = {p_value}, {name}: r_0 != (delta^2-1)/4")
            verdict[name] = "log" if not obstruction.is_zero() else "no log"
        verdict = {"s1": verdict["s1"], "s2": verdict["s1"], "s3": verdict["s3"], "s4": verdict["s3"]}
    return verdict, elapsed[0]


# the conditions of the formulas of section 5.2 (printed with them, and in the formula catalog)
SECTION_HYPOTHESES = (r"$I_{13}=0$, with $p$, $d$ of section 4",
                      r"$d>0$, $c=\sqrt{d^2+1}$",
                      r"$\omega=\big(\tfrac pd\tanh t,\,-\tfrac pd\,c\operatorname{sech}t\big)$",
                      r"$z=e^t$")
DELTA_HYPOTHESIS = r"$\Delta_k$ up to sign: $\Delta_k^2=1+4\rho_k$ where $r\sim\rho_k/(z-s_k)^2$ (at $s_5$: $r\sim\rho_5/z^2$)"
S_NAMES = sp.symbols("s0:6")
DELTA_NAMES = sp.symbols("Delta0:6")


def singular_points_expr() -> list:
    """``Eq(s_k, ...)`` for k = 0..5: :data:`POINTS` in c, d (``m = c + d``, ``1/m = c - d`` as c^2 - d^2 = 1);
    s5 = oo written 1/s5 = 0 (SymPy's ``Eq(s5, zoo)`` does not read back from ``srepr``)."""
    values = [POINTS["s0"], POINTS["s1"], POINTS["s2"], POINTS["s3"].xreplace({m: cc + d_symbol}),
              -sp.I * (cc - d_symbol)]
    return ([sp.Eq(name, value, evaluate=False) for name, value in zip(S_NAMES, values)]
            + [sp.Eq(1 / S_NAMES[5], 0, evaluate=False)])


def exponent_differences_expr() -> list:
    """``Eq(Delta_k, ...)``: the exponent differences of the display (their squares are certified, c_delta)."""
    values = (sp.I * p / d_symbol, p, p, 2, 2, sp.I * p / d_symbol)
    return [sp.Eq(name, value, evaluate=False) for name, value in zip(DELTA_NAMES, values)]


def riccati_expr(A, B, C) -> sp.Tuple:
    """The riccati display as SymPy: u, w, A, B, C, A1, B1 functions of t, A, B, C the certified ones with
    ``omega_k = omega_k(t)``."""
    on_t = {w1: sp.Function("omega1")(t), w2: sp.Function("omega2")(t)}
    u, w, fA, fB, fC, fA1, fB1 = (sp.Function(name)(t) for name in ("u", "w", "A", "B", "C", "A1", "B1"))
    return sp.Tuple(sp.Eq(u.diff(t), fA + fB * u + fC * u**2, evaluate=False),
                    sp.Eq(fA, sp.sympify(A).xreplace(on_t), evaluate=False),
                    sp.Eq(fB, sp.sympify(B).xreplace(on_t), evaluate=False),
                    sp.Eq(fC, sp.sympify(C).xreplace(on_t), evaluate=False),
                    sp.Eq(w.diff(t, 2) - fB1 * w.diff(t) - fA1 * w, 0, evaluate=False),
                    sp.Eq(fA1, -fA * fC, evaluate=False),
                    sp.Eq(fB1, fB + fC.diff(t) / fC, evaluate=False))


def run(log: CertificateLog, options, special_result) -> DerivationResult:
    result = DerivationResult(NAME)
    A, B, C = riccati_coefficients()
    poisson = {g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}
    u1 = (g3 + 1) / (g1 - sp.I * g2)
    u2 = -(g1 + sp.I * g2) / (g3 + 1)
    dot = lambda f: sum(sp.diff(f, v) * rhs for v, rhs in poisson.items())  # noqa: E731
    c_ric = certify_zero(log, "$u1 = (g3+1)/(g1 - i g2)$ and $u2 = -(g1 + i g2)/(g3+1)$ solve $deriv(u, t) = A + B u + C u^2$ "
                         "on $abs(gamma) = 1$ (printed $A$, $B$, $C$; $omega3 = 0$)", "eq:rig, eq:ABC",
                         [dot(u) - (A + B * u + C * u**2) for u in (u1, u2)], SPHERE_DOMAIN)
    uu1, uu2 = sp.symbols("u1 u2")
    gi = [(1 - uu1 * uu2) / (uu1 - uu2), sp.I * (1 + uu1 * uu2) / (uu1 - uu2), (uu1 + uu2) / (uu1 - uu2)]
    c_gi = certify_zero(log, "eq:gi inverts eq:ui on the sphere", "eq:gi",
                        [e.subs({uu1: u1, uu2: u2}) - v for e, v in zip(gi, (g1, g2, g3))], SPHERE_DOMAIN)
    # u = -w'/(C w) with w'' = B1 w' + A1 w, A1 = -A C, B1 = B + C'/C: jet identity
    W, W1, Cs, C1, As, Bs = sp.symbols("W W1 Cs C1 As Bs")
    A1, B1 = -As * Cs, Bs + C1 / Cs
    u = -W1 / (Cs * W)
    udot = -((B1 * W1 + A1 * W) * Cs * W - W1 * (C1 * W + Cs * W1)) / (Cs * W) ** 2
    c_lin = certify_zero(log, "$u = -deriv(w, t)/(C w)$ solves the Riccati equation iff $deriv(w, t, 2) - B1 deriv(w, t) - A1 w = 0$ "
                         "($A1 = -A C$, $B1 = B + deriv(C, t)/C$)", "eq:r2, eq:lin", udot - (As + Bs * u + Cs * u**2),
                         Domain("Q(W,Wp,C,Cp,A,B)"))
    result.formula("riccati", "eq:rig, eq:ABC, eq:lin", "Riccati form and the linear equation",
                   r"\dot u=A+Bu+Cu^2,\ A=\tfrac12(\omega_2-i\omega_1),\ B=0,\ C=\tfrac12(\omega_2+i\omega_1);\quad"
                   r"\ddot w-B_1\dot w-A_1w=0,\ A_1=-AC,\ B_1=B+\dot C/C", c_ric, c_gi, c_lin,
                   expr=riccati_expr(A, B, C),
                   hypotheses=[r"$\omega_3=0$ (the constraint $a=e_3$), $\omega_1$ and $\omega_2$ any functions of $t$",
                               r"$|\gamma|=1$",
                               r"$u=\frac{\gamma_3+1}{\gamma_1-i\gamma_2}$ or $u=-\frac{\gamma_1+i\gamma_2}{\gamma_3+1}$",
                               r"$u=-\dot w/(Cw)$, $C\ne0$"])

    pz, qz, N, Qd = derived_pqr()
    ppz, pqz = printed_pq()
    P, Q = printed_PQ()
    c_pq = certify_zero(log, "in $z = e^t$: $deriv(w, z, 2) + p(z) deriv(w, z) + q(z) w = 0$ with the printed $p(z)$, $q(z)$", "eq:2rzedu",
                        [pz - ppz, qz - pqz], ZC)
    with stopwatch() as elapsed:
        same_r = (N - sp.Poly(P, z, cc, p, domain=sp.QQ_I)).is_zero and (Qd - sp.Poly(Q, z, cc, p, domain=sp.QQ_I)).is_zero
    c_r = log.record(Certificate("$r = deriv(p, z)/2 + p^2/4 - q$ equals the printed $P/Q$ ($p_0$ to $p_8$, eq:Q)", "eq:rlin, eq:Q",
                                 "exact polynomial identity in $Q(i)[z, c, p]$", Outcome.PASS if same_r else Outcome.FAIL,
                                 elapsed[0], len(N.terms())))
    pz_factored = sp.factor(pz)
    w_z, y_z = sp.Function("w")(z), sp.Function("y")(z)
    result.formula("rlin", "eq:2rzedu, eq:rlin", "Reduced form $y''=r(z)y$",
                   r"p(z)=" + latex(pz_factored) + r",\quad q(z)=" + latex(qz) + r",\quad r=\frac PQ", c_pq, c_r,
                   # the two equations the display's p, q and r belong to; P, Q the printed p_0..p_8 and eq:Q, certified
                   # equal to the derived ones (c_r)
                   expr=sp.Tuple(sp.Eq(w_z.diff(z, 2) + pz_factored * w_z.diff(z) + qz * w_z, 0, evaluate=False),
                                 sp.Eq(y_z.diff(z, 2), P / Q * y_z, evaluate=False)),
                   hypotheses=[*SECTION_HYPOTHESES, r"$w=y\,e^{-\frac12\int p(z)\,dz}$"])
    for item, cert in ((paper.RZEDU, c_pq), (paper.RLIN, c_r), (paper.RIG, c_ric)):
        result.errata.append(erratum(item, "confirmed", item.latex, "certified exactly", cert))

    # singular points and exponent differences, in the parametrisation c, d = (m^2 +- 1)/(2m)
    to_m = {cc: (m**2 + 1) / (2 * m)}
    num_e, den_e = reduced_form()
    ring_mp = sp.QQ_I[m, p]
    num, den = sp.Poly(num_e, z, domain=ring_mp), sp.Poly(den_e, z, domain=ring_mp)
    Kp = ring_mp.get_field()
    points = POINTS
    d_m = (m**2 - 1) / (2 * m)
    c_sing = certify_zero(log, "$Q$ vanishes at $s0 = 0$, $s1 = i$, $s2 = -i$, $s3 = -i (c + d)$, $s4 = -i (c - d)$", "eq:Q",
                          [Q.xreplace(to_m).xreplace({z: pt}) for pt in points.values()], Domain("Q(m)[i]"))
    deltas = {}
    for name, pt in points.items():
        rho0 = leading_coefficient_at_double_pole(num, den, pt)
        deltas[name] = Kp.to_sympy(1 + 4 * rho0)
    deltas["s5"] = Kp.to_sympy(1 + 4 * num.LC() / den.LC())  # r ~ rho/z^2 at infinity
    expected = {"s0": -p**2 / d_m**2, "s5": -p**2 / d_m**2, "s1": p**2, "s2": p**2, "s3": 4, "s4": 4}
    c_delta = certify_zero(log, "$Delta^2 = 1 + 4 rho0$: $Delta0 = Delta5 = i p/d$, $Delta1 = Delta2 = p$, $Delta3 = Delta4 = 2$",
                           "eq:Deltai", [deltas[k] - expected[k] for k in expected], Domain("Q(m,p)[i]"))
    result.formula("deltas", "eq:Q, eq:Deltai", "Singular points and exponent differences",
                   r"s_0=0,\ s_{1,2}=\pm i,\ s_{3,4}=-i(c\pm d),\ s_5=\infty;\quad \Delta_0=\Delta_5=\frac{ip}{d},\ "
                   r"\Delta_1=\Delta_2=p,\ \Delta_3=\Delta_4=2", c_sing, c_delta,
                   expr=sp.Tuple(*singular_points_expr(), *exponent_differences_expr()),
                   hypotheses=[*SECTION_HYPOTHESES, DELTA_HYPOTHESIS, r"$s_5=\infty$ is written $1/s_5=0$"])
    result.errata.append(erratum(paper.DELTAI, "confirmed", paper.DELTAI.latex, "$Delta^2 = 1 + 4 rho0$ at each pole",
                                 c_sing, c_delta))

    # logarithms, p = 1 .. galois_pmax
    galois_pmax = max(GALOIS_PMAX, options.pmax)
    rows = []
    # r is invariant under m -> 1/m (it depends on c and d^2 only), which exchanges s3 and s4
    swapped = cancelled((num_e / den_e).xreplace({m: 1 / m}) - num_e / den_e, Domain("Q(m,p)(z)[i]"))
    c_swap = certify_zero(log, "$r(z)$ is the same at $1/m$ as at $m$: the parametrisation's $to(m, 1/m)$ ($to(d, -d)$) exchanges $s3$ and $s4$",
                          "eq:rlin", swapped, Domain("Q(m,p)(z)[i]"))
    # the decisions run in w = -i z, where the reduced form is real
    num_w, den_w = rotated_form()
    expected_den = 1024 * m**6 * (m**2 - 1) ** 2 * w**2 * (w - 1) ** 2 * (w + 1) ** 2 * (w + m) ** 2 * (m * w + 1) ** 2
    c_rot = certify_zero(log, "in $w = -i z$, $deriv(y, w, 2) = rtilde(w) y$ with $rtilde(w) = -r(i w) = N(w)/Q(w)$ real (in $Q(m, p)(w)$), "
                         "$Q$ a constant times $w^2 (w-1)^2 (w+1)^2 (w+m)^2 (m w+1)^2$: double poles at $w = 0$, $1$, $-1$, $-m$, "
                         "$-1/m$, i.e. $z = s0$, $s1$, $s2$, $s3$, $s4$", "eq:rlin, eq:Q",
                         [num_w - num_w.xreplace({sp.I: -sp.I}), den_w - den_w.xreplace({sp.I: -sp.I}),
                          den_w - sp.expand(expected_den)],
                         Domain("Q(m,p)[w]"))
    mirrored = cancelled((num_w / den_w).xreplace({w: -w, m: -m}) - num_w / den_w, Domain("Q(m,p)(w)"))
    c_mirror = certify_zero(log, "$rtilde(w)$ is unchanged by $to(w, -w)$ with $to(m, -m)$, which maps $s1$ ($w = 1$) to $s2$ ($w = -1$), so "
                            "the obstruction at $s2$ is the one at $s1$ with $to(m, -m)$ (zero iff it is)", "eq:rlin",
                            mirrored, Domain("Q(m,p)(w)"))
    # the per-p decisions are independent: run in parallel (CertificateLog.map_per_p), recorded in p order; a
    # cross-check of pole_theorem (a theorem for every p): every p <= cross_check_pmax, a sample above it
    # (derivations.core.options.cross_check_p_values, galois_pmax and galois_pmax - 1 included)
    values = options.cross_check_p_values(galois_pmax)
    dense = dense_prefix(values)
    sample = [q for q in values if q > dense]
    # the p that ran, for the title and the hypotheses (unchanged when every p <= galois_pmax ran)
    range_tex = (f"$p\\le{galois_pmax}$" if not sample else
                 f"$p\\le{dense}$ and $p\\in\\{{{','.join(map(str, sample))}\\}}$")
    range_hypothesis = (f"$p$ an integer, $1\\le p\\le{galois_pmax}$" if not sample else
                        f"$p$ an integer, $1\\le p\\le{dense}$ or $p\\in\\{{{','.join(map(str, sample))}\\}}$ (the "
                        "theorem on the poles covers every $p$)")
    decisions = log.map_per_p("logarithms at s1..s4", values, decide_logarithms)
    for p_value, (verdict, seconds) in zip(values, decisions):
        conjecture = ("no log" if p_value % 2 else "log")
        ok = verdict["s1"] == verdict["s2"] == conjecture and verdict["s3"] == verdict["s4"] == "no log"
        cert = log.record(Certificate(
            f"$p = {p_value}$: $s1$, $s2$ " + ("non-logarithmic for every $d > 0$" if p_value % 2 else
                                         "logarithmic for all but finitely many $d > 0$")
            + ", $s3$, $s4$ non-logarithmic for every $d > 0$", "Conjecture 1",
            "exact Frobenius obstruction in $Q(m)$ at $w = 1$ and $w = -m$ ($w = -i z$, $c = (m^2 + 1)/(2 m)$, $d = (m^2 - 1)/(2 m)$), "
            "denominators cleared by the least $K$ such that the denominator of $r_j$ divides $K^j$ "
            "(`derivations.sections.local_obstruction`)",
            Outcome.PASS if ok else Outcome.FAIL, seconds, 4,
            ", ".join(f"${k}$: {v}" for k, v in verdict.items())))
        rows.append({"p": p_value, "s1": verdict["s1"], "s2": verdict["s2"], "s3": verdict["s3"], "s4": verdict["s4"],
                     "certificate": cert.key})
    result.formula("conjecture", "Conjecture 1", f"Logarithms at $s_1,\\dots,s_4$ for {range_tex} (the check of the "
                   "theorem on the poles)",
                   r"s_1,s_2\text{ logarithmic}\iff p\text{ even};\quad s_3,s_4\text{ never}", c_swap, c_rot, c_mirror,
                   *[c for c in log.certificates if c.derivation == NAME and c.label == "Conjecture 1"],
                   # the statement's relations: the four points and their integer exponent differences (a logarithm
                   # is possible only at a point whose exponent difference is an integer)
                   expr=sp.Tuple(*singular_points_expr()[1:5], *exponent_differences_expr()[1:5]),
                   hypotheses=[*SECTION_HYPOTHESES, DELTA_HYPOTHESIS, range_hypothesis,
                               (r"even $p$: logarithmic for all but finitely many $d>0$ (for every $d>0$ by the theorem "
                                r"on the poles)")])
    result.notes.append(
        f"Conjecture (section 5.2) decided for {checked_words(values)}: $s1$, $s2$ are logarithmic exactly for even $p$; "
        "$s3$, $s4$ never. The obstruction for odd $p$ vanishes identically in $m$ (all $d > 0$); for even $p$ it is a non-zero "
        "element of $Q(m)$, so logarithms occur for all but finitely many $d$ (and the Frobenius recursion of the "
        "Poisson system itself, section 3.2, shows them for every $d > 0$). The conjecture is proved for every $p$ and every "
        "$d > 0$ by the theorem on the poles (`pole_theorem`: Gauss's equation at $s = i$, $Lambda = p$); this per-$p$ table "
        "is its check" + (f", sampled above $p = {options.cross_check_pmax}$." if sample else "."))

    # Proposition 5.8 bookkeeping for even p
    prop_rows = []
    for p_value in [q for q in range(2, galois_pmax + 1, 2)]:
        with stopwatch() as elapsed:
            ns = set()
            for s0, s5, s3, s4 in itertools.product((1, -1), repeat=4):
                # each exponent as (rational part, coefficient of i p/d): rho_s0 = (1 + s0 i p/d)/2, ...
                rho = {"s0": (Fraction(1, 2), Fraction(s0, 2)), "s5": (Fraction(-1, 2), Fraction(-s5, 2)),
                       "s1": (Fraction(1 + p_value, 2), 0), "s2": (Fraction(1 + p_value, 2), 0),
                       "s3": (Fraction(1 + 2 * s3, 2), 0), "s4": (Fraction(1 + 2 * s4, 2), 0)}
                rational, imaginary = (-sum(part) for part in zip(*rho.values()))
                # n = -sum rho is an integer for the d > 0 at hand only if its part i p/d (p != 0) cancels
                if imaginary == 0 and rational.denominator == 1:
                    ns.add(int(rational))
            ok = bool(ns) and max(ns) < 0
        cert = log.record(Certificate(
            f"$p = {p_value}$: every admissible exponent choice gives $deg(R) = -Sum(rho_k, (k, 0, 5)) < 0$ (no exponential solution)",
            "Proposition 5.8", "enumeration of exponent choices (exact rationals)", Outcome.PASS if ok else Outcome.FAIL,
            elapsed[0], len(ns), "values of $deg(R)$: " + ", ".join(f"${n}$" for n in sorted(ns))))
        prop_rows.append({"p": p_value, "degrees": sorted(ns), "certificate": cert.key})
    result.exports.update(log_rows=rows, prop_rows=prop_rows, galois_pmax=galois_pmax)
    return result
