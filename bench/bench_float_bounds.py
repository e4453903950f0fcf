"""What the proven float64 error bounds cost the build (issue 34), beside the sampled checks they replace.

Side by side, in one run, on the committed generated module:

* the proofs (``derivations.proofs.float_proofs``: the emitted ``_omega`` / ``_omega_general`` / ``_scattering_angle`` on error
  balls over their boxes, plus the bit-for-bit check of the public function against the analysed composition;
  ``derivations.proofs.integral_proof``: ``first_integral``'s Horner sequence for every p in INTEGRAL_PS, plus its
  bit-for-bit check);
* ``derivations.proofs.basis_proof`` (``gamma_basis``, both phase branches, every p in BASIS_PS, with its bit-for-bit
  and assembly checks) and ``derivations.proofs.general_angle_proof`` (``general_scattering_angle``'s mixed bound);
* the sampled round-trip checks they replaced (float64 against the mpmath twin at 40 digits at the old
  seeded points; the loops of the old ``float_paths.check_omega`` / ``check_omega_general`` /
  ``check_scattering_angle``).

The share is taken against a cold default build on both cores, ~40 s (``bench/results/build.md``: 40.1 s
at pmax 15, all cores); target: the proofs under 20% of it.

Run: ``python bench/bench_float_bounds.py`` (about 30 s); writes ``bench/results/float_bounds.md`` and
``.json``.  Medians of 5 runs on a shared 2-core machine.
"""
from __future__ import annotations

import json
import math
import platform
import sys
from pathlib import Path

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from timing import median_seconds  # noqa: E402

from derivations.core.certificates import CertificateLog  # noqa: E402
from derivations.output import float_paths  # noqa: E402
from derivations.proofs import (  # noqa: E402
    basis_proof,
    float_proofs,
    general_angle_proof,
    integral_proof,
)
from generated import suslov_formulas as sf  # noqa: E402

COLD_BUILD_SECONDS = 40.1          # bench/results/build.md, pmax 15, all cores
HARD_T = (-1e4, -700.0, -30.0, -1.0, -1e-8, 0.0, 1e-8, 0.3, 5.0, 711.0, 1e4)
HARD_D = (1e-3, 0.5, 3.0, 1e3)


def sampled_omega():
    """The old sampled check: 12 (p, d) x 11 t against omega_mp at 40 digits."""
    rng = np.random.default_rng(1201)
    cases = [(1, 0.5), (3, 0.5), (15, 2.0), (-4, 1.0), (2.5, 1e-3), (7, 1e3)]
    cases += [(float(rng.uniform(-40, 40)), float(10 ** rng.uniform(-3, 3))) for _ in range(6)]
    worst = 0.0
    for p, d in cases:
        w1, w2 = sf.omega(np.array(HARD_T), p, d)
        bound = 4e-16 * abs(p) / d * math.sqrt(d * d + 1)
        for i, t in enumerate(HARD_T):
            e1, e2 = sf.omega_mp(t, p, d, dps=40)
            worst = max(worst, float(abs(w1[i] - e1) / bound), float(abs(w2[i] - e2) / bound))
    return worst


def sampled_angle():
    """The old sampled check: 25 p x 8 d against scattering_angle_mp at 40 digits."""
    rng = np.random.default_rng(1500)
    ps = [1.0, 3.0, 2.0, 0.5, 2.5, 1 + 1e-13, 3 - 1e-13, 2 + 1e-13, 7.3, 5.6, 1.9, -2.7, -0.6]
    ps += [float(v) for v in rng.uniform(-60, 60, 12)]
    ds = list(HARD_D) + [float(v) for v in 10 ** rng.uniform(-3, 3, 4)]
    values = sf.scattering_angle(np.array(ps)[:, None], np.array(ds)[None, :])
    worst = 0.0
    for i, p in enumerate(ps):
        for j, d in enumerate(ds):
            exact = sf.scattering_angle_mp(p, d, dps=40)
            worst = max(worst, float(abs(values[i, j] - exact) / (1e-13 * abs(exact))) if exact else 0.0)
    return worst


def sampled_omega_general():
    """The old sampled check: 8 bodies x 2 branches x 9 t against omega_general_mp at 40 digits."""
    rng = np.random.default_rng(1202)
    worst = 0.0
    for _ in range(8):
        I11, I22 = (float(v) for v in rng.uniform(0.2, 5, 2))
        I13, I23 = (float(v) for v in rng.uniform(-2, 2, 2))
        for branch in (1, -1):
            w1, w2 = sf.omega_general(np.array(HARD_T[1:-1]), I11, I22, I13, I23, branch)
            r = math.sqrt(I11 * I22)
            D = I13**2 * I22 + I23**2 * I11
            bound = 1e-15 * (I11 * I22 * abs(I23) + I22 * abs(I13) * r + I11 * I22 * abs(I13) + I11 * abs(I23) * r) / D
            for i, t in enumerate(HARD_T[1:-1]):
                e1, e2 = sf.omega_general_mp(t, I11, I22, I13, I23, branch, dps=40)
                worst = max(worst, float(abs(w1[i] - e1) / bound), float(abs(w2[i] - e2) / bound))
    return worst


def sampled_first_integral():
    """The old sampled check: per p, 4 d x 3 omega scales against first_integral_mp at 40 digits."""
    worst = 0.0
    for p in sf.INTEGRAL_PS:
        rng = np.random.default_rng(1300 + p)
        for d in (0.5, 1e-2, 50.0, float(10 ** rng.uniform(-1, 1))):
            coefficients = sf.first_integral_coefficients(p, d)
            sizes = [sum(abs(a) for a in coefficients[name]) for name in ("P1", "P2", "P3")]
            sizes = [mpmath.mpf(v.numerator) / v.denominator for v in sizes]
            for size in (1e-3, 1.0, 20.0):
                w1, w2 = (float(v) for v in rng.uniform(-size, size, 2))
                g = rng.normal(size=3)
                g /= np.linalg.norm(g)
                exact = sf.first_integral_mp(p, d, w1, w2, *(float(v) for v in g), dps=40)
                value = float(sf.first_integral(p, d, w1, w2, *g))
                s = mpmath.mpf(max(abs(w1), abs(w2)))
                bound = 2e-15 * (p + 1) * s**p * mpmath.fsum(abs(gi) * si for gi, si in zip(g, sizes)) + 5e-324
                worst = max(worst, float(abs(value - exact) / bound))
    return worst


def sampled_gamma_basis():
    """The old sampled check of gamma_basis (before its proof): per p, 4 d x 6 t and 2 d x 5 far t against the twin."""
    worst = 0.0
    for p in sf.BASIS_PS:
        rng = np.random.default_rng(1400 + p)
        points = [(d, [0.0, -1e-8, 2.2, -30.0, float(rng.uniform(-8, 8)), 1e4 if d >= 0.5 else 50.0])
                  for d in (0.5, float(10 ** rng.uniform(-1, 1)), 1e-3, 1e3)]
        points += [(d, [1e5, -3.3e6, 2.9e7, -1e9, 3e10]) for d in (1e-3, 2.5e-3)]
        for d, ts in points:
            B = sf.gamma_basis(np.array(ts), p, d)
            for i, t in enumerate(ts):
                M = sf.gamma_basis_mp(t, p, d, dps=40)
                error = max(abs(B[i][r][c] - float(M[r, c])) for r in range(3) for c in range(3))
                worst = max(worst, error / (1e-15 * (p + 1) ** 1.5 + 4e-16 * abs(p * t / d) + 2e-16 * abs(t)))
    return worst


def prove_all_bases():
    log = CertificateLog(derivation="bench")
    from derivations.output.roundtrip import BASIS_RING

    cores = {p: tuple(part.M for part in sf._basis_core(p, BASIS_RING)) for p in sf.BASIS_PS}
    return lambda: [basis_proof.certificates(log, sf, p, cores[p]) for p in sf.BASIS_PS]


def prove_all_integrals():
    log = CertificateLog(derivation="bench")
    return [integral_proof.certificate(log, sf, p) for p in sf.INTEGRAL_PS]


def main():
    rows = []
    for name, sampled in (("omega", sampled_omega), ("omega_general", sampled_omega_general),
                          ("scattering_angle", sampled_angle)):
        proof = float_proofs.PROOFS[name](sf)
        proof_seconds = median_seconds(lambda name=name: float_proofs.certificate(CertificateLog(derivation="bench"),
                                                                                   sf, name), 5)
        with mpmath.workdps(15):
            sampled_seconds = median_seconds(sampled, 5)
        rows.append({"function": name, "boxes": proof.boxes, "proven": proof.statement,
                     "proof_seconds": proof_seconds, "sampled_seconds": sampled_seconds})
    proofs = [integral_proof.prove_first_integral(p) for p in sf.INTEGRAL_PS]
    with mpmath.workdps(15):
        sampled_seconds = median_seconds(sampled_first_integral, 5)
    rows.append({"function": f"first_integral (p = {sf.INTEGRAL_PS[0]}..{sf.INTEGRAL_PS[-1]})",
                 "boxes": sum(proof.boxes for proof in proofs),
                 "proven": f"{proofs[0].bound_u}..{proofs[-1].bound_u} u s^p sum_j |g_j| sum_k |a_jk| + 5e-324",
                 "proof_seconds": median_seconds(prove_all_integrals, 5), "sampled_seconds": sampled_seconds})
    with mpmath.workdps(15):
        sampled_seconds = median_seconds(sampled_gamma_basis, 5)
    bound = basis_proof.prove(sf.BASIS_PS[-1])["near"]
    rows.append({"function": f"gamma_basis (p = {sf.BASIS_PS[0]}..{sf.BASIS_PS[-1]}, both branches)",
                 "boxes": sum(basis_proof.prove(p)["boxes"] for p in sf.BASIS_PS),
                 "proven": f"1e-14 (p+1)^1.5 ({math.ceil(float((bound / basis_proof.U).upper()))} u at p = "
                           f"{sf.BASIS_PS[-1]})",
                 "proof_seconds": median_seconds(prove_all_bases(), 5), "sampled_seconds": sampled_seconds})
    log = CertificateLog(derivation="bench")
    with mpmath.workdps(15):
        sampled_seconds = median_seconds(lambda: float_paths.check_general_scattering_angle(log, sf), 5)
    general = general_angle_proof.prove(sf)
    rows.append({"function": "general_scattering_angle (mixed bound)", "boxes": general["boxes"],
                 "proven": f"{math.ceil(float((general['angle'] / general_angle_proof.U).upper()))} u at arguments "
                           "within 200 u of a body within 2u",
                 "proof_seconds": median_seconds(lambda: general_angle_proof.certificate(CertificateLog(
                     derivation="bench"), sf), 5), "sampled_seconds": sampled_seconds})
    total = sum(r["proof_seconds"] for r in rows)
    machine = f"{cpu_name()}, {platform.python_version()}, 2 cores (shared)"
    lines = ["# Proven float64 error bounds: what they cost the build", "",
             f"Machine: {machine}. Command: `python bench/bench_float_bounds.py`. Medians of 5 runs.", "",
             "| function | boxes | proven bound | proof (s) | old sampled check (s) | ratio |",
             "| --- | ---: | --- | ---: | ---: | ---: |"]
    for r in rows:
        proven = r["proven"].replace("|", "\\|")     # a table cell
        lines.append(f"| {r['function']} | {r['boxes']} | {proven} | {r['proof_seconds']:.2f} | "
                     f"{r['sampled_seconds']:.2f} | {r['proof_seconds'] / r['sampled_seconds']:.1f} |")
    lines += ["", "gamma_basis's walks of tanh/sech and of the tan half-angle rational are the same for every p and are "
              "cached per process: the first call in a process adds about 0.13 s (a build pays it once per process)."]
    lines += ["", f"All proofs: {total:.2f} s = {100 * total / COLD_BUILD_SECONDS:.1f}% of a cold default build on "
              f"both cores ({COLD_BUILD_SECONDS} s, bench/results/build.md); target under 20%.", ""]
    out = ROOT / "bench" / "results"
    (out / "float_bounds.md").write_text("\n".join(lines), encoding="utf-8")
    (out / "float_bounds.json").write_text(json.dumps({"machine": machine, "rows": rows, "total_seconds": total,
                                                       "cold_build_seconds": COLD_BUILD_SECONDS}, indent=1) + "\n",
                                           encoding="utf-8")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
