"""Exact substitution x = e^t: the second exact route for solutions written in tanh t, sech t (eq:o12,
omegas) and for the printed examples of section 6.2, replacing the mpmath.diff spot checks.

With x = e^t, ``tanh t = (x^2 - 1)/(x^2 + 1)``, ``sech t = 2x/(x^2 + 1)`` and ``d/dt = x d/dx``: an ODE
residual becomes a rational function of x (and of the parameters), zero iff the identity holds for
every t.  Solutions with a rotating phase (the printed examples, cos(p t/d), sin(p t/d)) add the
generators ``C, Sn`` with ``C^2 + Sn^2 = 1`` and ``dC/dt = -(p/d) Sn``, ``dSn/dt = (p/d) C``: for d not
a rational multiple of pi's period structure, x, C, Sn are algebraically independent up to that single
relation (e^t and e^{i p t/d} with p/d real are independent transcendentals), so the zero test in
Q(params)(x)[C, Sn]/(C^2 + Sn^2 - 1) decides the identity in t.

Independent of ``derivations.core.differential`` (which differentiates in T, S): a different ring and
a different derivation, the same exact zero test (``derivations.core.exact``).
"""
from __future__ import annotations

import sympy as sp

from derivations.core.differential import S, T
from derivations.core.exact import Domain, Extension, certify_zero

X = sp.Symbol("x_t", positive=True)        # x = e^t
COS, SIN = sp.symbols("C_t S_t")           # cos(k t), sin(k t) of a rotating phase
PHASE = Extension(COS, 1 - SIN**2, "C_t = cos(k t), S_t = sin(k t)")
IN_X = {T: (X**2 - 1) / (X**2 + 1), S: 2 * X / (X**2 + 1)}


def in_exp(expr: sp.Expr) -> sp.Expr:
    """An expression in T = tanh t, S = sech t, rewritten in x = e^t."""
    return sp.sympify(expr).xreplace(IN_X)


def d_dt(expr: sp.Expr, rate: sp.Expr | None = None) -> sp.Expr:
    """d/dt = x d/dx (+ rate (C d/dSn - Sn d/dC) for a phase cos(rate t), sin(rate t))."""
    out = X * sp.diff(expr, X)
    if rate is not None:
        out += rate * (COS * sp.diff(expr, SIN) - SIN * sp.diff(expr, COS))
    return out


def ode_residuals_in_exp(solution: list, field: list, state: list) -> list:
    """x d/dx (solution) - field(solution), the solution given in T, S (the field is autonomous)."""
    in_x = [in_exp(s) for s in solution]
    values = dict(zip(state, in_x))
    return [d_dt(s) - sp.sympify(f).xreplace(values) for s, f in zip(in_x, field)]


def certify_ode_in_exp(log, claim: str, label: str, solution: list, field: list, state: list,
                       domain_name: str, extensions: tuple = (), expect=None):
    """Certify that ``solution`` (in T, S) solves ``state' = field`` by substituting x = e^t."""
    extra = {} if expect is None else {"expect": expect}
    return certify_zero(log, claim, label, ode_residuals_in_exp(solution, field, state),
                        Domain(domain_name, tuple(extensions)), **extra)
