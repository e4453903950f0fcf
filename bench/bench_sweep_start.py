"""How long a large sweep takes to start computing: from the command to its first progress line.

Before its workers start, ``suslov simulate`` classifies the points of a sweep (``plan_sweep``: a body per
point, up to 20000 sampled points) and times sample points of each class (``measure_costs``).  Building a
body computed its kinetic energy through the public, validated ``omega_general`` (about 0.3 ms of a 0.4 ms
body), and the sample was classified twice (once to plan, once to time it).  Now the energy goes through
``Body.omega_at`` (the same bits) and the timing reuses the plan's classes.

The scene is the sweep of ``tests/test_interrupt.py`` (43923 general bodies, closed form and integrated
angle).  Each revision runs ``--repeat`` times, alternating with ``--baseline`` (a git worktree) in one run; the
table gives the median wall seconds to the line ``43923 points in ... chunks; estimated ...`` and to the first
``chunks`` line, where the run is stopped (SIGINT).

Usage::

    python bench/bench_sweep_start.py --baseline b9b242f --repeat 5
"""
from __future__ import annotations

import argparse
import os
import platform
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_build import worktree  # noqa: E402 - the bench scripts share their helpers by path
from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
import test_interrupt as _interrupt_test  # noqa: E402

SWEEP = _interrupt_test.SWEEP   # the scene of tests/test_interrupt.py, one definition


def start_times(tree: Path, work: Path) -> tuple[float, float]:
    """(seconds to the plan's line, seconds to the first progress line) of the sweep run from ``tree``."""
    scene = work / "sweep.toml"
    scene.write_text(SWEEP)
    out = work / f"out-{time.monotonic_ns()}"
    env = dict(os.environ, PYTHONPATH=str(tree))
    start = time.perf_counter()
    process = subprocess.Popen([sys.executable, "-m", "suslov", "simulate", str(scene), "--out", str(out), "--yes"],
                               cwd=tree, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                               start_new_session=True)
    planned = first = float("nan")
    for line in process.stderr:
        if "points in" in line and planned != planned:
            planned = time.perf_counter() - start
        if line.startswith("chunks "):
            first = time.perf_counter() - start
            break
    os.killpg(process.pid, signal.SIGINT)
    process.wait(timeout=120)
    return planned, first


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--baseline", required=True, help="git revision to compare with (a worktree, in the same run)")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    samples = {"this": [], "baseline": []}
    with tempfile.TemporaryDirectory(prefix="bench-sweep-") as tmp, worktree(args.baseline, Path(tmp) / "base") as base:
        trees = {"this": ROOT, "baseline": base}
        for _ in range(args.repeat):
            for which, tree in trees.items():
                samples[which].append(start_times(tree, Path(tmp)))
    row = {which: {"plan_line": statistics.median(p for p, _ in runs), "first_progress": statistics.median(f for _, f in runs),
                   "samples": runs} for which, runs in samples.items()}
    machine = f"{cpu_name()}, Python {platform.python_version()}, {os.cpu_count()} cores (shared)"
    lines = ["# A large sweep's start", "",
             f"Machine: {machine}. Command: `python bench/bench_sweep_start.py --baseline {args.baseline} --repeat "
             f"{args.repeat}`. The sweep of `tests/test_interrupt.py` (43923 general bodies); medians of {args.repeat} "
             "runs each, alternating with the baseline in one run.", "",
             "| revision | to the plan's line (s) | to the first progress line (s) |", "| --- | ---: | ---: |",
             f"| this | {row['this']['plan_line']:.1f} | {row['this']['first_progress']:.1f} |",
             f"| {args.baseline} | {row['baseline']['plan_line']:.1f} | {row['baseline']['first_progress']:.1f} |", "",
             f"Ratio (first progress line): {row['this']['first_progress'] / row['baseline']['first_progress']:.2f}."]
    write_results("sweep_start", {"machine": machine, "baseline": args.baseline, "repeat": args.repeat, "rows": row},
                  "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
