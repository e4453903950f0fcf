"""The closed-form angle's connection step from Kummer's Gamma-function coefficients, in mpmath (issue 45).

The build certifies (``general_angle._kummer_connection``, an exact zero test after the reflection formula) that
the diagonal product ``a d`` of the loop matrix about s = i, computed from Gauss's connection formulas, equals the
one of the monodromy relation, and ``cos^2(Delta psi/2) = a d``.  Here the same route is walked numerically with
the Gamma functions themselves (no reflection formula, no trigonometric form): the connection coefficients
``P11, P12, P21, P22`` (DLMF 15.8.2 for f1 and for f2's parameters) in mpmath at 50 digits, ``rho = P12 P21/(P11
P22)``, ``a d = e^(2 pi i kappa)(1 - lam rho)(lam - rho)/(1 - rho)^2``, against the public
``general_scattering_angle_mp`` (the emitted evaluation form) on seeded bodies, both branches of kappa.
"""
import mpmath
import pytest

from derivations.sections.general_angle import seeded_bodies
from generated.suslov_formulas import general_scattering_angle_mp
from suslov.kernel.kimura import exact_body, exact_invariants

DPS = 50


def _gauss_data(body, branch):
    a11, a22, a13, a23 = exact_body(*body)
    inv = exact_invariants(a11, a22, a13, a23)
    q, R = inv["Im w_-^2"]
    U = mpmath.sqrt(mpmath.mpf(inv["U^2"].numerator) / inv["U^2"].denominator)
    w2 = (mpmath.mpf(inv["Re w_-^2"].numerator) / inv["Re w_-^2"].denominator
          + 1j * mpmath.mpf(q.numerator) / q.denominator * mpmath.sqrt(mpmath.mpf(R.numerator) / R.denominator))
    kappa = branch * 0.5j * mpmath.sqrt(w2)
    mu = -mpmath.conj(kappa)
    return kappa, mu, U


def _ad_from_gamma(kappa, mu, U):
    G = mpmath.gamma
    A, B, C = (2 + kappa + mu + 1j * U) / 2, (kappa + mu - 1j * U) / 2, 1 + kappa
    P11 = G(C) * G(B - A) / (G(B) * G(C - A))
    P12 = G(C) * G(A - B) / (G(A) * G(C - B))
    A2, B2, C2 = A - C + 1, B - C + 1, 2 - C           # f2 = z^(1-C) F(A2, B2; C2; z)
    P21 = G(C2) * G(B2 - A2) / (G(B2) * G(C2 - A2))
    P22 = G(C2) * G(A2 - B2) / (G(A2) * G(C2 - B2))
    rho = P12 * P21 / (P11 * P22)
    lam = mpmath.exp(-2j * mpmath.pi * kappa)
    return mpmath.exp(2j * mpmath.pi * kappa) * (1 - lam * rho) * (lam - rho) / (1 - rho) ** 2


@pytest.mark.parametrize("body", seeded_bodies()[:6] + [("2", "1", "0", "-2/5"), ("5/4", "1", "3/10", "-1/2")])
@pytest.mark.parametrize("branch", [1, -1])
def test_gamma_connection_gives_the_emitted_angle(body, branch):
    with mpmath.workdps(DPS):
        ad = _ad_from_gamma(*_gauss_data(body, branch))
        angle = general_scattering_angle_mp(*body, dps=DPS)
        expected = mpmath.cos(angle / 2) ** 2
        assert abs(mpmath.im(ad)) < mpmath.mpf(10) ** (10 - DPS)
        assert abs(mpmath.re(ad) - expected) < mpmath.mpf(10) ** (10 - DPS)
