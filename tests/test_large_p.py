"""Every per-p certificate at p = 101 (and 201 where it is cheap), without a whole build (issue 43).

``python build_formulas.py --pmax 101`` crashed (OverflowError in the first-integral proof's replica at p >= 71)
while the tests ran the per-p certificates only at the default pmax 15.  Here each per-p certificate function is
called directly, with the inputs each section's ``run()`` passes it, at p = 101 and, where it takes a few seconds
there, at p = 201; each test asserts the certificate's outcome, not only that nothing raised:

* ``meromorphic.basis_for_p`` (a worker's certificates of one odd p's orthonormal basis, constructed from the
  recipe: the route of a build that emits no module) and ``meromorphic.genhip_for_p``;
* ``residue.logarithm_verdict`` (Frobenius obstructions at t0 = i pi/2; the series' certificate for pmax 201):
  no logarithms for odd p, logarithms for every d > 0 for even p (the paper's Theorem 3.2 claims none for every
  p: refuted for even p, as expected);
* ``galois.decide_logarithms``: Conjecture 1 (s1, s2 logarithmic exactly for even p, s3, s4 never);
* ``first_integrals.certify_p`` with the derived field of ``special_case``;
* the round trip: ``roundtrip.per_p_checks`` (the emitted core's numerators certified directly, as a build
  beyond p = 15 does, then the first-integral proof, both gamma_basis proofs and the exact check of
  gamma_basis_mp) and ``certify_basis_core`` at 101 (at 201 they take
  about 25 s: only the parts of ``basis_proof`` that need no basis run there), ``certify_integral_core`` and
  ``integral_proof.certificate`` at 101 and 201.

The emitted module.  ``suslov.load_formulas(pmax=101)`` builds a module covering p <= 101 (a whole build, minutes)
unless the per-user store has one, and the committed module refuses p outside ``INTEGRAL_PS`` / ``BASIS_PS``.  The
module's code does not depend on pmax (``templates/suslov_formulas.py.j2``: only ``PMAX``, ``INTEGRAL_PS``,
``BASIS_PS`` and ``_BASIS_SIGMA`` do), so the fixture writes ``generated/suslov_formulas.py`` with the data lines
a build certifying these p writes (sigma = -1, ``meromorphic_sigma.sigma_certificate``; the rotation test below checks it
independently) and loads it as ``per_p_checks`` does
(``roundtrip.load_module_once``).

Independent routes for the expected values: the paper's theorems and the conjecture (as in
tests/test_build_pmax51.py); the proven first-integral bound against the (3p + 14) u its docstring states; the
first integral constant along the basis solution and zero on gamma^(2), gamma^(3) (which turn with e^(i(p/d)t));
the rows a rotation solving the Poisson equations by finite differences of the 40-digit twin.

Overflow edges.  For each float proof's replica (the operation sequence whose bits the certificate compares with
the public function's), adjacent floats just below and just above where the public function, or the float
composition inside it, leaves float64: ``first_integral`` (ValueError, read as inf by the check), ``gamma_basis``
(fl(p t/d) overflows: the ball phase, finite rows), ``omega`` and ``omega_general`` (the composition's inf, the
public function's mpmath repair, then its ValueError), ``scattering_angle`` (fl(pi |p|) and 2d overflow) and
``general_scattering_angle`` (Y/lam overflows, lam underflows).  Values there are also checked against the mpmath
twins or the ball; the public functions must stay silent (warnings are errors).
"""
import math
import re
import struct
import sys
import warnings
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
from flint import arb, ctx, fmpq

from derivations.core.certificates import CertificateLog, CertificationFailure, Outcome
from derivations.output import roundtrip
from derivations.proofs import (
    basis_proof,
    float_proofs,
    general_angle_proof,
    integral_proof,
)
from derivations.sections import first_integrals, galois, meromorphic, residue
from suslov.kernel import phase, trig_series
from suslov.kernel.contexts import FLOAT
from suslov.runtime import basis as runtime_basis
from suslov.validated import local_behaviour

ROOT = Path(__file__).resolve().parents[1]
P, P2 = 101, 201
FLOAT_MAX = sys.float_info.max


# ---------------------------------------------------------------- helpers


def _bits(x: float) -> int:
    return struct.unpack("<q", struct.pack("<d", x))[0]


def _from_bits(n: int) -> float:
    return struct.unpack("<d", struct.pack("<q", n))[0]


def edge(ok, good: float, bad: float) -> tuple:
    """The adjacent positive floats (a, b) between ``good`` and ``bad`` with ok(a) true and ok(b) false."""
    assert good > 0 and bad > 0 and ok(good) and not ok(bad)
    lo, hi = _bits(good), _bits(bad)             # positive floats: the bit patterns are in the same order
    while abs(hi - lo) > 1:
        mid = (lo + hi) // 2
        if ok(_from_bits(mid)):
            lo = mid
        else:
            hi = mid
    return _from_bits(lo), _from_bits(hi)


def silent(function, *args, **kwargs):
    """``function(*args)`` with every warning an error (the public functions must not warn at the edges)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return function(*args, **kwargs)


def raises_value_error(function, *args) -> bool:
    try:
        silent(function, *args)
    except ValueError:
        return True
    return False


def outcomes(certificates) -> list:
    return [c.outcome for c in certificates]


# ---------------------------------------------------------------- fixtures


@pytest.fixture(scope="module")
def basis101():
    return meromorphic.basis_for_p(P)


@pytest.fixture(scope="module")
def emitted(basis101, tmp_path_factory):
    """(directory, module): the emitted module with the data of a build that certified the basis at p = 101 and
    the first integral at p = 101 and 201."""
    text = (ROOT / "generated" / "suslov_formulas.py").read_text(encoding="utf-8")
    data = {"PMAX": str(P2), "INTEGRAL_PS": f"({P}, {P2})", "BASIS_PS": f"({P},)",
            "_BASIS_SIGMA": repr({P: -1})}
    for name, value in data.items():
        text, count = re.subn(rf"^{name} = .*$", f"{name} = {value}", text, flags=re.MULTILINE)
        assert count == 1, f"{name}: not one data line in the generated module"
    directory = tmp_path_factory.mktemp("pmax201")
    (directory / "suslov_formulas.py").write_text(text, encoding="utf-8")
    return directory, roundtrip.load_module_once(directory)


@pytest.fixture(scope="module")
def module(emitted):
    return emitted[1]


@pytest.fixture(scope="module")
def field():
    """The derived eq:sysfin field, as first_integrals.run() takes it from special_case."""
    from derivations.core.options import BuildOptions
    from derivations.output.pipeline import derive

    return derive(BuildOptions(), ["special_case"]).results["special_case"].exports["field"]


# ---------------------------------------------------------------- sections: the per-p exact certificates


@pytest.mark.parametrize("p", [P, P2])
def test_meromorphic_basis_for_p_certifies(request, p):
    """A worker's certificates of one odd p's basis from the recipe (about 5 s at p = 201), and its genhip check."""
    outcome = request.getfixturevalue("basis101") if p == P else meromorphic.basis_for_p(p)
    certs = meromorphic.genhip_for_p(p) + outcome["certificates"]
    assert outcomes(certs) == [Outcome.PASS] * 6, [(c.label, c.detail) for c in certs]
    assert [c.label for c in certs] == ["pol_sol", "eq:gam3", "F_23_pol", "eq:ps", "gam1, gam2, gam3", "asymp"]
    assert all(str(c.claim).startswith(f"p = {p}:") for c in certs)
    # beyond KEEP_BASES the orthonormality is certified by conservation, as in a --pmax 101 build
    assert "conservation" in str(certs[4].method)
    # asymp with the derived sigma = -1 (V/k -> (0, 1, -i)); the rotation test below checks it independently
    assert "(0, 1, -i)" in str(certs[5].claim)
    assert len(outcome["terms"]) == 6 and min(outcome["terms"]) > 0


@pytest.mark.parametrize("p", [P, P + 1, P2, P2 + 1])
def test_residue_logarithm_verdict(p):
    """Theorem 3.5 / section 3.2: odd p no logarithms at t0; even p a non-zero obstruction at the resonance k = p
    (mu = 0), non-zero for every d > 0 (the paper's 'no logarithms for every integer p' refuted for even p)."""
    verdict, detail, count, typeset, _ = residue.logarithm_verdict(p)
    assert count >= 1
    # the cross-check agrees with the pole theorem (which decides every p; above p = 101 the build samples the
    # recursion, and P2, P2 + 1 are the top of that sample): the body (2, 1, 0, -1/p) has Lambda = p
    exact = local_behaviour(2, 1, 0, Fraction(-1, p))
    assert exact.Lambda == p and exact.meromorphic == (p % 2 == 1)
    assert verdict == ("no logarithms" if exact.meromorphic else "logarithms for every $d > 0$")
    if p % 2:
        assert verdict == "no logarithms" and typeset == [] and "vanish identically" in detail
    else:
        assert verdict == "logarithms for every $d > 0$" and typeset
        assert detail.startswith(f"non-zero obstruction $k = {p}$"), detail


def test_residue_laurent_series_for_pmax_201():
    """run() certifies the Laurent series to the order pmax + 1 needs; a coefficient off by one is refused."""
    coth, csch = residue.laurent_coefficients(P2 + 1)
    assert residue.certify_laurent_series(CertificateLog(), coth, csch).outcome is Outcome.PASS
    with pytest.raises(CertificationFailure):
        residue.certify_laurent_series(CertificateLog(), coth[:-1] + [coth[-1] + 1], csch)


@pytest.mark.parametrize("p", [P, P + 1, P2, P2 + 1])
def test_galois_decide_logarithms(p):
    """Conjecture 1: s1, s2 logarithmic exactly for even p, s3, s4 never (galois.run()'s criterion)."""
    verdict, _ = galois.decide_logarithms(p)
    s12 = "no log" if p % 2 else "log"
    assert verdict == {"s1": s12, "s2": s12, "s3": "no log", "s4": "no log"}


@pytest.mark.parametrize("p", [P, P2])
def test_first_integrals_certify_p(field, p):
    ff, certs = first_integrals.certify_p(CertificateLog(), p, field)
    assert outcomes(certs) == [Outcome.PASS] * 3, [c.detail for c in certs]
    assert [c.label for c in certs] == ["eq:liniowiec", "eq:p23", "Theorem 6.2"]
    assert "has 0 terms" in str(certs[0].detail)          # K dG/dt is the zero polynomial
    assert ff.K == p * (first_integrals.D_**2 + 1)


# ---------------------------------------------------------------- round trip


def test_roundtrip_per_p_checks_101(emitted, basis101):
    """The worker's round-trip work for p = 101 with the derived sigma (as the build passes): the meromorphic
    certificates made on the emitted core's numerators, the same claims and term counts as the recipe's basis
    certified in this process, then the float-path checks."""
    directory, _ = emitted
    outcome = roundtrip.per_p_checks((str(directory), P, -1))
    basis, certs = outcome["basis"], outcome["checks"]
    assert outcomes(basis) == [Outcome.PASS] * 5, [(c.label, c.detail) for c in basis]
    assert [str(c.claim) for c in basis] == [str(c.claim) for c in basis101["certificates"]]
    assert "the emitted module's _basis_core" in str(basis[0].detail) and outcome["terms"] == basis101["terms"]
    assert outcomes(certs) == [Outcome.PASS] * 4, [(str(c.claim)[:60], c.detail) for c in certs]
    claims = [str(c.claim) for c in certs]
    assert all(claim.startswith(f"p = {P}:") for claim in claims)
    assert "first_integral float64" in claims[0] and "gives the analysed sequence's bits" in str(certs[0].detail)
    assert "double-double phase" in claims[1] and "ball phase" in claims[2]
    assert "gamma_basis_mp equals the certified numerators" in claims[3]


def test_roundtrip_exact_cores(module):
    """certify_integral_core (the build passes every odd p's objects) at 101 and 201; certify_basis_core at 101;
    the objects of another p are refused (the comparison is not vacuous at this size)."""
    log = CertificateLog()
    objects = {p: first_integrals.construct(p)[0] for p in (P, P2)}
    certs = roundtrip.certify_integral_core(log, module, objects)
    assert outcomes(certs) == [Outcome.PASS] * 2 and [str(c.detail) for c in certs] == ["identical"] * 2
    real, cplx = meromorphic.construct(P)
    (cert,) = roundtrip.certify_basis_core(log, module, {P: (real.M, cplx.M)})
    assert cert.outcome is Outcome.PASS and str(cert.detail) == "identical"
    with pytest.raises(CertificationFailure):
        roundtrip.certify_integral_core(log, module, {P: first_integrals.construct(P - 2)[0]})


@pytest.mark.parametrize("p", [P, P2])
def test_integral_proof_certificate(module, p):
    """The first-integral proof and its bit check at p; the proven bound is the (3p + 14) u the docstring states."""
    cert = integral_proof.certificate(CertificateLog(), module, p)
    assert cert.outcome is Outcome.PASS, cert.detail
    assert "gives the analysed sequence's bits at 88 points" in str(cert.detail)
    assert integral_proof.prove_first_integral(p).bound_u <= 3 * p + 14


def test_basis_proof_at_201(module):
    """The parts of the gamma_basis certificate that depend on p alone (the rest needs the basis of p = 201, 20 s):
    the bound within the stated one, the run-time phase and powers bit for bit, the ball phase."""
    proof = basis_proof.prove(P2)
    assert proof["near"].upper() <= basis_proof.stated(P2) and proof["far"].upper() <= basis_proof.stated(P2)
    same, points = basis_proof.same_operations(module, P2)
    assert same and points > 500
    assert basis_proof.far_phase_ok(P2)


# ---------------------------------------------------------------- the emitted module at p = 101


def test_basis_rows_rotate_and_solve_poisson_101(module):
    """gamma_basis at p = 101: a rotation (det +1: sigma), gamma^(1) -> -+e1 at t -> -+oo, and the 40-digit twin
    solves gamma' = gamma x omega (central differences, step 1e-12)."""
    for d in (0.5, 3.0):
        ts = np.array([-40.0, -2.5, -0.3, 0.0, 0.7, 4.0, 40.0])
        B = silent(module.gamma_basis, ts, P, d)
        assert np.max(np.abs(np.einsum("tij,tkj->tik", B, B) - np.eye(3))) < 1e-12
        assert np.max(np.abs(np.linalg.det(B) - 1)) < 1e-12
        assert np.allclose(B[0, 0], [-1, 0, 0], atol=1e-12) and np.allclose(B[-1, 0], [1, 0, 0], atol=1e-12)
        with mpmath.workdps(40):
            h = mpmath.mpf("1e-12")
            for t in (mpmath.mpf("-0.8"), mpmath.mpf("0.25")):
                plus, minus = (module.gamma_basis_mp(t + s, P, d, dps=40) for s in (h, -h))
                here = module.gamma_basis_mp(t, P, d, dps=40)
                w1, w2 = module.omega_mp(t, P, d, dps=40)
                scale = abs(w1) + abs(w2)
                for i in range(3):
                    g = [here[i, j] for j in range(3)]
                    rhs = [-g[2] * w2, g[2] * w1, g[0] * w2 - g[1] * w1]       # gamma x omega, omega3 = 0
                    for j in range(3):
                        assert abs((plus[i, j] - minus[i, j]) / (2 * h) - rhs[j]) < 1e-15 * scale


def test_first_integral_along_the_basis_101(module):
    """F3 at p = 101 along (omega(t), gamma^(i)(t)): constant on gamma^(1), zero on gamma^(2), gamma^(3) (their
    complex combination turns with e^(i(p/d)t), so its constant F3 can only be 0); relative to the largest
    |P_i| along the way."""
    for d in (0.5, 3.0):
        ts = np.linspace(-3.0, 3.0, 7)
        w1, w2 = silent(module.omega, ts, P, d)
        B = silent(module.gamma_basis, ts, P, d)
        sizes = [max(abs(float(silent(module.first_integral, P, d, w1[k], w2[k], *e))) for e in np.eye(3))
                 for k in range(ts.size)]
        scale = max(sizes)
        F = np.array([[float(silent(module.first_integral, P, d, w1[k], w2[k], *B[k, i])) for k in range(ts.size)]
                      for i in range(3)])
        assert abs(F[0, 3]) > 0.5 * scale
        assert np.max(np.abs(F[0] - F[0, 3])) <= 1e-10 * scale
        assert np.max(np.abs(F[1:])) <= 1e-10 * scale


# ---------------------------------------------------------------- replicas at the public functions' overflow edges


@pytest.mark.parametrize("p", [P, P2])
@pytest.mark.parametrize("direction, gamma, d", [((1.0, 0.3), (0.6, 0.0, 0.8), 0.5),      # |w1| >= |w2|, F3 > 0
                                                 ((-0.2, -1.0), (0.0, 0.6, -0.8), 3.7)])  # reversed Horner, F3 < 0
def test_first_integral_replica_at_the_overflow_edge(module, monkeypatch, p, direction, gamma, d):
    """omega = lam * direction, lam at adjacent floats: below, the replica gives the public function's bits; above,
    the public function raises its ValueError and the replica gives inf (how the check reads it).  The edge is
    float64's: |F3| of the 40-digit twin is at DBL_MAX there.  The certificate, its bit check at these points, passes
    (at p >= 71 the replica raised OverflowError)."""
    g = np.array(gamma)

    def public(lam):
        return silent(module.first_integral, p, d, direction[0] * lam, direction[1] * lam, *g)

    below, above = edge(lambda lam: not raises_value_error(public, lam), 1.0, 1e4)
    replica = [integral_proof.replica(module, p, d, direction[0] * lam, direction[1] * lam, g)
               for lam in (below, above)]
    assert math.isfinite(replica[0]) and replica[0] == float(public(below))
    with pytest.raises(ValueError, match="overflows float64"):
        public(above)
    assert replica[1] == math.inf
    for lam, side in ((below, -1), (above, 1)):
        exact = module.first_integral_mp(p, d, direction[0] * lam, direction[1] * lam, *g, dps=40)
        with mpmath.workdps(40):
            assert side * (abs(exact) / FLOAT_MAX - 1) > -1e-11
    points = [(d, direction[0] * lam, direction[1] * lam, g) for lam in (below, above)]
    monkeypatch.setattr(integral_proof, "model_points", lambda _p: points)
    cert = integral_proof.certificate(CertificateLog(), module, p)
    assert cert.outcome is Outcome.PASS and "bits at 2 points" in str(cert.detail)


@pytest.mark.parametrize("d", [1e-3, 1e3])     # fl(p t) overflows first at d = 1e3, the quotient at d = 1e-3
def test_gamma_basis_at_the_phase_overflow_edge(module, d):
    """t at adjacent floats where fl(fl(p t)/d) (the branch test) overflows: the far branch on both sides, the rows
    finite and exactly the analysed far-branch rows (series, ball phase, rows as in the proof), the ball phase
    within one ulp plus 2^-70 of the exact cos, sin, the rows within the proven bound of the 40-digit twin."""
    below, above = edge(lambda t: math.isfinite(P * t / d), 1.0, FLOAT_MAX)
    ts = np.array([below, above, -below, -above])
    rows = silent(module.gamma_basis, ts, P, d)
    assert np.all(np.isfinite(rows))
    assert all(not abs(P * t / d) < phase.PHASE_LIMIT for t in ts.tolist())     # Python floats: inf, silently
    T, S = FLOAT.tanh_sech(ts)
    values = trig_series.evaluate(T, S, runtime_basis._series_matrix(module._basis_core, P, d))
    cphi, sphi = runtime_basis.careful_phase(P, d, ts)
    sigma = module._BASIS_SIGMA[P]
    for j in range(3):
        re, im = values[3 + j], values[6 + j]
        assert np.array_equal(rows[:, 0, j], values[j])
        assert np.array_equal(rows[:, 1, j], cphi * re - sphi * im)
        assert np.array_equal(rows[:, 2, j], -sigma * (sphi * re + cphi * im))
    u = 2.0**-53
    with ctx.workprec(1400):
        for t, c, s in zip(ts, cphi, sphi):
            angle = arb(fmpq(P) * fmpq(*Fraction(float(t)).as_integer_ratio()) / fmpq(*Fraction(d).as_integer_ratio()))
            for value, exact in ((c, angle.cos()), (s, angle.sin())):
                assert abs(arb(float(value)) - exact) <= 2 * u * abs(exact) + basis_proof.FAR_RADIUS
    bound = float(basis_proof.prove(P)["far"].upper())
    for t, row in zip(ts, rows):
        twin = module.gamma_basis_mp(float(t), P, d, dps=40)
        with mpmath.workdps(40):
            assert max(abs(mpmath.mpf(float(row[i, j])) - twin[i, j]) for i in range(3) for j in range(3)) <= bound


def _omega_replica(module, t, p, d):
    """float_proofs.modelled's composition for omega: the emitted core on float64."""
    with np.errstate(all="ignore"):
        return np.stack(module._omega(FLOAT, np.float64(t), np.float64(p), np.float64(d)))


@pytest.mark.parametrize("t, d", [(0.0, 1.0), (0.7, 1.0), (-3.0, 0.25)])
def test_omega_replica_at_the_overflow_edge(module, monkeypatch, t, d):
    """p at adjacent floats: where the composition (the replica) stays finite it gives the public function's bits
    (float_proofs.modelled at these points); where only an intermediate (p/d, c p/d) overflows, the public function
    repairs the entry in mpmath (the twin's value, within the stated 5e-15; no proof covers it) and the replica has
    inf; where the value itself leaves float64 the public function raises ValueError and the replica has inf.
    At t = 0 the two edges are one."""
    def replica_finite(p):
        return bool(np.all(np.isfinite(_omega_replica(module, t, p, d))))

    def public_finite(p):
        return not raises_value_error(module.omega, t, p, d)

    core_below, core_above = edge(replica_finite, 1.0, FLOAT_MAX)
    public_below, public_above = edge(public_finite, 1.0, FLOAT_MAX) if not public_finite(FLOAT_MAX) else (None, None)
    for name, value in (("MODEL_T", t), ("MODEL_P", core_below), ("MODEL_D", d)):
        monkeypatch.setattr(float_proofs, name, np.array([value]))
    public, core = silent(float_proofs.modelled, module, "omega")
    assert np.array_equal(public, core) and np.all(np.isfinite(core))
    if t == 0.0:
        assert (public_below, public_above) == (core_below, core_above)
    else:
        assert public_below is None or public_below > core_above
        repaired = np.array(silent(module.omega, t, core_above, d))
        exact = module.omega_mp(t, core_above, d, dps=40)
        assert all(abs(w - float(e)) <= 5e-15 * abs(float(e)) for w, e in zip(repaired, exact))
        assert not replica_finite(core_above)
    if public_above is not None:
        with pytest.raises(ValueError, match="beyond float64"):
            silent(module.omega, t, public_above, d)
        assert np.any(np.isinf(_omega_replica(module, t, public_above, d)))
        with mpmath.workdps(40):
            assert max(abs(w) for w in module.omega_mp(t, public_above, d, dps=40)) > FLOAT_MAX
            assert max(abs(w) for w in module.omega_mp(t, public_below, d, dps=40)) <= FLOAT_MAX


def _omega_general_replica(module, t, I11, I22, I13, I23):
    """float_proofs.modelled's composition for omega_general (branch -1): entries over the largest, the core."""
    size = max(I11, I22, abs(I13), abs(I23))
    I11, I22, I13, I23 = (np.float64(x) / size for x in (I11, I22, I13, I23))
    with np.errstate(all="ignore"):
        return np.stack(module._omega_general(FLOAT, np.float64(t), I11, I22, I13, I23, -np.sqrt(I11 * I22)))


@pytest.mark.parametrize("t, shape", [(0.3, (1.0, 0.5, 1.0, 0.6)), (-1.2, (2.0, 3.0, -0.2, 1.0))])
def test_omega_general_replica_at_the_overflow_edge(module, t, shape):
    """Bodies (I11, I22, eps I13, eps I23), eps at adjacent floats: while the composition is finite (its divisor
    D = I11 I23^2 + I13^2 I22 is not yet 0) it gives the public function's bits; beyond, the public function repairs
    in mpmath (the twin's value) and the replica has inf or NaN; where omega itself passes 1.8e308 (eps near
    1e-308) the public function raises ValueError and the replica is not finite."""
    I11, I22, a13, a23 = shape

    def body(eps):
        return I11, I22, a13 * eps, a23 * eps

    def replica_finite(eps):
        return bool(np.all(np.isfinite(_omega_general_replica(module, t, *body(eps)))))

    def public_finite(eps):
        return not raises_value_error(module.omega_general, t, *body(eps), -1)

    core_ok, core_bad = edge(replica_finite, 1.0, 5e-324)
    public_ok, public_bad = edge(public_finite, 1.0, 5e-324)
    assert public_bad < public_ok < core_bad < core_ok < 1e-150
    below = np.array(silent(module.omega_general, t, *body(core_ok), -1))
    assert np.array_equal(below, _omega_general_replica(module, t, *body(core_ok)))
    for eps in (core_bad, public_ok):
        repaired = np.array(silent(module.omega_general, t, *body(eps), -1))
        exact = module.omega_general_mp(t, *body(eps), branch=-1, dps=40)
        assert all(abs(w - float(e)) <= 1e-14 * abs(float(e)) for w, e in zip(repaired, exact))
        assert not replica_finite(eps)
    with pytest.raises(ValueError, match="beyond float64"):
        silent(module.omega_general, t, *body(public_bad), -1)
    assert not replica_finite(public_bad)


def test_scattering_angle_replica_at_the_overflow_edges(module, monkeypatch):
    """Where fl(pi |p|) overflows (d = 1), where 2d overflows (p = d and p = d/2) and at the 2^1020 beyond which p
    and d are divided by 4: the public function gives the replica's bits (float_proofs.modelled at these points),
    silently, and within the proven 1.5e-14 of the twin (at p = d = 1e308 it gave NaN, at 2d overflowing 0)."""
    p_below, p_above = edge(lambda p: math.isfinite(math.pi * p), 1.0, FLOAT_MAX)
    d_below, d_above = edge(lambda d: math.isfinite(2.0 * d), 1.0, FLOAT_MAX)
    q_below, q_above = math.nextafter(2.0**1020, 0), math.nextafter(2.0**1020, math.inf)
    points = [(p_below, 1.0), (p_above, 1.0), (-p_above, 1.0)]
    for d in (d_below, d_above, q_below, 2.0**1020, q_above):
        points += [(d, d), (0.5 * d, d), (2.5, d)]
    points += [(q_below, 3.0), (q_above, 3.0)]
    p, d = (np.array(column) for column in zip(*points))
    angles = silent(module.scattering_angle, p, d)
    monkeypatch.setattr(float_proofs, "MODEL_P", p)
    monkeypatch.setattr(float_proofs, "MODEL_D", d)
    public, core = silent(float_proofs.modelled, module, "scattering_angle")
    assert np.array_equal(public, core) and np.array_equal(np.diagonal(public), angles)
    for (pv, dv), angle in zip(points, angles):
        assert abs(angle - float(module.scattering_angle_mp(pv, dv, dps=30))) <= 1.5e-14, (pv, dv)


@pytest.mark.parametrize("shape", [(2.0, 1.0, 1.0, -1.0), (1.0, 3.0, 0.3, 1.0)])
def test_general_angle_replica_at_the_overflow_edge(module, monkeypatch, shape):
    """Bodies (I11, I22, eps I13, eps I23) next to the equilibrium: eps at the h cap (1e300), where Y/lam overflows
    (lam subnormal), where lam underflows to 0: the composition model gives the public function's bits on both
    sides of each edge (where the float composition has none, both take the mpmath value; the model raised
    OverflowError there), silently, and the angle is within 1e-13 of the 400-bit ball."""
    from suslov.runtime.general_angle import _HUGE

    I11, I22, a13, a23 = shape

    def body(eps):
        return I11, I22, a13 * eps, a23 * eps

    def parts(eps):
        """(h, Y/lam) of the analysed composition (general_angle_proof's invariants and lengths)."""
        size = max(I11, I22, abs(a13 * eps), abs(a23 * eps))
        entries = [x / size for x in body(eps)]
        lam = max(abs(entries[2]), abs(entries[3]))
        if lam == 0:
            return math.nan, math.nan
        U2, a, b, c2 = (float(v) for v in general_angle_proof.invariants_model(
            entries[0], entries[1], entries[2] / lam, entries[3] / lam))
        U, _, Y = general_angle_proof.lengths_model(U2, a, b, c2)
        return 0.5 * math.pi * U / lam, Y / lam

    epsilons = list(edge(lambda eps: parts(eps)[0] <= _HUGE, 1.0, 1e-310))
    epsilons += edge(lambda eps: math.isfinite(parts(eps)[1]), 1.0, 1e-320)
    epsilons += edge(lambda eps: max(abs(a13 * eps), abs(a23 * eps)) / max(I11, I22) > 0, 1.0, 5e-324)
    bodies = [body(eps) for eps in epsilons]
    public = np.array([float(silent(module.general_scattering_angle, *b)) for b in bodies])
    model = np.array([silent(general_angle_proof.composition_model, module, *b) for b in bodies])
    assert np.array_equal(public, model)
    # the certificate's bit check at the bodies with lam > 0 (at lam = 0 its invariants are NaN, compared unequal)
    monkeypatch.setattr(general_angle_proof, "seeded_bodies", lambda: bodies[:5])
    assert silent(general_angle_proof.same_operations, module) == (True, 5)
    for b, angle in zip(bodies, public):
        ball = module.general_scattering_angle_ball(*b, prec=400)
        assert abs(angle - float(ball.mid())) <= 1e-13 + float(ball.rad()), b
