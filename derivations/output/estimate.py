"""How long a build will take, before it starts (issue 13: "say the estimate before starting").

From ``bench/results/build.json`` (written by ``bench/bench_build.py`` on the 2-core machine): for
each per-p phase the fitted cost of one p, ``c p^k`` (residue's Frobenius logarithms at t0
(Theorem 3.5), the meromorphic bases (Theorem 6.1), the logarithms at s1..s4 of section 5.2, the
first integrals, the round trip of the emitted module), summed over the p the build will certify
and, for the phases that run on the workers, divided by their number; plus the rest of the build
as measured by the largest one-process benchmark.  An estimate from a power law,
not a promise: the build says so, and proceeds.

That estimate is the benchmark machine's.  While the build runs, :class:`Calibration` rescales it
to *this* machine (issue 26: "calibrated per machine on the fly, not from a committed
constant"): :func:`predicted_seconds` splits the benchmark's prediction by derivation (the nearest
benchmarked run of the same kind, one process or all cores, with its per-p phases moved to this
pmax along their power laws), and after each finished derivation the time left is the prediction
for the rest times the ratio measured / predicted over what has finished.  The committed numbers
give only the *shape* (which derivation costs what share, how each phase grows with p); the
scale is measured here.
"""
from __future__ import annotations

import json
from pathlib import Path

from derivations.core.options import CROSS_CHECK_PMAX, cross_check_p_values
from derivations.sections.galois import (
    GALOIS_PMAX,  # galois decides the conjecture for p <= max(pmax, GALOIS_PMAX)
)
from suslov.executor import default_workers

MIN_CALIBRATION = 0.02   # the time left is said once this share of the prediction has finished

BENCH = Path(__file__).resolve().parents[2] / "bench" / "results" / "build.json"
PARALLEL = ("galois", "meromorphic", "residue", "roundtrip")   # the phases run through CertificateLog.map_per_p
SAMPLED = ("galois", "residue")   # per-p cross-checks: every p up to cross_check_pmax, a sample above


def _cost(c: dict, name: str, top: int, dense: int) -> float:
    """Benchmark seconds of one parity class ``c`` of phase ``name`` over the p it runs on up to ``top``."""
    ps = cross_check_p_values(top, dense) if name in SAMPLED else range(1, top + 1)
    return sum(c["coefficient"] * p ** c["exponent"] for p in ps if p >= c["first"] and (p - c["first"]) % c["step"] == 0)


def estimate_seconds(pmax: int, workers: int | None = None, bench: Path = BENCH,
                     cross_check_pmax: int = CROSS_CHECK_PMAX) -> float | None:
    """Estimated wall seconds of a full build at ``pmax``, or None without benchmark data."""
    try:
        data = json.loads(bench.read_text(encoding="utf-8"))
        growth = data["growth"]
        # the rest of the build from the largest one-process run (pmax 201 is benchmarked on all cores only)
        base_run = max((r for r in data["runs"] if r["jobs"] == 1), key=lambda r: r["pmax"])
    except (OSError, ValueError, KeyError):
        return None
    workers = max(1, workers or default_workers())
    per_p_total, measured_total = 0.0, 0.0
    for name, g in growth.items():
        share = 1.0 / workers if name in PARALLEL else 1.0
        top = max(pmax, GALOIS_PMAX) if name == "galois" else pmax
        measured_top = max(base_run["pmax"], GALOIS_PMAX) if name == "galois" else base_run["pmax"]
        for c in g["classes"]:
            per_p_total += share * _cost(c, name, top, cross_check_pmax)
            measured_total += _cost(c, name, measured_top, CROSS_CHECK_PMAX)
    rest = max(0.0, base_run["wall_seconds"] - measured_total)   # everything that is not a per-p phase
    return rest + per_p_total


def _phase(growth: dict, name: str, pmax: int, dense: int = CROSS_CHECK_PMAX) -> float:
    """Benchmark seconds of derivation ``name``'s per-p phase for the p it runs on up to ``pmax`` (0 without a
    law; the sampled cross-checks every p up to ``dense``, a sample above)."""
    top = max(pmax, GALOIS_PMAX) if name == "galois" else pmax
    return sum(_cost(c, name, top, dense) for c in growth.get(name, {}).get("classes", ()))


def predicted_seconds(pmax: int, workers: int | None = None, bench: Path = BENCH,
                      cross_check_pmax: int = CROSS_CHECK_PMAX) -> dict | None:
    """Benchmark-machine seconds per derivation of a build at ``pmax`` (and ``"rest"``: start-up,
    rendering, the round trip), or None without benchmark data with per-derivation times."""
    try:
        data = json.loads(bench.read_text(encoding="utf-8"))
        growth = data["growth"]
        kind = 1 if workers == 1 else "all cores"
        runs = [r for r in data["runs"] if r.get("derivations") and r["jobs"] == kind] or \
            [r for r in data["runs"] if r.get("derivations")]
        below = [r for r in runs if r["pmax"] <= pmax]
        run = max(below, key=lambda r: r["pmax"]) if below else min(runs, key=lambda r: r["pmax"])
    except (OSError, ValueError, KeyError, TypeError):
        return None
    workers = max(1, workers or default_workers()) if run["jobs"] != 1 else 1

    def moved(name: str) -> float:
        share = 1.0 / workers if name in PARALLEL else 1.0
        return share * (_phase(growth, name, pmax, cross_check_pmax) - _phase(growth, name, run["pmax"]))

    predicted = {name: max(0.0, seconds + moved(name)) for name, seconds in run["derivations"].items()}
    predicted["rest"] = max(0.0, run["wall_seconds"] - sum(run["derivations"].values()) + moved("roundtrip"))
    return predicted


class Calibration:
    """The time left in a build, on this machine: the benchmark's per-derivation prediction for what
    has not finished, times measured / predicted over what has (module docstring).  Derivations the
    benchmark did not know are left out of both sums."""

    def __init__(self, predicted: dict | None):
        self.predicted = dict(predicted or {})
        self.measured: dict = {}

    def finished(self, name: str, seconds: float) -> None:
        self.measured[name] = seconds

    def factor(self) -> float | None:
        """This machine's seconds per benchmark second so far (None until enough has finished)."""
        done = [n for n in self.measured if n in self.predicted and n != "rest"]
        predicted = sum(self.predicted[n] for n in done)
        total = sum(self.predicted.values())
        if not total or predicted < MIN_CALIBRATION * total or predicted <= 0:
            return None
        return sum(self.measured[n] for n in done) / predicted

    def left(self) -> float | None:
        factor = self.factor()
        if factor is None:
            return None
        return factor * sum(s for n, s in self.predicted.items() if n not in self.measured)
