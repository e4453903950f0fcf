"""A sparse multivariate polynomial with generic coefficients, for the shared recipes.

The recipes of :mod:`suslov.recipes` are written once with ``+``, ``-``, ``*``, ``**``
and a few ring operations; the build runs them on python-flint's ``fmpz_mpoly`` /
``fmpq_mpoly`` (exact, symbolic d) and the generated module runs them on
:class:`Sparse` with ``Fraction`` or ``mpmath`` coefficients (numeric d).  Only what the
recipes use is implemented: ring arithmetic, partial derivatives, exact division by a
monic polynomial in one variable, and the substitution x -> x^2.

Coefficients may be any objects with ``+``, ``-``, ``*`` (int, Fraction, mpf, mpc);
zero coefficients are dropped, so equality is structural.
"""
from __future__ import annotations

__all__ = ["Sparse"]


class Sparse:
    """Polynomial in ``nvars`` variables: ``{exponent tuple: coefficient}``.

    >>> x, y = Sparse.gens(2)
    >>> ((x + y) ** 2).terms == {(2, 0): 1, (1, 1): 2, (0, 2): 1}
    True
    """

    __slots__ = ("nvars", "terms")

    def __init__(self, nvars: int, terms: dict | None = None):
        self.nvars = nvars
        self.terms = {m: c for m, c in (terms or {}).items() if c != 0}

    @classmethod
    def gens(cls, nvars: int) -> list["Sparse"]:
        return [cls(nvars, {tuple(int(i == k) for i in range(nvars)): 1}) for k in range(nvars)]

    def constant(self, value) -> "Sparse":
        return Sparse(self.nvars, {(0,) * self.nvars: value})

    def _lift(self, other) -> "Sparse":
        return other if isinstance(other, Sparse) else self.constant(other)

    def __add__(self, other):
        other = self._lift(other)
        out = dict(self.terms)
        for m, c in other.terms.items():
            out[m] = out[m] + c if m in out else c
        return Sparse(self.nvars, out)

    __radd__ = __add__

    def __neg__(self):
        return Sparse(self.nvars, {m: -c for m, c in self.terms.items()})

    def __sub__(self, other):
        return self + (-self._lift(other))

    def __rsub__(self, other):
        return self._lift(other) - self

    def __mul__(self, other):
        if not isinstance(other, Sparse):
            return Sparse(self.nvars, {m: c * other for m, c in self.terms.items()})
        out: dict = {}
        for m1, c1 in self.terms.items():
            for m2, c2 in other.terms.items():
                m = tuple(a + b for a, b in zip(m1, m2))
                out[m] = out[m] + c1 * c2 if m in out else c1 * c2
        return Sparse(self.nvars, out)

    __rmul__ = __mul__

    def __pow__(self, n: int):
        if not isinstance(n, int) or n < 0:
            raise ValueError(f"exponent {n!r}: must be a non-negative integer")
        result, base = self.constant(1), self
        while n:
            if n & 1:
                result = result * base
            base = base * base
            n >>= 1
        return result

    def __eq__(self, other):
        other = self._lift(other)
        return self.terms == other.terms

    def __hash__(self):  # pragma: no cover - mutable-looking value type, hash by content
        return hash(frozenset(self.terms.items()))

    def is_zero(self) -> bool:
        return not self.terms

    def derivative(self, k: int) -> "Sparse":
        out = {}
        for m, c in self.terms.items():
            if m[k]:
                e = list(m)
                e[k] -= 1
                out[tuple(e)] = c * m[k]
        return Sparse(self.nvars, out)

    def map_coefficients(self, f) -> "Sparse":
        return Sparse(self.nvars, {m: f(c) for m, c in self.terms.items()})

    def square_variable(self, k: int) -> "Sparse":
        """Substitute x_k -> x_k^2."""
        return Sparse(self.nvars, {m[:k] + (2 * m[k],) + m[k + 1:]: c for m, c in self.terms.items()})

    def coefficient_list(self, k: int = 0) -> list:
        """Coefficients by the degree in x_k (a univariate polynomial; other exponents must be 0)."""
        if not self.terms:
            return [0]
        degree = max(m[k] for m in self.terms)
        out = [0] * (degree + 1)
        for m, c in self.terms.items():
            if any(e for i, e in enumerate(m) if i != k):
                raise ValueError("coefficient_list: the polynomial depends on other variables")
            out[m[k]] = c
        return out

    def divide_exact(self, divisor: "Sparse", k: int = 0) -> tuple["Sparse", bool]:
        """(quotient, remainder == 0) of division by a polynomial monic in x_k (univariate in x_k)."""
        b = divisor.coefficient_list(k)
        if b[-1] != 1:
            raise ValueError("divide_exact: the divisor must be monic")
        a = self.coefficient_list(k)
        n = len(b) - 1
        quotient = [0] * max(len(a) - n, 1)
        for i in range(len(a) - n - 1, -1, -1):
            q = a[i + n]
            quotient[i] = q
            for j, v in enumerate(b):
                a[i + j] = a[i + j] - q * v
        unit = tuple(int(i == k) for i in range(self.nvars))
        out = {tuple(e * deg for e in unit): c for deg, c in enumerate(quotient)}
        return Sparse(self.nvars, out), all(v == 0 for v in a[:n])
