"""Proven float64 error bounds (issue 34): the proofs hold at held-out hard points, and a seeded change to one
emitted operation makes the proof fail or its bound grow.

Expected values come from mpmath at 50 digits (the exact formulas, not the emitted code); the points are
not the proof's boxes' ends: large and tiny |t|, d from 1e-3 to 1e3, p next to odd and even integers.
"""
import re
import types

import mpmath
import numpy as np
import pytest
from flint import arb, ctx

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.proofs import float_bounds as fb
from derivations.proofs import float_proofs as fp
from generated import suslov_formulas as sf

U = 2.0**-53


@pytest.fixture(scope="module")
def proofs():
    return {name: prove(sf) for name, prove in fp.PROOFS.items()}


def test_proofs_pass_within_the_stated_bounds(proofs):
    for name, proof in proofs.items():
        assert proof.bound <= fp.STATED[name], proof
        assert proof.boxes >= 64


def test_omega_bound_holds_at_hard_points(proofs):
    bound = proofs["omega"].bound
    rng = np.random.default_rng(3434)
    ts = [-1e4, -745.2, -37.5, -1.0 / 3, -1e-300, 0.0, 2.0**-30, 0.7, 19.99, 700.1, 1023.9]
    cases = [(1.0, 1e-3), (3.0, 0.5), (-7.5, 1e3), (1e200, 3.3), (2.0**-500, 0.07)]
    cases += [(float(rng.uniform(-50, 50)), float(10 ** rng.uniform(-3, 3))) for _ in range(6)]
    with mpmath.workdps(50):
        for p, d in cases:
            w1, w2 = sf.omega(np.array(ts), p, d)
            for i, t in enumerate(ts):
                a = mpmath.mpf(p) / mpmath.mpf(d)
                exact = (a * mpmath.tanh(t), -a * mpmath.sqrt(mpmath.mpf(d) ** 2 + 1) * mpmath.sech(t))
                for got, want in zip((w1[i], w2[i]), exact):
                    scale = abs(a) * mpmath.sqrt(mpmath.mpf(d) ** 2 + 1)
                    assert abs(got - want) <= bound * abs(want) + 1e-300 * scale, (p, d, t)


def test_scattering_angle_bound_holds_at_hard_points(proofs):
    bound = proofs["scattering_angle"].bound
    ps = [1.0, 3.0, 2.0, 1 + 2.0**-40, 3 - 1e-13, 2 + 1e-13, 0.5, 1e-300, 7.3, -2.7, 101.0, 40.0]
    ds = [1e-3, 0.31, 1.0, 7.0, 1e3]
    with mpmath.workdps(50):
        for p in ps:
            for d in ds:
                if np.pi * abs(p) / (2 * d) > 1024:
                    continue
                half = mpmath.cospi(mpmath.mpf(p) / 2) / mpmath.cosh(mpmath.pi * mpmath.mpf(p) / (2 * mpmath.mpf(d)))
                exact = 2 * mpmath.acos(abs(half))        # half-angle in [0, pi/2]: acos is well-conditioned here
                got = float(sf.scattering_angle(p, d))
                assert abs(got - exact) <= bound, (p, d)


def _seeded(name: str, old: str, new: str):
    """The module's emitted function ``_name`` with one operation changed (text replaced), as a module stand-in."""
    source = open(sf.__file__, encoding="utf-8").read()
    block = re.search(rf"^def _{name}\(ctx.*?(?=^\S)", source, re.S | re.M).group(0)
    assert old in block
    namespace = {}
    exec(block.replace(old, new), namespace)
    return types.SimpleNamespace(**{f"_{name}": namespace[f"_{name}"]})


def test_a_cancelling_rewrite_of_the_angle_makes_the_bound_grow(proofs):
    # s^2 sech^2 + tanh^2 = 1 - c^2 sech^2 exactly, but the subtraction cancels for small x and c next to 1
    seeded = _seeded("scattering_angle", "(s*s)*(ctx.sech(x)*ctx.sech(x)) + (ctx.tanh(x)*ctx.tanh(x))",
                     "1.0 - (c*c)*(ctx.sech(x)*ctx.sech(x))")
    try:
        proof = fp.prove_scattering_angle(seeded)
        assert proof.bound > 100 * proofs["scattering_angle"].bound
    except fb.BoundFailure:
        pass
    from suslov.runtime import angle

    seeded.scattering_angle = lambda p, d: angle.scattering_angle(seeded._scattering_angle, p, d)
    log = CertificateLog(derivation="test")
    with pytest.raises(CertificationFailure):
        fp.certificate(log, seeded, "scattering_angle")      # the build's certificate fails
    assert log.certificates[-1].outcome is Outcome.FAIL


def test_sech_from_tanh_makes_the_omega_proof_fail_or_grow(proofs):
    # sech t = sqrt(1 - tanh^2 t): exact, but 1 - T*T cancels for large t
    seeded = _seeded("omega", "T, S = ctx.tanh_sech(t)", "T = ctx.tanh(t)\n    S = ctx.sqrt(1.0 - T*T)")
    try:
        assert fp.prove_omega(seeded).bound > 1000 * proofs["omega"].bound
    except fb.BoundFailure:
        pass


def test_reordered_product_keeps_a_proof_but_changes_nothing_silently(proofs):
    # k1 = -c*p/d computed as -(c*(p/d)): still proven (same number of roundings), within the stated bound
    seeded = _seeded("omega", "k1 = -c*p/d", "k1 = -(c*(p/d))")
    assert fp.prove_omega(seeded).bound <= fp.STATED["omega"]


def test_error_arithmetic_against_mpmath_on_a_float_chain():
    """fl((x*y + z)/w) for float inputs: the FE bound contains the true error (mpmath at 60 digits)."""
    rng = np.random.default_rng(7)
    with ctx.workprec(128):
        for _ in range(200):
            x, y, z, w = (float(v) for v in rng.uniform(-3, 3, 4))
            if abs(w) < 1e-3:
                continue
            got = (x * y + z) / w
            with mpmath.workdps(60):
                exact = (mpmath.mpf(x) * y + z) / w
            fe = (fb.FE(arb(x)) * fb.FE(arb(y)) + fb.FE(arb(z))) / fb.FE(arb(w))
            assert abs(got - exact) <= float(fe.e.upper()) * (1 + 1e-12)
            assert float(fe.e.upper()) < 1e-12 + 10 * U * abs(float(exact)) + 1e-300 or abs(x * y + z) < 1e-3


def test_omega_general_bound_holds_at_hard_points(proofs):
    bound = proofs["omega_general"].bound
    bodies = [(2.0, 1.0, 0.3, 0.5), (1.0, 2.0, -0.7, 0.01), (1e150, 5e149, 3e149, -4e149), (1.0, 1.0, 1e-3, -1e-3),
              (3.0, 0.2, 0.9, -0.01), (0.2, 3.0, -0.01, 0.9), (1e-300, 2e-300, 5e-301, 7e-301)]
    ts = [-1e4, -40.0, -1.5, -1e-9, 0.0, 0.25, 3.0, 709.0, 1e3]
    with mpmath.workdps(50):
        for I11, I22, I13, I23 in bodies:
            for branch in (1, -1):
                w1, w2 = sf.omega_general(np.array(ts), I11, I22, I13, I23, branch)
                J = [mpmath.mpf(x) for x in (I11, I22, I13, I23)]
                r = branch * mpmath.sqrt(J[0] * J[1])
                D = J[2] ** 2 * J[1] + J[3] ** 2 * J[0]
                B = (J[0] * J[1] * abs(J[3]) + J[1] * abs(J[2]) * abs(r) + J[0] * J[1] * abs(J[2])
                     + J[0] * abs(J[3]) * abs(r)) / D
                for i, t in enumerate(ts):
                    exact = sf.omega_general_mp(t, I11, I22, I13, I23, branch, dps=50)
                    for got, want in zip((w1[i], w2[i]), exact):
                        assert abs(got - want) <= bound * B + 1e-300, (I11, I22, I13, I23, branch, t)


# ---------------------------------------------------------------- first_integral (derivations.proofs.integral_proof)

from derivations.proofs import integral_proof as ip  # noqa: E402


@pytest.fixture(scope="module")
def integral_proofs():
    return {p: ip.prove_first_integral(p) for p in sf.INTEGRAL_PS}


def test_first_integral_proofs_within_the_stated_bound(integral_proofs):
    for p, proof in integral_proofs.items():
        assert proof.bound <= ip.stated(p), proof
        assert proof.bound_u < 3 * p + 20      # Horner's 2p roundings, the ratio's p, the three-term sums


def _integral_case(p, d, w1, w2, g):
    """(computed, exact at 50 digits, M = s^p sum_j |g_j| sum_k |a_jk|, in the domain)."""
    coefficients = sf.first_integral_coefficients(p, d)          # exact Fractions of the float d
    sizes = [sum(abs(a) for a in coefficients[name]) for name in ("P1", "P2", "P3")]
    top = max(abs(a) for name in ("P1", "P2", "P3") for a in coefficients[name])
    with mpmath.workdps(50):
        s = max(abs(mpmath.mpf(w1)), abs(mpmath.mpf(w2)))
        total = mpmath.fsum(abs(mpmath.mpf(gj)) * mpmath.mpf(size.numerator) / size.denominator
                            for gj, size in zip(g, sizes))
        inside = total >= mpmath.mpf(2) ** -600 * mpmath.mpf(top.numerator) / top.denominator
        exact = sf.first_integral_mp(p, d, w1, w2, *g, dps=50)
        return float(sf.first_integral(p, d, w1, w2, *g)), mpmath.mpf(exact), s**p * total, inside


def test_first_integral_bound_holds_at_hard_points(integral_proofs):
    rng = np.random.default_rng(3436)
    for p in (1, 7, 15):
        bound = integral_proofs[p].bound
        for d in (1e-2, 0.31, 1.0, 50.0):
            coefficients = sf.first_integral_coefficients(p, d)
            cases = [(1e-25, -3e-26), (2.0**-40, 1.0), (20.0, -19.999999), (1.0, 1.0), (-7.5, 1e-300)]
            cases += [tuple(float(v) for v in rng.uniform(-5, 5, 2)) for _ in range(3)]
            for w1, w2 in cases:
                # a gamma orthogonal to (P1, P2, P3) at the point: F3 cancels to next to 0
                with mpmath.workdps(50):
                    P = [mpmath.fsum(mpmath.mpf(a.numerator) / a.denominator * mpmath.mpf(w1) ** (p - k)
                                     * mpmath.mpf(w2) ** k for k, a in enumerate(coefficients[name]))
                         for name in ("P1", "P2", "P3")]
                cancelling = np.array([float(P[1]), -float(P[0]), 0.0])
                gammas = [rng.normal(size=3), cancelling, np.array([0.0, 0.0, 1.0])]
                for g in gammas:
                    if not np.any(g):
                        continue
                    g = g / np.max(np.abs(g))
                    got, exact, M, inside = _integral_case(p, d, w1, w2, g)
                    assert inside, (p, d, w1, w2, g)
                    assert abs(got - exact) <= bound * M + 5e-324, (p, d, w1, w2, g)


def test_a_constant_added_and_taken_away_fails_the_integral_proof(monkeypatch):
    walk = ip.walk

    def seeded(p, coefficient, g, small, big, power):
        return walk(p, lambda i, k: (coefficient(i, k) + 1.0) - 1.0, g, small, big, power)

    monkeypatch.setattr(ip, "walk", seeded)
    with pytest.raises(fb.BoundFailure):
        ip.prove_first_integral(7)


def test_the_ratio_by_a_reciprocal_makes_the_integral_bound_grow(integral_proofs, monkeypatch):
    # r = small * (1/big): two roundings in place of one, in every Horner step
    monkeypatch.setattr(ip, "ratio", lambda small, big: small * (1.0 / big))
    assert ip.prove_first_integral(15).bound_u >= integral_proofs[15].bound_u + 15
