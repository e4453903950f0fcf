"""The generated module is certified as emitted: round trip, --verify, and mutations of a copy.

Each mutation below is a single deliberate arithmetic fault in a copy of the committed
module (a flipped sign, a changed coefficient, an exponent off by one, a wrong branch or
frame convention) or in the run-time kernel it uses; ``--verify`` must reject each one and
name the function.  The expected outcome is independent of the code under test: the
certified objects of the derivations (exact) and the mpmath twins (numeric).
"""
import shutil
import subprocess
import sys

import numpy as np
import pytest

from derivations.output.pipeline import GENERATED, ROOT
from derivations.output.roundtrip import load_module, verify

MUTATIONS = [
    # faults in the emitted formulas of the generated module: (function named in the message, original, mutated)
    ("_omega", "k1 = -c*p/d", "k1 = c*p/d"),
    ("_omega_general", "k3 = I11*I23*r/(I11*(I23*I23) + (I13*I13)*I22)", "k3 = I11*I23*r/(I11*(I23*I23) + (I13*I13*I13)*I22)"),
    ("_lambda_squared", "return (I11*I22*(I11 - I22)*", "return (I11*I22*(I11 + I22)*"),
    ("_p_squared_i23_zero", "return -I11*(I11 - I22)/(I13*I13)", "return I11*(I11 - I22)/(I13*I13)"),
    ("_special_parameters", "return (-I22*d/I23, d)", "return (-I22*d/I23, d*d)"),
    ("_scattering_angle", "c*ctx.sech(x))", "c*ctx.sech(2*x))"),
    # the thin public functions themselves (what they pass to suslov.runtime)
    ("gamma_basis", "_basis.gamma_basis(_basis_core, _BASIS_SIGMA, BASIS_PS, t, p, d)",
     "_basis.gamma_basis(_basis_core, {p: -s for p, s in _BASIS_SIGMA.items()}, BASIS_PS, t, p, d)"),
]

# faults in the modules the public functions call (suslov/runtime): (name in the message, file, original, mutated)
RUNTIME_MUTATIONS = [
    ("first_integral", "integrals.py", '"P2": numerators.K**2 * numerators.Den', '"P2": numerators.K * numerators.Den'),
    ("special_case_parameters", "bodies.py", "if I23 > 0:", "if I23 < 0:"),
    ("gamma_basis", "basis.py", "sign = -sigma[p]", "sign = sigma[p]"),
    # shared by the float path and the mp twin, and still a rotation: no float-path proof sees it, the exact
    # evaluations do (the run-time route check of gamma_basis, which verify() runs first, at (t, p, d) =
    # (12000, 5, 0.001); the mp twin's): "gamma_basis" is in both names
    ("gamma_basis", "basis.py", "rows += [[f * v / k for v in comp]", "rows += [[f * v / k.conjugate() for v in comp]"),
    # the coefficients rounded to the caller's precision instead of dps: off by 1e-17, seen only at high dps
    ("gamma_basis_mp", "basis.py", "return mpmath.mp.make_mpf(mpmath.libmp.from_man_exp(int(man), int(exp)))",
     "return mpmath.mpf((int(man), int(exp)))"),
    ("meromorphy", "bodies.py", 'case, p2 = "I23=0", float(p_squared_i23_zero(FLOAT, I11, I22, I13))',
     'case, p2 = "I23=0", float(p_squared_i13_zero(FLOAT, I11, I22, I13))'),
    # issue 27, finding 9: the careful phase beyond the double-double range (|p t/d| >= 5.3e7)
    ("gamma_basis", "basis.py", "cos_out[index], sin_out[index] = float(cos_ball.mid()), float(sin_ball.mid())",
     "cos_out[index], sin_out[index] = float(sin_ball.mid()), float(cos_ball.mid())"),
    ("gamma_basis", "basis.py", "sin_ball, cos_ball = flint.arb(angle).sin_cos()",
     "sin_ball, cos_ball = flint.arb(float(angle)).sin_cos()"),
    # finding 10: the fifth exponent, and the odd-p test of meromorphy
    ("kovalevskaya_exponents", "bodies.py", "[-1, 1, 2, 1 + lam, 1 - lam]", "[-1, 1, 2, 1 + lam, 2 - lam]"),
    ("meromorphy", "bodies.py", "round(p) % 2 == 1", "round(p) % 2 == 0"),
    ("omega", "angular.py", 'finite.repair("omega", (full(w1, shape), full(w2, shape))',
     'finite.repair("omega", (full(w1, shape), full(-w2, shape))'),
    ("scattering_angle", "angle.py", "x = np.pi * np.abs(p * quarter) / (2.0 * (d * quarter))",
     "x = np.pi * np.abs(p * quarter) / (2.0 * (d * quarter)) * (1 + 1e-12)"),
    ("first_integral", "integrals.py", "value[mask] = horner.combination(coefficients, w1[mask], w2[mask], g[:, mask]) * "
     "mantissa[mask] ** p", "value[mask] = horner.combination(coefficients, w2[mask], w1[mask], g[:, mask]) * "
     "mantissa[mask] ** p"),
]


def mutated_runtime(monkeypatch, filename, original, mutated):
    """Replace ``suslov.runtime.<module>`` by a copy with one fault, for every import made from now on."""
    import importlib
    import types

    import suslov.runtime

    name = f"suslov.runtime.{filename[:-3]}"
    path = ROOT / "suslov" / "runtime" / filename
    text = path.read_text(encoding="utf-8")
    assert text.count(original) == 1, f"mutation site not unique: {original!r}"
    module = types.ModuleType(name)
    module.__file__, module.__package__ = str(path), "suslov.runtime"
    exec(compile(text.replace(original, mutated), str(path), "exec"), module.__dict__)
    importlib.import_module(name)   # the real one is loaded, so the patch below is what later imports see
    monkeypatch.setitem(sys.modules, name, module)
    monkeypatch.setattr(suslov.runtime, filename[:-3], module)


@pytest.mark.parametrize("name, filename, original, mutated", RUNTIME_MUTATIONS,
                         ids=[f"{m[1][:-3]}-{m[0]}-{i}" for i, m in enumerate(RUNTIME_MUTATIONS)])
def test_each_runtime_mutation_is_rejected_and_named(default_build, monkeypatch, name, filename, original, mutated):
    mutated_runtime(monkeypatch, filename, original, mutated)
    problem = verify(default_build, GENERATED, jobs=1)   # the fault is patched into this process
    assert problem is not None, f"mutation in suslov/runtime/{filename} passed the round trip"
    assert name in problem


def replaced_copy(source, target, original, mutated):
    """A copy of the tree ``source`` at ``target`` whose module has one unique text replaced."""
    shutil.copytree(source, target, ignore=shutil.ignore_patterns("__pycache__"))
    path = target / "suslov_formulas.py"
    text = path.read_text(encoding="utf-8")
    assert text.count(original) == 1, f"mutation site not unique: {original!r}"
    path.write_text(text.replace(original, mutated), encoding="utf-8")
    return target


def mutated_copy(tmp_path, original, mutated):
    target = replaced_copy(GENERATED, tmp_path / "generated", original, mutated)
    # a consistent tree with a wrong formula (its manifest rewritten, as a faulty build would write it): what
    # the round trip must reject; a tree changed after its build is refused earlier (tests/test_manifest.py)
    from suslov.manifest import MANIFEST, read, write

    write(target, read(target))
    assert (target / MANIFEST).is_file()
    return target


def test_committed_module_passes_the_round_trip(default_build):
    assert verify(default_build, GENERATED) is None


@pytest.mark.parametrize("name, original, mutated", MUTATIONS, ids=[m[0] for m in MUTATIONS])
def test_each_mutation_is_rejected_and_named(tmp_path, default_build, name, original, mutated):
    problem = verify(default_build, mutated_copy(tmp_path, original, mutated), jobs=1)   # detection, not workers
    assert problem is not None, f"mutation in {name} passed the round trip"
    assert name.lstrip("_") in problem


def test_fault_in_the_runtime_kernel_is_rejected(default_build, monkeypatch):
    """The r >= 1/2 branch of the exact reduction of pi p/2 (scattering angle near odd p)."""
    from suslov.kernel import phase

    def faulty(p):
        p = np.asarray(p, dtype=float)
        r = np.abs(p - 2.0 * np.round(p / 2.0))
        return np.sin(0.5 * np.pi * r), np.where(r >= 0.5, np.cos(0.5 * np.pi * (1.0 - r)), np.cos(0.5 * np.pi * r))

    monkeypatch.setattr(phase, "half_pi_parts", faulty)
    problem = verify(default_build, GENERATED, jobs=1)   # the fault is patched into this process
    assert problem is not None and "scattering_angle" in problem


def test_emitted_functions_are_the_ones_the_public_api_calls():
    """The public functions evaluate the emitted code: patching it changes their values."""
    module = load_module(GENERATED)
    w1, _ = module.omega(0.5, 3, 0.5)
    module._omega = lambda ctx, t, p, d: (0 * t + 7.0, 0 * t)
    assert float(module.omega(0.5, 3, 0.5)[0]) == 7.0 != float(w1)


def run_cli(*args):
    return subprocess.run([sys.executable, "build_formulas.py", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=600)


def test_verify_cli_on_committed_tree_and_on_a_mutated_copy(tmp_path):
    ok = run_cli("--verify", "generated", "--quiet")
    assert ok.returncode == 0, ok.stderr
    assert "reproduces the certified objects" in ok.stdout
    name, original, mutated = MUTATIONS[0]
    copy = mutated_copy(tmp_path, original, mutated)
    before = (copy / "suslov_formulas.py").read_bytes()
    bad = run_cli("--verify", str(copy), "--quiet")
    assert bad.returncode == 1
    assert "_omega" in bad.stderr and "differs" in bad.stderr
    assert (copy / "suslov_formulas.py").read_bytes() == before  # nothing rewritten


def test_verify_bad_directory_is_a_clear_error(tmp_path):
    result = run_cli("--verify", str(tmp_path), "--quiet")
    assert result.returncode == 2 and "no suslov_formulas.py" in result.stderr


# ---------------------------------------------------------------- bases beyond the kept ones (p > 15)


@pytest.fixture(scope="module")
def build19(tmp_path_factory):
    """A build of what the module needs at pmax 19 (one process) and its emitted module: p = 17, 19 are the bases
    the meromorphic derivation leaves to the round trip (certified on the emitted core's numerators)."""
    from derivations.core.options import BuildOptions
    from derivations.output.pipeline import MODULE_NEEDS, derive, render_into

    build = derive(BuildOptions(pmax=19, jobs=1), list(MODULE_NEEDS))
    assert build.results["meromorphic"].exports["pending"] == [17, 19]
    tree = tmp_path_factory.mktemp("pmax19")
    render_into(build, tree, only=("__init__.py", "suslov_formulas.py"))
    return build, tree


def faulty_copy(tmp_path, tree, original, mutated):
    return replaced_copy(tree, tmp_path / "tree", original, mutated)


def in_workers(monkeypatch):
    """The per-p phases of two values through the worker processes (PARALLEL_MIN is 16)."""
    from derivations.core import certificates

    monkeypatch.setattr(certificates, "PARALLEL_MIN", 1)


def test_bases_beyond_15_are_certified_on_the_emitted_core(build19, monkeypatch):
    """p = 17, 19: the meromorphic certificates are made in the round trip, on the emitted core's numerators, and
    recorded as the derivation's (labels and claims as for a kept basis); the term counts handed back are those of
    the recipe's basis constructed here; one process and the workers write the same log."""
    from derivations.core.certificates import CertificateLog
    from derivations.core.statement import say
    from derivations.output.roundtrip import EMITTED_CORE, certify_module
    from derivations.sections import meromorphic

    build, tree = build19
    logs, bases = {}, {}
    for jobs in (1, 2):
        if jobs == 2:
            in_workers(monkeypatch)
        logs[jobs], bases[jobs] = CertificateLog(workers=jobs), {}
        certify_module(logs[jobs], build, tree, bases=bases[jobs])
    assert [c.deterministic_record() for c in logs[1].certificates] == [c.deterministic_record() for c in logs[2].certificates]
    assert bases[1] == bases[2] and sorted(bases[1]) == [17, 19]
    by_key = {c.key: c for c in logs[1].certificates}
    for p in (17, 19):
        made = [by_key[k] for k in bases[1][p]["certificates"]]
        assert [c.label for c in made] == ["eq:gam3", "F_23_pol", "eq:ps", "gam1, gam2, gam3", "asymp"]
        assert all(c.derivation == "meromorphic" and c.claim.startswith(f"p = {p}:") for c in made)
        assert str(made[0].detail) == str(say(EMITTED_CORE)) and "conservation" in str(made[3].method)
        real, cplx = meromorphic.construct(p)
        assert bases[1][p]["terms"] == [len(m) for m in real.M + cplx.M]
    cores = [c for c in logs[1].certificates if "exact core of gamma_basis reproduces" in c.claim]
    assert [int(str(c.claim).split(":")[0][4:]) for c in cores] == list(range(1, 16, 2))   # the kept ones only
    # and the rows the build renders: completed once the round trip has certified them
    assert all(row["terms"] == [] for row in build.results["meromorphic"].exports["rows"] if row["p"] > 15)


def perturbed_core(line: str) -> tuple:
    """The emitted ``_basis_core`` with ``line`` applied to its numerators at p = 17 (a mutation site)."""
    return ("    return _basis_recipe.construct(p, ring)\n",
            "    real, cplx = _basis_recipe.construct(p, ring)\n    if p == 17:\n" + line + "    return real, cplx\n")


@pytest.mark.parametrize("jobs", [1, 2])
@pytest.mark.parametrize("line", ["        real.M[1] = 3 * real.M[1]\n", "        cplx.M[1] = cplx.M[1] + ring.x**3\n"],
                         ids=["gamma1-component-2-times-3", "V2-plus-x3"])
def test_a_perturbed_emitted_core_beyond_15_is_refused(build19, tmp_path, monkeypatch, jobs, line):
    """The emitted ``_basis_core`` changes one numerator at p = 17: no certified basis is compared with it any more,
    so the certificates made on it must refuse it (numerators that solve no Poisson equation), in one process and in
    the workers, with the same message.  The first perturbation passes every float-path check (they evaluate the
    numerators the core gives, and a second component of gamma^(1) three times too large keeps the parity, the degree
    and sigma): only the certificates on the core see it (measured: with them skipped the round trip passes)."""
    build, tree = build19
    if jobs == 2:
        in_workers(monkeypatch)
    problem = verify(build, faulty_copy(tmp_path, tree, *perturbed_core(line)), jobs=jobs)
    assert problem is not None and problem.startswith("p = 17: gammaI and the complex solution"), problem
    assert "Poisson equations" in problem and "emitted module's _basis_core" in problem


@pytest.mark.parametrize("jobs", [1, 2])
def test_sigma_plus_one_beyond_15_is_refused(build19, tmp_path, monkeypatch, jobs):
    """The emitted module says sigma = +1 for p = 17 (derived and certified: -1): the exact check of gamma_basis_mp
    against the certified numerators refuses it, in one process and in the workers."""
    build, tree = build19
    if jobs == 2:
        in_workers(monkeypatch)
    problem = verify(build, faulty_copy(tmp_path, tree, "15: -1, 17: -1, 19: -1}", "15: -1, 17: 1, 19: -1}"), jobs=jobs)
    assert problem is not None and problem.startswith("p = 17: gamma_basis_mp"), problem


def test_a_derived_sigma_the_numerators_contradict_fails_the_round_trip(build19, monkeypatch):
    """Had the derivation emitted sigma = +1 for p = 17, the asymp certificate on the emitted core's numerators (which
    give -1) fails, and the round trip stops there."""
    from derivations.core.certificates import Outcome
    from derivations.output.roundtrip import certify_emitted_basis, load_module

    build, tree = build19
    module = load_module(tree)
    certs, numerators, _ = certify_emitted_basis(module, 17, 1)
    assert [c.outcome for c in certs] == [Outcome.PASS] * 4 + [Outcome.FAIL] and numerators is None
    assert "sigma = -1 from the numerators" in str(certs[-1].detail)
    assert [c.outcome for c in certify_emitted_basis(module, 17, -1)[0]] == [Outcome.PASS] * 5
    monkeypatch.setitem(build.results["meromorphic"].exports["sigma"], 17, 1)
    problem = verify(build, tree, jobs=1)
    assert problem is not None and problem.startswith("p = 17: gammaI tends to"), problem
