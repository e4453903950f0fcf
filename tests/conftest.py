"""Shared fixtures: one certified build per test session (it takes about a second).

The build's certificate cache is off for the whole session (``SUSLOV_NO_CACHE``, inherited by the
``build_formulas.py`` subprocesses): tests that perturb a derivation at run time must not be
answered from a cache keyed by unchanged sources.  tests/test_cache.py turns it on in its own
temporary cache directory.
"""
import os

import pytest

os.environ["SUSLOV_NO_CACHE"] = "1"

from derivations.core.options import BuildOptions
from derivations.output.pipeline import derive


@pytest.fixture(scope="session")
def default_build():
    return derive(BuildOptions())


def circle_monodromy(matrix, center, radius, dim):
    """Monodromy of Y' = matrix(t) Y around the circle |t - center| = radius (SciPy DOP853, complex state).

    Shared by the logarithm tests: an independent numerical route to local monodromy.
    """
    import numpy as np
    from scipy.integrate import solve_ivp

    def rhs(th, y):
        t = center + radius * np.exp(1j * th)
        return (matrix(t) @ y.reshape(dim, dim) * 1j * radius * np.exp(1j * th)).ravel()

    sol = solve_ivp(rhs, (0, 2 * np.pi), np.eye(dim, dtype=complex).ravel(), method="DOP853", rtol=1e-12, atol=1e-12)
    return sol.y[:, -1].reshape(dim, dim)
