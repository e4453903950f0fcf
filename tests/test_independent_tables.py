"""Rigour that cannot be weakened silently (issue 27, finding 11).

1. The truncation bound of the validated integrator (``suslov.kernel.enclosure._truncation``) against
   the exact remainder of a Taylor series known in closed form: the worst case the bound must cover
   is a constant rotation with ||A||_2 = M, whose solution is e^{i M s}; its Taylor remainder after
   order N at h, evaluated with mpmath at 60 digits, must not exceed the bound.  For these
   parameters the exact remainder is 2% to 15% of the bound, so a bound understated by the
   factor (h/rho)^2 (the exponent N + 3 for N + 1) is refused.
2. The logarithm table (``monodromy_tables.tex``, rows from ``residue.logarithm_verdict``) against
   an independent recomputation: the Frobenius recursion at t0 = i pi/2 written again here in
   plain SymPy rational functions, with coth and csch expanded by SymPy's ``series`` (not the
   module's Bernoulli formula, Laurent ring or sparse matrices); the first two non-zero
   obstructions of every even p must be the ones the table prints.
"""
import mpmath
import pytest
import sympy as sp
from flint import arb

from derivations.core.options import BuildOptions
from derivations.core.typeset import breakable_product
from derivations.output.pipeline import derive
from suslov.kernel.enclosure import RHO, _truncation


def rotation_remainder(M, h, N):
    with mpmath.workdps(60):
        z = 1j * mpmath.mpf(M) * mpmath.mpf(h)
        return abs(mpmath.exp(z) - sum(z**k / mpmath.factorial(k) for k in range(N + 1)))


@pytest.mark.parametrize("N", [1, 2, 3, 4, 6, 8, 12, 20])
@pytest.mark.parametrize("M, h", [(2, 0.05), (4, 0.1), (8, 0.05), (20, 0.05), (50, 0.01), (1, 0.25)])
def test_truncation_bound_covers_the_exact_remainder(N, M, h):
    bound = _truncation(arb(1), arb(M), arb(h), N)
    assert rotation_remainder(M, h, N) <= mpmath.mpf(bound.mid().str(30, radius=False)) * (1 + 1e-20)


def test_truncation_bound_is_not_loose_where_it_matters():
    """The check above has teeth: at these points the remainder is within a factor 20 of the bound,
    while (h/rho)^2 (what one wrong exponent would remove) is smaller than 1/20."""
    for N, M, h in ((2, 4, 0.05), (4, 8, 0.05), (6, 20, 0.01), (8, 8, 0.05)):
        rho = min(RHO, max(2 * h, (N + 1) / M))
        ratio = rotation_remainder(M, h, N) / mpmath.mpf(float(_truncation(arb(1), arb(M), arb(h), N)))
        assert ratio > 1 / 20 > (h / rho) ** 2


d, tau = sp.symbols("d tau", positive=True)


def reference_obstructions(p):
    """Nonzero obstructions (k, value) of the chain from exponent -p, in plain SymPy."""
    a, e = sp.Integer(p) / d, d**2 + 1
    n = p + 2
    coth = sp.series(tau * sp.coth(tau), tau, 0, 2 * n + 2).removeO()
    csch = sp.series(tau * sp.csch(tau), tau, 0, 2 * n + 2).removeO()
    A = [sp.Matrix([[0, 0, a * csch.coeff(tau, 2 * k)], [0, 0, a * coth.coeff(tau, 2 * k)],
                    [a * e * csch.coeff(tau, 2 * k), -a * coth.coeff(tau, 2 * k), 0]]) for k in range(n)]
    eig = {}
    for nu in (-p, 0, p):
        right = sp.Matrix([1, e, 0]) if nu == 0 else sp.Matrix([a, a, nu])
        left = sp.Matrix([1, -1, 0]) if nu == 0 else sp.Matrix([a * e, -a, nu])
        eig[nu] = (right, left, sp.cancel(left.dot(right)))
    Y = {0: {"alpha": eig[-p][0]}}
    found = []
    for k in range(1, 2 * p + 1):
        rhs = {}
        for m in range(1, k // 2 + 1):
            for name, vec in Y.get(k - 2 * m, {}).items():
                rhs[name] = rhs.get(name, sp.zeros(3, 1)) + A[m] * vec
        mu, solution = k - p, {}
        for name, vec in rhs.items():
            vec = vec.applyfunc(sp.cancel)
            if vec == sp.zeros(3, 1):
                continue
            comps = sp.zeros(3, 1)
            for nu, (right, left, norm) in eig.items():
                weight = sp.cancel(left.dot(vec) / norm)
                if nu == mu:
                    if weight != 0:
                        found.append((k, weight))
                    continue
                comps += weight / (mu - nu) * right
            solution[name] = comps.applyfunc(sp.cancel)
        if mu in eig:
            solution[f"free{k}"] = eig[mu][0]
        if solution:
            Y[k] = solution
    return found


@pytest.fixture(scope="module")
def log_rows():
    return {row["p"]: row for row in derive(BuildOptions(pmax=6), ["residue"]).results["residue"].exports["log_rows"]}


@pytest.mark.parametrize("p", [1, 2, 3, 4, 6])
def test_logarithm_table_matches_an_independent_recursion(log_rows, p):
    reference = reference_obstructions(p)
    row = log_rows[p]
    assert (row["verdict"] == "no logarithms") == (not reference) == (p % 2 == 1)
    assert row["obstructions"] == [breakable_product(value) for _, value in reference][:2]


def majorant_partial_tail(W, x, k, terms=3000):
    """sqrt(3) sum_(m = k+1 .. k+terms) b_m x^m with b_0 = 1, b_m = (W/m)(b_0 + ... + b_(m-1)), in mpmath."""
    with mpmath.workdps(40):
        W, x = mpmath.mpf(W), mpmath.mpf(x)
        b, total, tail = [mpmath.mpf(1)], mpmath.mpf(1), mpmath.mpf(0)
        for m in range(1, k + terms + 1):
            b.append(W * total / m)
            total += b[-1]
            if m > k:
                tail += b[-1] * x**m
        return mpmath.sqrt(3) * tail, b[k]


@pytest.mark.parametrize("W, x, k", [(0.3, 0.22, 5), (0.8, 0.5, 12), (0.05, 0.9, 3), (2.5, 0.22, 8), (7.0, 0.1, 20)])
def test_limit_series_tail_bound_covers_the_majorant_tail(W, x, k):
    """The limit series' remainder bound (enclosure._majorant_tail) is at least the majorant's own tail,
    summed directly (3000 terms: a lower estimate of the full tail), for W below and above 1."""
    from suslov.kernel.enclosure import _majorant_tail

    direct, b_k = majorant_partial_tail(W, x, k)
    bound = _majorant_tail(arb(str(b_k)), k, arb(W), arb(x) ** k, arb(x))
    assert bound is not None
    assert direct <= mpmath.mpf(bound.mid().str(30, radius=False)) * (1 + 1e-12) + 1e-25


def test_every_steps_truncation_bound_enters_the_final_radius(monkeypatch):
    """With each step's truncation bound forced to 1e-12, the accumulated error (and so the radius of
    cos Delta psi) must be at least steps x 1e-12: the bound of every step is carried, none dropped."""
    from derivations.sections.scattering_balls import omega_pd
    from suslov.kernel import enclosure

    monkeypatch.setattr(enclosure, "_truncation", lambda *a: arb("1e-12"))
    result = enclosure.ss_angle_enclosure(*omega_pd(arb(3), arb("0.5")), digits=8)
    assert result.error_budget["steps"] >= result.steps * 1e-12
    assert float(result.cos_angle.rad()) >= result.steps * 1e-12
