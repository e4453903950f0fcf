"""Mutation suite: seeded single-point faults, each expected to be rejected by the build, ``--verify`` or a test.

Issue 27 ("bugs the certificates and tests let through"): a certified pipeline must fail loudly when
its code is wrong.  Each mutant below changes one place in ``derivations/``, ``suslov/kernel``,
``suslov/recipes``, the template or the emitted module (a flipped sign, an index or exponent off by
one, a swapped pair, a weakened bound, a dropped element) and names the detector that must reject
it:

* ``build``: ``build_formulas.py --no-cache --out DIR`` exits non-zero (a certificate or the round
  trip of the emitted module fails);
* ``verify``: ``build_formulas.py --verify generated`` exits 1 (the committed module, mutated);
* ``test:NODE``: ``pytest NODE`` fails.

Each mutant runs in a fresh copy of the working tree (tracked and untracked, not ignored files),
with ``PYTHONPATH`` pointing at the copy and the certificate cache off.  A mutant the detector does
not reject is *silent*; the table says so.  Equivalent mutants (no observable change) are listed in
``EQUIVALENT`` with the reason and not run.

    python bench/mutation_suite.py                # all mutants, table in bench/results/mutations.md
    python bench/mutation_suite.py --only phase   # mutants whose id contains "phase"
"""
from __future__ import annotations

import argparse
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
T = "templates/suslov_formulas.py.j2"
G = "generated/suslov_formulas.py"
R = "suslov/runtime/"

# (id, file, original text (unique in the file), mutated text, detector)
MUTANTS = [
    # derivations: the certification core and the paper's sections (the build must fail)
    ("exact-zero-test-always-zero", "derivations/core/exact.py", "    return form.is_zero\n", "    return True\n", "build"),
    ("residue-drop-first-obstruction", "derivations/sections/residue.py",
     "for k, name, value in obstructions if not value.is_zero()]",
     "for k, name, value in obstructions[1:] if not value.is_zero()]", "test:tests/test_independent_tables.py"),
    ("common-denominator-no-gcd-test", "derivations/core/common_denominator.py",
     "if not numerator.is_zero() and any(", "if False and any(", "test:tests/test_common_denominator.py"),
    ("polynomial-reader-fractional-exponent", "derivations/core/common_denominator.py",
     "isinstance(factor.args[0], se.Symbol) and isinstance(\n                    factor.args[1], se.Integer):",
     "isinstance(factor.args[0], se.Symbol):", "test:tests/test_exact.py"),
    ("obstruction-convolution-recursion", "derivations/sections/local_obstruction.py",
     "rhs += aE[j] * Y[k - j] - bE[j] * S[k - j]", "rhs += aE[j] * Y[k - j] - bE[j] * Y[k - j]", "build"),
    ("fingerprint-without-coefficients", "derivations/sections/meromorphic.py",
     'digest.update(",".join([c.p.str(16) for c in coefficients]).encode())', "pass",
     "test:tests/test_basis_fingerprint.py"),
    ("factor-generators-alphabetical", "derivations/core/flint_factor.py", "return tuple(_sort_gens(list(symbols)))",
     "return tuple(sorted(symbols, key=str))", "test:tests/test_flint_factor.py"),
    ("laurent-csch-sign", "derivations/sections/residue.py", "csch = [-2 * (sp.Integer(2) ** (2 * k - 1) - 1)",
     "csch = [2 * (sp.Integer(2) ** (2 * k - 1) - 1)", "build"),
    # suslov/recipes: written once, run exactly by the build (the build must fail)
    ("recipe-integrals-qk", "suslov/recipes/integrals.py", "q_k = (2 * k + 1) ** 2 * D**2 + p**2",
     "q_k = (2 * k + 1) ** 2 * D**2 + p", "build"),
    ("recipe-basis-DD-factor", "suslov/recipes/basis.py", "base = D * (X * ring.dx(N) * (1 + X**2) - 2 * q * X**2 * N)",
     "base = D * (X * ring.dx(N) * (1 + X**2) - q * X**2 * N)", "build"),
    ("runtime-integrals-K-power", R + "integrals.py", '"P2": numerators.K**2 * numerators.Den',
     '"P2": numerators.K * numerators.Den', "verify"),
    # suslov/kernel: run-time numerics (the round trip, in the build and in --verify)
    ("phase-cody-waite-constant", "suslov/kernel/phase.py", "_C1, _C2, _C3 = 6.283185303211212, 3.9683743166540886e-09",
     "_C1, _C2, _C3 = 6.283185303211212, 3.9683743166540886e-08", "verify"),
    ("phase-half-angle-sign", "suslov/kernel/phase.py", "np.subtract(1.0, u2, out=u2)", "np.subtract(u2, 1.0, out=u2)",
     "verify"),
    ("horner-reversed-branch", "suslov/kernel/horner.py", "c = np.where(first, c, c[::-1])",
     "c = np.where(first, c[::-1], c)", "verify"),
    ("trig-series-sin-rows", "suslov/kernel/trig_series.py", "real[p + 1:, :m] = powers[:, :m].imag",
     "real[p + 1:, :m] = -powers[:, :m].imag", "verify"),
    ("frames-no-scaling", "suslov/kernel/frames.py", "M, scale = M / scale, 1.0", "scale = scale",
     "test:tests/test_bad_input.py"),
    ("validate-dps-lower-limit", "suslov/kernel/validate.py", "DPS_RANGE = (1, 10_000)", "DPS_RANGE = (-10, 10_000)",
     "test:tests/test_bad_input.py"),
    ("enclosure-truncation-exponent", "suslov/kernel/enclosure.py", "ratio ** (order + 1)", "ratio ** (order + 3)",
     "test:tests/test_independent_tables.py"),
    ("enclosure-limit-series-ratio", "suslov/kernel/enclosure.py", "q = max(arb(1), (k + 1 + W) / (k + 2))",
     "q = max(arb(1) / 2, (k + 1 + W) / (k + 2))", "test:tests/test_independent_tables.py"),
    ("enclosure-no-step-error", "suslov/kernel/enclosure.py",
     "step_error += _norm_upper([arb(0, b.rad()) for b in balls]) + truncation",
     "step_error += _norm_upper([arb(0, b.rad()) for b in balls])", "test:tests/test_independent_tables.py"),
    # the template (the build's round trip must reject the module it emits)
    ("runtime-careful-phase-swap", R + "basis.py",
     "cos_out[index], sin_out[index] = float(cos_ball.mid()), float(sin_ball.mid())",
     "cos_out[index], sin_out[index] = float(sin_ball.mid()), float(cos_ball.mid())", "verify"),
    ("runtime-careful-phase-digits", R + "basis.py", "sin_ball, cos_ball = flint.arb(angle).sin_cos()",
     "sin_ball, cos_ball = flint.arb(float(angle)).sin_cos()", "verify"),
    ("phase-lost-double-double-term", "suslov/kernel/phase.py", "    low += q2 * b1\n", "", "verify"),
    ("runtime-kovalevskaya-fifth", R + "bodies.py", "[-1, 1, 2, 1 + lam, 1 - lam]", "[-1, 1, 2, 1 + lam, 2 - lam]",
     "verify"),
    ("runtime-meromorphy-odd", R + "bodies.py", "round(p) % 2 == 1", "round(p) % 2 == 0", "verify"),
    ("runtime-basis-sigma", R + "basis.py", "sign = -sigma[p]", "sign = sigma[p]", "verify"),
    ("runtime-special-case-turn", R + "bodies.py", "if I23 > 0:", "if I23 < 0:", "verify"),
    ("template-basis-call", T, "{{ f.call }}", "{{ f.call.replace('BASIS_PS, t, p, d)', 'BASIS_PS, -t, p, d)') }}",
     "build"),
    ("runtime-dps-unchecked", R + "angle.py", '    dps = mp_dps(dps)\n    with mpmath.workdps(dps + 10):',
     '    with mpmath.workdps(dps + 10):', "verify"),
    # the emitted module itself (--verify of the committed tree)
    ("emitted-omega-sign", G, "k1 = -c*p/d", "k1 = c*p/d", "verify"),
    ("emitted-lambda-squared", G, "return (I11*I22*(I11 - I22)*", "return (I11*I22*(I11 + I22)*", "verify"),
    ("emitted-scattering-sech", G, "c*ctx.sech(x))", "c*ctx.sech(2*x))", "verify"),
    ("emitted-meromorphy-call", G, "_p_squared_i13_zero, _p_squared_i23_zero, I, tol)",
     "_p_squared_i23_zero, _p_squared_i13_zero, I, tol)", "verify"),
    # the Galois decisions (issue 38: the first two passed the build and every test, the third made the build
    # emit a false "irreducible: pass" that only byte identity noticed); targeted: groups known by construction
    ("galois-so3-without-squares", "suslov/kernel/monodromy.py", 'infinite == commutator == squares == "pass"',
     'infinite == commutator == "pass"',
     "test:tests/test_galois_decisions.py::test_the_infinite_dihedral_group_is_not_so3"),
    ("galois-infinite-order-flipped", "suslov/kernel/monodromy.py", "s.real > 2 or s.real < -2",
     "s.real < 2 or s.real < -2",
     "test:tests/test_galois_decisions.py::test_infinite_order_is_claimed_exactly_for_an_eigenvalue_off_the_unit_circle"),
    ("galois-commutator-vs-1", "suslov/kernel/monodromy.py", "if not (trace - 3).contains(0):",
     "if not (trace - 1).contains(0):", "test:tests/test_galois_decisions.py::test_the_torus_is_not_irreducible"),
    # the exact decision (Kimura) and the closed-form angle of every body (issue 37's code)
    ("kimura-no-square-test", "suslov/kernel/kimura.py", "root * root == minus.numerator and root % 2 == 1",
     "root % 2 == 1", "test:tests/test_galois_decisions.py::test_exact_decision_needs_an_odd_square"),
    ("kimura-even-root", "suslov/kernel/kimura.py", "and root % 2 == 1:", "and root % 2 == 0:",
     "test:tests/test_galois_decisions.py::test_exact_decision_needs_an_odd_square"),
    ("kimura-sign-of-w2", "suslov/kernel/kimura.py", "minus = -a", "minus = a",
     "test:tests/test_galois_decisions.py::test_exact_decision_needs_an_odd_square"),
    ("gauss-angle-gap-sign", "suslov/kernel/gauss_angle.py", "gap = 2.0 * c2 / ((2.0 * U2 - a + modulus) * (U + X))",
     "gap = 2.0 * c2 / ((2.0 * U2 + a + modulus) * (U + X))",
     "test:tests/test_general_angle.py::test_float_against_300_digit_ball"),
    ("gauss-angle-mp-sin-cos", "suslov/kernel/gauss_angle.py", "abs(mpmath.sinpi(Y / 2)), abs(mpmath.cospi(Y / 2))",
     "abs(mpmath.cospi(Y / 2)), abs(mpmath.sinpi(Y / 2))",
     "test:tests/test_general_angle.py::test_mp_twin_matches_ball_on_hard_bodies"),
    ("gauss-angle-ball-half", "suslov/kernel/gauss_angle.py", "half = abs(Y) / 2", "half = abs(Y)",
     "test:tests/test_general_angle.py::test_ball_against_validated_integration"),
    ("general-angle-phase-not-rescaled", R + "general_angle.py", "_HUGE), Y / lam", "_HUGE), Y",
     "test:tests/test_general_angle.py::test_float_against_300_digit_ball"),
    ("general-angle-no-equilibrium-check", R + "general_angle.py", "    _equilibrium((I13 == 0) & (I23 == 0))",
     "    pass", "test:tests/test_general_angle.py::test_equilibrium_is_refused"),
    # verified loading (issue 38)
    ("manifest-digest-ignored", "suslov/manifest.py", "if found != expected:", "if False:",
     "test:tests/test_manifest.py::test_tampered_store_module_is_refused_never_run"),
    ("manifest-world-writable-ignored", "suslov/manifest.py",
     "if mode & stat.S_IWOTH and not (ancestor and mode & stat.S_ISVTX):", "if False:",
     "test:tests/test_manifest.py::test_a_tree_others_can_write_is_refused"),
    ("manifest-ancestors-unchecked", "suslov/manifest.py", "    for parent in directory.parents:",
     "    for parent in []:", "test:tests/test_manifest.py::test_a_tree_others_can_write_is_refused"),
    ("manifest-unlisted-python", "suslov/manifest.py",
     'extra = sorted(p.name for p in directory.iterdir() if p.suffix == ".py" and p.name not in entries)',
     "extra = []", "test:tests/test_manifest.py::test_incomplete_or_extended_trees_are_refused"),
    # the output directories (the data-loss findings)
    ("outdir-no-ownership-check", "suslov/outdir.py", "if any(path.iterdir()) and not _owned(path, tool, signature):",
     "if False:", "test:tests/test_outdir.py"),
    ("outdir-journal-no-recovery", "suslov/outdir.py", "            if staging.is_dir():\n                os.rename(staging, target)",
     "            if False:\n                os.rename(staging, target)", "test:tests/test_outdir.py"),
    ("executor-no-parent-watch", "suslov/executor.py",
     "    die_with_parent()\n\n    def watch():\n        while os.getppid() == parent:",
     "    def watch():\n        while True:", "test:tests/test_outdir.py::test_workers_die_with_their_parent"),
]

# mutants with no observable effect (not run), and why
EQUIVALENT = [
    ("executor-one-death-signal", "suslov/executor.py: removing either the kernel's PR_SET_PDEATHSIG or the watching "
     "thread alone leaves the other to end orphaned workers (the two are redundant on Linux by design)"),
    ("horner-block-size", "suslov/kernel/horner.py: block = 4096 for 8192 changes only the memory per pass"),
]


def working_tree_copy(target: Path) -> None:
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout.split("\0")
    for name in filter(None, files):
        source = ROOT / name
        if source.is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, target / name)


def reseal(directory: Path) -> None:
    """Rewrite the tree's manifest (SHA256SUMS) after a mutation: the mutant is then a consistent tree with a
    wrong formula, which the round trip must reject (a tree changed after its build is refused earlier, by
    the manifest, which would make every mutant of the emitted module trivially 'rejected')."""
    manifest = directory / "SHA256SUMS"
    names = [line.split("  ", 1)[1] for line in manifest.read_text(encoding="utf-8").splitlines()]
    manifest.write_text("".join(f"{hashlib.sha256((directory / n).read_bytes()).hexdigest()}  {n}\n"
                                for n in sorted(names)), encoding="utf-8")


def detector_command(detector: str, tree: Path) -> list[str]:
    if detector == "build":
        return [sys.executable, "build_formulas.py", "--quiet", "--no-cache", "--out", str(tree.parent / "out")]
    if detector == "verify":
        return [sys.executable, "build_formulas.py", "--quiet", "--verify", "generated"]
    if detector.startswith("test:"):
        # -n 0: one detector subset is small, and the mutants already run side by side
        return [sys.executable, "-m", "pytest", "-x", "-q", "-n", "0", "-p", "no:cacheprovider", detector[5:]]
    raise ValueError(f"unknown detector {detector!r}")


def run_mutant(mutant) -> dict:
    ident, path, original, mutated, detector = mutant
    with tempfile.TemporaryDirectory(prefix=f"mutant-{ident}-") as tmp:
        tree = Path(tmp) / "tree"
        working_tree_copy(tree)
        text = (tree / path).read_text(encoding="utf-8")
        if text.count(original) != 1:
            return {"id": ident, "file": path, "detector": detector, "outcome": "site not unique or missing",
                    "seconds": 0.0}
        (tree / path).write_text(text.replace(original, mutated), encoding="utf-8")
        if path.startswith("generated/"):
            reseal(tree / "generated")
        env = dict(os.environ, PYTHONPATH=str(tree), SUSLOV_NO_CACHE="1")
        start = time.perf_counter()
        done = subprocess.run(detector_command(detector, tree), cwd=tree, env=env, capture_output=True, text=True,
                              timeout=1800)
        seconds = time.perf_counter() - start
    rejected = done.returncode != 0
    return {"id": ident, "file": path, "detector": detector, "seconds": round(seconds, 1),
            "outcome": "rejected" if rejected else "SILENT",
            "evidence": _evidence(done.stdout + "\n" + done.stderr)}


def _evidence(output: str) -> str:
    """The line that says why: a failed test's name, or the build's message naming the claim."""
    lines = [line.strip() for line in output.splitlines() if line.strip()]
    for marker in ("FAILED ", "build_formulas.py: --verify", "build_formulas.py: "):
        found = [line for line in lines if line.startswith(marker) and "nothing was written" not in line]
        if found:
            return found[0][:200]
    return (lines or [""])[-1][:200]


def table(rows: list, equivalent: list) -> str:
    silent = [r for r in rows if r["outcome"] != "rejected"]
    lines = ["# Mutation suite", "", "Seeded single-point faults (`bench/mutation_suite.py`); each must be rejected by "
             "the named detector.", "", f"Machine: {cpu_name()}, {os.cpu_count()} cores", "",
             f"**{len(rows) - len(silent)} of {len(rows)} non-equivalent mutants rejected; {len(silent)} silent.**", "",
             "| mutant | file | detector | outcome | seconds | what rejected it |", "|---|---|---|---|---|---|"]
    for r in rows:
        evidence = r.get("evidence", "").replace("|", "\\|")
        lines.append(f"| {r['id']} | `{r['file']}` | {r['detector']} | {r['outcome']} | {r['seconds']} | {evidence} |")
    lines += ["", "Equivalent mutants (not run):", ""] + [f"- {name}: {why}" for name, why in equivalent]
    lines += ["", "Reproduce: `python bench/mutation_suite.py` (about 10 minutes on 2 cores)."]
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=None, help="run the mutants whose id contains this text (no table written)")
    ap.add_argument("--jobs", type=int, default=1, help="mutants run at once (each may use all cores)")
    args = ap.parse_args(argv)
    chosen = [m for m in MUTANTS if args.only is None or args.only in m[0]]
    rows = []
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for row in pool.map(run_mutant, chosen):
            rows.append(row)
            print(f"{row['outcome']:>9}  {row['id']}  ({row['detector']}, {row['seconds']} s)", flush=True)
    if args.only is None:
        write_results("mutations", {"machine": cpu_name(), "mutants": rows,
                                    "equivalent": [{"id": i, "why": w} for i, w in EQUIVALENT]},
                      table(rows, EQUIVALENT))
    return 0 if all(r["outcome"] == "rejected" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
