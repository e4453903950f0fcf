"""What the build costs as pmax grows (issue 13): time and peak memory per derivation, one process vs all cores.

For each pmax, ``python build_formulas.py --pmax N --out TMP`` runs in a subprocess: with
``--jobs 1`` (everything in one process, the old way), with the default (the per-p certificates on
all cores through ``suslov.executor``), both cold, and the all-cores command again with the cache
it filled (the warm rebuild).  ``--baseline REV`` also builds an older revision (a git worktree,
its own packages first on the path) on all cores in the same run, so the speed-up is measured
side by side on the same machine state.  Per derivation: the seconds the build reports; for the
run: wall time and the peak resident memory of the largest process
(``getrusage(RUSAGE_CHILDREN)``).  From the per-p certificate costs of the largest run
(``certificate_costs.json`` joined with the claims ``p = N: ...`` of ``certificates.json``) it
fits the growth exponent k of the cost of one p (cost ~ p^k over the upper half of p) for each
per-p phase, and extrapolates the phase to pmax 101 and 201 (sum of c p^k).

``--repeat N`` (issue 43) first times the default cold build N times, alternating with the baseline's
when ``--baseline`` is given (the two see the same machine state; the table quotes medians and their
ratio), and ``build_formulas.py --verify`` of each tree N times.

The machine is shared, so every timed build first waits (at most ``--max-wait`` seconds) until the other
processes have used less than ``--quiet-below`` cores for 3 s, and measures what they used while it ran
(the busy time of ``/proc/stat`` minus this run's children's CPU time, over the wall time: "foreign
load").  A sample of the interleaved default build during which the foreign load exceeded
``--quiet-below`` is discarded and taken again (at most ``--retries`` times); the report lists every
sample with its foreign load, the discarded ones too.  ``--quiet-below 0`` turns the gate off.

Run: ``python bench/bench_build.py [--pmax 15 51 101 201] [--one-process-max 101] [--baseline REV]
[--baseline-pmax 15 51] [--repeat 5]`` (about 20 minutes with the defaults on the 2-core machine, plus the
baseline's builds; pmax 201 is built on all cores only); writes ``bench/results/build.md`` and ``.json``.
"""
from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

from machine_info import cpu_name  # noqa: E402

sys.path.insert(0, str(ROOT))
from derivations.core.options import cross_check_p_values  # noqa: E402
from derivations.output.estimate import SAMPLED  # noqa: E402
from results_io import write_results  # noqa: E402

LINE = re.compile(r"\[\d+/\d+\] (\w+): (\d+) certificates, ([0-9.]+) s")
ESTIMATE = re.compile(r"build: (\d+) s so far, about (\d+) s left")
PER_P = re.compile(r"^p = (\d+):")


GATE = {"below": 0.15, "max_wait": 600.0}   # set from the command line (main)


def _busy_seconds() -> float | None:
    """CPU seconds the whole machine has been busy since boot (``/proc/stat``), None where unknown."""
    try:
        with open("/proc/stat", encoding="ascii") as handle:
            fields = [int(x) for x in handle.readline().split()[1:]]
    except (OSError, ValueError):
        return None
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)      # idle + iowait
    return (sum(fields[:8]) - idle) / os.sysconf("SC_CLK_TCK")


def _children_seconds() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def wait_for_quiet() -> float:
    """Wait until the machine's other processes used less than ``GATE['below']`` cores over 3 s (at most
    ``GATE['max_wait']`` seconds); returns the seconds waited."""
    if not GATE["below"] or _busy_seconds() is None:
        return 0.0
    start = time.perf_counter()
    while time.perf_counter() - start < GATE["max_wait"]:
        before = _busy_seconds()
        time.sleep(3.0)
        if (_busy_seconds() - before) / 3.0 < GATE["below"]:
            break
    return time.perf_counter() - start


def build(pmax: int, jobs: int | None, out: Path, cache: Path | None = None, root: Path = ROOT) -> dict:
    """One build in a subprocess: cold with ``--no-cache`` (cache None) or with the cache in ``cache``;
    ``root`` another checkout (the baseline), run with its own packages first on the path."""
    command = [sys.executable, str(root / "build_formulas.py"), "--pmax", str(pmax), "--out", str(out)]
    command += ["--no-cache"] if cache is None else []
    if jobs is not None:
        command += ["--jobs", str(jobs)]
    env = dict(os.environ, PYTHONPATH=str(root))
    if cache is not None:
        env["SUSLOV_CACHE_DIR"] = str(cache)
        env.pop("SUSLOV_NO_CACHE", None)
    waited = wait_for_quiet()
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    busy, ours = _busy_seconds(), _children_seconds()
    start = time.perf_counter()
    proc = subprocess.run(command, capture_output=True, text=True, cwd=root, env=env)
    wall = time.perf_counter() - start
    # what the other processes used meanwhile, in cores (the busy time not spent by this run's children)
    foreign = None if busy is None else max(0.0, (_busy_seconds() - busy) - (_children_seconds() - ours)) / wall
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{proc.stderr[-2000:]}")
    peak = max(before, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
    derivations = {m.group(1): float(m.group(3)) for m in LINE.finditer(proc.stdout + proc.stderr)}
    # the progress lines' calibrated estimate of the whole build ("so far" + "left"), as a share of the wall time
    estimates = [round((float(a) + float(b)) / wall, 3) for a, b in ESTIMATE.findall(proc.stderr)]
    return {"pmax": pmax, "jobs": jobs or "all cores", "wall_seconds": wall, "peak_rss_mib": peak / 1024,
            "derivations": derivations, "estimate_over_wall": estimates, "foreign_load": foreign,
            "waited_seconds": waited}


def quiet_build(pmax: int, jobs: int | None, out: Path, root: Path, retries: int, discarded: list) -> dict:
    """:func:`build`, taken again (at most ``retries`` times) while other processes loaded the machine by more
    than ``GATE['below']`` cores during it; the discarded runs are appended to ``discarded``."""
    for attempt in range(retries + 1):
        run = build(pmax, jobs, out, root=root)
        noisy = GATE["below"] and run["foreign_load"] is not None and run["foreign_load"] > GATE["below"]
        if not noisy or attempt == retries:
            return run
        discarded.append({"root": "baseline" if root != ROOT else "this revision", "wall_seconds": run["wall_seconds"],
                          "foreign_load": run["foreign_load"]})
        print(f"  discarded: {run['wall_seconds']:.1f} s with {run['foreign_load']:.2f} cores of other load",
              file=sys.stderr)
        shutil.rmtree(out, ignore_errors=True)
    return run


def verify_seconds(tree: Path, root: Path = ROOT) -> float:
    """Wall seconds of ``build_formulas.py --verify tree`` with ``root``'s sources (it must pass)."""
    wait_for_quiet()
    start = time.perf_counter()
    proc = subprocess.run([sys.executable, str(root / "build_formulas.py"), "--verify", str(tree), "--quiet"],
                          capture_output=True, text=True, cwd=root, env=dict(os.environ, PYTHONPATH=str(root)))
    if proc.returncode != 0:
        raise RuntimeError(f"--verify {tree} failed:\n{proc.stderr[-2000:]}")
    return time.perf_counter() - start


def interleaved(repeat: int, tmp: Path, tree: Path | None, retries: int = 3) -> dict:
    """The default cold build (all cores) ``repeat`` times, alternating with the baseline's (``tree``), then
    ``--verify`` of each output ``repeat`` times: every sample and the medians (a sample taken under other
    load is discarded and taken again, :func:`quiet_build`)."""
    pmax = 15
    ours, base, verify_ours, verify_base = [], [], [], []
    load_ours, load_base, discarded = [], [], []
    for i in range(repeat):
        run = quiet_build(pmax, None, tmp / f"ours-{i}", ROOT, retries, discarded)
        ours.append(run["wall_seconds"])
        load_ours.append(run["foreign_load"])
        if tree is not None:
            run = quiet_build(pmax, None, tmp / f"base-{i}", tree, retries, discarded)
            base.append(run["wall_seconds"])
            load_base.append(run["foreign_load"])
        print(f"default cold build {i + 1}/{repeat}: {ours[-1]:.1f} s" + (f", baseline {base[-1]:.1f} s" if base else ""),
              file=sys.stderr)
    for i in range(repeat):
        verify_ours.append(verify_seconds(tmp / "ours-0"))
        if tree is not None:
            try:
                verify_base.append(verify_seconds(tmp / "base-0", tree))
            except RuntimeError as failure:   # an old revision may not verify its own tree: said, not timed
                print(f"baseline --verify: {str(failure).splitlines()[-1]}", file=sys.stderr)
    median = lambda xs: statistics.median(xs) if xs else None  # noqa: E731
    return {"pmax": pmax, "ours": ours, "baseline": base, "verify_ours": verify_ours, "verify_baseline": verify_base,
            "median_ours": median(ours), "median_baseline": median(base), "median_verify_ours": median(verify_ours),
            "median_verify_baseline": median(verify_base), "foreign_load_ours": load_ours,
            "foreign_load_baseline": load_base, "discarded": discarded, "quiet_below": GATE["below"]}


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
        # a sampled cross-check's fit uses the p its recursion ran on (the residue's cheap physical-body rows of every
        # p carry "p = N:" claims too, and would fit a law of their own above the threshold)
        ran = set(cross_check_p_values(max(row))) if name in SAMPLED else set(row)
        for parity in sorted(parities, reverse=True):
            points = sorted((p, s) for p, s in row.items() if p % 2 == parity and p in ran)
            fit = _fit(points)
            if fit is None:
                continue
            first = 1 if parity else 2
            step = 2 if len(parities) == 2 or parity else 1
            classes.append({"parity": "odd" if parity else "even", "exponent": fit[0], "coefficient": fit[1],
                            "first": first, "step": step})
        if not classes:
            continue
        # a sampled cross-check (residue, galois) runs on every p up to CROSS_CHECK_PMAX and a sample above
        ps = (lambda n: cross_check_p_values(n)) if name in SAMPLED else (lambda n: range(1, n + 1))
        total = lambda n, ps=ps, classes=classes: sum(  # noqa: E731
            c["coefficient"] * p ** c["exponent"] for c in classes for p in ps(n)
            if p >= c["first"] and (p - c["first"]) % c["step"] == 0)
        out[name] = {"classes": classes, "largest_p": max(row), "seconds_at_largest_p": row[max(row)],
                     "extrapolated_101": total(101), "extrapolated_201": total(201)}
    return out


def report(data: dict) -> str:
    names = sorted({n for r in data["runs"] for n in r["derivations"]},
                   key=lambda n: -max(r["derivations"].get(n, 0) for r in data["runs"]))
    head = ("| pmax | jobs | wall (s) | warm rebuild (s) | peak RSS (MiB) | " + " | ".join(names)
            + " | other load (cores) |")
    lines = ["# What the build costs as pmax grows", "",
             f"Machine: {data['machine']}, Python {data['python']}, 2 cores (shared). Command: "
             "`python bench/bench_build.py`. Seconds per derivation as the build reports them (the round trip of "
             "the emitted module and rendering make up the rest of the wall time). Cold builds (`--no-cache`); a "
             "rebuild with nothing changed (same command again, cache filled by the all-cores run) is the warm "
             "column.", "",
             head, "|" + " --- |" * (6 + len(names))]
    for r in data["runs"]:
        cells = [f"{r['derivations'].get(n, 0):.1f}" for n in names]
        warm = data.get("warm", {}).get(r["pmax"]) if r["jobs"] != 1 else None
        warm = f"{warm:.1f}" if warm is not None else ""
        load = "" if r.get("foreign_load") is None else f"{r['foreign_load']:.2f}"
        lines.append(f"| {r['pmax']} | {r['jobs']} | {r['wall_seconds']:.1f} | {warm} | {r['peak_rss_mib']:.0f} | "
                     + " | ".join(cells) + f" | {load} |")
    paired = data.get("interleaved")
    if paired:
        base_rev = (data.get("baseline") or {}).get("revision")
        lines += ["", f"## The default cold build, {len(paired['ours'])} times"
                  + (f" alternating with {base_rev}" if base_rev else "") + " (all cores, `--no-cache`; medians)", "",
                  "| | this revision (s) | " + (f"{base_rev} (s) | ratio |" if base_rev else ""),
                  "| --- | ---: | " + ("---: | ---: |" if base_rev else "")]
        for what, mine, theirs in (("cold build, default pmax", paired["median_ours"], paired["median_baseline"]),
                                   ("`--verify` of the tree", paired["median_verify_ours"],
                                    paired["median_verify_baseline"])):
            row = f"| {what} | {mine:.1f} |"
            if base_rev:
                row += f" {theirs:.1f} | {mine / theirs:.2f} |" if theirs else " | |"
            lines.append(row)
        lines += ["", "Samples (s): this revision " + ", ".join(f"{x:.1f}" for x in paired["ours"])
                  + ("; baseline " + ", ".join(f"{x:.1f}" for x in paired["baseline"]) if paired["baseline"] else "")
                  + "; --verify " + ", ".join(f"{x:.1f}" for x in paired["verify_ours"]) + "."]
        if paired.get("foreign_load_ours"):
            def cores(xs):
                return ", ".join("?" if x is None else f"{x:.2f}" for x in xs)
            lines += ["", f"Other processes' load during each sample (cores, from `/proc/stat`; a sample above "
                      f"{paired['quiet_below']:.2f} is discarded and taken again): this revision "
                      f"{cores(paired['foreign_load_ours'])}"
                      + (f"; baseline {cores(paired['foreign_load_baseline'])}" if paired["foreign_load_baseline"] else "")
                      + ". Discarded: " + (", ".join(f"{d['root']} {d['wall_seconds']:.1f} s at {d['foreign_load']:.2f}"
                                                     for d in paired["discarded"]) or "none") + "."]
    if data.get("baseline"):
        base = data["baseline"]
        ours = {r["pmax"]: r["wall_seconds"] for r in data["runs"] if r["jobs"] != 1}
        lines += ["", f"## Against the baseline revision {base['revision']} (same run, all cores, cold)", "",
                  "| pmax | baseline wall (s) | this revision (s) | ratio |", "| ---: | ---: | ---: | ---: |"]
        for r in base["runs"]:
            mine = ours.get(r["pmax"])
            if r["wall_seconds"] is None:
                lines.append(f"| {r['pmax']} | failed: {r['failed']} | {f'{mine:.1f}' if mine else ''} | |")
                continue
            ratio = f"{r['wall_seconds'] / mine:.1f}x" if mine else ""
            lines.append(f"| {r['pmax']} | {r['wall_seconds']:.1f} | {f'{mine:.1f}' if mine else ''} | {ratio} |")
    estimated = [r for r in data["runs"] if r.get("estimate_over_wall")]
    if estimated:
        lines += ["", "## The progress estimate, calibrated on this machine as the build runs", "",
                  "After each derivation the build prints its time so far and the time left (the benchmark's "
                  "per-derivation prediction rescaled by what this machine measured so far; "
                  "`derivations/output/estimate.py`). Their sum over the measured wall time, first line and worst "
                  "line (target: within a factor 1.5 from the second line on):", "", "| pmax | jobs | lines | first | min | max |",
                  "| ---: | ---: | ---: | ---: | ---: | ---: |"]
        for r in estimated:
            e = r["estimate_over_wall"]
            lines.append(f"| {r['pmax']} | {r['jobs']} | {len(e)} | {e[0]:.2f} | {min(e):.2f} | {max(e):.2f} |")
    lines += ["", f"## Growth of the per-p certificates (from the pmax {data['largest_pmax']} run, "
              f"{data.get('costs_from', 'one process')})", "",
              "| derivation | exponent k (cost of one p ~ p^k; odd / even p) | largest p | its seconds | "
              "whole phase at pmax 101, one core (s) | at pmax 201 (s) |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for name, g in sorted(data["growth"].items()):
        exponents = " / ".join(f"{c['exponent']:.1f} ({c['parity']})" for c in g["classes"])
        lines.append(f"| {name} | {exponents} | {g['largest_p']} | {g['seconds_at_largest_p']:.2f} | "
                     f"{g['extrapolated_101']:.0f} | {g['extrapolated_201']:.0f} |")
    lines += ["", "Extrapolations assume the fitted power law holds beyond the measured range; divide by the "
              "number of cores for the parallel per-p phases. Residue and galois sum the p they run on (every p up to "
              "101 and a sample above: `derivations.core.options.cross_check_p_values`)."]
    before = data.get("growth_before")
    if before:
        lines += ["", f"## The same growth before this run (the previous `build.json`, {before['what']})", "",
                  "| derivation | exponent k before | after | whole phase at pmax 201 before (s) | after (s) |",
                  "| --- | ---: | ---: | ---: | ---: |"]
        for name in sorted(set(before["growth"]) | set(data["growth"])):
            old_g, new_g = before["growth"].get(name), data["growth"].get(name)
            k = [" / ".join(f"{c['exponent']:.1f}" for c in g["classes"]) if g else "" for g in (old_g, new_g)]
            t = [f"{g['extrapolated_201']:.0f}" if g else "" for g in (old_g, new_g)]
            lines.append(f"| {name} | {k[0]} | {k[1]} | {t[0]} | {t[1]} |")
    return "\n".join(lines) + "\n"


@contextlib.contextmanager
def worktree(revision: str, tree: Path):
    """``revision`` checked out at ``tree`` (a detached git worktree) for the ``with`` block, then removed."""
    subprocess.run(["git", "worktree", "add", "--detach", "-q", str(tree), revision], cwd=ROOT, check=True)
    try:
        yield tree
    finally:
        subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT, check=False)


def run_baseline(revision: str, pmaxes: list, tmp: Path) -> list:
    """Cold all-cores builds of ``revision`` (a git worktree in ``tmp``) in the same run as the others."""
    with worktree(revision, tmp / "baseline") as tree:
        runs = []
        for pmax in pmaxes:
            try:
                runs.append(build(pmax, None, tmp / f"baseline-p{pmax}", root=tree))
            except RuntimeError as failure:   # an old revision may not reach this pmax: say how it ended
                last = str(failure).strip().splitlines()[-1]
                runs.append({"pmax": pmax, "wall_seconds": None, "failed": last})
                print(f"baseline {revision}, pmax {pmax}: failed ({last})", file=sys.stderr)
                continue
            print(f"baseline {revision}, pmax {pmax}, all cores: {runs[-1]['wall_seconds']:.1f} s", file=sys.stderr)
        return runs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--pmax", type=int, nargs="+", default=[15, 51, 101, 201])
    ap.add_argument("--one-process-max", type=int, default=101, help="the one-process (--jobs 1) cold build only "
                    "for pmax up to this (pmax 201 in one process takes about 20 minutes)")
    ap.add_argument("--baseline", metavar="REV", help="also build this git revision (the old way) on all cores, "
                    "in the same run, for --baseline-pmax")
    ap.add_argument("--baseline-pmax", type=int, nargs="+", default=[15, 51])
    ap.add_argument("--repeat", type=int, default=0, help="time the default cold build this many times first, "
                    "alternating with the baseline's, and --verify of each tree (medians)")
    ap.add_argument("--quiet-below", type=float, default=GATE["below"], metavar="CORES",
                    help="before each timed build wait until other processes use fewer cores than this; a repeated "
                         "sample under more is taken again (0: no gate)")
    ap.add_argument("--max-wait", type=float, default=GATE["max_wait"], metavar="S",
                    help="wait at most this long for the machine to be quiet before each build")
    ap.add_argument("--retries", type=int, default=3, help="how often a sample under other load is taken again")
    args = ap.parse_args(argv)
    GATE.update(below=args.quiet_below, max_wait=args.max_wait)
    runs, warm, paired = [], {}, None
    with tempfile.TemporaryDirectory() as tmp:
        if args.repeat and args.baseline:
            with worktree(args.baseline, Path(tmp) / "paired-baseline") as tree:
                paired = interleaved(args.repeat, Path(tmp), tree, args.retries)
        elif args.repeat:
            paired = interleaved(args.repeat, Path(tmp), None, args.retries)
        for pmax in args.pmax:
            if pmax <= args.one_process_max:
                runs.append(build(pmax, 1, Path(tmp) / f"p{pmax}-1"))   # the old way: one process, cold
                print(f"pmax {pmax}, one process: {runs[-1]['wall_seconds']:.1f} s", file=sys.stderr)
            cache = Path(tmp) / f"cache{pmax}"                       # empty: this run is cold too
            runs.append(build(pmax, None, Path(tmp) / f"p{pmax}-all", cache))
            print(f"pmax {pmax}, all cores: {runs[-1]['wall_seconds']:.1f} s", file=sys.stderr)
            warm[pmax] = build(pmax, None, Path(tmp) / f"p{pmax}-warm", cache)["wall_seconds"]
            print(f"pmax {pmax}, warm rebuild: {warm[pmax]:.1f} s", file=sys.stderr)
        largest = max(args.pmax)
        # the per-p costs of the largest build, from its one-process run where there is one
        one = Path(tmp) / f"p{largest}-1"
        costs_from = "one process" if one.is_dir() else "all cores: two workers share the machine"
        costs = per_p_costs(one if one.is_dir() else Path(tmp) / f"p{largest}-all")
        baseline = run_baseline(args.baseline, args.baseline_pmax, Path(tmp)) if args.baseline else []
    try:   # the growth the previous run measured, kept beside the new one ("before and after")
        previous = json.loads((ROOT / "bench" / "results" / "build.json").read_text(encoding="utf-8"))
        before = {"what": f"largest pmax {previous['largest_pmax']}, {previous.get('costs_from', '')}",
                  "growth": previous["growth"]}
    except (OSError, ValueError, KeyError):
        before = None
    data = {"machine": cpu_name(), "python": platform.python_version(), "runs": runs, "warm": warm,
            "growth_before": before,
            "baseline": {"revision": args.baseline, "runs": baseline} if args.baseline else None,
            "interleaved": paired,
            "largest_pmax": largest, "costs_from": costs_from,
            "growth": growth(costs), "per_p_costs": {k: {str(p): s for p, s in v.items()} for k, v in costs.items()}}
    write_results("build", data, report(data))
    print(report(data))


if __name__ == "__main__":
    main()
