"""The run-time route certificates of the round trip (``derivations/output/runtime_routes.py``, issue 44).

Their points must reach the branches they are listed for (a check that never reaches the repair or the far
phase certifies nothing about them), their references must be right (two independent closed forms agree,
and a textbook value), and on the committed module every route passes.  ``tests/test_verify_faults.py``
seeds faults and runs ``--verify``.
"""
import math

import numpy as np
import pytest
from flint import arb, ctx

from derivations.output import ball_reference
from derivations.output import runtime_routes as routes
from derivations.output.pipeline import GENERATED
from derivations.output.roundtrip import load_module


@pytest.fixture(scope="module")
def module():
    return load_module(GENERATED)


def test_the_listed_points_reach_the_branches_they_name(module, monkeypatch):
    from suslov.kernel import finite, phase
    from suslov.runtime import basis, general_angle

    seen = []
    repair, careful, certified, again, balls = (finite.repair, basis.careful_phase, general_angle._certified_float,
                                                general_angle._again, general_angle._ball_and_radii)

    def spy_repair(function, outputs, *rest):
        if not all(np.all(np.isfinite(o)) for o in outputs):
            seen.append(("repair", function))
        return repair(function, outputs, *rest)

    monkeypatch.setattr(finite, "repair", spy_repair)
    monkeypatch.setattr(basis, "careful_phase", lambda p, d, t: seen.append(("far", float(d), len(t))) or careful(p, d, t))
    monkeypatch.setattr(general_angle, "_certified_float",
                        lambda *a: seen.append(("checked", type(a[3]).__name__)) or certified(*a))
    monkeypatch.setattr(general_angle, "_again", lambda *a: seen.append(("again",)) or again(*a))
    monkeypatch.setattr(general_angle, "_ball_and_radii", lambda *a: seen.append(("ball", a[3])) or balls(*a))

    module.omega(*(np.array(c) for c in zip(*routes.REPAIR_OMEGA)))
    module.omega_general(*(np.array(c) for c in zip(*routes.REPAIR_GENERAL)), 1)
    assert ("repair", "omega") in seen and ("repair", "omega_general") in seen
    for route_points in (routes.OMEGA, routes.GENERAL_OMEGA):   # the ordinary points are not repaired
        seen.clear()
        (module.omega if route_points is routes.OMEGA else module.omega_general)(*(np.array(c) for c in zip(*route_points)))
        assert not any(s[0] == "repair" for s in seen)

    seen.clear()
    for d, ts in routes.BASIS_T.items():
        module.gamma_basis(np.array(ts), 5, d)
        far = [t for t in ts if abs(5 * t / d) >= phase.PHASE_LIMIT]
        assert far and ("far", d, len(far)) in seen

    seen.clear()
    module.general_scattering_angle(*(np.array(c) for c in zip(*routes.BODY)))
    assert ("checked", "float64") in seen and ("again",) in seen and ("checked", "mpf") in seen

    seen.clear()
    args, dps = next(item for item in routes.BODY_MP if item[0] is routes.GROWTH)
    module.general_scattering_angle_mp(*args, dps=dps)
    bits = [s[1] for s in seen if s[0] == "ball"]
    assert len(bits) > 1 and bits[-1] > bits[0]       # the working precision grew

    assert any(max(abs(p), d) > 2.0**1020 for p, d in routes.ANGLE)   # the scaled branch of scattering_angle


def test_two_references_agree_on_theorem_5_2_and_give_the_textbook_value():
    """I13 = 0: the general angle (certified invariants, then the certified angle of any body) at I11 = 2, I22 = 1,
    I23 = -1/2 is Theorem 5.4's at p = 2, d = 1, which is 2 arccos(1/cosh pi)."""
    import sympy as sp
    from sympy.codegen.cfunctions import expm1

    reference = ball_reference.Reference.__new__(ball_reference.Reference)    # the forms below, not a build's
    x, s, c, h, g = sp.symbols("x s c h g")
    I11, I22, I13, I23 = sp.symbols("I11 I22 I13 I23")
    D = I11 * I23**2 + I13**2 * I22
    # the certified expressions, as the build's Emitted items print them (derivations/sections/*.py)
    reference.forms = {
        "scattering_angle": ((x, s, c), [2 * sp.atan2(sp.sqrt(s**2 * sp.sech(x)**2 + sp.tanh(x)**2), c * sp.sech(x))]),
        "gauss_invariants": ((I11, I22, I13, I23), [I11**2 * I22**2 * (I13**2 + I23**2) / D**2,
                                                    I11 * I22 * (I11 - I22) * (-I11 * I23**2 + I13**2 * I22) / D**2,
                                                    -2 * I11**sp.Rational(3, 2) * I13 * I22**sp.Rational(3, 2) * I23
                                                    * (I11 - I22) / D**2, I11**3 * I22**3 / D**2]),
        "general_angle": ((h, g, s, c), [2 * sp.atan2(
            sp.sqrt(expm1(-2 * g) * expm1(2 * g - 4 * h) / expm1(-2 * h)**2) * sp.sqrt(s**2 * sp.sech(h)**2
                                                                                      + sp.tanh(h)**2),
            sp.sqrt(c**2 * sp.sech(h)**2 + (s**2 * sp.sech(h)**2 + sp.tanh(h)**2) * sp.exp(-2 * g)
                    * expm1(2 * g - 2 * h)**2 / expm1(-2 * h)**2))])}
    theorem = ball_reference.enclose(200, reference.scattering_angle, 2, 1)[0]
    general, Y = ball_reference.enclose(200, reference.general_angle, 2, 1, 0, "-1/2")
    with ctx.workprec(300):
        textbook = 2 * (1 / arb.pi().cosh()).acos()
        assert theorem.overlaps(textbook) and general.overlaps(textbook) and general.overlaps(theorem)
        assert abs(Y - 2) < arb(2) ** -190                   # w_-^2 = -p^2: |Y| = p
    assert math.isclose(float(theorem.mid()), 2.968844459491, rel_tol=1e-12)


def test_a_route_that_raises_or_returns_garbage_fails_naming_itself():
    tally = routes.Tally("omega")
    assert tally.call("omega(1, 2, 3)", lambda: 1 / 0) is None
    with ctx.workprec(128):
        tally.within("omega(0)", complex(1, 2), arb(1), arb("1e-10"))
        tally.within("omega(0)", float("nan"), arb(1), arb("1e-10"))
        tally.within("omega(0)", 1.0, arb(1), arb("1e-10"))
    assert len(tally.failed) == 3 and tally.points == 4
    assert all("omega" in f for f in tally.failed)
    balls = routes.Tally("scattering_angle_ball")
    with ctx.workprec(128):
        balls.contains("narrow", arb(1, 1e-30), arb(1), 64)       # contains, 99 bits
        balls.contains("wide", arb(1, 1e-5), arb(1), 64)          # contains, but 16 bits for 64 asked
        balls.contains("off", arb(2, 1e-30), arb(1), 64)          # excludes
    assert [f.split(":")[0] for f in balls.failed] == ["wide", "off"]


@pytest.mark.slow
def test_every_route_passes_on_the_committed_module(default_build, module):
    from derivations.core.certificates import CertificateLog, Outcome, text

    log = CertificateLog(derivation="roundtrip")
    certificates = routes.certify(log, module, default_build)
    assert all(c.outcome is Outcome.PASS for c in certificates)
    named = {text(c.claim).split(":")[0] for c in certificates}
    public = {"omega", "omega_mp", "omega_general", "omega_general_mp", "first_integral", "first_integral_mp",
              "gamma_basis", "gamma_basis_mp", "scattering_angle", "scattering_angle_mp", "scattering_angle_ball",
              "general_scattering_angle", "general_scattering_angle_mp", "general_scattering_angle_ball",
              "finite.repair (omega, omega_general)"}
    assert named == public   # their cost is measured in bench/bench_runtime_routes.py, not asserted here
