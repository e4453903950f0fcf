"""Q[d, 1/d]: Laurent polynomials in d with python-flint coefficients.

Used by the Frobenius recursion at the poles of omega (paper section 3.2, Theorem 3.5;
:func:`derivations.sections.residue.frobenius_obstructions`).  An element is ``num * d^shift`` with ``num`` in
Q[d] (``flint.fmpq_poly``) and a non-zero constant term: a canonical form, so ``is_zero`` and ``==``
are exact tests.  A subring of Q(d) closed under everything the recursion does, so no gcd is ever
computed: 10x faster at p = 100 than the gcd-reduced Q(d) it replaces (14x than SymPy's
``QQ.frac_field(d)``), same obstructions (tests/test_rational_field.py, against SymPy's field).
"""
from __future__ import annotations

import flint
import sympy as sp


class LaurentQD:
    """``num * d^shift`` in the Laurent ring Q[d, 1/d], a subring of Q(d).

    The Frobenius recursion at the poles of omega only ever divides by ``d``, by constants and by
    the eigenvector norms ``2 p^2`` and ``-d^2`` (section 3.2: with a = p/d the norms l.v are
    ``a^2 d^2 + p^2 = 2 p^2`` and ``1 - (d^2+1) = -d^2``), all units of Q[d, 1/d].  So the
    recursion never leaves this ring, and there no gcd is needed: adding two elements aligns their
    shifts, multiplying adds them.  Division by anything else raises ``ArithmeticError`` (the
    element is not a unit here), so a result is never silently wrong.  The form is canonical
    (``num`` has a non-zero constant term, or is zero with shift 0): ``==`` and ``is_zero`` are exact.
    """

    __slots__ = ("num", "shift")

    def __init__(self, num, shift: int = 0, normal: bool = False):
        if not normal:
            if num.is_zero():
                shift = 0
            else:
                low = 0
                while num[low] == 0:
                    low += 1
                if low:
                    num, shift = num.right_shift(low), shift + low
        self.num, self.shift = num, shift

    @classmethod
    def constant(cls, value) -> LaurentQD:
        value = sp.Rational(value)
        return cls(flint.fmpq_poly([flint.fmpq(int(value.p), int(value.q))]))

    @classmethod
    def variable(cls) -> LaurentQD:
        return cls(flint.fmpq_poly([1]), 1, normal=True)

    def __add__(self, other: LaurentQD) -> LaurentQD:
        if self.num.is_zero():
            return other
        if other.num.is_zero():
            return self
        low, high = (self, other) if self.shift <= other.shift else (other, self)
        return LaurentQD(low.num + high.num.left_shift(high.shift - low.shift), low.shift,
                         normal=high.shift > low.shift)

    def __neg__(self) -> LaurentQD:
        return LaurentQD(-self.num, self.shift, normal=True)

    def __sub__(self, other: LaurentQD) -> LaurentQD:
        return self + (-other)

    def __mul__(self, other: LaurentQD) -> LaurentQD:
        product = self.num * other.num
        if product.is_zero():
            return LaurentQD(product)
        return LaurentQD(product, self.shift + other.shift, normal=True)   # Q[d] has no zero divisors

    def __truediv__(self, other: LaurentQD) -> LaurentQD:
        if other.num.is_zero():
            raise ZeroDivisionError("division by zero in Q[d, 1/d]")
        if other.num.degree() != 0:
            raise ArithmeticError(f"{other.to_sympy(sp.Symbol('d'))} is not a unit of Q[d, 1/d]")
        return LaurentQD(self.num / other.num[0], self.shift - other.shift, normal=True)

    def is_zero(self) -> bool:
        return self.num.is_zero()

    @classmethod
    def combination(cls, pairs) -> LaurentQD:
        """``sum c x`` over ``(c, x)`` pairs, ``c`` a python-flint ``fmpq``: one polynomial sum over the
        lowest shift instead of an element per product and per partial sum (exact, the same element)."""
        pairs = [(c, x) for c, x in pairs if c != 0 and not x.num.is_zero()]
        if not pairs:
            return cls(flint.fmpq_poly([]))
        low = min(x.shift for _, x in pairs)
        # over Z with one common denominator: a sum of fmpq_poly would reduce every partial sum by a gcd
        denominators = [c.q * x.num.denom() for c, x in pairs]
        common = flint.fmpz(1)
        for q in denominators:
            common = common // common.gcd(q) * q
        total = flint.fmpz_poly([])
        for (c, x), q in zip(pairs, denominators):
            total += x.num.numer().left_shift(x.shift - low) * (c.p * (common // q))
        return cls(flint.fmpq_poly(total, common), low)

    def __eq__(self, other) -> bool:
        return isinstance(other, LaurentQD) and self.shift == other.shift and self.num == other.num

    __hash__ = None

    def to_sympy(self, symbol) -> sp.Expr:
        poly = sp.Add(*(sp.Rational(int(c.p), int(c.q)) * symbol**i for i, c in enumerate(self.num.coeffs())))
        return poly * symbol**self.shift
