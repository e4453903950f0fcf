"""The round trip's per-p work at large p (``roundtrip.per_p_checks``): the exact routes before and after, one run.

For every odd p > 15 the build runs :func:`derivations.output.roundtrip.per_p_checks` in a worker: the emitted
``_basis_core(p, BASIS_RING)`` (the recipe ``suslov.recipes.basis`` on the exact ring), the meromorphic
certificates of its numerators, then the float-path checks.  This script times that call both ways, at
p = 101, 151, 201 (medians of ``--repeat`` runs per route, each run a fresh process, old and new alternating):

* old: the code before the exact-ring routes, patched in from copies kept here: the recipe on a ring that does
  not declare ``exact`` (so the recipe's generic operations, which the ball ring of the module still runs:
  ``gamma1_numerator`` forming a tail product and a power of (1+x^2) afresh for every j, ``F`` summed term after
  term, ``DD`` and ``Fhat`` forming i^2 terms and dividing them out), the Kronecker product unpacked with one
  ``divmod`` per coefficient, the limits' coefficient of x^(2p) read from every monomial, and the complex
  solution's first numerator split into its i-coordinates three times, and
  the worker keeping FLINT's cache of freed big integers from one p to the next;
* new: the project's code (``exact = True`` and ``mul_i`` of ``FlintBasisRing``; the recipe's exact routes;
  ``roundtrip.release_freed_integers`` after each p).

Each route is also run as a build worker runs it: one process doing ``--sequence`` (p = 201, 199, ..., 187) in turn,
where the cache of freed integers slowed every later p before.

It also checks, at every p timed (both routes in one process), that they return the same certificates
(claims, outcomes, details) and the same numerators term by term.  Needs a module emitted with pmax >= the largest p timed:

    python build_formulas.py --pmax 201 --no-cache --out /tmp/m201b
    python bench/bench_basis_roundtrip.py --module /tmp/m201b [--ps 101 151 201] [--repeat 4]

Writes ``bench/results/basis_roundtrip.{json,md}`` (about 8 minutes with ``--repeat 4`` on 2 shared cores).
"""
from __future__ import annotations

import argparse
import contextlib
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import flint
from machine_info import cpu_name
from results_io import write_results

from derivations.core.recipe_rings import BASIS_CTX
from derivations.output import roundtrip
from derivations.sections import meromorphic
from suslov.recipes import flint_rings
from suslov.recipes.flint_rings import FlintBasisRing

D, I = BASIS_CTX.gens()[1:]


# ---------------------------------------------------------------- the old routes, kept here


class OldRing(FlintBasisRing):
    """The exact ring without the declaration that lets the recipe regroup its operations (no exact routes)."""

    exact = False


def old_kronecker_mul_red(A, B, ctx=flint_rings.BASIS_CTX):
    """suslov.recipes.flint_rings.kronecker_mul_red before the unpacking by rows (one divmod per coefficient)."""
    if A.degrees()[2] > 1 or B.degrees()[2] > 1:
        return None
    parity_a, parity_b = flint_rings._parity(A), flint_rings._parity(B)
    if parity_a is None or parity_b is None:
        return None
    stride = A.degrees()[1] + parity_a + B.degrees()[1] + parity_b + 1
    den_a, packed_a = flint_rings._packed(A, parity_a, stride)
    den_b, packed_b = flint_rings._packed(B, parity_b, stride)
    shift = parity_a + parity_b
    terms = {}
    for k, c in enumerate((packed_a * packed_b).coeffs()):
        if c:
            ex, m = divmod(k, stride)
            terms[(ex, m - shift, m & 1)] = -c if m & 2 else c
    product = ctx.from_dict(terms)
    den = den_a * den_b
    return product if den == 1 else product / den


def old_coefficient_x(poly, degree: int):
    """meromorphic._coefficient_x before: every monomial read."""
    total = BASIS_CTX.constant(0)
    for monomial, coefficient in zip(poly.monoms(), poly.coeffs()):
        if monomial[0] == degree:
            total += coefficient * D ** monomial[1] * I ** monomial[2]
    return total


NEW_THIRD, NEW_POISSON = meromorphic.third_order_holds, meromorphic.poisson_hold


def old_third_order_holds(N, p, rate, first=None, parts=None):
    return NEW_THIRD(N, p, rate, first)          # split again, as before


def old_poisson_hold(sol, first=None, parts=None):
    return NEW_POISSON(sol, first)               # split again, as before


@contextlib.contextmanager
def old_routes():
    saved = [(roundtrip, "BASIS_RING", roundtrip.BASIS_RING), (flint_rings, "kronecker_mul_red", flint_rings.kronecker_mul_red),
             (meromorphic, "_coefficient_x", meromorphic._coefficient_x),
             (meromorphic, "third_order_holds", meromorphic.third_order_holds),
             (meromorphic, "poisson_hold", meromorphic.poisson_hold)]
    saved.append((roundtrip, "release_freed_integers", roundtrip.release_freed_integers))
    roundtrip.BASIS_RING = OldRing()
    roundtrip.release_freed_integers = lambda: None
    flint_rings.kronecker_mul_red = old_kronecker_mul_red
    meromorphic._coefficient_x = old_coefficient_x
    meromorphic.third_order_holds = old_third_order_holds
    meromorphic.poisson_hold = old_poisson_hold
    try:
        yield
    finally:
        for owner, name, value in saved:
            setattr(owner, name, value)


# ---------------------------------------------------------------- one run


def clear_runtime_caches() -> None:
    """Empty the run-time caches per (p, d) (ball series, float coefficients) that the float-path checks fill."""
    from suslov.runtime import basis, integrals

    for owner in (basis, integrals):
        for value in vars(owner).values():
            if hasattr(value, "cache_info"):   # the functools caches
                value.cache_clear()


def parts(outcome: dict) -> dict:
    """Seconds per part, from the certificates per_p_checks returns (the construction is in the first one's)."""
    basis = {c.label: c.seconds for c in outcome["basis"]}
    return {"construct (in eq:gam3)": basis["eq:gam3"], "third order (F_23_pol)": basis["F_23_pol"],
            "Poisson (eq:ps)": basis["eq:ps"],
            "orthonormality and limits": basis["gam1, gam2, gam3"] + basis["asymp"],
            "float-path checks": sum(c.seconds for c in outcome["checks"])}


def timed_run(directory: str, p: int, route: str) -> dict:
    """One ``per_p_checks`` call by one route in this (fresh) process, after a warm-up at p = 17."""
    # imported, and the caches every p shares (the proofs' boxes) filled, before the timed call
    roundtrip.per_p_checks((Path(directory), 17, -1))
    clear_runtime_caches()
    with old_routes() if route == "old" else contextlib.nullcontext():
        start = time.perf_counter()
        outcome = roundtrip.per_p_checks((Path(directory), p, -1))
        return {"per_p_checks": time.perf_counter() - start, **parts(outcome)}


def sequence_run(directory: str, ps: list, route: str) -> dict:
    """``per_p_checks`` for each p of ``ps`` in turn in this (fresh) process, as a build worker does: wall seconds per p."""
    roundtrip.per_p_checks((Path(directory), 17, -1))
    seconds = {}
    with old_routes() if route == "old" else contextlib.nullcontext():
        for p in ps:
            start = time.perf_counter()
            roundtrip.per_p_checks((Path(directory), p, -1))
            seconds[str(p)] = time.perf_counter() - start
    return seconds


def checks(directory: str, p: int) -> dict:
    """Both routes in this process: the same certificates (claims, outcomes, details), all passing, and the same
    numerators term by term."""
    results = {}
    for route in ("old", "new"):
        clear_runtime_caches()
        with old_routes() if route == "old" else contextlib.nullcontext():
            outcome = roundtrip.per_p_checks((Path(directory), p, -1))
        results[route] = [(c.claim, c.outcome.name, c.detail) for c in outcome["basis"] + outcome["checks"]]
    module = roundtrip.load_module_once(directory)
    with old_routes():
        old = module._basis_core(p, roundtrip.BASIS_RING)
    new = module._basis_core(p, roundtrip.BASIS_RING)
    same_numerators = all(a.divisions_exact == b.divisions_exact and all(m == n and m.monoms() == n.monoms()
                                                                         and m.coeffs() == n.coeffs()
                                                                         for m, n in zip(a.M, b.M))
                          for a, b in zip(old, new))
    return {"same certificates": results["old"] == results["new"],
            "all passed": all(outcome == "PASS" for _, outcome, _ in results["new"]), "same numerators": same_numerators}


def child(*arguments) -> dict:
    run = subprocess.run([sys.executable, __file__, *arguments], capture_output=True, text=True, check=True)
    return json.loads(run.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--module", required=True, help="a generated tree built with --pmax >= max(--ps)")
    ap.add_argument("--ps", type=int, nargs="+", default=[101, 151, 201])
    ap.add_argument("--repeat", type=int, default=4)
    ap.add_argument("--run", nargs=2, metavar=("P", "ROUTE"), help=argparse.SUPPRESS)
    ap.add_argument("--check", type=int, metavar="P", help=argparse.SUPPRESS)
    ap.add_argument("--sequence", type=int, nargs="*", default=list(range(201, 186, -2)),
                    help="p done in turn in one process per route, as a worker does (default 201, 199, ..., 187)")
    ap.add_argument("--sequence-route", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.sequence_route:   # a child: the sequence by one route
        print(json.dumps(sequence_run(args.module, args.sequence, args.sequence_route)))
        return 0
    if args.run:     # a child: one timed run, the result as JSON on the last line
        print(json.dumps(timed_run(args.module, int(args.run[0]), args.run[1])))
        return 0
    if args.check:   # a child: the identity checks at one p
        print(json.dumps(checks(args.module, args.check)))
        return 0
    load_before = os.getloadavg()
    results, verdicts = {}, {}
    for p in args.ps:
        samples = {}
        for repetition in range(args.repeat):
            # each run in a fresh process: the second per_p_checks of a process was up to 1.6x slower in its zero
            # tests whichever route it was (the heap of the first), so two routes in one process favour the first
            for route in (("old", "new") if repetition % 2 == 0 else ("new", "old")):
                for name, value in child("--module", args.module, "--run", str(p), route).items():
                    samples.setdefault(name, {"old": [], "new": []})[route].append(value)
        verdicts[p] = child("--module", args.module, "--check", str(p))
        results[p] = {name: {route: statistics.median(v) for route, v in routes.items()} for name, routes in samples.items()}
        print(p, {name: f"{r['old']:.2f} -> {r['new']:.2f}" for name, r in results[p].items()}, file=sys.stderr, flush=True)
    sequence = {}
    if args.sequence:
        for route in ("old", "new"):
            sequence[route] = child("--module", args.module, "--sequence", *map(str, args.sequence), "--sequence-route", route)
        print("sequence", {route: round(sum(v.values()), 2) for route, v in sequence.items()}, file=sys.stderr, flush=True)
    load_after = os.getloadavg()
    assert all(all(c.values()) for c in verdicts.values()), verdicts
    machine = f"{cpu_name()}, {os.cpu_count()} cores (shared), Python {sys.version.split()[0]}, python-flint {flint.__version__}"
    command = " ".join(["python bench/bench_basis_roundtrip.py", *(sys.argv[1:] if argv is None else list(argv))])
    lines = ["# The round trip's per-p work (`per_p_checks`): exact routes before and after", "",
             (f"Machine: {machine}; load average {load_before[0]:.2f} before, {load_after[0]:.2f} after (other jobs "
              f"shared the machine). Command: `{command}`. Wall seconds, median of {args.repeat} runs per route, each "
              "run a fresh process (a warm-up at p = 17, then one timed `per_p_checks`), old and new alternating; "
              "the parts are the seconds the returned certificates record."), "",
             "| p | part | old (s) | new (s) | old / new |", "|---:|---|---:|---:|---:|"]
    for p in args.ps:
        lines += [f"| {p} | {name} | {r['old']:.3f} | {r['new']:.3f} | {r['old'] / r['new']:.2f}x |"
                  for name, r in results[p].items()]
    if sequence:
        lines += ["", (f"One process per route doing p = {', '.join(map(str, args.sequence))} in turn (a build worker "
                       "takes the largest p first), wall seconds per p, one run each:"), "",
                  "| p | old (s) | new (s) | old / new |", "|---:|---:|---:|---:|"]
        lines += [f"| {p} | {sequence['old'][str(p)]:.2f} | {sequence['new'][str(p)]:.2f} | "
                  f"{sequence['old'][str(p)] / sequence['new'][str(p)]:.2f}x |" for p in args.sequence]
        total = [sum(sequence[route].values()) for route in ("old", "new")]
        lines.append(f"| **all** | {total[0]:.2f} | {total[1]:.2f} | {total[0] / total[1]:.2f}x |")
    lines += ["", "Checks at every p timed (both routes in one process): the same certificates (claims, outcomes, "
              "details), every one passing, and the same numerators term by term: "
              + ("yes" if all(all(c.values()) for c in verdicts.values()) else "NO") + ".", ""]
    data = {"machine": machine, "command": command, "repeat": args.repeat, "load": [load_before[0], load_after[0]],
            "seconds": {str(p): results[p] for p in args.ps}, "checks": {str(p): c for p, c in verdicts.items()},
            "sequence": sequence}
    write_results("basis_roundtrip", data, "\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
