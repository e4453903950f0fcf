"""heyoka Taylor route (suslov.simulator.taylor) against independent references.

Expected values come from the certified closed forms (``scattering_angle``, ``gamma_basis``), the
rigorous ball enclosure (``suslov.validated``) and the SciPy route's own series start
(``integrate.ss_initial``), never from suslov.simulator.taylor itself.
"""
import doctest

import numpy as np
import pytest

from generated import suslov_formulas as gf
from suslov.simulator import integrate, taylor
from suslov.simulator.body import make_body
from suslov.validated import scattering_angle_enclosure

pytest.importorskip("heyoka")   # suslov.simulator.taylor imports it only when an integrator is built

GENERAL = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]


@pytest.fixture(scope="module")
def general_enclosure():
    return scattering_angle_enclosure(*make_body(GENERAL).entries, dps=20, method="integration")


@pytest.mark.parametrize("p, d", [(2.5, 0.7), (3, 0.5), (7.5, 0.2), (0.3, 3.0), (11.2, 0.05)])
def test_angle_matches_closed_form(p, d):
    """The general-body definition reduces to Theorem 5.4 for I13 = 0, fast rotation (p/d up to 224) included."""
    body = make_body(p=p, d=d)
    angle, error, run = taylor.taylor_angle(body)
    assert abs(angle - float(gf.scattering_angle(p, d))) < 1e-10
    assert error < 1e-9
    assert run.max_step == taylor.TRANSITION_CAP / body.rate   # the transition cap is applied


def test_angle_general_body_matches_enclosure(general_enclosure):
    assert general_enclosure.width < 1e-15
    angle, error, run = taylor.taylor_angle(make_body(GENERAL))
    assert abs(angle - float(general_enclosure.angle.mid())) < 1e-10
    assert error < 1e-9
    assert run.error_estimate > 0   # the check run does not repeat the main run's arithmetic (CHECK_CAP)


def test_angle_general_body_at_two_energies(general_enclosure):
    bodies = [make_body(GENERAL, energy=energy) for energy in (0.5, 4.0)]
    assert abs(bodies[0].rate - bodies[1].rate) > 0.1   # different lam: not assumed away
    for body in bodies:
        angle, error, run = taylor.taylor_angle(body)
        assert abs(angle - float(general_enclosure.angle.mid())) < 1e-10
        assert error < 1e-9
        assert run.max_step == taylor.TRANSITION_CAP / body.rate


def test_basis_p3_from_its_initial_value():
    body = make_body(p=3, d=0.5)
    t = np.linspace(-8.0, 8.0, 33)
    basis = gf.gamma_basis(body.rate * t, 3, 0.5)            # rows gamma^(1..3), shape (33, 3, 3)
    run = taylor.solve_poisson_taylor(body, t, basis[0])
    assert run.values.shape == (33, 3, 3)
    assert np.max(np.abs(run.values - basis)) < 1e-9
    assert run.norm_drift < 1e-10 and run.error_estimate < 1e-9
    assert run.max_step == integrate.max_step_for(body)


def test_basis_p3_from_identity():
    body = make_body(p=3, d=0.5)
    t = np.linspace(-8.0, 8.0, 33)
    basis = gf.gamma_basis(body.rate * t, 3, 0.5)
    run = taylor.solve_poisson_taylor(body, t, np.eye(3))     # Y(t0) = I, so B(t) = B(t0) Y(t)
    assert np.max(np.abs(basis[0] @ run.values - basis)) < 1e-9
    assert run.norm_drift < 1e-10


def test_start_before_the_grid():
    body = make_body(p=3, d=0.5)
    t0, t = -6.0, np.linspace(-2.0, 5.0, 8)
    basis = gf.gamma_basis(body.rate * np.concatenate([[t0], t]), 3, 0.5)
    run = taylor.solve_poisson_taylor(body, t, basis[0, 0], t_start=t0)   # gamma^(1), one solution
    assert run.values.shape == (8, 1, 3)
    assert np.max(np.abs(run.values[:, 0] - basis[1:, 0])) < 1e-9


def test_compiled_once_for_two_bodies():
    taylor.taylor_angle(make_body(p=2.5, d=0.7))
    before = taylor.integrator.cache_info()
    taylor.taylor_angle(make_body(GENERAL, energy=2.0))
    after = taylor.integrator.cache_info()
    assert after.misses == before.misses and after.hits > before.hits


@pytest.mark.parametrize("body", [make_body(GENERAL), make_body(GENERAL, energy=4.0), make_body(p=2.5, d=0.7),
                                  make_body(p=0.3, d=3.0)], ids=["general", "general E=4", "p=2.5", "p=0.3"])
def test_series_start_matches_integrate(body):
    t_ref, g_ref = integrate.ss_initial(body, integrate.SERIES_START / body.rate)
    t_start, g0 = taylor._ss_start(body)
    assert t_start == pytest.approx(t_ref, rel=1e-15)
    assert np.max(np.abs(np.array(g0) - g_ref)) < 1e-14


def test_errors():
    body = make_body(p=3, d=0.5)
    with pytest.raises(ValueError, match="cosh overflows"):
        taylor.solve_poisson_taylor(body, [0.0, 800.0], [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="strictly increasing"):
        taylor.solve_poisson_taylor(body, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="after t_eval"):
        taylor.solve_poisson_taylor(body, [0.0, 1.0], [1.0, 0.0, 0.0], t_start=0.5)
    with pytest.raises(ValueError, match="tol"):
        taylor.taylor_angle(body, tol=0.0)
    with pytest.raises(ValueError, match="horizon"):
        taylor.taylor_angle(body, horizon=1000.0)
    with pytest.raises(RuntimeError, match="err_nf_state"):
        taylor.solve_poisson_taylor(body, [0.0, 1.0], [np.nan, 0.0, 0.0])


def test_doctests():
    assert doctest.testmod(taylor).failed == 0
