"""Q(d): rational functions in one variable with python-flint numerators and denominators.

Used by the Frobenius recursion at the poles of omega (paper section 3.2, Theorem 3.5;
:func:`derivations.residue.frobenius_obstructions`).  An element is ``num/den`` with ``num, den`` in
Q[d] (``flint.fmpq_poly``), reduced by their gcd and with a monic denominator after every
operation: a canonical form, so ``is_zero`` and ``==`` are exact tests.  The same field as SymPy's
``QQ.frac_field(d)``, with the polynomial arithmetic and gcds in C (5-10 times faster on the
recursion at p = 11..40, identical obstructions: tests/test_rational_field.py).
"""
from __future__ import annotations

import flint
import sympy as sp


class QD:
    """``num/den`` in Q(d), gcd-reduced, denominator monic."""

    __slots__ = ("num", "den")

    def __init__(self, num, den=None, reduce: bool = True):
        den = flint.fmpq_poly([1]) if den is None else den
        if reduce:
            if num.is_zero():
                den = flint.fmpq_poly([1])
            else:
                g = num.gcd(den)
                if g.degree() > 0:
                    num, den = num / g, den / g     # exact: g divides both
                lc = den.coeffs()[-1]
                if lc != 1:
                    num, den = num / lc, den / lc
        self.num, self.den = num, den

    @classmethod
    def constant(cls, value) -> QD:
        """From an int, a Fraction-like (``.p``/``.q`` or numerator/denominator) or a SymPy Rational."""
        value = sp.Rational(value)
        return cls(flint.fmpq_poly([flint.fmpq(int(value.p), int(value.q))]), reduce=False)

    @classmethod
    def variable(cls) -> QD:
        return cls(flint.fmpq_poly([0, 1]), reduce=False)

    def __add__(self, other: QD) -> QD:
        if self.den == other.den:
            return QD(self.num + other.num, self.den)
        return QD(self.num * other.den + other.num * self.den, self.den * other.den)

    def __sub__(self, other: QD) -> QD:
        return self + (-other)

    def __neg__(self) -> QD:
        return QD(-self.num, self.den, reduce=False)

    def __mul__(self, other: QD) -> QD:
        return QD(self.num * other.num, self.den * other.den)

    def __truediv__(self, other: QD) -> QD:
        if other.is_zero():
            raise ZeroDivisionError("division by zero in Q(d)")
        return QD(self.num * other.den, self.den * other.num)

    def is_zero(self) -> bool:
        return self.num.is_zero()

    def __eq__(self, other) -> bool:
        return isinstance(other, QD) and self.num == other.num and self.den == other.den

    __hash__ = None

    def to_sympy(self, symbol) -> sp.Expr:
        def poly(p):
            return sp.Add(*(sp.Rational(int(c.p), int(c.q)) * symbol**i for i, c in enumerate(p.coeffs())))
        return poly(self.num) / poly(self.den)
