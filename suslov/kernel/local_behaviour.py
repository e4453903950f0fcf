"""Meromorphic, logarithmic or branching at the poles of omega: the theorem for every body, decided exactly.

Paper: Theorem 3.2 (eq:necc1), section 3.2 and Conjecture 1.  The theorem and its proof are certified by
the build (:mod:`derivations.sections.pole_theorem`): at every pole t0 = +-i pi/2 + i pi k of
``omega = u tanh t + v sech t`` the Poisson equations have exponents 0, +-conj(Lambda), where
``Lambda^2 = -conj(w_-^2)`` is the Kovalevskaya exponent's square, and

* Lambda an odd integer: every solution is meromorphic at t0;
* Lambda an even integer (0 included): a logarithm at t0;
* otherwise a branch point (a loop about t0 multiplies some solution by ``e^(2 pi i Lambda) != 1``).

Decision, in rational arithmetic (the invariants of :func:`suslov.kernel.kimura.exact_invariants`): Lambda^2
is real only when ``u.v = 0``, i.e. ``I13 I23 (I11 - I22) = 0``; then ``Lambda^2 = -Re w_-^2`` and Lambda is an
integer iff that rational is the square of an integer.  Entries are read exactly (decimal strings as the
decimals they are, floats as their binary values) and bounded in size before any work
(:func:`suslov.kernel.validate.rational`).  No SymPy; microseconds per body.
"""
from __future__ import annotations

from dataclasses import dataclass
from math import isqrt

from suslov.kernel.kimura import exact_body, exact_invariants
from suslov.kernel.reprs import local_latex
from suslov.kernel.validate import shown

__all__ = ["LocalBehaviour", "classify", "local_behaviour"]

METHOD = ("exact: the certified theorem (pole_theorem: the local monodromy of Gauss's equation at s = +-i, "
          "two loops per pole of omega) decided in rational arithmetic")


@dataclass(frozen=True)
class LocalBehaviour:
    """The solutions of the Poisson equations of one body at the poles of omega (every pole alike)."""

    kind: str                        # "meromorphic", "logarithmic" or "branching"
    lambda_squared: tuple            # (real part, imaginary part) of Lambda^2; the imaginary part as (q, R): q sqrt(R)
    Lambda: int | None               # |Lambda| when it is an integer, else None
    exponents: str                   # the local exponents at t0 (in t), as text
    reason: str
    method: str = METHOD

    @property
    def meromorphic(self) -> bool:
        return self.kind == "meromorphic"

    @property
    def logarithmic(self) -> bool:
        return self.kind == "logarithmic"

    @property
    def branching(self) -> bool:
        return self.kind == "branching"

    def _repr_html_(self) -> str:   # notebooks: the verdict first, then why
        return f"<b>{self.kind}</b> at every pole of &omega;: {self.reason}"

    def _repr_latex_(self) -> str:  # notebooks: Lambda and the exponents in math (suslov.kernel.reprs)
        return local_latex(self)


def local_behaviour(I11, I22, I13, I23) -> LocalBehaviour:
    """Decide, exactly, whether the Poisson solutions are meromorphic, logarithmic or branching at the poles of omega.

    ``I11, I22 > 0`` and ``(I13, I23) != (0, 0)`` (ValueError naming the field otherwise, as
    :func:`suslov.kernel.kimura.galois_group`).

    >>> local_behaviour(2, 1, 0, "-1/3").kind        # I13 = 0, p = 3
    'meromorphic'
    >>> local_behaviour(2, 1, 0, "-1/2").kind        # p = 2
    'logarithmic'
    >>> local_behaviour(2, 1, 0, "-0.3333333333333333").kind   # not -1/3: p^2 is not an integer
    'branching'
    >>> local_behaviour("5/4", 1, "3/10", "-1/2").kind          # u.v != 0
    'branching'
    """
    a11, a22, a13, a23 = values = exact_body(I11, I22, I13, I23)
    invariants = exact_invariants(*values)
    q, R = invariants["Im w_-^2"]
    lambda_squared = (-invariants["Re w_-^2"], (q, R))     # Lambda^2 = -conj(w_-^2)
    if a13 * a23 * (a11 - a22) != 0:
        return classify(None, lambda_squared, "u.v != 0 (I13 I23 (I11 - I22) != 0)")
    return classify(-invariants["Re w_-^2"], lambda_squared, "u.v = 0")


def classify(real_square, lambda_squared, why_uv: str, method: str = METHOD) -> LocalBehaviour:
    """The theorem's verdict from Lambda^2: ``real_square`` is Lambda^2 when it is real (u.v = 0, a Fraction), else
    None (then Lambda is not real, hence not an integer); ``why_uv`` says how u.v was decided (shown in the reason)."""
    if real_square is None:
        return LocalBehaviour("branching", lambda_squared, None, "0, +-conj(Lambda) with Lambda not real",
                              f"{why_uv}: Lambda^2 is not real, so Lambda is not an integer and a loop about a pole "
                              "multiplies a solution by e^(2 pi i Lambda) != 1", method)
    square = real_square
    root = isqrt(square.numerator) if square >= 0 and square.denominator == 1 else None
    if root is None or root * root != square.numerator:
        return LocalBehaviour("branching", lambda_squared, None, f"0, +-Lambda with Lambda^2 = {shown(square)}",
                              f"{why_uv} and Lambda^2 = {shown(square)} is not the square of an integer: a loop about a "
                              "pole multiplies a solution by e^(2 pi i Lambda) != 1", method)
    exponents = f"0, +-{root}" if root else "0, 0, 0"
    if root % 2:
        return LocalBehaviour("meromorphic", lambda_squared, root, exponents,
                              f"{why_uv} and Lambda = {root} is odd: the spinor's local monodromy M has trace 0, M^2 = -I, "
                              "and the Poisson solutions are single-valued, hence meromorphic, at every pole", method)
    return LocalBehaviour("logarithmic", lambda_squared, root, exponents,
                          f"{why_uv} and Lambda = {root} is even: Gauss's A = 1 + iU/2 and B = -iU/2 are not integers, so "
                          "the integer exponent difference brings a logarithm at every pole", method)
