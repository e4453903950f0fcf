"""The exact meromorphic basis at large p: the plain routes and the fast ones side by side, same objects.

Per odd p the build constructs the basis twice (the certifying worker, ``derivations.sections.meromorphic``,
and the round trip, the emitted ``_basis_core`` = ``suslov.recipes.basis.construct(p, BASIS_RING)``) and
fingerprints it twice (``numerators_digest``); the worker also runs the third-order and Poisson zero tests
and the orthonormality certificate.  This script times each step both ways in one run, at p = 51, 101, 151,
201 (medians of ``--repeat`` runs, old and new interleaved, one process):

* old: the recipe on :class:`PlainBasisRing` (a copy of the exact ring adapter before the fast routes:
  ``red`` always divides by i^2 + 1, ``divide_exact`` by ``divmod``, ``square_x`` by ``compose``, no
  ``mul_red``, so the recipe forms ``red(F * Fhat)`` with flint's multivariate product), the residuals
  formed and tested with ``is_zero`` (copies of ``third_order_residual`` and ``poisson_residuals`` on that
  ring), the conservation products with ``red(A * B)`` and ``compose``, and the first ``numerators_digest``;
* new: ``BASIS_RING`` (Kronecker product in x and j = i d, the other primitives), ``third_order_holds`` and
  ``poisson_hold`` (coordinates, shared first derivative), ``mul_red`` and ``subs`` in the conservation
  products, and today's ``numerators_digest``.

It checks, for every p timed (and p = 1, 3, 15, 17), that the six numerators are equal (``==`` and term by
term), that the digests are equal, that the zero tests agree, and that a perturbed numerator fails both
routes' tests.

    python bench/bench_basis_construct.py [--ps 51 101 151 201] [--repeat 3]

Writes ``bench/results/basis_construct.{json,md}`` (about 3 minutes on 2 shared cores).
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import statistics
import subprocess
import sys
import time
from array import array
from itertools import chain
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import flint
from machine_info import cpu_name
from results_io import write_results

from derivations.core.recipe_rings import BASIS_CTX, BASIS_RING
from derivations.sections import meromorphic
from derivations.sections.meromorphic_ring import (
    DD_split,
    conj,
    split_i,
    third_order_holds,
)
from suslov.recipes import basis as recipe

X, D, I = BASIS_CTX.gens()
ONE = BASIS_CTX.constant(1)


# ---------------------------------------------------------------- the old routes, kept here


class PlainBasisRing:
    """The exact basis ring as it was before the fast routes (suslov/recipes/flint_rings.py at 8378f2c)."""

    def __init__(self):
        self.x, self.d, self.i = BASIS_CTX.gens()
        self._i2 = self.i**2 + 1

    def red(self, P):
        return divmod(P, self._i2)[1]

    @staticmethod
    def dx(P):
        return P.derivative("x")

    @staticmethod
    def divide_exact(P, Q):
        quotient, remainder = divmod(P, Q)
        return quotient, remainder.is_zero()

    def square_x(self, P):
        return P.compose(self.x**2, self.d, self.i)

    @staticmethod
    def rational(n: int, q: int):
        return BASIS_CTX.constant(flint.fmpq(n, q))


PLAIN = PlainBasisRing()


def plain_DD(N, p, rate, q=None):
    return recipe.DD(N, p, rate, PLAIN, q)


def plain_third_order_residual(N, p: int, rate: int):
    """derivations.sections.meromorphic_ring.third_order_residual on the plain ring."""
    G0 = N
    G1 = plain_DD(G0, p, rate, p)
    G2 = plain_DD(G1, p, rate, p + 1)
    G3 = plain_DD(G2, p, rate, p + 2)
    e = D**2 + 1
    u = X**2 - 1
    v = 1 + X**2
    return PLAIN.red(e * p**3 * u * G3 + D * p**3 * e * (2 * u**2 - 4 * X**2) * G2
                     + e * p**3 * u * ((D**2 + p * p) * u**2 + 4 * p * p * e * X**2) * G1
                     - 4 * p**5 * e**2 * D * X**2 * v**2 * G0)


def plain_poisson_residuals(sol) -> list:
    M1, M2, M3 = sol.M
    p, r = sol.p, sol.rate
    return [PLAIN.red(plain_DD(M1, p, r) - 2 * p * X * M3),
            PLAIN.red(plain_DD(M2, p, r) - p * (X**2 - 1) * M3),
            PLAIN.red(plain_DD(M3, p, r) + 2 * p * (D**2 + 1) * X * M1 + p * (X**2 - 1) * M2)]


def plain_digest(real_M, complex_M) -> str:
    """numerators_digest as it was (one string per numerator and per denominator list)."""
    digest = hashlib.sha256()
    for poly in list(real_M) + list(complex_M):
        digest.update(array("q", [len(poly), *chain.from_iterable(poly.monoms())]).tobytes())
        coefficients = poly.coeffs()
        digest.update(",".join([c.p.str(16) for c in coefficients]).encode())
        digest.update(b"/")
        digest.update(",".join([c.q.str(16) for c in coefficients]).encode())
        digest.update(b";")
    return digest.hexdigest()


def conservation(real, cplx, product, at0) -> bool:
    """The zero tests of the orthonormality certificate beyond KEEP_BASES (meromorphic.certify_p), with the
    products and the values at x = 0 taken by ``product`` and ``at0``."""
    p = real.p
    Den1 = ONE
    for m in range((p - 1) // 2):
        Den1 *= (2 * m + 1) ** 2 * D**2 + p * p
    scale_real = 2 * p * p * Den1
    k = at0(cplx.M[1])
    unit_target = 2 * product(k, conj(k))
    real0, V0 = [at0(c) for c in real.M], [at0(c) for c in cplx.M]
    Vbar0 = [conj(v) for v in V0]

    def dot(A, B):
        return (D**2 + 1) * product(A[0], B[0]) + product(A[1], B[1]) + product(A[2], B[2])

    return (dot(real0, real0) - (D**2 + 1) * scale_real**2).is_zero() and (dot(V0, Vbar0) - unit_target).is_zero()


def old_at0(poly):
    return poly.compose(BASIS_CTX.constant(0), D, I)


def new_at0(poly):
    return poly.subs({"x": 0})


# ---------------------------------------------------------------- the steps


def steps(p: int, cache: dict):
    """(name, old callable, new callable) per step; ``cache`` holds one construct of each route for the later steps."""
    def construct_old():
        cache["old"] = recipe.construct(p, PLAIN)

    def construct_new():
        cache["new"] = recipe.construct(p, BASIS_RING)

    def hyp():
        return recipe.hypergeometric_polynomials(p, BASIS_RING)

    F, Fhat = hyp()

    def third_new():
        cplx = cache["new"][1]
        cache["first"] = DD_split(split_i(cplx.M[0]), p, 1)
        return third_order_holds(cplx.M[0], p, 1, cache["first"])

    def poisson_new():
        real, cplx = cache["new"]
        return meromorphic.poisson_hold(real) and meromorphic.poisson_hold(cplx, cache["first"])

    return [
        ("construct (recipe)", construct_old, construct_new),
        ("of which F * Fhat", lambda: PLAIN.red(F * Fhat), lambda: BASIS_RING.mul_red(F, Fhat)),
        ("third-order zero test", lambda: plain_third_order_residual(cache["old"][1].M[0], p, 1).is_zero(), third_new),
        ("Poisson zero tests (6)", lambda: all(r.is_zero() for r in plain_poisson_residuals(cache["old"][0])
                                               + plain_poisson_residuals(cache["old"][1])), poisson_new),
        ("orthonormality (conservation)", lambda: conservation(*cache["old"], lambda a, b: PLAIN.red(a * b), old_at0),
         lambda: conservation(*cache["new"], BASIS_RING.mul_red, new_at0)),
        ("numerators_digest", lambda: plain_digest(cache["old"][0].M, cache["old"][1].M),
         lambda: meromorphic.numerators_digest(cache["new"][0].M, cache["new"][1].M)),
    ]


def timed(function):
    start = time.perf_counter()
    value = function()
    return time.perf_counter() - start, value


def identity(p: int, cache: dict) -> dict:
    """The checks: the same numerators, digests, zero-test answers; a perturbed numerator fails both routes."""
    (real_o, cplx_o), (real_n, cplx_n) = cache["old"], cache["new"]
    pairs = list(zip(real_o.M + cplx_o.M, real_n.M + cplx_n.M))
    out = {"numerators ==": all(a == b for a, b in pairs),
           "terms identical": all(a.monoms() == b.monoms() and a.coeffs() == b.coeffs() for a, b in pairs),
           "divisions exact": real_n.divisions_exact and cplx_n.divisions_exact
           and (real_o.divisions_exact, cplx_o.divisions_exact) == (real_n.divisions_exact, cplx_n.divisions_exact),
           "digest ==": plain_digest(real_o.M, cplx_o.M) == meromorphic.numerators_digest(real_n.M, cplx_n.M)}
    if p <= 101:   # the perturbed runs of the old route cost as much as the tests themselves
        bad = recipe.Solution(p, 1, [cplx_n.M[0] + X**3 * D, cplx_n.M[1], cplx_n.M[2]])
        out["perturbed caught by both"] = (
            not plain_third_order_residual(bad.M[0], p, 1).is_zero() and not third_order_holds(bad.M[0], p, 1)
            and not all(r.is_zero() for r in plain_poisson_residuals(bad)) and not meromorphic.poisson_hold(bad))
    return out


def one_run(p: int, new_first: bool, checks: bool) -> dict:
    """One repetition at ``p`` in this (fresh) process: every step both ways, interleaved; the checks if asked."""
    cache, seconds = {}, {}
    for name, old, new in steps(p, cache):
        order = [("new", new), ("old", old)] if new_first else [("old", old), ("new", new)]
        values = {}
        for route, function in order:
            seconds.setdefault(name, {})[route], values[route] = timed(function)
        if name not in ("construct (recipe)", "of which F * Fhat"):
            assert values["old"] == values["new"], (p, name, values)
    return {"seconds": seconds, "checks": identity(p, cache) if checks else None}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ps", type=int, nargs="+", default=[51, 101, 151, 201])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--one", type=int, nargs=3, metavar=("P", "NEW_FIRST", "CHECKS"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one:   # a child: one repetition, the result as JSON on the last line
        p, new_first, with_checks = args.one
        print(json.dumps(one_run(p, bool(new_first), bool(with_checks))))
        return 0
    load_before = os.getloadavg()
    checks = {}
    for p in (1, 3, 15, 17):
        cache = {}
        for _, old, new in steps(p, cache)[:1]:
            old(), new()
        checks[p] = identity(p, cache)
    results = {}
    for p in args.ps:
        samples = {}
        for repetition in range(args.repeat):
            # each repetition in a fresh process: the heap of the earlier ones (python-flint keeps some of it) made
            # the later steps up to 1.6x slower in one long process, whichever route they were
            child = subprocess.run([sys.executable, __file__, "--one", str(p), str(repetition % 2), str(int(repetition == 0))],
                                   capture_output=True, text=True, check=True)
            outcome = json.loads(child.stdout.strip().splitlines()[-1])
            for name, routes in outcome["seconds"].items():
                samples.setdefault(name, ([], []))
                samples[name][0].append(routes["old"])
                samples[name][1].append(routes["new"])
            if outcome["checks"] is not None:
                checks[p] = outcome["checks"]
        results[p] = {name: [statistics.median(o), statistics.median(n)] for name, (o, n) in samples.items()}
        print(p, {name: f"{o:.2f} -> {n:.2f}" for name, (o, n) in results[p].items()}, file=sys.stderr, flush=True)
    load_after = os.getloadavg()
    assert all(all(v for v in c.values()) for c in checks.values()), checks

    def per_p(p, names):
        return [sum(results[p][n][k] for n in names) for k in (0, 1)]

    worker = ["construct (recipe)", "third-order zero test", "Poisson zero tests (6)", "orthonormality (conservation)",
              "numerators_digest"]
    rt = ["construct (recipe)", "numerators_digest"]
    machine = f"{cpu_name()}, {os.cpu_count()} cores (shared), Python {sys.version.split()[0]}, python-flint {flint.__version__}"
    arguments = sys.argv[1:] if argv is None else list(argv)
    command = " ".join(["python bench/bench_basis_construct.py", *arguments])
    lines = ["# The exact meromorphic basis at large p: plain and fast routes, same objects", "",
             (f"Machine: {machine}; load average {load_before[0]:.2f} before, {load_after[0]:.2f} after. "
              f"Command: `{command}`. Seconds, median of {args.repeat} runs per step, each run a fresh process doing "
              "every step both ways (old and new interleaved, which first alternating), one core."), "",
             "| p | step | old (s) | new (s) | old / new |", "|---:|---|---:|---:|---:|"]
    for p in args.ps:
        rows = [(name, *results[p][name]) for name in results[p]]
        rows += [("**certifying worker per p** (construct, third order, Poisson, orthonormality, digest)", *per_p(p, worker)),
                 ("**round trip per p** (construct, digest)", *per_p(p, rt))]
        lines += [f"| {p} | {name} | {o:.3f} | {n:.3f} | {o / n:.2f}x |" for name, o, n in rows]
    lines += ["", "Identity checks (old route against new):", ""]
    for p, c in checks.items():
        lines.append(f"- p = {p}: " + ", ".join(f"{k}: {'yes' if v else 'NO'}" for k, v in c.items()))
    lines += ["", ("The old routes are kept in this script (`PlainBasisRing`, `plain_third_order_residual`, "
                   "`plain_poisson_residuals`, `plain_digest`); the new ones are the project's "
                   "(`suslov/recipes/flint_rings.py`, `derivations/sections/meromorphic_ring.py`, "
                   "`derivations/sections/meromorphic.py`)."), ""]
    data = {"machine": machine, "command": command, "repeat": args.repeat, "load": [load_before[0], load_after[0]],
            "seconds": {str(p): {name: {"old": o, "new": n} for name, (o, n) in results[p].items()} for p in args.ps},
            "checks": {str(p): c for p, c in checks.items()}}
    write_results("basis_construct", data, "\n".join(lines))
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
