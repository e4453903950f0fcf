"""The Laurent series of coth and csch that derivations/sections/residue.py takes as input are certified.

A fault in the series (the fault-injection run changed 2^(2k-1) - 1 into 2^(2k-1) + 1 in csch and
passed the whole build before this certificate existed) must now fail.
"""
import pytest
import sympy as sp

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.sections.residue import certify_laurent_series, laurent_coefficients


def test_the_series_used_by_the_build_are_certified():
    coth, csch = laurent_coefficients(17)
    assert certify_laurent_series(CertificateLog(), coth, csch).outcome is Outcome.PASS


def test_the_injected_csch_fault_is_rejected():
    n = 9
    coth, _ = laurent_coefficients(n)
    faulty = [-2 * (sp.Integer(2) ** (2 * k - 1) + 1) * sp.bernoulli(2 * k) / sp.factorial(2 * k) for k in range(n + 1)]
    with pytest.raises(CertificationFailure, match="Laurent series"):
        certify_laurent_series(CertificateLog(), coth, faulty)


def test_one_changed_coth_coefficient_is_rejected():
    coth, csch = laurent_coefficients(6)
    coth = list(coth)
    coth[4] = coth[4] * (1 + sp.Rational(1, 10**6))
    with pytest.raises(CertificationFailure):
        certify_laurent_series(CertificateLog(), coth, csch)
