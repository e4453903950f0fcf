"""The build's time estimate before starting (issue 13): a power law per per-p phase, from the benchmark."""
import json

from derivations.output.estimate import BENCH, estimate_seconds


def test_estimate_from_a_synthetic_benchmark(tmp_path):
    """Per-p costs c p^k: galois 0.001 p^2 (every p, at least up to 40), residue 0.01 p (every p),
    first_integrals 0.5 (serial: it runs in the main process); 100 s measured at pmax 20 with one
    job, so 'the rest' is 100 minus the phases at pmax 20; the larger pmax 40 was benchmarked on all
    cores only (as pmax 201 is), so it does not set the rest."""
    def law(c, k):
        return {"classes": [{"coefficient": c, "exponent": k, "first": 1, "step": 1}]}

    growth = {"galois": law(0.001, 2.0), "residue": law(0.01, 1.0), "first_integrals": law(0.5, 0.0)}
    bench = tmp_path / "build.json"
    bench.write_text(json.dumps({"growth": growth, "largest_pmax": 40,
                                 "runs": [{"pmax": 20, "jobs": 1, "wall_seconds": 100.0},
                                          {"pmax": 40, "jobs": "all cores", "wall_seconds": 70.0}]}))
    galois = lambda n: 0.001 * sum(p * p for p in range(1, n + 1))  # noqa: E731
    residue = lambda n: 0.01 * sum(range(1, n + 1))  # noqa: E731
    rest = 100.0 - (galois(40) + residue(20) + 0.5 * 20)
    expected = rest + (galois(60) + residue(60)) / 2 + 0.5 * 60
    assert abs(estimate_seconds(60, 2, bench) - expected) < 1e-9


def test_no_benchmark_no_estimate(tmp_path):
    assert estimate_seconds(101, 2, tmp_path / "missing.json") is None


def test_committed_benchmark_gives_an_estimate():
    data = json.loads(BENCH.read_text())
    largest = max((r for r in data["runs"] if r["jobs"] == 1), key=lambda r: r["pmax"])
    measured = largest["wall_seconds"]
    assert abs(estimate_seconds(largest["pmax"], 1) - measured) < 1e-6 * measured
    assert estimate_seconds(101, 2) > estimate_seconds(51, 2)
