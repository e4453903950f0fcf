"""Differential rings in which the time-dependent formulas of the paper live.

The solutions of the reduced Euler equations (paper section 2, ``eq:o12``;
section 4, ``omegas``) are polynomials in ``T = tanh t`` and ``S = sech t``.
Those two generators satisfy

    dT/dt = S**2,    dS/dt = -S*T,    S**2 + T**2 = 1,

and the ideal ``(S**2 + T**2 - 1)`` is prime and is the only algebraic relation
between them, so an expression in ``T, S`` vanishes identically in ``t`` iff its
normal form modulo that relation is zero (``derivations.core.exact``).  Time
derivatives are computed with the chain rule on the generators, which keeps
every ODE residual inside the ring: no ``exp``, no ``simplify``.

The same module gives the Lie derivative of a function along a polynomial
vector field (first integrals, ``eq:ccalki``).
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derivations.core.exact import Domain, Extension

T, S = sp.symbols("T S")
t = sp.Symbol("t", real=True)

SECH_TANH = Extension(S, 1 - T**2, "S = sech t, T = tanh t, S^2 + T^2 = 1")


@dataclass(frozen=True)
class DifferentialRing:
    """Generators with their time derivatives, plus the domain for zero tests."""

    derivatives: dict
    domain: Domain
    realisation: dict  # generator -> the function of t it stands for

    def d_dt(self, expr: sp.Expr) -> sp.Expr:
        """Total time derivative of an expression in the generators."""
        expr = sp.sympify(expr)
        return sp.Add(*(sp.diff(expr, g) * dg for g, dg in self.derivatives.items()))

    def as_function_of_t(self, expr: sp.Expr) -> sp.Expr:
        """Replace generators by the functions of ``t`` they stand for."""
        return sp.sympify(expr).subs(self.realisation)


def hyperbolic_ring(name: str, *extensions: Extension) -> DifferentialRing:
    """The ring Q(params)[ext][T][S]/(S^2+T^2-1) with d/dt on T, S."""
    domain = Domain(name, tuple(extensions) + (SECH_TANH,))
    return DifferentialRing(
        derivatives={T: S**2, S: -S * T},
        domain=domain,
        realisation={T: sp.tanh(t), S: sp.sech(t)},
    )


def lie_derivative(function: sp.Expr, field: dict) -> sp.Expr:
    """Derivative of ``function`` along the vector field ``{x: dx/dt}``."""
    return sp.Add(*(sp.diff(function, x) * fx for x, fx in field.items()))


def ode_residuals(ring: DifferentialRing, solution: dict, field: dict) -> list[sp.Expr]:
    """``d/dt x(t) - f(x(t))`` for each component of a candidate solution.

    ``solution`` maps each state variable to its expression in the ring's
    generators; ``field`` maps each state variable to its right-hand side.
    """
    return [
        ring.d_dt(solution[x]) - sp.sympify(field[x]).subs(solution, simultaneous=True)
        for x in field
    ]
