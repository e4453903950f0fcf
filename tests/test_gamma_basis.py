"""gamma_basis: Poisson solutions, orthonormal, stable; against independent references.

References: SciPy's DOP853 integrating eq:ps between two times; the mpmath twin
at 50 digits; the derivation's exact python-flint numerators evaluated with
mpmath at 60 digits (a different code path: no Fourier conversion, no template
recipe); the paper's printed p = 1 solution gamma^(1), typed here.
"""
import warnings

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from derivations.core.certificates import CertificateLog
from derivations.sections import meromorphic, meromorphic_printed
from generated import suslov_formulas as sf


def poisson_rhs(p, d):
    def rhs(t, g):
        w1, w2 = (float(v) for v in sf.omega(t, p, d))
        return [-w2 * g[2], w1 * g[2], w2 * g[0] - w1 * g[1]]
    return rhs


@pytest.mark.parametrize("p, d", [(1, 0.5), (3, 0.7), (7, 1.5), (15, 2.0), (15, 0.3)])
def test_rows_solve_poisson_by_independent_integration(p, d):
    t0, t1 = -1.5, 1.0
    start, end = sf.gamma_basis(t0, p, d), sf.gamma_basis(t1, p, d)
    for row in range(3):
        sol = solve_ivp(poisson_rhs(p, d), (t0, t1), start[row], method="DOP853", rtol=1e-12, atol=1e-13)
        assert np.max(np.abs(sol.y[:, -1] - end[row])) < 1e-9


@pytest.mark.parametrize("p", [1, 3, 9, 15])
@pytest.mark.parametrize("d", [1e-3, 0.05, 0.5, 2.0, 50.0, 1e3])
def test_orthonormal_rotation_everywhere(p, d):
    t = np.concatenate([np.linspace(-40, 40, 161), [-1e4, -1e-12, 0.0, 1e-12, 1e4]])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        B = sf.gamma_basis(t, p, d)
    assert B.shape == t.shape + (3, 3) and np.all(np.isfinite(B))
    gram = np.einsum("...ij,...kj->...ik", B, B)
    assert np.max(np.abs(gram - np.eye(3))) < 1e-13
    assert np.max(np.abs(np.linalg.det(B) - 1)) < 1e-13


@pytest.mark.parametrize("p, d", [(1, 0.5), (3, 0.5), (15, 0.05), (15, 2.0), (15, 50.0)])
def test_float_matches_mp_twin_at_50_digits(p, d):
    ts = [-1e4, -30.0, -2.0, -1e-9, 0.0, 1e-9, 0.4, 3.0, 30.0, 1e4]
    B = sf.gamma_basis(np.array(ts), p, d)
    for i, t in enumerate(ts):
        M = sf.gamma_basis_mp(t, p, d, dps=50)
        # 1e-13 absolute, plus the conditioning of the phase (p/d) t itself
        tol = 1e-13 + abs(t) * (p / d) * 4e-16
        assert max(abs(B[i][r][c] - float(M[r, c])) for r in range(3) for c in range(3)) < tol


@pytest.mark.parametrize("p", [1, 3, 5, 11])
def test_generated_recipe_equals_certified_numerators(p):
    basis = meromorphic.certify_p(CertificateLog(), p)
    d = mpmath.mpf(3) / 7
    for t in (mpmath.mpf("-1.3"), mpmath.mpf("0.05"), mpmath.mpf("2.2")):
        with mpmath.workdps(60):
            exact = meromorphic_printed.basis_mp(basis, t, d)
            twin = sf.gamma_basis_mp(t, p, d, dps=60)
            assert max(abs(exact[r][c] - twin[r, c]) for r in range(3) for c in range(3)) < mpmath.mpf(10) ** -45


def test_exact_values_of_the_certified_numerators_match_the_printed_p1_solution():
    """The round trip's exact route (float_paths.exact_basis_values) at x = e^t = 2/3, d = 3/4, c = 5/4:
    the paper's p = 1 gamma^(1) = (tanh t, -sech t / c, d sech t / c) with tanh t = -5/13, sech t = 12/13,
    typed here; and V -> (0, 1, i sigma) as x -> 0 (the numerators' own normalisation)."""
    from fractions import Fraction

    from derivations.output import float_paths

    real, cplx = meromorphic.construct(1)
    x, d, c = Fraction(2, 3), Fraction(3, 4), Fraction(5, 4)
    g1, G, sigma = float_paths.exact_basis_values((real.M, cplx.M), 1, x, d, c)
    assert g1 == [Fraction(-5, 13), Fraction(-48, 65), Fraction(36, 65)]
    assert sigma == sf._BASIS_SIGMA[1] == -1
    tiny = Fraction(1, 10**30)
    _, G0, _ = float_paths.exact_basis_values((real.M, cplx.M), 1, tiny, d, c)
    assert abs(G0[0][0]) + abs(G0[0][1]) < 1e-25 and abs(G0[1][0] - 1) < 1e-25 and abs(G0[1][1]) < 1e-25
    assert abs(G0[2][0]) < 1e-25 and abs(G0[2][1] - sigma) < 1e-25


def test_mp_twin_accuracy_is_set_by_dps_not_by_the_callers_precision():
    """Called at mpmath's default 15 digits with dps = 60 (as a user would), p = 1 must match the paper's
    printed gamma^(1) = (tanh t, -sech t / c, d sech t / c) to 1e-55; and two d that agree to 40 digits
    are two d (the coefficient cache is keyed by the exact value), so their results differ."""
    t, d = mpmath.mpf(0.25), mpmath.mpf(0.5)
    assert mpmath.mp.dps == 15
    M = sf.gamma_basis_mp(t, 1, d, dps=60)
    with mpmath.workdps(60):
        c = mpmath.sqrt(d * d + 1)
        printed = [mpmath.tanh(t), -mpmath.sech(t) / c, d * mpmath.sech(t) / c]
        assert max(abs(M[0, j] - printed[j]) for j in range(3)) < mpmath.mpf(10) ** -55
        assert abs(mpmath.det(M) - 1) < mpmath.mpf(10) ** -55
        near = d + mpmath.mpf(10) ** -45
    N = sf.gamma_basis_mp(t, 1, near, dps=60)
    with mpmath.workdps(60):
        c = mpmath.sqrt(near * near + 1)
        assert abs(N[0, 1] + mpmath.sech(t) / c) < mpmath.mpf(10) ** -55 and N[0, 1] != M[0, 1]


def test_boundary_condition_and_limits():
    for p in (1, 5, 15):
        B = sf.gamma_basis(np.array([-40.0, 40.0]), p, 0.8)
        assert np.allclose(B[0][0], [-1, 0, 0], atol=1e-15) and np.allclose(B[1][0], [1, 0, 0], atol=1e-15)
        # gamma^(2) + i gamma^(3) -> e^{i p t/d} (0, 1, -i) as t -> -oo
        phase = p / 0.8 * -40.0
        assert np.allclose(B[0][1], [0, np.cos(phase), np.sin(phase)], atol=1e-13)


def test_printed_p1_gamma1_agrees():
    d = 0.5
    t = np.linspace(-3, 3, 13)
    c = np.sqrt(d * d + 1)
    printed = np.stack([np.tanh(t), -1 / np.cosh(t) / c, d / np.cosh(t) / c], axis=-1)
    assert np.allclose(sf.gamma_basis(t, 1, d)[:, 0, :], printed, atol=1e-15)


@pytest.mark.parametrize("kwargs, needle", [
    ({"p": 2}, "p=2"), ({"p": 3.5}, "p=3.5"), ({"p": -3}, "p=-3"), ({"p": 10**6 + 1}, "certified range"),
    ({"d": 0.0}, "d=0.0"), ({"d": float("inf")}, "d=inf"), ({"t": np.nan}, "t"),
])
def test_bad_input(kwargs, needle):
    args = {"t": 0.0, "p": 3, "d": 1.0}
    args.update(kwargs)
    with pytest.raises(ValueError) as info:
        sf.gamma_basis(args["t"], args["p"], args["d"])
    assert needle in str(info.value)
