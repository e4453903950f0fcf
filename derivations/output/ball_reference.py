"""Certified closed forms of the Suslov problem in ball arithmetic: the references of the route checks.

Used by :mod:`derivations.output.runtime_routes` (issue 44) to check the generated module's run-time routes
by a route that shares none of their code.  Method:

* :func:`arb_value` walks a certified SymPy expression (the build's ``Emitted.substituted()``: the very
  expressions the derivations certified and the round trip compares the emitted code with) in python-flint
  ``arb``: sums, products, integer and half-integer powers, tanh, sech, exp, expm1, atan2.  No ``suslov``
  number context and no emitted code is involved.
* :class:`Reference` feeds it the arguments computed here from their definitions, from the exact inputs (a
  float is its binary value, ``"0.7"`` is 7/10): Theorem 5.4's evaluation form (certified equal to
  ``cos(Delta psi/2) = |cos(pi p/2)|/cosh(pi p/(2d))``) at ``x = pi |p|/(2d)``, ``s, c = |sin|, |cos| (pi p/2)``;
  for any body the certified invariants ``(U^2, a, b)`` (``w_-^2 = a + i b``), the root ``w_- = X + i Y`` taken
  without cancellation (``2 X |Y| = |b|``), ``h = pi U/2``, ``g = pi (U - X)/2``, then the certified angle.
* :func:`enclose` doubles the working precision until every ball has the bits a comparison needs.
* :func:`basis_rows`: the basis from the certified numerators (``Q[x, d, i]/(i^2 + 1)``, d substituted
  exactly) at ``x = e^t`` enclosed in arb, normalised by their exact limits at ``x = 0``, rotated by the phase
  ``e^(i p t/d)`` enclosed from the exact rational ``p t/d`` (far phases included);
  :func:`integral_value`: the first integral from the certified numerators, exactly in Q.
"""
from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import sympy as sp
from flint import arb, ctx, fmpq

MAX_BITS = 1 << 15          # a reference's working precision stops doubling here (the comparison is then unknown)


def exact(value) -> Fraction:
    """A route's input as the number it denotes: ints and Fractions as they are, floats their binary value,
    strings (``"5/2"``, ``"0.7"``, ``"1e-300"``) their rational."""
    return Fraction(value) if not isinstance(value, float) else Fraction(*value.as_integer_ratio())


def ball(value) -> arb:
    """An exact input, a float, an mpf or a ball as an arb (exact where the number is; at the working precision
    for a non-dyadic rational)."""
    if isinstance(value, arb):
        return value
    if isinstance(value, mpmath.mpf):
        sign, mantissa, exponent, _ = value._mpf_
        if not mantissa and exponent:          # inf or nan: not a number the comparison can pass
            return arb("nan")
        return arb((-int(mantissa) if sign else int(mantissa), int(exponent)))
    if isinstance(value, (float, np.floating)):
        return arb(float(value)) if math.isfinite(value) else arb("nan")
    q = exact(value)
    return arb(fmpq(q.numerator, q.denominator))


_FUNCTIONS = {"tanh": lambda x: x.tanh(), "sech": lambda x: 1 / x.cosh(), "exp": lambda x: x.exp(),
              "expm1": lambda x: x.expm1(), "Abs": abs}


def _power(x: arb, n: int) -> arb:
    """x^n by repeated squaring (python-flint's ``arb ** int`` goes through exp and log: NaN for a ball about 0,
    such as expm1(2g - 2h) of a body with I13 = 0, where g = h)."""
    if n < 0:
        return 1 / _power(x, -n)
    result = arb(1)
    while n:
        if n & 1:
            result *= x
        n >>= 1
        if n:
            x = x * x
    return result


def arb_value(expr, env: dict) -> arb:
    """``expr`` (a certified SymPy expression) in ball arithmetic at the current precision; ``env`` maps its
    symbols to balls.  Powers with half-integer exponents are square roots of non-negative bases (as in the
    certified forms); anything else is refused."""
    if expr.is_Symbol:
        return env[expr]
    if expr.is_Integer:
        return arb(int(expr))
    if expr.is_Rational:
        return arb(fmpq(int(expr.p), int(expr.q)))
    if expr.is_Add:
        total = arb(0)
        for term in expr.args:
            total += arb_value(term, env)
        return total
    if expr.is_Mul:
        product = arb(1)
        for factor in expr.args:
            product *= arb_value(factor, env)
        return product
    if expr.is_Pow:
        base, power = arb_value(expr.args[0], env), expr.args[1]
        if power.is_Integer:
            return _power(base, int(power))
        if power.is_Rational and power.q == 2:
            return _power(base.sqrt(), int(power.p))
        raise ValueError(f"arb_value: the power {expr} is not an integer or half-integer one")
    name = type(expr).__name__
    if name == "atan2":
        return arb.atan2(arb_value(expr.args[0], env), arb_value(expr.args[1], env))
    if name in _FUNCTIONS:
        return _FUNCTIONS[name](arb_value(expr.args[0], env))
    raise ValueError(f"arb_value: no ball evaluation of {name} in {expr}")


def enclose(target: int, evaluate, *args, absolute: bool = False):
    """``evaluate(*args)`` (a tuple of balls) at a working precision doubled from ``target + 64`` until every
    ball has ``target`` relative bits (``absolute``: radius at most ``2^-target``); None beyond ``MAX_BITS``."""
    bits = target + 64
    while bits <= MAX_BITS:
        with ctx.workprec(bits):
            values = tuple(evaluate(*args))
        if all(v.is_finite() and (v.rad() <= arb(2) ** -target if absolute else
                                  (v.rad().is_zero() or v.rel_accuracy_bits() >= target)) for v in values):
            return values
        bits *= 2
    return None


class Reference:
    """The certified closed forms of one build, evaluated in arb (see the module docstring)."""

    def __init__(self, build):
        from derivations.core.emit import emitted_formulas

        items = emitted_formulas(build)
        self.forms = {name: (item.args, [sp.sympify(e) for e in item.substituted()])
                      for name, item in items.items() if name in ("omega", "omega_general", "gauss_invariants",
                                                                   "scattering_angle", "general_angle")}

    def _form(self, name: str, *values) -> list:
        args, outputs = self.forms[name]
        env = dict(zip(args, values))
        return [arb_value(e, env) for e in outputs]

    def omega(self, t, p, d):
        return tuple(self._form("omega", ball(t), ball(p), ball(d)))

    def omega_general(self, t, I11, I22, I13, I23, branch: int):
        a, b = ball(I11), ball(I22)
        return tuple(self._form("omega_general", ball(t), a, b, ball(I13), ball(I23), branch * (a * b).sqrt()))

    def scattering_angle(self, p, d):
        """Theorem 5.4 (evaluation form, certified equal to cos(Delta psi/2) = |cos(pi p/2)|/cosh(pi p/(2d)))."""
        p, d = ball(p), ball(d)
        half = p / 2
        return tuple(self._form("scattering_angle", arb.pi() * abs(p) / (2 * d), abs(half.sin_pi()),
                                abs(half.cos_pi())))

    def general_angle(self, I11, I22, I13, I23):
        """(angle, |Y|) of any body: the certified invariants, w_- = X + i Y, then the certified angle."""
        U2, a, b, _ = self._form("gauss_invariants", *(ball(x) for x in (I11, I22, I13, I23)))
        modulus = (a * a + b * b).sqrt()
        if a < 0:
            Y = ((modulus - a) / 2).sqrt()
            X = abs(b) / (2 * Y)
        else:
            X = ((modulus + a) / 2).sqrt()
            Y = abs(b) / (2 * X)
        U = U2.sqrt()
        half = Y / 2
        angle = self._form("general_angle", arb.pi() * U / 2, arb.pi() * (U - X) / 2, abs(half.sin_pi()),
                           abs(half.cos_pi()))[0]
        return angle, Y


# ---------------------------------------------------------------- first integral (exact) and the basis


def integral_value(coefficients: dict, p: int, w1, w2, gammas) -> tuple:
    """(F3, sum_i |gamma_i| sum_k |a_ik| s^p) exactly, s = max(|w1|, |w2|)."""
    w1, w2 = exact(w1), exact(w2)
    s = max(abs(w1), abs(w2))
    value = scale = Fraction(0)
    for name, g in zip(("P1", "P2", "P3"), gammas):
        g = exact(g)
        value += g * sum(a * w1 ** (p - k) * w2**k for k, a in enumerate(coefficients[name]))
        scale += abs(g) * sum(abs(a) for a in coefficients[name]) * s**p
    return value, scale


def _in_x(poly, d: Fraction) -> list:
    """The monomials (x power, i power, coefficient) of a certified numerator with d substituted exactly."""
    in_x = poly.subs({"d": fmpq(d.numerator, d.denominator)})
    return [(int(m[0]), int(m[2]), fmpq(c)) for m, c in zip(in_x.monoms(), in_x.coeffs())]


def _at_x(terms, x: arb) -> tuple:
    re, im = arb(0), arb(0)
    for power, i_power, coefficient in terms:
        value = arb(coefficient) * x**power
        if i_power == 0:
            re += value
        else:
            im += value
    return re, im


def basis_rows(core, p: int, t: float, d: float) -> tuple:
    """The nine entries of the basis at t (rows gamma^(1), gamma^(2), gamma^(3), row by row) from the certified
    numerators (as :func:`derivations.output.float_paths.exact_basis_values`, with x a ball): x = e^t enclosed from
    the exact t; gamma^(1)_j = R_j/(f_j s (1+x^2)^p), G_j = f'_j V_j/(k (1+x^2)^p), f = (1, c, c), f' = (c, 1, 1),
    c = sqrt(d^2+1), s and k the certified limits at x = 0 (exact), and gamma^(2) - i sigma gamma^(3) =
    e^(i p t/d) G, sigma read from V_3(0) = i sigma V_2(0) (not from the module)."""
    from derivations.output.float_paths import _at

    real, cplx = core
    d_exact = exact(d)
    s = -_at(real[0], Fraction(0), d_exact)[0]
    k = _at(cplx[1], Fraction(0), d_exact)
    v3 = _at(cplx[2], Fraction(0), d_exact)
    sigma = 1 if (v3[0], v3[1]) == (-k[1], k[0]) else -1 if (v3[0], v3[1]) == (k[1], -k[0]) else None
    if sigma is None:
        raise ArithmeticError("basis_rows: V_3(0) is not +-i V_2(0)")
    x, D = ball(t).exp(), ball(d)
    c = (D * D + 1).sqrt()
    den = (1 + x * x) ** p
    rows = [[_at_x(_in_x(m, d_exact), x)[0] / (f * ball(s) * den) for m, f in zip(real, (1, c, c))], [], []]
    phase = ball(exact(t) * p / d_exact)
    cos_, sin_ = phase.cos(), phase.sin()
    k_re, k_im = ball(k[0]), ball(k[1])
    norm = k_re * k_re + k_im * k_im
    for m, f in zip(cplx, (c, 1, 1)):
        a, b = _at_x(_in_x(m, d_exact), x)
        re, im = f * (a * k_re + b * k_im) / (norm * den), f * (b * k_re - a * k_im) / (norm * den)
        rows[1].append(cos_ * re - sin_ * im)
        rows[2].append(-sigma * (sin_ * re + cos_ * im))
    return tuple(v for row in rows for v in row)


def integral_at(ff, d: Fraction) -> dict:
    """Certified P1, P2, P3 at a rational d, as homogeneous coefficient lists of Fractions."""
    def value(poly):
        total: dict = {}
        for monomial, coefficient in zip(poly.monoms(), poly.coeffs()):
            k = int(monomial[2])  # power of w2
            total[k] = total.get(k, 0) + int(coefficient) * d ** int(monomial[0])
        return [Fraction(total.get(k, 0)) for k in range(ff.p + 1)]

    den, K = _scalar_at(ff.Den, d), _scalar_at(ff.K, d)
    return {"P1": [v / den for v in value(ff.P1t)], "P2": [v / (K * K * den) for v in value(ff.M2)],
            "P3": [v / (K * den) for v in value(ff.M3)]}


def _scalar_at(poly, d: Fraction) -> Fraction:
    if isinstance(poly, int):
        return Fraction(poly)
    return sum((int(c) * d ** int(m[0]) for m, c in zip(poly.monoms(), poly.coeffs())), Fraction(0))
