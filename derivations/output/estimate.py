"""How long a build will take, before it starts (issue 13: "say the estimate before starting").

From ``bench/results/build.json`` (written by ``bench/bench_build.py`` on the 2-core machine): for
each per-p phase the fitted cost of one p, ``c p^k`` (residue's Frobenius logarithms at t0
(Theorem 3.5), the meromorphic bases (Theorem 6.1), the logarithms at s1..s4 of section 5.2, the
first integrals, the round trip of the emitted module), summed over the p the build will certify
and, for the phases that run on the workers, divided by their number; plus the rest of the build
as measured by the largest one-process benchmark.  An estimate from a power law,
not a promise: the build says so, and proceeds.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

from derivations.sections.galois import (
    GALOIS_PMAX,  # galois decides the conjecture for p <= max(pmax, GALOIS_PMAX)
)

BENCH = Path(__file__).resolve().parents[2] / "bench" / "results" / "build.json"
PARALLEL = ("galois", "meromorphic", "residue", "roundtrip")   # the phases run through CertificateLog.map_per_p


def estimate_seconds(pmax: int, workers: int | None = None, bench: Path = BENCH) -> float | None:
    """Estimated wall seconds of a full build at ``pmax``, or None without benchmark data."""
    try:
        data = json.loads(bench.read_text(encoding="utf-8"))
        growth = data["growth"]
        # the rest of the build from the largest one-process run (pmax 201 is benchmarked on all cores only)
        base_run = max((r for r in data["runs"] if r["jobs"] == 1), key=lambda r: r["pmax"])
    except (OSError, ValueError, KeyError):
        return None
    workers = max(1, workers or os.cpu_count() or 1)
    per_p_total, measured_total = 0.0, 0.0
    for name, g in growth.items():
        share = 1.0 / workers if name in PARALLEL else 1.0
        top = max(pmax, GALOIS_PMAX) if name == "galois" else pmax
        measured_top = max(base_run["pmax"], GALOIS_PMAX) if name == "galois" else base_run["pmax"]
        for c in g["classes"]:
            cost = lambda n, c=c: sum(c["coefficient"] * p ** c["exponent"]  # noqa: E731
                                      for p in range(c["first"], n + 1, c["step"]))
            per_p_total += share * cost(top)
            measured_total += cost(measured_top)
    rest = max(0.0, base_run["wall_seconds"] - measured_total)   # everything that is not a per-p phase
    return rest + per_p_total
