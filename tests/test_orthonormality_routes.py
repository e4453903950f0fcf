"""Orthonormality of the odd-p bases (sections 5.1, 6.1; gam1, gam2, gam3): two certificate routes.

``derivations.sections.meromorphic.certify_p`` certifies orthonormality either by expanding the four
product identities (direct, exact zero tests) or by the conservation argument (products of two
solutions of the certified G-skew Poisson system are constant; constants from x = 0).  The routes
must agree on the true bases, and both must refuse a basis that solves the Poisson equations but is
not normalised (gamma^(1) scaled by 2: still a solution, |gamma^(1)| = 2).
"""
import dataclasses

import pytest

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.sections import meromorphic

ORTHONORMAL = "gam1, gam2, gam3"


def orthonormality(p, direct):
    log = CertificateLog(derivation="meromorphic")
    meromorphic.certify_p(log, p, direct=direct)
    (cert,) = [c for c in log.certificates if c.label == ORTHONORMAL]
    return cert


@pytest.mark.parametrize("p", [1, 3, 7, 17])
def test_both_routes_pass_on_the_true_basis(p):
    direct, conserved = orthonormality(p, True), orthonormality(p, False)
    assert direct.outcome is conserved.outcome is Outcome.PASS
    assert "conservation" in conserved.method and "exact zero test" in direct.method


@pytest.mark.parametrize("direct", [True, False])
def test_a_scaled_solution_is_refused(monkeypatch, direct):
    original = meromorphic.construct

    def scaled(p):
        real, cplx = original(p)
        return dataclasses.replace(real, M=[2 * c for c in real.M]), cplx

    monkeypatch.setattr(meromorphic, "construct", scaled)
    with pytest.raises(CertificationFailure) as failure:
        meromorphic.certify_p(CertificateLog(derivation="meromorphic"), 5, direct=direct)
    assert failure.value.certificate.label == ORTHONORMAL


def test_the_metric_is_conserved_by_the_poisson_system():
    log = CertificateLog(derivation="meromorphic")
    assert meromorphic.conservation_certificate(log).outcome is Outcome.PASS
