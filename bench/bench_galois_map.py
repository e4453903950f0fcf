"""The 41 x 41 Galois map decided exactly (Kimura's theorem), beside the monodromy balls (issue 37).

The slice of ``bench/bench_monodromy.py`` -- (I13, I23) in [-0.6, 0.6]^2 as exact decimals, I11 = 2,
I22 = 1 -- decided by :func:`suslov.validated.galois_group` (exact rational arithmetic on the body's
Gauss equation), timed (median of 5 runs, one process), and compared cell by cell with the verdicts of
the validated complex-path monodromy committed in ``bench/results/monodromy.json`` (the old route; its
time is that file's, measured on the same kind of machine).  Also the exact map of the general-body
study's wider question: every cell's verdict and the count of "unknown" (must be 0).

    python bench/bench_galois_map.py [--size 41] [--repeat 5]

Writes ``bench/results/galois_map.{json,md}``.
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from fractions import Fraction
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

from suslov.validated import galois_group, monodromy  # noqa: E402


def grid(n: int) -> list[str]:
    """The same exact decimal values as bench_monodromy.slice_tasks."""
    return [str(Fraction(-6, 10) + Fraction(12, 10) * Fraction(k, n - 1)) for k in range(n)]


def exact_map(values: list[str]) -> list[str]:
    out = []
    for I13 in values:
        for I23 in values:
            if Fraction(I13) == 0 and Fraction(I23) == 0:
                out.append("equilibrium")
            else:
                out.append(galois_group("2", "1", I13, I23).group)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=41)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--ball-cells", type=int, default=6, help="cells re-timed with the monodromy balls in this run")
    args = ap.parse_args(argv)
    values = grid(args.size)
    # the old route in the same run, on a few cells spread over the slice (its full map takes minutes)
    sample = [(values[(7 * k + 3) % args.size], values[(11 * k + 5) % args.size]) for k in range(args.ball_cells)]
    ball_times, ball_match = [], 0
    for I13, I23 in sample:
        start = time.perf_counter()
        verdict = monodromy("2", "1", I13, I23, dps=20, max_dps=80).verdict
        ball_times.append(time.perf_counter() - start)
        ball_match += verdict == galois_group("2", "1", I13, I23).group
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        verdicts = exact_map(values)
        times.append(time.perf_counter() - start)
    counts = {v: verdicts.count(v) for v in sorted(set(verdicts))}
    committed = json.loads((ROOT / "bench" / "results" / "monodromy.json").read_text())["slice"]
    compared = committed["size"] == args.size and committed["grid"] == values
    agree = disagree = undecided = 0
    if compared:
        for exact, balls in zip(verdicts, committed["verdicts"]):
            if balls == "unknown":
                undecided += 1
            elif balls == exact:
                agree += 1
            else:
                disagree += 1
    median = statistics.median(times)
    data = {"machine": f"{cpu_name()}, {os.cpu_count()} cores", "size": args.size, "seconds": times,
            "median_seconds": median, "counts": counts, "unknown": verdicts.count("unknown"),
            "balls": {"seconds": committed["seconds"], "counts": committed["counts"]} if compared else None,
            "ball_cells": {"cells": sample, "seconds": ball_times, "median_seconds": statistics.median(ball_times),
                           "same_verdict": ball_match},
            "agree": agree, "disagree": disagree, "undecided_by_balls": undecided, "verdicts": verdicts}
    lines = ["# The Galois map decided exactly (Kimura) beside the monodromy balls", "",
             f"Machine: {data['machine']}. Reproduce: `python bench/bench_galois_map.py`.", "",
             "| route | cells | time | unknown |", "|---|---:|---:|---:|",
             f"| exact (Kimura's theorem, rational arithmetic), one process | {args.size ** 2} | "
             f"{median * 1e3:.1f} ms (median of {args.repeat}) | {data['unknown']} |"]
    if compared:
        lines.append(f"| monodromy balls, 20 digits (`bench/results/monodromy.json`) | {args.size ** 2} | "
                     f"{committed['seconds']:.0f} s on 2 workers | {committed['counts'].get('unknown', 0)} |")
        lines.append(f"| monodromy balls, this run, {len(sample)} cells | {len(sample)} | "
                     f"{statistics.median(ball_times):.2f} s per cell (median; "
                     f"{statistics.median(ball_times) / (median / args.size ** 2):.0f}x the exact route per cell) | "
                     f"{len(sample) - ball_match} differ |")
        lines += ["", f"Cell by cell: {agree} agree, {disagree} disagree, {undecided} left unknown by the balls "
                  "(the exact route decides them).", ""]
    lines += [f"Exact verdicts: {', '.join(f'{k}: {v}' for k, v in counts.items())}.", ""]
    write_results("galois_map", data, "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0 if data["unknown"] == 0 and disagree == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
