"""What the build costs as pmax grows (issue 13): time and peak memory per derivation, one process vs all cores.

For each pmax, ``python build_formulas.py --pmax N --out TMP`` runs twice in a subprocess: with
``--jobs 1`` (everything in one process, the old way) and with the default (the per-p
certificates on all cores through ``suslov.executor``).  Per derivation: the seconds the build
reports; for the run: wall time and the peak resident memory of the largest process
(``getrusage(RUSAGE_CHILDREN)``).  From the per-p certificate costs of the largest run
(``certificate_costs.json`` joined with the claims ``p = N: ...`` of ``certificates.json``) it
fits the growth exponent k of the cost of one p (cost ~ p^k over the upper half of p) for each
per-p phase, and extrapolates the phase to pmax 101 and 201 (sum of c p^k), which is what bounds
the targets this machine cannot reach today.

Run: ``python bench/bench_build.py [--pmax 15 51]`` (about 6 minutes for 15 and 51); writes
``bench/results/build.md`` and ``.json``.
"""
from __future__ import annotations

import argparse
import json
import math
import platform
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402

LINE = re.compile(r"\[\d+/\d+\] (\w+): (\d+) certificates, ([0-9.]+) s")
PER_P = re.compile(r"^p = (\d+):")


def build(pmax: int, jobs: int | None, out: Path) -> dict:
    command = [sys.executable, str(ROOT / "build_formulas.py"), "--pmax", str(pmax), "--out", str(out), "--no-cache"]
    if jobs is not None:
        command += ["--jobs", str(jobs)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    start = time.perf_counter()
    proc = subprocess.run(command, capture_output=True, text=True, cwd=ROOT)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{proc.stderr[-2000:]}")
    peak = max(before, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
    derivations = {m.group(1): float(m.group(3)) for m in LINE.finditer(proc.stdout + proc.stderr)}
    return {"pmax": pmax, "jobs": jobs or "all cores", "wall_seconds": wall, "peak_rss_mib": peak / 1024,
            "derivations": derivations}


def per_p_costs(out: Path) -> dict:
    """derivation -> {p: seconds} from the certificates whose claim starts with 'p = N:'."""
    costs = json.loads((out / "certificate_costs.json").read_text())
    claims = json.loads((out / "certificates.json").read_text())["certificates"]
    table: dict = {}
    for c in claims:
        match = PER_P.match(c["claim"])
        if match and c["key"] in costs:
            row = table.setdefault(c["derivation"], {})
            p = int(match.group(1))
            row[p] = row.get(p, 0.0) + costs[c["key"]]
    return table


def _fit(points):
    """Least-squares (k, c) of log(cost) = log(c) + k log(p) over the upper half of ``points``."""
    points = [(p, s) for p, s in points if p >= 9 and s > 0]
    points = points[len(points) // 2:]
    if len(points) < 3 or sum(s for _, s in points) < 0.5:
        return None
    xs, ys = [math.log(p) for p, _ in points], [math.log(s) for _, s in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    k = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return k, math.exp(my - k * mx)


def growth(costs: dict) -> dict:
    """Per derivation, a power law per parity class of p (galois decides even p by one evaluation and odd p
    by a polynomial, so the two grow differently), with the extrapolated phase at pmax 101 and 201."""
    out = {}
    for name, row in costs.items():
        classes = []
        parities = {p % 2 for p in row}
        for parity in sorted(parities, reverse=True):
            points = sorted((p, s) for p, s in row.items() if p % 2 == parity)
            fit = _fit(points)
            if fit is None:
                continue
            first = 1 if parity else 2
            step = 2 if len(parities) == 2 or parity else 1
            classes.append({"parity": "odd" if parity else "even", "exponent": fit[0], "coefficient": fit[1],
                            "first": first, "step": step})
        if not classes:
            continue
        total = lambda n: sum(c["coefficient"] * p ** c["exponent"]  # noqa: E731
                              for c in classes for p in range(c["first"], n + 1, c["step"]))
        out[name] = {"classes": classes, "largest_p": max(row), "seconds_at_largest_p": row[max(row)],
                     "extrapolated_101": total(101), "extrapolated_201": total(201)}
    return out


def report(data: dict) -> str:
    names = sorted({n for r in data["runs"] for n in r["derivations"]},
                   key=lambda n: -max(r["derivations"].get(n, 0) for r in data["runs"]))
    head = "| pmax | jobs | wall (s) | peak RSS (MiB) | " + " | ".join(names) + " |"
    lines = ["# What the build costs as pmax grows", "",
             f"Machine: {data['machine']}, Python {data['python']}, 2 cores (shared). Command: "
             "`python bench/bench_build.py`. Seconds per derivation as the build reports them (the round trip of "
             "the emitted module and rendering make up the rest of the wall time). Cold builds (`--no-cache`); a "
             "rebuild with nothing changed comes from the certificate cache in under a second.", "", head, "|" + " --- |" * (4 + len(names))]
    for r in data["runs"]:
        cells = [f"{r['derivations'].get(n, 0):.1f}" for n in names]
        lines.append(f"| {r['pmax']} | {r['jobs']} | {r['wall_seconds']:.1f} | {r['peak_rss_mib']:.0f} | "
                     + " | ".join(cells) + " |")
    lines += ["", f"## Growth of the per-p certificates (from the pmax {data['largest_pmax']} run)", "",
              "| derivation | exponent k (cost of one p ~ p^k; odd / even p) | largest p | its seconds | "
              "whole phase at pmax 101, one core (s) | at pmax 201 (s) |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for name, g in sorted(data["growth"].items()):
        exponents = " / ".join(f"{c['exponent']:.1f} ({c['parity']})" for c in g["classes"])
        lines.append(f"| {name} | {exponents} | {g['largest_p']} | {g['seconds_at_largest_p']:.2f} | "
                     f"{g['extrapolated_101']:.0f} | {g['extrapolated_201']:.0f} |")
    lines += ["", "Extrapolations assume the fitted power law holds beyond the measured range; divide by the "
              "number of cores for the parallel per-p phases."]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pmax", type=int, nargs="+", default=[15, 51])
    args = ap.parse_args(argv)
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for pmax in args.pmax:
            for jobs in (1, None):
                out = Path(tmp) / f"p{pmax}-{jobs}"
                runs.append(build(pmax, jobs, out))
                print(f"pmax {pmax}, jobs {jobs or 'all'}: {runs[-1]['wall_seconds']:.1f} s", file=sys.stderr)
        largest = max(args.pmax)
        costs = per_p_costs(Path(tmp) / f"p{largest}-1")
    data = {"machine": cpu_name(), "python": platform.python_version(), "runs": runs, "largest_pmax": largest,
            "growth": growth(costs), "per_p_costs": {k: {str(p): s for p, s in v.items()} for k, v in costs.items()}}
    write_results("build", data, report(data))
    print(report(data))


if __name__ == "__main__":
    main()
