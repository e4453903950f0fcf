"""``build_formulas.py --verify`` rejects a seeded fault in every public run-time route (issue 44).

The emitted module is thin: its public functions call ``suslov/runtime/*.py`` and ``suslov/kernel/*.py``.  A user
who runs ``--verify`` on an install trusts it to notice a wrong answer from any of them, so each fault below (a
sign, a constant, an off-by-one in each route) is seeded into a copy and ``--verify`` must reject it with a
message naming the function.  Mechanism, as in ``bench/mutation_suite.py`` (one unique text replacement in a copy,
the detector run in a subprocess whose path starts with the copy) and ``tests/test_roundtrip.py`` (a generated
tree resealed with ``suslov.manifest`` after a change, so the round trip, not the manifest, must reject it): a COPY
of ``suslov/`` and ``generated/`` in ``tmp_path``, then ``build_formulas.py --verify <copy>/generated`` with the
copy first on ``sys.path`` (``python -c`` in the copy: ``sys.path[0]`` is the copy; the derivations from
``PYTHONPATH``, after it).  The checks that see these faults are the round trip's run-time route certificates
(``derivations/output/runtime_routes.py``) unless another check names the function first.

Each fault says why it changes behaviour at a checked point (a fault that changes nothing is not a fault);
``EQUIVALENT`` lists changes that were tried and change nothing observable, with the reason, and are not run.
The command line's --verify on the committed tree and on a mutated copy is tests/test_roundtrip.py's; here the
unmutated copy (which must pass) and the faults run in one batch that derives once (``tests/verify_faults_batch.py``): every suite run seeds
issue 44's four and one per public route (16), ``SUSLOV_ALL_FAULTS=1`` all 47 (all were rejected when written).
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
R, K = "suslov/runtime/", "suslov/kernel/"

# (id, names of which one must appear in the message, file, original (unique), mutated, why it is a fault)
FAULTS = [
    # issue 44's four silent ones first
    ("angle-mp-sign", ("scattering_angle_mp",), R + "angle.py", "out = emitted(MP, mpmath.pi * abs(p) / (2 * d), s, c)",
     "out = emitted(MP, mpmath.pi * abs(p) / (2 * d), s, -c)",
     "c = |cos(pi p/2)| enters atan2's second argument: the angle becomes 2 pi minus it (p = 2: c = 1)"),
    ("finite-repair-digits", ("omega",), K + "finite.py", "REPAIR_DPS = 30", "REPAIR_DPS = 3",
     "repaired entries get 3 digits (omega at p = 1e300, d = 1e10: c p overflows, 1e-3 relative error)"),
    ("careful-phase-constant", ("gamma_basis",), R + "basis.py",
     "angle = flint.fmpq(p) * flint.fmpq(*Fraction(float(tv)).as_integer_ratio()) / d_exact",
     "angle = flint.fmpq(p, 2) * flint.fmpq(*Fraction(float(tv)).as_integer_ratio()) / d_exact",
     "the far phase p t/d halved (|p t/d| >= 5.3e7: every far point's rotation changes)"),
    ("general-ball-target", ("general_scattering_angle_ball",), R + "general_angle.py",
     "_integer_body(exact), prec, prec + 30,", "_integer_body(exact), prec - 64, prec + 30,",
     "the ball stops growing 64 bits early: at |Y| ~ 1e20 it carries fewer relative bits than the prec asked"),
    # Theorem 5.4's angle: float64, mp twin, ball
    ("angle-float-sign", ("scattering_angle",), R + "angle.py", "return np.asarray(emitted(FLOAT, x, s, c), dtype=float)",
     "return np.asarray(emitted(FLOAT, x, s, -c), dtype=float)", "as angle-mp-sign, in float64"),
    ("angle-float-quarter", ("scattering_angle",), R + "angle.py", "> 2.0**1020, 0.25, 1.0)", "> 2.0**1020, 0.5, 1.0)",
     "p = 1.5e308, d = 1e308: pi p/2 overflows, x = inf gives pi for about 2.78"),
    ("angle-float-half-pi", ("scattering_angle",), R + "angle.py", "s, c = phase.half_pi_parts(p)",
     "s, c = phase.half_pi_parts(p + 1)", "p off by one swaps |sin| and |cos| of pi p/2 (p = 7.3: 0.41 and 0.91)"),
    ("angle-mp-digits", ("scattering_angle_mp",), R + "angle.py", "with mpmath.workdps(dps + 10):",
     "with mpmath.workdps(dps - 10):", "20 working digits for dps = 30"),
    ("angle-mp-half-pi", ("scattering_angle_mp",), R + "angle.py", "s, c = abs(mpmath.sinpi(p / 2))",
     "s, c = abs(mpmath.sinpi((p + 1) / 2))", "p off by one in |sin(pi p/2)| (p = 7.3)"),
    ("angle-ball-sign", ("scattering_angle_ball",), R + "angle.py", "abs((p / 2).cos_pi())", "-abs((p / 2).cos_pi())",
     "as angle-mp-sign, in balls: the ball excludes the angle"),
    ("angle-ball-precision", ("scattering_angle_ball",), R + "angle.py", "flint.ctx.workprec(prec + 20)",
     "flint.ctx.workprec(prec - 20)", "the ball carries about prec - 3 relative bits, fewer than asked"),
    ("angle-ball-d", ("scattering_angle_ball",), R + "angle.py", "flint.arb.pi() * abs(p) / (2 * d)",
     "flint.arb.pi() * abs(p) / (2 * d + 1)", "d off by one in x = pi |p|/(2d)"),
    # the angle of every body: float64 (three branches), mp twin, ball
    ("general-float-gap-sign", ("general_scattering_angle",), R + "general_angle.py",
     "angle = np.asarray(emitted(FLOAT, h, g, s, c), dtype=float)",
     "angle = np.asarray(emitted(FLOAT, h, -g, s, c), dtype=float)", "g = pi (U - X)/2 > 0 enters the exponentials"),
    ("general-float-repair-bits", ("general_scattering_angle",), R + "general_angle.py", "_REPAIR_BITS = 60",
     "_REPAIR_BITS = 6", "outside the proven domain the float64 value is replaced by a ball midpoint of ~30 bits"),
    ("general-float-phase", ("general_scattering_angle",), R + "general_angle.py", "_HUGE), Y / lam",
     "_HUGE), Y / lam + 1", "Y off by one shifts the phase pi Y/2 by pi/2 (|sin| and |cos| swap)"),
    ("general-mp-sign", ("general_scattering_angle_mp",), R + "general_angle.py", "return MPValue(+out, dps)",
     "return MPValue(-out, dps)", "the angle negated"),
    ("general-mp-target", ("general_scattering_angle_mp",), R + "general_angle.py",
     "target = math.ceil(dps * _LOG2_10) + 8", "target = math.ceil(dps * 1) + 8",
     "target bits = digits: at |Y| ~ 1e20 the first 35 working digits leave ~15 correct ones for dps = 20"),
    ("general-mp-entries", ("general_scattering_angle_mp",), R + "general_angle.py",
     "entries = _integer_body(tuple(rational(n, x) for n, x in zip(NAMES, given)))",
     "entries = _integer_body(tuple(rational(n, x) for n, x in zip(NAMES, given[1:] + given[:1])))",
     "the entries shifted by one place: another body"),
    ("general-extra-bits", ("general_scattering_angle",), R + "general_angle.py", "MAX_EXTRA_BITS = 65_536",
     "MAX_EXTRA_BITS = 16", "the routes refuse the body with |Y| ~ 1e20 (needs ~67 bits more than asked)"),
    ("general-ball-sign", ("general_scattering_angle_ball",), R + "general_angle.py",
     "return Ball(_certified_ball(invariants, emitted, _integer_body(exact)",
     "return Ball(-_certified_ball(invariants, emitted, _integer_body(exact)", "the ball of the angle negated"),
    ("general-ball-entries", ("general_scattering_angle_ball",), R + "general_angle.py",
     "else rational(n, x) for n, x in zip(NAMES, given))",
     "else rational(n, x) for n, x in zip(NAMES, given[1:] + given[:1]))",
     "the entries shifted by one place: another body"),
    # omega and omega_general: float64, mp twins, the repair
    ("omega-float-sign", ("omega",), R + "angular.py", "w1, w2 = emitted(FLOAT, t, p, d)",
     "w1, w2 = emitted(FLOAT, -t, p, d)",
     "omega1 is odd in t (t = 0.3)"),
    ("omega-float-sech-constant", ("omega", "gamma_basis"), K + "contexts.py", "            e *= 2.0\n",
     "            e *= 2.5\n",
     "sech t = 2e/(1 + e^2) scaled by 5/4 (float64 tanh_sech: omega, omega_general, gamma_basis)"),
    ("omega-float-repair-arguments", ("omega", "finite.repair"), R + "angular.py",
     '("t", "p", "d"), (t, p, d),', '("t", "p", "d"), (p, t, d),',
     "the repair evaluates at (p, t, d): at t = 0.5, p = 1e300 the repaired omega2 overflows"),
    ("omega-mp-sign", ("omega_mp",), R + "angular.py",
     "w1, w2 = emitted(MP, t, p, d)\n        return MPValue(+w1, dps), MPValue(+w2, dps)",
     "w1, w2 = emitted(MP, t, p, d)\n        return MPValue(+w1, dps), MPValue(-w2, dps)", "omega2 negated"),
    ("omega-mp-digits", ("omega_mp",), R + "angular.py",
     '    with mpmath.workdps(dps):\n        t, p, d = mp_real("t", t)',
     '    with mpmath.workdps(dps - 20):\n        t, p, d = mp_real("t", t)', "10 working digits for dps = 30"),
    ("omega-mp-t", ("omega_mp",), R + "angular.py", "w1, w2 = emitted(MP, t, p, d)\n",
     "w1, w2 = emitted(MP, t + 1, p, d)\n",
     "t off by one"),
    ("omega-general-float-branch", ("omega_general",), R + "angular.py", "r = sign * np.sqrt(I11 * I22)",
     "r = -sign * np.sqrt(I11 * I22)", "the other branch of r: the sech t terms change sign"),
    ("omega-general-repair-root", ("omega_general", "finite.repair"), R + "angular.py",
     "sign * mpmath.sqrt(a * b))", "sign * mpmath.sqrt(a * b + 1))",
     "r off by one in the repair: at I11 I22 = 1 the repaired omega2 has r = sqrt 2"),
    ("omega-general-float-scale", ("omega_general",), R + "angular.py",
     "I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / size\n    sign",
     "I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / (2 * size)\n    sign",
     "I23 scaled by a different constant: another body"),
    ("omega-general-mp-sign", ("omega_general_mp",), R + "angular.py", "r = branch_sign(branch) * mpmath.sqrt(I11 * I22)",
     "r = -branch_sign(branch) * mpmath.sqrt(I11 * I22)", "the other branch of r"),
    ("omega-general-mp-digits", ("omega_general_mp",), R + "angular.py",
     '    with mpmath.workdps(dps):\n        t = mp_real("t", t)',
     '    with mpmath.workdps(dps - 20):\n        t = mp_real("t", t)',
     "10 to 20 working digits for dps = 30 and 40"),
    ("omega-general-mp-t", ("omega_general_mp",), R + "angular.py", "w1, w2 = emitted(MP, t, I11, I22, I13, I23, r)",
     "w1, w2 = emitted(MP, t + 1, I11, I22, I13, I23, r)", "t off by one"),
    # the finite-value repair itself
    ("finite-repair-sign", ("omega", "finite.repair"), K + "finite.py", "o[index] = float(v)", "o[index] = -float(v)",
     "repaired entries negated"),
    ("finite-repair-output-index", ("omega", "finite.repair"), K + "finite.py",
     "enumerate(zip(outputs, values))", "enumerate(zip(outputs, values[1:]))",
     "output k gets value k + 1 and the last stays non-finite"),
    # the first integral: float64 and mp twin
    ("integral-float-sign", ("first_integral",), R + "integrals.py", "* mantissa[mask] ** p\n",
     "* (-mantissa[mask]) ** p\n", "odd p: F3 negated"),
    ("integral-float-exponent", ("first_integral",), R + "integrals.py",
     "exponents = p * exponent[mask].astype(np.int64) + E", "exponents = p * exponent[mask].astype(np.int64) + E + 1",
     "the power-of-two scale off by one: F3 doubled"),
    ("integral-float-clip", ("first_integral",), R + "integrals.py", "np.clip(exponents, -4000, 4000)",
     "np.clip(exponents, -4000, 40)", "s^p about 2^900: the scale clipped at 2^40"),
    ("integral-mp-sign", ("first_integral_mp",), R + "integrals.py", "w1 ** (p - k) * w2**k", "w1 ** (p - k) * (-w2)**k",
     "the odd powers of omega2 negated"),
    ("integral-mp-digits", ("first_integral_mp",), R + "integrals.py",
     "    with mpmath.workdps(dps):\n        w1, w2, g1, g2, g3",
     "    with mpmath.workdps(dps - 20):\n        w1, w2, g1, g2, g3",
     "10 working digits for dps = 30"),
    ("integral-mp-index", ("first_integral_mp",), R + "integrals.py", "for k, a in enumerate(exact[name]))",
     "for k, a in enumerate(exact[name], 1))", "the power of omega2 off by one"),
    # the basis: float64 (near and far phase), mp twin
    ("basis-float-sign", ("gamma_basis",), R + "basis.py", "out[:, 1, j] = cphi * re - sphi * im",
     "out[:, 1, j] = cphi * re + sphi * im", "gamma^(2) rotated the other way"),
    ("careful-phase-sign", ("gamma_basis",), R + "basis.py",
     "cos_out[index], sin_out[index] = float(cos_ball.mid()), float(sin_ball.mid())",
     "cos_out[index], sin_out[index] = float(cos_ball.mid()), -float(sin_ball.mid())", "the far phase's sine negated"),
    ("careful-phase-t", ("gamma_basis",), R + "basis.py",
     "flint.fmpq(*Fraction(float(tv)).as_integer_ratio()) / d_exact",
     "flint.fmpq(*Fraction(float(tv) + 1).as_integer_ratio()) / d_exact", "t off by one in the far phase"),
    ("basis-mp-sign", ("gamma_basis_mp",), R + "basis.py", "out[2, j] = -sigma[p] * (sphi * re + cphi * im)",
     "out[2, j] = sigma[p] * (sphi * re + cphi * im)", "gamma^(3) negated"),
    ("basis-mp-phase-digits", ("gamma_basis_mp",), R + "basis.py", "with mpmath.workdps(dps + 10 + extra):",
     "with mpmath.workdps(dps - 10 + extra):", "the phase p t/d ~ 1e11 to 20 fewer digits"),
    ("basis-mp-harmonic", ("gamma_basis_mp",), R + "basis.py", "mpf_cos_sin(mpf_mul_int(th_, k, prec, rnd), prec, rnd)",
     "mpf_cos_sin(mpf_mul_int(th_, k + 1, prec, rnd), prec, rnd)", "the harmonics (cos and sin of k th) off by one"),
]

# tried, and observable nowhere: not faults (not run)
EQUIVALENT = [
    ("careful_phase precision constants",
     ("suslov/runtime/basis.py careful_phase: the start 64 + size bits (4, 640), the +1, FAR_RADIUS (2^-7, 1) and the "
     "doubling factor (3) only change how many passes its loop makes until both radii are below 2^-70 (the first "
     "pass is already near 2^-64): bit-identical cos and sin at 500 far phases (p = 5, d = 1e-3, t up to 1e300); "
     "probably the issue's silent 'constant changed in careful_phase'")),
    ("scale constants",
     ("suslov/runtime/angular.py omega_general: dividing every entry by 2 size instead of size, and "
     "suslov/runtime/integrals.py float_coefficients: E + 1 (the coefficients' scale, undone with the same E): "
     "exact rescalings of quantities homogeneous of degree 0")),
    ("signs under abs or an even function",
     "suslov/runtime/angle.py: -pi |p|/(2d) or |-p| (x enters through sech and tanh^2, p through |sin|, |cos|)"),
    ("thresholds beyond the reach of float64",
     "suslov/runtime/angle.py: 2^1021 or 2^1022 for 2^1020 (pi |p| and 2d are still finite there)"),
]


def seeded_tree(tmp_path: Path, path: str | None = None, original: str = "", mutated: str = "") -> Path:
    """A copy of suslov/ and generated/ in tmp_path with one unique text replaced (none for path=None)."""
    for name in ("suslov", "generated"):
        shutil.copytree(ROOT / name, tmp_path / name, ignore=shutil.ignore_patterns("__pycache__"))
    if path is not None:
        target = tmp_path / path
        text = target.read_text(encoding="utf-8")
        assert text.count(original) == 1, f"fault site not unique or missing in {path}: {original!r}"
        target.write_text(text.replace(original, mutated), encoding="utf-8")
        if path.startswith("generated/"):     # a consistent tree, as a faulty build writes it (tests/test_roundtrip.py)
            from suslov.manifest import read, write
            write(tmp_path / "generated", read(tmp_path / "generated"))
    return tmp_path


def run_in(tree: Path, *args: str) -> subprocess.CompletedProcess:
    """``python -c CODE ARGS`` in ``tree``: sys.path[0] is the tree (its suslov), then the project (derivations)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(tree), str(ROOT)]), SUSLOV_NO_CACHE="1")
    return subprocess.run([sys.executable, *args], cwd=tree, env=env, capture_output=True, text=True, timeout=900,
                          check=False)


def test_each_fault_site_is_unique_and_changes_the_text():
    for ident, _, path, original, mutated, why in FAULTS:
        assert (ROOT / path).read_text(encoding="utf-8").count(original) == 1, f"{ident}: site not unique in {path}"
        assert original != mutated and why, ident
    assert len({f[0] for f in FAULTS}) == len(FAULTS)


def test_a_copy_is_what_runs(tmp_path):
    """A process started in a copy imports the copy's run-time code and the project's derivations (the command
    line's --verify on the committed tree and on a mutated copy: tests/test_roundtrip.py)."""
    tree = seeded_tree(tmp_path)
    where = run_in(tree, "-c", "import suslov.runtime.angle as a, derivations; print(a.__file__, derivations.__file__)")
    assert where.returncode == 0, where.stderr
    runtime, derivations = where.stdout.split()
    assert Path(runtime).is_relative_to(tree) and Path(derivations).is_relative_to(ROOT)


def _every_run() -> list:
    """The faults of every suite run: issue 44's four silent ones and the first fault of every other route (one
    per public function); SUSLOV_ALL_FAULTS=1 runs all of them (about 70 s more on 2 cores)."""
    if os.environ.get("SUSLOV_ALL_FAULTS") == "1":
        return list(FAULTS)
    chosen, routes = [], set()
    for index, fault in enumerate(FAULTS):
        if index < 4 or fault[1][0] not in routes:
            chosen.append(fault)
            routes.add(fault[1][0])
    return chosen


def test_every_public_route_has_a_fault_in_every_run():
    routes = {f[1][0] for f in FAULTS}
    assert routes == {f[1][0] for f in _every_run()} and len(routes) == 14


@pytest.mark.slow
def test_each_seeded_fault_is_rejected_naming_the_function(tmp_path):
    """The faults of :func:`_every_run` through --verify's checks, derived once (tests/verify_faults_batch.py: each
    copy's suslov and the checking layers imported afresh from the copy)."""
    import json

    trees = {str(seeded_tree(tmp_path / ident, path, original, mutated)): (ident, names, why)
             for ident, names, path, original, mutated, why in _every_run()}
    control = str(seeded_tree(tmp_path / "unmutated"))   # the batch must pass an unmutated copy, or it proves nothing
    env = dict(os.environ, PYTHONPATH=str(ROOT), SUSLOV_NO_CACHE="1")
    done = subprocess.run([sys.executable, str(ROOT / "tests" / "verify_faults_batch.py"), control, *trees], cwd=ROOT,
                          env=env, capture_output=True, text=True, timeout=900, check=False)
    assert done.returncode == 0, done.stderr[-3000:]
    outcome = json.loads(done.stdout.strip().splitlines()[-1])
    assert outcome[control] is None, f"the unmutated copy fails the batch's checks: {outcome[control][:600]}"
    passed = [f"{ident} ({why})" for tree, (ident, _, why) in trees.items() if outcome[tree] is None]
    assert not passed, f"seeded faults that pass the checks: {passed}"
    unnamed = [f"{ident}: {outcome[tree][:300]}" for tree, (ident, names, _) in trees.items()
               if not any(name in outcome[tree] for name in names)]
    assert not unnamed, f"rejections that name none of the function's names: {unnamed}"
