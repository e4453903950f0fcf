"""The differential Galois group of the Poisson equations of every body, decided exactly (Kimura's theorem).

The general case in closed form (``derivations/sections/gauss.py``, ``general_galois.py``): in
``s = sinh t`` the spinor lift of the Poisson equations is gauge-equivalent over C(s) to Gauss's
equation with exponent differences ``kappa = (i/2) w_-`` (z = 0), ``mu = (i/2) w_+`` (z = 1) and
``1 + i U`` (z = oo); ``w_-^2 = a + i b``, ``a = |u|^2 - |v|^2``, ``b = -2 u.v``.  Kimura (1969): the
equation has Liouvillian solutions iff (i) one of ``+-kappa +- mu +- (1 + iU)`` is an odd integer, or
(ii) ``(kappa, mu, 1 + iU)`` up to signs and integer shifts is on Schwarz's list.

* (i) never holds for a body: u, v are real, so ``mu = -conj(kappa)``, ``kappa + mu = i X`` is imaginary
  and ``kappa - mu = -Y`` real (``w_- = X + iY``); ``i X +- (1 + i U)`` is an odd integer only for
  ``X = U``, i.e. ``(u x v)_3 = 0`` (the gap ``U^2 - X^2 = 2 (u x v)_3^2/(...)``), and for a body
  ``(u x v)_3 = -I11 I22 r/D != 0``; ``-Y +- (1 + iU)`` has imaginary part ``+-U != 0``.
* (ii): every family but the first needs three real rational entries, and ``1 + iU`` is not real
  (``U > 0``).  The first family, ``(1/2 + l, 1/2 + m, any)``, needs ``kappa`` and ``mu`` half-odd:
  ``w_-^2 = -(odd)^2``, i.e. ``u.v = 0`` (``I13 I23 (I11 - I22) = 0``) and ``-a`` the square of an
  odd integer P.  Then ``w_-^2 = -conj(Lambda^2)`` says ``Lambda^2 = P^2``: the Kovalevskaya exponent is
  an odd integer, for I13 = 0 the paper's odd p (and by eq:lina the mirror case I23 = 0).

The group itself.  Not Liouvillian: the identity component is not solvable, so the spinor group is
SL(2, C) and the Poisson group (its adjoint image) SO(3, C), over C(s) and over C(e^t) alike (a
finite extension keeps the identity component).  Liouvillian: over C(s) the local monodromies at
s = +-i have trace 0 (order 4) and the one at infinity eigenvalues ``e^(-+pi U)`` (infinite order),
so the spinor group is the normaliser of a torus (imprimitive, infinite dihedral); over C(e^t), the
field of the paper's equations, x = e^t is a double cover ramified at s = +-i (``s - i ~ (x - i)^2``):
the loops about x = +-i are the squares ``M_(+-i)^2 = -I`` and the Poisson group is the closure of
``<Ad M_oo>``, the torus SO(2, C) of rotations about n = u/|u|: **reducible**, abelian.

Exact arithmetic throughout (Fractions; decimal strings and floats are read as the numbers they
are: ``"-0.3333333333333333"`` is not -1/3).  No SymPy.
"""
from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import isqrt

from suslov.kernel.reprs import galois_html, galois_latex
from suslov.kernel.validate import rational, shown

__all__ = ["GaloisGroup", "exact_body", "exact_invariants", "galois_group"]

NAMES = ("I11", "I22", "I13", "I23")
METHOD = ("exact: Kimura's theorem on Gauss's equation of the body (exponent differences kappa, mu, 1 + iU), "
          "decided in rational arithmetic (u.v = 0 iff I13 I23 (I11 - I22) = 0; then w_-^2 = |u|^2 - |v|^2 "
          "must be minus the square of an odd integer)")


@dataclass(frozen=True)
class GaloisGroup:
    """The differential Galois group of the Poisson equations of one body (over C(e^t))."""

    group: str                 # "reducible" (the torus SO(2,C)) or "SO(3,C)"
    liouvillian: bool
    method: str
    spinor_group: str          # over C(sinh t): "imprimitive (normaliser of a torus)" or "SL(2,C)"
    reason: str
    P: int | None = None       # the odd integer with w_-^2 = -P^2 (Liouvillian case)

    @property
    def identity_component(self) -> str:
        return "SO(2,C)" if self.liouvillian else "SO(3,C)"

    def _repr_latex_(self) -> str:   # notebooks: the group in math (suslov.kernel.reprs)
        return galois_latex(self)

    def _repr_html_(self) -> str:    # notebooks: the verdict first, then why
        return galois_html(self)


def exact_body(I11, I22, I13, I23) -> tuple:
    """The four entries as Fractions, validated: each at most ``MAX_ENTRY_BITS`` (:func:`suslov.kernel.validate.rational`,
    strings measured before conversion), I11, I22 > 0, not I13 = I23 = 0 (ValueError naming the field)."""
    values = tuple(rational(n, x) for n, x in zip(NAMES, (I11, I22, I13, I23)))
    for name, x in zip(NAMES[:2], values[:2]):
        if x <= 0:
            raise ValueError(f"{name}={shown(x)}: must be positive (a principal moment of the paper's frame)")
    if values[2] == 0 and values[3] == 0:
        raise ValueError("I13=0 and I23=0: the constraint axis is a principal axis; every motion is an equilibrium "
                         "(no Poisson equations with omega = u tanh t + v sech t)")
    return values


def exact_invariants(a11: Fraction, a22: Fraction, a13: Fraction, a23: Fraction) -> dict:
    """U^2, Re w_-^2 = |u|^2 - |v|^2 and Im w_-^2 = q sqrt(R) as (q, R), exactly (certified forms: gauss)."""
    den = a11 * a23 * a23 + a13 * a13 * a22
    return {"U^2": a11 * a11 * a22 * a22 * (a13 * a13 + a23 * a23) / den**2,
            "Re w_-^2": a11 * a22 * (a11 - a22) * (a13 * a13 * a22 - a11 * a23 * a23) / den**2,
            "Im w_-^2": (-2 * a11 * a13 * a22 * a23 * (a11 - a22) / den**2, a11 * a22)}


def galois_group(I11, I22, I13, I23) -> GaloisGroup:
    """Decide the Galois group exactly (module docstring): never "unknown" for exact input.

    >>> galois_group(2, 1, 0, "-1/3").group       # I13 = 0, p = 3 (odd)
    'reducible'
    >>> galois_group(2, 1, 0, "-0.3333333333333333").group   # not -1/3: p^2 is not an integer
    'SO(3,C)'
    """
    a11, a22, a13, a23 = values = exact_body(I11, I22, I13, I23)
    if a13 * a23 * (a11 - a22) != 0:
        return GaloisGroup("SO(3,C)", False, METHOD, "SL(2,C)",
                           "u.v != 0 (I13 I23 (I11 - I22) != 0): w_-^2 is not real, kappa is not half-odd, and no "
                           "reducible case exists ((u x v)_3 != 0): not Liouvillian")
    a = exact_invariants(*values)["Re w_-^2"]     # = w_-^2 here (u.v = 0)
    minus = -a
    root = isqrt(minus.numerator) if minus > 0 and minus.denominator == 1 else None
    if root is not None and root * root == minus.numerator and root % 2 == 1:
        return GaloisGroup("reducible", True, METHOD, "imprimitive (normaliser of a torus)",
                           f"u.v = 0 and w_-^2 = -{root}^2 (odd): kappa, mu half-odd (Kimura's first family); over "
                           "C(e^t) the loops about x = +-i are trivial and the group is the torus of rotations about "
                           "n = u/|u|", root)
    return GaloisGroup("SO(3,C)", False, METHOD, "SL(2,C)",
                       f"u.v = 0 but w_-^2 = {a} is not minus the square of an odd integer: kappa is not half-odd; "
                       "not Liouvillian")
