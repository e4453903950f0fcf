"""The round trip's per-p ``gamma_basis`` checks at large p: the earlier route and the current one side by side.

``python build_formulas.py --pmax 201`` runs :func:`derivations.output.float_paths.check_gamma_basis` for every odd p
(the proven bounds of ``gamma_basis``, the rows as assembled against ``gamma_basis_mp`` at 4 d x 8 t, and
``gamma_basis_mp`` against the certified numerators evaluated exactly at two points): 3.9 s at p = 201 on one core.
The same checks, with the same points, bounds and claims, now cost less through three changes that leave every
value bit for bit as it was:

* ``suslov.kernel.fourier``: the exact Fourier matrices C/4^p, S/4^p built once per p in C (``fmpz_mat`` ->
  ``acb_mat``) and shared by every precision at which they are exact, instead of once per (p, precision) entry by
  entry in Python (the checks use three precisions per p);
* ``suslov.runtime.basis.gamma_basis_mp``: the series summed with mpmath's ``libmp`` functions that its ``mpf``
  operators and ``fsum`` call, in the same order (one ``mpf_cos_sin`` per harmonic instead of ``cos`` and ``sin``);
* ``derivations.proofs.basis_proof.parity_holds``: the parity of the exponents of x read from the deflation
  (C) instead of collecting 300,000 monomials in Python.

The earlier route is kept here (:func:`old_to_fourier_acb`, :func:`old_gamma_basis_mp`, :func:`old_parity_holds`:
copies of the code before the change) and patched in for the "old" runs; every run starts from empty caches
(series, matrices), as a build's first check at a new p does; the p-independent tables of the proof
(``tanh_sech_error``, ``rational_error``, computed once per process in a build) are warmed first.  Old and new
runs alternate; times are medians of ``--repeat`` runs on one core (the machine has 2 shared cores).

Also checked in the same run, old against new (the bench fails if any differs): the certificates (claim, outcome,
detail, measured value), the ball series of ``series_balls`` at the float and the mp precision (midpoints and
radii exactly), the float64 coefficients of ``series_float``, and ``gamma_basis_mp`` at the 32 points of
``assembly_gap`` and the two exact points (mantissa and exponent of each entry).

Needs a generated tree whose ``BASIS_PS`` reaches the largest p (``python build_formulas.py --pmax 201 --out
/tmp/p201``, about 9 minutes).

Run:  python bench/bench_gamma_basis_checks.py --tree /tmp/p201     (writes bench/results/gamma_basis_checks.{md,json})
"""
from __future__ import annotations

import argparse
import contextlib
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import flint
import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.machine_info import cpu_name
from bench.results_io import write_results
from derivations.core.certificates import CertificateLog
from derivations.output import float_paths, roundtrip
from derivations.proofs import basis_proof
from suslov.kernel import fourier
from suslov.kernel.phase import PHASE_LIMIT
from suslov.kernel.validate import mp_dps, mp_real
from suslov.runtime import basis
from suslov.runtime.basis import _series_mp, basis_p, phase_digits

PS = (51, 101, 151, 201)
ASSEMBLY_D = (0.5, 1e-3, 1e3, 2.75)           # basis_proof.assembly_gap's d and t
ASSEMBLY_T = (0.0, -1e-8, 2.2, -30.0, 0.61, 1e4)


# ------------------------------------------------------------------ the earlier route (copies of the code before)


def old_to_fourier_acb(numerators: list, p: int):
    """suslov.kernel.fourier.to_fourier_acb before: the matrices built per (p, precision)."""
    size = 2 * p + 1
    if any(0 not in v for n in numerators for v in list(n)[size:]):
        raise ArithmeticError("to_fourier_acb: a numerator exceeds degree 2p (increase the precision)")
    rows = [list(n)[:size] + [flint.acb(0)] * (size - len(n)) for n in numerators]
    N = flint.acb_mat(len(rows), size, [v for row in rows for v in row])
    C, S = fourier._matrices_acb(p, flint.ctx.prec)
    return N * C, N * S


def old_gamma_basis_mp(core, sigma, ps, t, p, d, dps):
    """suslov.runtime.basis.gamma_basis_mp before: mpf operators, mpmath.cos and mpmath.sin, mpmath.fsum."""
    dps = mp_dps(dps)
    p = basis_p(p, ps)
    with mpmath.workdps(dps):
        t_in, d_in = t, d
        t = mp_real("t", t)
        d = mp_real("d", d, positive=True)
    extra = phase_digits(p, t, d, dps)
    if extra:
        with mpmath.workdps(dps + extra):
            t, d = mp_real("t", t_in), mp_real("d", d_in, positive=True)
    rows = _series_mp(core, p, d, max(dps, 40))
    with mpmath.workdps(dps + 10):
        th = 2 * mpmath.atan(mpmath.exp(-t))
        cosines = [mpmath.cos(k * th) for k in range(p + 1)]
        sines = [mpmath.sin(k * th) for k in range(p + 1)]

        def series(part):
            alpha, beta = part
            return mpmath.fsum(alpha[k] * cosines[k] + beta[k] * sines[k] for k in range(p + 1))

        out = mpmath.matrix(3, 3)
        with mpmath.workdps(dps + 10 + extra):
            phase_mp = p * t / d
            cphi, sphi = mpmath.cos(phase_mp), mpmath.sin(phase_mp)
        cphi, sphi = +cphi, +sphi
        for j in range(3):
            out[0, j] = series(rows[0][j][0])
            re, im = series(rows[1][j][0]), series(rows[1][j][1])
            out[1, j] = cphi * re - sphi * im
            out[2, j] = -sigma[p] * (sphi * re + cphi * im)
    with mpmath.workdps(dps):
        return +out


def old_parity_holds(numerators) -> bool:
    """derivations.proofs.basis_proof.parity_holds before: every monomial's parity collected in Python."""
    real, cplx = numerators
    for poly in list(real) + list(cplx):
        parities = {monomial[0] % 2 for monomial in poly.monoms()}
        if len(parities) > 1:
            return False
    return True


@contextlib.contextmanager
def route(name: str):
    """Run the checks on the earlier code ("old") or on the current one ("new")."""
    if name == "new":
        yield
        return
    patched = [(fourier, "to_fourier_acb", old_to_fourier_acb), (basis, "gamma_basis_mp", old_gamma_basis_mp),
               (basis_proof, "parity_holds", old_parity_holds)]
    saved = [(owner, attribute, getattr(owner, attribute)) for owner, attribute, _ in patched]
    try:
        for owner, attribute, replacement in patched:
            setattr(owner, attribute, replacement)
        yield
    finally:
        for owner, attribute, original in saved:
            setattr(owner, attribute, original)


def empty_caches() -> None:
    """What a build's first check at a new p finds: no series, no matrices."""
    for cached in (basis.series_float, basis._series_mp, basis._series_matrix, fourier.fourier_matrices,
                   fourier._matrices_acb, fourier._exact_matrices, fourier.exact_bits):
        cached.cache_clear()


# ------------------------------------------------------------------ one measured run and what it produced


def _arb_key(x) -> tuple:
    (m, e), (rm, re) = x.mid().man_exp(), x.rad().man_exp()
    return int(m), int(e), int(rm), int(re)


def _matrix_key(matrix) -> tuple:
    return tuple((_arb_key(v.real), _arb_key(v.imag)) for v in matrix.entries())


def _mp_key(matrix) -> tuple:
    return tuple(v._mpf_ for v in matrix)


def run(module, p: int, numerators, name: str) -> tuple[float, dict]:
    """(seconds of check_gamma_basis from empty caches, what it produced) on route ``name``."""
    empty_caches()
    log = CertificateLog(derivation="roundtrip")
    with route(name), mpmath.workdps(15):
        start = time.perf_counter()
        certs = float_paths.check_gamma_basis(log, module, p, numerators)
        seconds = time.perf_counter() - start
        # the values the checks compared, from this route's caches and code
        produced = {"certificates": [(c.claim, c.outcome.name, c.detail, c.measured) for c in certs],
                    "series_float": [basis.series_float(module._basis_core, p, d).tobytes() for d in ASSEMBLY_D]}
        twins = []
        for d in ASSEMBLY_D:
            ts = list(ASSEMBLY_T) + [3e-3 * PHASE_LIMIT * d / p, -1.7 * PHASE_LIMIT * d / p]
            twins += [_mp_key(module.gamma_basis_mp(t, p, d, dps=40)) for t in ts]
        for x, d, _ in float_paths.EXACT_POINTS:
            with mpmath.workdps(80):
                t = mpmath.log(mpmath.mpf(x.numerator) / x.denominator)
            twins.append(_mp_key(module.gamma_basis_mp(t, p, mpmath.mpf(d.numerator) / d.denominator, dps=50)))
        produced["gamma_basis_mp"] = twins
        produced["balls"] = [_matrix_key(m) for bits in (64 + 12 * p, int(3.33 * 50) + 12 * p)
                             for m in basis.series_balls(module._basis_core, p, 0.5, mpmath.mpf(10) ** 10, bits)]
    return seconds, produced


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tree", type=Path, default=Path("/tmp/p201"),
                    help="a generated tree with BASIS_PS up to max(--p) (default %(default)s)")
    ap.add_argument("--p", type=int, nargs="+", default=list(PS))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-write", action="store_true", help="print the table only")
    args = ap.parse_args(argv)
    if not (args.tree / "suslov_formulas.py").exists():
        ap.error(f"no generated module in {args.tree}: python build_formulas.py --pmax {max(args.p)} --out {args.tree}")
    module = roundtrip.load_module_once(args.tree)
    missing = [p for p in args.p if p not in module.BASIS_PS]
    if missing:
        ap.error(f"p = {missing} beyond the tree's BASIS_PS (build it with --pmax {max(args.p)})")
    basis_proof.tanh_sech_error()
    basis_proof.rational_error()
    load_before = os.getloadavg()[0]
    rows, identical = {}, True
    for p in args.p:
        _, numerators = roundtrip.basis_core_by_digest(module, p, "")
        times = {"old": [], "new": []}
        produced = {}
        for _ in range(args.repeat):
            for name in ("old", "new"):
                seconds, made = run(module, p, numerators, name)
                times[name].append(seconds)
                produced.setdefault(name, made)
        same = {key: produced["old"][key] == produced["new"][key] for key in produced["old"]}
        passed = all(c[1] == "PASS" for c in produced["new"]["certificates"])
        identical &= all(same.values())
        old, new = statistics.median(times["old"]), statistics.median(times["new"])
        rows[p] = {"old_s": old, "new_s": new, "ratio": new / old, "old_runs": times["old"], "new_runs": times["new"],
                   "identical": same, "all_pass": passed}
        print(f"p = {p}: old {old:.3f} s, new {new:.3f} s, new/old {new / old:.2f}; identical: {same}; "
              f"certificates pass: {passed}", file=sys.stderr)
    machine = f"{cpu_name()}, {platform.python_implementation()} {platform.python_version()}, python-flint " \
              f"{flint.__version__}, mpmath {mpmath.__version__} (backend {mpmath.libmp.BACKEND}), NumPy {np.__version__}"
    lines = ["# The round trip's per-p `gamma_basis` checks: earlier route against current", "",
             (f"Machine: {machine}; 2 shared cores, the checks on one (medians of {args.repeat} runs, old and new "
              f"alternating, each from empty caches; load average {load_before:.1f} before, {os.getloadavg()[0]:.1f} "
              "after: other work shared the machine, compare the ratios)."),
             (f"Command: `python bench/bench_gamma_basis_checks.py --tree {args.tree}"
              f"{'' if args.repeat == 3 else f' --repeat {args.repeat}'}` (a `--pmax 201` tree)."), "",
             ("Timed: `derivations.output.float_paths.check_gamma_basis(log, module, p, numerators)` at 15 digits, as "
              "`roundtrip.per_p_checks` calls it.  Old: the code before (copies in the bench script, patched in); "
              "new: the code in the tree."), "",
             "| p | old (s) | new (s) | new/old | identical (certificates, balls, float coefficients, mp twin) |",
             "|---|---|---|---|---|"]
    for p, row in rows.items():
        lines.append(f"| {p} | {row['old_s']:.3f} | {row['new_s']:.3f} | {row['ratio']:.2f} | "
                     f"{'yes' if all(row['identical'].values()) else 'NO: ' + str(row['identical'])} |")
    lines += ["", ("Identical means: the certificates' claims, outcomes, details and measured values; the ball series "
                   "of `series_balls` (d = 0.5, at 64 + 12p and 166 + 12p bits, midpoints and radii exactly); "
                   "`series_float`'s float64 coefficients at the 4 d of `assembly_gap`; `gamma_basis_mp` at its 32 "
                   "points (dps 40) and at the two exact points (dps 50), every entry's mantissa and exponent.")]
    markdown = "\n".join(lines) + "\n"
    print(markdown)
    if not args.no_write:
        write_results("gamma_basis_checks", {"machine": machine, "repeat": args.repeat, "tree": str(args.tree),
                                             "load_average": [load_before, os.getloadavg()[0]],
                                             "rows": {str(p): row for p, row in rows.items()}}, markdown)
    return 0 if identical else 1


if __name__ == "__main__":
    sys.exit(main())
