"""gamma(t) of every body from Gauss's 2F1 (issue 44): the closed form against independent integrations.

The routine (:mod:`suslov.kernel.gauss_gamma`) builds gamma from the basis at infinity of Gauss's equation
(``mpmath.hyp2f1``), joined across s = 0 by the Taylor series at z = 1/2; nothing here shares its code.  The
references are mpmath's Taylor integrator ``odefun`` at 35 digits (for the mpmath route at 25) and SciPy's DOP853
(for the float64 twin), both on ``gamma' = gamma x (u tanh t + v sech t)`` in t itself, with u, v from the
generated module's certified ``omega_coefficients``.  Bodies: the special case p = 2, d = 1 (even p: kappa is an
integer, the bases at z = 0 and z = 1 are logarithmic; integration was the only other route), a general body
(5/4, 1, 3/10, -1/2), I13 != 0 with I23 = 0, and I11 = I22 (kappa = 0); times up to |t| = 10.
"""
import sys

import flint
import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import suslov
from suslov.kernel.gauss_gamma import gamma_gauss, gamma_gauss_uv
from suslov.kernel.gauss_gamma_float import solve
from suslov.kernel.gauss_gamma_mp import GaussGamma
from suslov.simulator import engine, integrate
from suslov.simulator.body import make_body
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import SceneError, load_scene, parse_scene
from suslov.validated import hypergeometric_form, omega_coefficients

BODIES = {"p=2,d=1": (2, 1, 0, "-1/2"), "general": ("5/4", 1, "3/10", "-1/2"), "I23=0": ("5/4", 1, "3/10", 0),
          "I11=I22": (1, 1, "1/3", "-1/2")}
TIMES = ("-10", "-2.5", "-0.3", "0.45", "1.7", "10")
GAMMA0 = ("0.6", "0", "0.8")
T0 = "0.7"


def certified_uv(body, dps=60):
    """u, v at ``dps`` digits from the generated module's emitted omega (validated.omega_coefficients)."""
    with mpmath.workdps(dps), flint.ctx.workdps(dps + 10):
        u, v = omega_coefficients(*body)
        return tuple(mpmath.mpf(x.mid().str(dps + 5, radius=False)) for x in u), \
            tuple(mpmath.mpf(x.mid().str(dps + 5, radius=False)) for x in v)


def odefun_reference(u, v, gamma0, t0, times, dps=45):
    """gamma at ``times`` by mpmath's Taylor integrator at ``dps`` digits (forward and backward from t0)."""
    def field(t, y, sign=1):
        th, sh = mpmath.tanh(sign * t), mpmath.sech(t)
        w1, w2 = u[0] * th + v[0] * sh, u[1] * th + v[1] * sh
        return [sign * x for x in (-y[2] * w2, y[2] * w1, y[0] * w2 - y[1] * w1)]

    with mpmath.workdps(dps):
        t0, g0 = mpmath.mpf(t0), [mpmath.mpf(x) for x in gamma0]
        forward = mpmath.odefun(field, t0, g0)
        backward = mpmath.odefun(lambda t, y: field(t, y, -1), -t0, g0)
        return [forward(mpmath.mpf(t)) if mpmath.mpf(t) >= t0 else backward(-mpmath.mpf(t)) for t in times]


@pytest.mark.parametrize("name", list(BODIES))
def test_mpmath_route_agrees_with_taylor_integration_at_higher_precision(name):
    """20 digits asked: agreement with odefun at 28 digits to 1e-19 at every time up to |t| = 10, |gamma| = 1
    (docs/simulator.md: 30 digits asked agree with odefun at 45 to 2e-31; fewer digits here keep the suite short)."""
    body = BODIES[name]
    u, v = certified_uv(body)
    reference = odefun_reference(u, v, GAMMA0, T0, TIMES, dps=28)
    with mpmath.workdps(20):
        got = gamma_gauss([mpmath.mpf(t) for t in TIMES], *body, gamma0=[mpmath.mpf(x) for x in GAMMA0],
                          t0=mpmath.mpf(T0), dps=20)
        for t, g, ref in zip(TIMES, got, reference):
            assert max(abs(a - b) for a, b in zip(g, ref)) < mpmath.mpf("1e-19"), (name, t)
            assert abs(sum(x * x for x in g) - 1) < mpmath.mpf("1e-19")


def test_the_parameters_are_the_certified_hypergeometric_form():
    """A, B, C of the routine are those of suslov.validated.hypergeometric_form (the same kappa root)."""
    for body in BODIES.values():
        form = hypergeometric_form(*body, dps=30)
        with mpmath.workdps(30):
            mine = GaussGamma(*certified_uv(body), 30)
            for ours, ball in ((mine.A, form.A), (mine.B, form.B), (mine.C, form.C)):
                exact = mpmath.mpc(ball.real.mid().str(35, radius=False), ball.imag.mid().str(35, radius=False))
                assert abs(ours - exact) < mpmath.mpf("1e-25"), body


def scipy_reference(u, v, t, gamma0):
    """gamma at the samples t (increasing, gamma0 at t[0]) by DOP853 at rtol 1e-12 in t."""
    def rhs(s, y):
        th, sh = np.tanh(s), 1 / np.cosh(s)
        w1, w2 = u[0] * th + v[0] * sh, u[1] * th + v[1] * sh
        return [-y[2] * w2, y[2] * w1, y[0] * w2 - y[1] * w1]

    sol = solve_ivp(rhs, (t[0], t[-1]), gamma0, method="DOP853", t_eval=t, rtol=1e-12, atol=1e-14, max_step=0.02)
    return sol.y.T


@pytest.mark.parametrize("name", list(BODIES))
def test_float64_twin_agrees_with_dop853_and_the_mpmath_route(name):
    body = BODIES[name]
    u, v = (tuple(float(x) for x in w) for w in certified_uv(body))
    t = np.linspace(-10, 10, 401)
    g0 = np.array([0.6, 0.0, 0.8])
    got = gamma_gauss(t, *body, gamma0=g0, t0=-10.0)
    assert got.shape == (401, 3)
    assert np.max(np.abs(got - scipy_reference(u, v, t, g0))) < 1e-10
    assert np.max(np.abs(np.linalg.norm(got, axis=-1) - 1)) < 1e-14
    picks = [0, 133, 190, 215, 300, 400]
    exact = gamma_gauss([mpmath.mpf(float(t[i])) for i in picks], *body, gamma0=g0, t0=-10, dps=25)
    assert max(abs(float(a) - b) for i, g in zip(picks, exact) for a, b in zip(g, got[i])) < 2e-14


def test_ss_solution_is_the_limit_axis_at_minus_infinity_and_matches_its_series():
    """The ss solution needs no start: G (i/2) sigma3 G^-1 is exact; at t = -1 it is the Frobenius series value."""
    body = make_body(p=2.5, d=0.7)
    series = integrate.ss_series_value(body.u, body.v, -1.0)
    assert np.max(np.abs(gamma_gauss_uv(-1.0, body.u, body.v) - series)) < 1e-14
    far = gamma_gauss_uv(-40, body.u, body.v, dps=20)
    assert abs(far[0] + 1) < 1e-15 and abs(far[2]) < 1e-16


def test_large_times_keep_float64_accuracy_and_the_unit_norm():
    body = make_body([[1.25, 0, 0.3], [0, 1, -0.5], [0.3, -0.5, 1.5]])
    t = np.linspace(-30, 30, 301)
    sol = solve(body.u, body.v, t, np.array([0.6, 0.0, 0.8]))
    exact = gamma_gauss_uv([mpmath.mpf(float(t[i])) for i in (0, 150, 300)], body.u, body.v, (0.6, 0, 0.8),
                           t0=-30, dps=25)
    assert max(abs(float(a) - b) for i, g in zip((0, 150, 300), exact) for a, b in zip(g, sol.values[i, 0])) < 1e-13
    assert sol.norm_drift < 1e-14 and sol.checks["ode_residual"] < 1e-18


def test_odd_p_equals_the_certified_basis():
    """For odd p the certified meromorphic basis (Theorem 6.1, gamma_basis) is a third route: the same rows."""
    from suslov.loader import gf
    t = np.linspace(-8, 8, 161)
    for p in (1, 3):
        body = make_body(p=p, d=0.5)
        basis = gf.gamma_basis(t, p, 0.5)
        assert np.max(np.abs(solve(body.u, body.v, t, basis[0]).values - basis)) < 1e-13


# ------------------------------------------------------------------------------------------ the simulator

FIG2 = "scenes/fig2_gamma_ss.toml"


def test_fig2_scene_uses_the_gauss_route_and_matches_integration():
    """suslov.simulate on Fig. 2: the gamma_gauss step, every check passed, equal to the DOP853 integration
    (the same scene with gamma_route = "integrate") within its estimate at all 2001 samples."""
    result = suslov.simulate(FIG2)
    assert [s["step"] for s in result.steps] == ["omega", "gamma_gauss", "integrals", "angle_closed_form"]
    meta = result.results["gamma"]
    assert meta["route"] == "gauss_2f1" and meta["checks_passed"] and meta["method"].startswith("gauss_2f1")
    assert meta["norm_drift"] < 1e-14 and meta["mp_check"]["max_abs_difference"] < 1e-14
    assert meta["ode_residual"] < 1e-18 and meta["initial_error"] < 1e-16
    scene = load_scene(FIG2)
    scene.gamma_route = "integrate"
    integrated = suslov.simulate(scene)
    assert [s["step"] for s in integrated.steps][1] == "gamma_integrate"
    assert integrated.results["gamma"]["method"].startswith("DOP853")
    difference = np.max(np.abs(result["gamma"] - integrated["gamma"]))
    assert difference < 1e-12 and difference <= 10 * integrated.results["gamma"]["error_estimate"] + 1e-14
    assert result["gamma"].shape == integrated["gamma"].shape == (2001, 3)


def test_orientation_by_the_gauss_route_is_orthonormal_and_matches_integration():
    scene = {"body": {"inertia": [["5/4", 0, "3/10"], [0, 1, "-1/2"], ["3/10", "-1/2", "3/2"]]},
             "motion": {"time": [-6, 6], "samples": 121, "energy": 0.8},
             "effects": {"compute": ["orientation", "gamma"]}, "numerics": {"method": "scipy:DOP853", "rtol": 1e-12}}
    gauss = suslov.simulate(scene)
    assert [s["step"] for s in gauss.steps] == ["gamma_gauss", "orientation_gauss"]
    R = gauss["orientation"]
    assert R.shape == (121, 3, 3) and np.max(np.abs(R @ np.swapaxes(R, 1, 2) - np.eye(3))) < 1e-14
    scene["numerics"]["gamma_route"] = "integrate"
    numeric = suslov.simulate(scene)
    assert np.max(np.abs(R - numeric["orientation"])) < 1e-10
    assert np.max(np.abs(gauss["gamma"] - numeric["gamma"])) < 1e-10


def test_gamma0_scene_in_the_scene_frame_and_at_an_energy():
    scene = {"body": {"inertia": [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]},
             "motion": {"time": [-4, 7], "samples": 45, "energy": 2.5, "gamma0": [0.0, 0.6, 0.8]},
             "effects": {"compute": ["gamma", "integral_drift"]}, "numerics": {"method": "DOP853", "rtol": 1e-12}}
    gauss = suslov.simulate(scene)
    assert np.allclose(gauss["gamma"][0], [0.0, 0.6, 0.8], atol=1e-14, rtol=0)
    assert gauss.results["gamma"]["start"] == "gamma0" and gauss.results["gamma"]["initial_error"] < 1e-14
    scene["numerics"]["gamma_route"] = "integrate"
    assert np.max(np.abs(gauss["gamma"] - suslov.simulate(scene)["gamma"])) < 1e-10
    assert gauss["integral_drift"]["F2"]["max_abs_drift"] < 1e-14


def test_the_gauss_route_runs_on_the_core_install(monkeypatch):
    """No integrator needed: gamma of p = 2.5 with heyoka and SciPy hidden."""
    for name in ("heyoka", "scipy", "scipy.integrate"):
        monkeypatch.setitem(sys.modules, name, None)
    result = suslov.simulate({"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 7},
                              "effects": {"compute": ["gamma"]}})
    assert result["gamma"].shape == (7, 3) and result.results["gamma"]["route"] == "gauss_2f1"


def test_a_failed_check_is_never_silent_the_run_integrates_and_says_why(monkeypatch):
    original = engine.gauss_problems
    monkeypatch.setattr(engine, "gauss_problems", lambda summary: original(summary) + ["forced by the test"])
    result = suslov.simulate({"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 7},
                              "effects": {"compute": ["gamma"]}, "numerics": {"method": "DOP853"}})
    meta = result.results["gamma"]
    assert meta["route"] == "integrate (gauss_2f1 refused)" and "forced by the test" in meta["gauss_2f1_refused"]
    assert meta["method"].startswith("DOP853")


def test_planner_integrates_beyond_the_size_limit_and_the_route_is_validated(tmp_path):
    fast = {"body": {"p": 300, "d": 1}, "motion": {"time": [-1, 1], "samples": 3}, "effects": {"compute": ["gamma"]}}
    plan = make_plan(parse_scene(fast))
    assert plan.names() == ["gamma_integrate"] and "not gamma_gauss [any Suslov body with |u| + |v| <= 500" in \
        plan.explain()
    with pytest.raises(SceneError, match="numerics.gamma_route"):
        parse_scene(fast | {"numerics": {"gamma_route": "bogus"}})
