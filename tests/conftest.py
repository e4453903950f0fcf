"""Shared fixtures: one certified build per test session (it takes about a second)."""
import pytest

from derivations.options import BuildOptions
from derivations.pipeline import derive


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
