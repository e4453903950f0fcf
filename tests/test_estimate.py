"""The build's time estimate before starting (issue 13): a power law per per-p phase, from the benchmark;
and while it runs, calibrated on this machine (issue 26)."""
import json

from derivations.output.estimate import BENCH, Calibration, estimate_seconds, predicted_seconds


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


def test_predicted_seconds_per_derivation_from_a_synthetic_benchmark(tmp_path):
    """residue costs 0.01 p per p; the one-process run at pmax 20 measured residue 3 s, model 1 s in 10 s of
    wall time: at pmax 60 residue takes its measured 3 s plus the phase from p = 21 to 60, the rest
    (10 - 4 s: start-up, rendering) stays."""
    growth = {"residue": {"classes": [{"coefficient": 0.01, "exponent": 1.0, "first": 1, "step": 1}]}}
    bench = tmp_path / "build.json"
    bench.write_text(json.dumps({"growth": growth, "runs": [
        {"pmax": 20, "jobs": 1, "wall_seconds": 10.0, "derivations": {"model": 1.0, "residue": 3.0}},
        {"pmax": 80, "jobs": 1, "wall_seconds": 99.0, "derivations": {"model": 1.0, "residue": 50.0}}]}))
    predicted = predicted_seconds(60, 1, bench)
    assert predicted["model"] == 1.0 and predicted["rest"] == 6.0
    assert abs(predicted["residue"] - (3.0 + 0.01 * sum(range(21, 61)))) < 1e-12


def test_calibration_scales_the_prediction_by_what_this_machine_measured():
    calibration = Calibration({"model": 1.0, "residue": 2.0, "galois": 7.0, "rest": 0.5})
    assert calibration.left() is None                         # nothing measured yet
    calibration.finished("fuchsian", 3.0)                     # unknown to the benchmark: left out
    assert calibration.left() is None
    calibration.finished("model", 2.0)                        # this machine: twice as slow
    assert calibration.factor() == 2.0
    assert abs(calibration.left() - 2.0 * (2.0 + 7.0 + 0.5)) < 1e-12
    calibration.finished("residue", 3.0)                      # 5 s for 3 benchmark seconds
    assert abs(calibration.left() - 5.0 / 3.0 * 7.5) < 1e-12


def test_the_committed_benchmark_splits_by_derivation():
    data = json.loads(BENCH.read_text())
    run = min((r for r in data["runs"] if r["jobs"] == 1), key=lambda r: r["pmax"])
    predicted = predicted_seconds(run["pmax"], 1)
    assert abs(sum(predicted.values()) - run["wall_seconds"]) < 1e-6 * run["wall_seconds"]
