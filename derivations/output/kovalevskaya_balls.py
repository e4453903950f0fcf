"""Consistency checks of ``kovalevskaya_exponents`` and ``meromorphy`` as ball certificates (issue 34; paper
section 3.1, ``eq:kowal``, ``eq:necc1``, Theorem 3.2 corrected).

Part of the round trip's float paths (:mod:`derivations.output.float_paths`).  The reference is the certified
Kovalevskaya matrix K of the derivation ``kovalevskaya`` (a route sharing nothing with the emitted Lambda^2),
evaluated in complex ball arithmetic (python-flint ``acb``, 200 bits) at the body's canonical entries: the
float64 numbers read exactly, r = sqrt(I11 I22) a ball.  Its eigenvalues are enclosed with multiplicity by
Arb (``acb_mat_eig_multiple``) or, where two cannot be isolated, as roots of its ball characteristic polynomial
over the certified factor (x + 1)(x - 2)(x - 1); Lambda^2 from the same quotient.  Each float result is then
shown within its stated distance of the balls, and each decision of ``meromorphy`` (case, oddness of p within
``tol``) is re-checked exactly and shown away from its tolerance edge: certificates at the listed bodies, where
mpmath's QR at 30 digits was evidence.
"""
from __future__ import annotations

import itertools
from fractions import Fraction

import flint
import numpy as np
import sympy as sp

from derivations.core.certificates import Certificate, CertificateLog, Outcome, stopwatch
from derivations.core.symbols import I11, I13, I22, I23

# the fixed bodies both checks use (the Kovalevskaya check adds four seeded ones)
BODIES = ([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]], [[2.0, 0, 0.4], [0, 1.0, 0], [0.4, 0, 1.5]],
          [[3.0, 0.2, 0.0], [0.2, 1.0, -0.7], [0.0, -0.7, 2.0]], [[1.5, 0, 0.3], [0, 1.2, 0], [0.3, 0, 2.0]])


def _acb_of(expression, values):
    """A SymPy expression (sums, products, integer powers, rationals, i, symbols) as a complex ball, exactly
    as written: no float enters (lambdify would print a rational as a float division)."""
    if expression.is_Symbol:
        return values[expression]
    if expression is sp.I:
        return flint.acb(0, 1)
    if expression.is_Rational:
        return flint.acb(flint.fmpq(int(expression.p), int(expression.q)))
    if expression.is_Add or expression.is_Mul:
        parts = [_acb_of(a, values) for a in expression.args]
        out = parts[0]
        for part in parts[1:]:
            out = out + part if expression.is_Add else out * part
        return out
    if expression.is_Pow and expression.exp.is_Integer:
        return _acb_of(expression.base, values) ** int(expression.exp)
    raise TypeError(f"no ball evaluation for {expression.func.__name__} in the Kovalevskaya matrix")


def _eigenvalue_balls(K) -> list:
    """Balls containing the five eigenvalues of K, with multiplicity: Arb's eigenvalue enclosure; where it
    cannot isolate them (two exponents next to each other: 1 - Lambda and -1 for p next to 2), the ball
    characteristic polynomial of K divided exactly by the certified factor (x + 1)(x - 2)(x - 1), the
    quotient x^2 + q1 x + q0 giving 1 +- sqrt(q1^2/4 - q0) (the remainder and q1 + 2 must contain 0)."""
    try:
        return list(K.eig(multiple=True))
    except ValueError:
        pass
    quotient, remainder = divmod(K.charpoly(), flint.acb_poly([2, -1, -2, 1]))
    q0, q1 = quotient[0], quotient[1]
    if not (all(remainder[k].contains(0) for k in range(3)) and (q1 + 2).contains(0)):
        raise ArithmeticError("the characteristic polynomial of K is not divisible by (x + 1)(x - 2)(x - 1)")
    root = (q1 * q1 / 4 - q0).sqrt()
    return [flint.acb(-1), flint.acb(2), flint.acb(1), -q1 / 2 + root, -q1 / 2 - root]


def check_kovalevskaya_exponents(log: CertificateLog, module, matrix) -> Certificate:
    """The five exponents against the eigenvalues of the certified Kovalevskaya matrix K (derivation
    ``kovalevskaya``, a route that shares nothing with the emitted Lambda^2): K evaluated in complex ball
    arithmetic at the body's canonical entries (the float64 numbers read exactly, r = sqrt(I11 I22) a ball),
    its eigenvalues enclosed with their multiplicities (Arb's ``acb_mat_eig_multiple``, else through the ball
    characteristic polynomial: :func:`_eigenvalue_balls`), and a matching of
    the float exponents to the balls with every distance at most 1e-9 found (a certificate for these
    bodies: every step is exact or a ball)."""
    rng = np.random.default_rng(1700)
    bodies = [list(body) for body in BODIES]
    for _ in range(4):
        A = rng.normal(size=(3, 3))
        bodies.append((A @ A.T + 0.5 * np.eye(3)).tolist())
    failures, points = [], 0
    tolerance = flint.arb("1e-9")
    with stopwatch() as elapsed, flint.ctx.workprec(200):
        for index, body in enumerate(bodies):
            K = k_ball(module, body, matrix)
            balls = _eigenvalue_balls(K)
            got = [flint.acb(complex(e).real, complex(e).imag) for e in module.kovalevskaya_exponents(body)]
            matched = any(all(abs(got[i] - balls[j]) < tolerance for i, j in enumerate(order))
                          for order in itertools.permutations(range(5)))
            if not matched:
                failures.append(f"body {index}: no matching within $10^(-9)$")
            points += 1
    return log.record(Certificate(
        "`kovalevskaya_exponents`: at eight bodies the five `float64` exponents are, as a multiset, within $10^(-9)$ of "
        "the eigenvalues of the certified Kovalevskaya matrix $K$ at the body's canonical entries", "round trip",
        "ball enclosure: $K$ in complex ball arithmetic at 200 bits at the `float64` canonical entries read exactly, "
        "$r = sqrt(I11 I22)$ a ball, its eigenvalues enclosed with multiplicity (Arb's `acb_mat_eig_multiple`; where "
        "it cannot isolate two, the roots of its ball characteristic polynomial over the certified factor "
        "$(x + 1) (x - 2) (x - 1)$), "
        "a matching within $10^(-9)$ found for every body",
        Outcome.FAIL if failures else Outcome.PASS, elapsed[0], points,
        "; ".join(failures) if failures else f"{points} bodies: every exponent within $10^(-9)$ of its ball"))


def _exact_decision(module, body, matrix, tol: float) -> tuple:
    """(case, p ball or None, odd) of the exact analysis of the float64 body, with whether each decision is away
    from meromorphy's tolerance edge (so that its float decision must agree): the case from the exact canonical
    entries, p^2 = Lambda^2 enclosed by :func:`lambda_squared_ball`, the ball's distance to the nearest odd
    integer compared with tol, 1e-12 away from it."""
    entries = [Fraction(float(v)) for v in module.canonical_frame(body)[1]]
    size = max(abs(v) for v in entries)
    edge = Fraction(tol) * size
    margin = Fraction(1, 2**40)       # meromorphy's tol * size is rounded: |I| must be clear of it
    if entries[2] == 0:
        case = "I13=0"
    elif entries[3] == 0:
        case = "I23=0"
    else:
        case = "neither"
    clear = all(v == 0 or abs(v) > edge * (1 + margin) for v in entries[2:])
    square = lambda_squared_ball(module, body, matrix)
    if case == "neither" or not square.imag.contains(0) or not square.real > 0:
        # p^2 not a positive real (the case neither has a complex Lambda^2; I23 = 0 gives p^2 <= 0): no p
        clear = clear and (case == "neither" and not square.imag.contains(0) or square.real < 0)
        return case, None, False, clear
    p = square.real.sqrt()
    nearest = round(float(p.mid()))
    distance = abs(p - nearest)
    scale = tol * max(flint.arb(1), p)
    odd = nearest % 2 == 1 and distance < scale
    clear = clear and (distance < scale - flint.arb("1e-12") or distance > scale + flint.arb("1e-12"))
    return case, p, odd, clear


def check_meromorphy_cases(log: CertificateLog, module, matrix) -> Certificate:
    """meromorphy against the exact analysis of bodies built from their parameters: I13 = 0 with p =
    sqrt(I22 (I11 - I22))/|I23| odd, even or not an integer (I = diag-block of (p, d), certified inverse of
    eq:necc1's substitution), I23 = 0 (p^2 <= 0: never odd), and neither.  Re-checked exactly and with balls
    (:func:`_exact_decision`): the float64 decisions at these bodies are those of the exact analysis of the
    same float64 bodies, each away from its tolerance edge, and the float p within 1e-13 of the ball."""
    cases = []
    for p, d in ((1, 0.5), (3, 2.0), (5, 0.3), (2, 1.0), (4, 0.7), (2.5, 0.7), (0.5, 3.0)):
        I22 = 1.3
        I23 = -I22 * d / p
        I33 = I22 * (d / p) ** 2 + 1.0   # keeps the tensor positive definite
        cases.append(([[I22 * (d * d + 1), 0, 0], [0, I22, I23], [0, I23, I33]], "I13=0", p,
                      float(p).is_integer() and int(p) % 2 == 1))
    cases.append(([[2.0, 0, 0.4], [0, 1.0, 0], [0.4, 0, 1.5]], "I23=0", None, False))
    cases.append(([[2.0, 0, 0.4], [0, 1.0, 0.3], [0.4, 0.3, 1.5]], "neither", None, False))
    failures, points = [], 0
    with stopwatch() as elapsed, flint.ctx.workprec(200):
        for body, case, p, odd in cases:
            got = module.meromorphy(body)
            exact_case, ball, exact_odd, clear = _exact_decision(module, body, matrix, 1e-9)
            built = (exact_case, exact_odd, ball is None) == (case, odd, p is None) and (
                ball is None or abs(ball - flint.arb(p)) < flint.arb("1e-12") * p)
            agrees = (got.case, got.odd, got.p is None) == (exact_case, exact_odd, ball is None) and (
                ball is None or abs(flint.arb(got.p) - ball) < flint.arb("1e-13") * max(flint.arb(1), ball))
            if not (built and agrees and clear):
                failures.append(f"{case} p={p}: got {got.case}, p={got.p}, odd={got.odd}; exact {exact_case}, "
                                f"p={ball}, odd={exact_odd}" + ("" if clear else ", at a tolerance edge"))
            points += 1
    return log.record(Certificate(
        "`meromorphy`: case, $p$ and oddness agree with the exact analysis of bodies built from $(p, d)$ "
        "(odd, even and non-integer $p$ with $I13 = 0$; $I23 = 0$; neither), at nine `float64` bodies", "round trip",
        "exact and ball re-check of the decisions: the case from the exact canonical entries, $p^2 = Lambda^2$ "
        "enclosed from the ball characteristic polynomial of the certified $K$ (within $10^(-12) p$ of the $p$ the "
        "body was built from), the `float64` $p$ within $10^(-13) Max(1, p)$ of the ball, every decision at least "
        "$10^(-12)$ away from its tolerance $10^(-9)$",
        Outcome.FAIL if failures else Outcome.PASS, elapsed[0], points,
        "; ".join(failures) if failures else f"{points} bodies agree"))


def lambda_squared_ball(module, body, matrix) -> "flint.acb":
    """Lambda^2 of the exact Kovalevskaya matrix K at the body's canonical entries (float64, read exactly) as a
    ball: the ball characteristic polynomial of K over the certified factor (x + 1)(x - 2)(x - 1) is
    (x - 1)^2 - Lambda^2 = x^2 + q1 x + q0, so Lambda^2 = q1^2/4 - q0 (precision set by the caller)."""
    K = k_ball(module, body, matrix)
    quotient, remainder = divmod(K.charpoly(), flint.acb_poly([2, -1, -2, 1]))
    if not (all(remainder[k].contains(0) for k in range(3)) and (quotient[1] + 2).contains(0)):
        raise ArithmeticError("the characteristic polynomial of K is not divisible by (x + 1)(x - 2)(x - 1)")
    return quotient[1] * quotient[1] / 4 - quotient[0]


def k_ball(module, body, matrix) -> "flint.acb_mat":
    """The certified Kovalevskaya matrix at the body's canonical entries (float64 numbers read exactly, r =
    sqrt(I11 I22) a ball) in complex ball arithmetic."""
    values = {name: flint.acb(flint.fmpq(*Fraction(float(v)).as_integer_ratio()))
              for name, v in zip((I11, I22, I13, I23), module.canonical_frame(body)[1])}
    values[sp.Symbol("r")] = (values[I11] * values[I22]).sqrt()
    return flint.acb_mat([[_acb_of(matrix[i, j], values) for j in range(5)] for i in range(5)])


def check_meromorphy(log: CertificateLog, module, matrix) -> Certificate:
    """meromorphy's p^2 and kovalevskaya_exponents' Lambda^2 (from the fourth exponent) each against a ball of
    the exact Lambda^2 of the certified K at the body (:func:`lambda_squared_ball`): a certificate at these
    four bodies that both are within 1e-12 (relative, or absolute below 1) of it, so of each other."""
    failures, points = [], 0
    tolerance = flint.arb("1e-12")
    with stopwatch() as elapsed, flint.ctx.workprec(200):
        for index, body in enumerate(BODIES):
            exact = lambda_squared_ball(module, body, matrix)
            scale = tolerance * max(flint.arb(1), abs(exact))
            lam = complex(module.kovalevskaya_exponents(body)[3]) - 1
            for name, value in (("p^2", complex(module.meromorphy(body).p_squared)), ("Lambda^2", lam * lam)):
                if not abs(flint.acb(value.real, value.imag) - exact) < scale:
                    failures.append(f"body {index}: {name} = {value!r} not within 1e-12 of {exact}")
            points += 1
    return log.record(Certificate(
        "the $p^2$ of `meromorphy` equals the $Lambda^2$ of `kovalevskaya_exponents` in the cases $I13 = 0$, $I23 = 0$ and neither: "
        "at four bodies both are within $10^(-12) Max(1, abs(Lambda^2))$ of the exact $Lambda^2$ at the body's "
        "canonical entries", "round trip",
        "ball enclosure: the characteristic polynomial of the certified Kovalevskaya matrix $K$ in complex ball "
        "arithmetic at 200 bits (`float64` canonical entries read exactly, $r = sqrt(I11 I22)$ a ball) divided by the "
        "certified factor $(x + 1) (x - 2) (x - 1)$ encloses $Lambda^2$",
        Outcome.FAIL if failures else Outcome.PASS, elapsed[0], points,
        "; ".join(failures) if failures else f"{points} bodies: both within the bound of the ball"))
