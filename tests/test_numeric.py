"""Numeric corroboration: detects wrong solutions, refuses low precision."""
import pytest
import sympy as sp

from derivations.core.certificates import CertificateLog, Outcome
from derivations.core.numeric import corroborate, ode_residual

t, k, y = sp.symbols("t k y")


def test_correct_solution_passes_and_wrong_one_fails():
    # y' = -k y^2 has y = 1/(k t + 1)
    good = ode_residual([1 / (k * t + 1)], [-k * y**2], [y], t, [k])
    bad = ode_residual([1 / (k * t + 1) + sp.Rational(1, 10**12) * t], [-k * y**2], [y], t, [k])
    log = CertificateLog()
    ranges = {"t": (0, 2), "k": (0.5, 2)}
    assert corroborate(log, "good", "test", good, ranges, seed=1).outcome is Outcome.PASS
    assert corroborate(log, "bad", "test", bad, ranges, seed=1, expect=Outcome.FAIL).outcome is Outcome.FAIL


def test_low_precision_is_refused():
    with pytest.raises(ValueError, match="30"):
        corroborate(CertificateLog(), "x", "test", lambda p: (0, 1), {"t": (0, 1)}, seed=0, digits_required=20)
