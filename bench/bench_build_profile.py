"""Where the cold default build spends its time, this revision beside an earlier one (issue 24).

For each revision (``--revision``, by default HEAD, and ``--base REV``; each a git worktree run with
its own packages first on the path, in the same run so both see the same machine state; the
working tree is not measured, so editing it during a run changes nothing):

* **wall time** of ``python build_formulas.py --no-cache --out TMP --quiet`` on all cores and with
  ``--jobs 1`` (one process), medians of ``--repeat`` runs;
* **per derivation and per library**: one ``--jobs 1`` build under cProfile (everything in one
  process, the imports included, so every library's self time is counted), self time summed by the
  package that owns the function (sympy, symengine, flint, mpmath, numpy/scipy, jinja2, our
  derivations/ and suslov/, builtins); the profiler roughly doubles the times and inflates code made
  of many small Python calls (SymPy's) the most, so with py-spy installed (the ``bench`` extra) the
  same build is also *sampled* from outside at 250 Hz: the unbiased shares;
* **outputs**: the two revisions' trees compared file by file (the volatile timing files
  excluded), at the default pmax and, with ``--pmax 51``, at pmax 51 too; ``--pmax 101`` adds the
  all-cores wall time at pmax 101 for both.

Run: ``python bench/bench_build_profile.py [--base 7b151a6] [--revision HEAD] [--repeat 3] [--pmax 51 101]
[--name build_profile]``
(about 3 minutes with the defaults on the 2-core machine, plus about 4 for ``--pmax 101``); writes
``bench/results/build_profile.md`` and ``.json``.
"""
from __future__ import annotations

import argparse
import filecmp
import json
import os
import platform
import re
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
from results_io import write_results  # noqa: E402

BASE = "7b151a6"    # the last revision before issue 24 (SymPy's expand/Poly on every zero test, no prefetch)
VOLATILE = {"certificate_costs.json", "certificate_costs.tex", "certificate_measurements.json", "cache_report.json"}
LINE = re.compile(r"^\s+(\w+)\s+\d+ certificates\s+([0-9.]+) s", re.M)
LIBRARIES = ("sympy", "symengine", "flint", "mpmath", "gmpy2", "numpy", "scipy", "jinja2")

# run inside the profiled subprocess: the build's main() under cProfile, self time by owning package
PROFILE_DRIVER = r"""
import cProfile, collections, json, pstats, sys
sys.argv = ["build_formulas.py", *sys.argv[1:]]
profile = cProfile.Profile()
profile.enable()   # before the import: a revision whose build_formulas imports SymPy at the top pays it here too
import build_formulas
status = build_formulas.main(sys.argv[1:])
profile.disable()
owners = collections.Counter()
for (path, _, name), (_, _, self_time, _, _) in pstats.Stats(profile).stats.items():
    # C extensions (python-flint, symengine, gmpy2) show as "~" with the type or module in the name
    owner = next((lib for lib in LIBRARIES if f"/{lib}/" in path or (path == "~" and f"{lib}." in name)), None)
    if owner is None:
        owner = ("derivations" if "/derivations/" in path else "suslov" if "/suslov/" in path
                 else "builtins" if path == "~" else "other")
    owners[owner] += self_time
print("PROFILE " + json.dumps({"status": status, "self": dict(owners)}))
"""


def run(root: Path, args: list, profile: bool = False) -> tuple[float, str]:
    """(wall seconds, stdout + stderr) of the build of checkout ``root`` with ``args``."""
    env = dict(os.environ, PYTHONPATH=str(root))
    command = ([sys.executable, "-c", f"LIBRARIES = {LIBRARIES!r}\n" + PROFILE_DRIVER] if profile
               else [sys.executable, "build_formulas.py"]) + args
    start = time.perf_counter()
    done = subprocess.run(command, cwd=root, env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        raise RuntimeError(f"{root}: {' '.join(args)} failed:\n{done.stderr[-2000:]}")
    return seconds, done.stdout + done.stderr


def py_spy() -> str | None:
    """The py-spy executable (``pip install py-spy``; the ``bench`` extra), or None."""
    beside = Path(sys.executable).parent / "py-spy"
    return str(beside) if beside.exists() else shutil.which("py-spy")


def sampled(root: Path, out: Path) -> dict | None:
    """Samples per owning package of one ``--jobs 1`` build under py-spy (250 Hz, sampled from outside:
    no per-call cost, so a library of many small Python calls is not inflated the way cProfile inflates
    it; time in a C extension counts for the Python function that called it).  None without py-spy."""
    spy = py_spy()
    if spy is None:
        return None
    raw = out.with_suffix(".raw")
    env = dict(os.environ, PYTHONPATH=str(root))
    subprocess.run([spy, "record", "-r", "250", "-f", "raw", "-o", str(raw), "--", sys.executable, "build_formulas.py",
                    "--no-cache", "--jobs", "1", "--quiet", "--out", str(out)], cwd=root, env=env, check=True,
                   capture_output=True)
    owners = {}
    for line in raw.read_text().splitlines():
        stack, count = line.rsplit(" ", 1)
        leaf = stack.split(";")[-1]
        path = leaf[leaf.rfind("(") + 1:leaf.rfind(":")] if "(" in leaf else leaf
        owner = next((lib for lib in LIBRARIES if path.startswith(f"{lib}/") or f"/{lib}/" in path), None)
        owner = owner or ("derivations" if "derivations/" in path else "suslov" if "suslov/" in path else "other")
        owners[owner] = owners.get(owner, 0) + int(count)
    return owners


def same_tree(a: Path, b: Path) -> list[str]:
    """The files that differ between two output trees (volatile timing files excluded)."""
    names = sorted((set(p.name for p in a.iterdir()) | set(p.name for p in b.iterdir())) - VOLATILE)
    return [n for n in names if not ((a / n).is_file() and (b / n).is_file() and filecmp.cmp(a / n, b / n, False))]


def measure(name: str, root: Path, tmp: Path, repeat: int, pmaxes: list) -> dict:
    out = {}
    for label, extra in (("all cores", []), ("one process", ["--jobs", "1"])):
        samples = []
        for k in range(repeat):
            seconds, _ = run(root, ["--no-cache", "--quiet", "--out", str(tmp / f"{name}-{label[0]}{k}"), *extra])
            samples.append(seconds)
        out[label] = {"median": statistics.median(samples), "samples": samples}
        print(f"{name}: {label} {out[label]['median']:.2f} s (median of {repeat})", file=sys.stderr)
    _, text = run(root, ["--no-cache", "--jobs", "1", "--out", str(tmp / f"{name}-profile")], profile=True)
    profile = json.loads(text.split("PROFILE ", 1)[1].splitlines()[0])
    out["profile"] = {"self": profile["self"], "derivations": {m[0]: float(m[1]) for m in LINE.findall(text)}}
    out["sampled"] = sampled(root, tmp / f"{name}-sampled")
    for pmax in pmaxes:
        seconds, _ = run(root, ["--no-cache", "--quiet", "--pmax", str(pmax), "--out", str(tmp / f"{name}-p{pmax}")])
        out[f"pmax {pmax}"] = seconds
        print(f"{name}: pmax {pmax} all cores {seconds:.1f} s", file=sys.stderr)
    return out


def report(data: dict) -> str:
    base, now = data["base"], data["this"]
    lines = ["# Cold default build: where the time goes (issue 24)", "",
             f"Machine: {data['machine']} ({data['cores']} cores, shared), Python {data['python']}; "
             f"`python bench/bench_build_profile.py --base {data['base_revision']}`; medians of {data['repeat']} "
             "cold builds (`--no-cache`), both revisions in the same run.", "",
             f"| measurement | {data['base_revision']} (before) | {data['revision']} | ratio | target |",
             "|---|---:|---:|---:|---|"]
    targets = {"all cores": "<= 8 s", "one process": "<= 10 s", "pmax 101": "<= 50 s", "pmax 201": "<= 600 s"}
    for key in ("all cores", "one process") + tuple(k for k in now if k.startswith("pmax")):
        b = base[key]["median"] if isinstance(base[key], dict) else base[key]
        n = now[key]["median"] if isinstance(now[key], dict) else now[key]
        lines.append(f"| {key} wall (s) | {b:.2f} | {n:.2f} | {b / n:.2f}x | {targets.get(key, '')} |")
    lines += ["", "Self time by library, one `--jobs 1` build under cProfile (the profiler inflates every "
              "time; the shares are what to read):", "", "| library | before (s) | share | this revision (s) | share |",
              "|---|---:|---:|---:|---:|"]
    total_b, total_n = sum(base["profile"]["self"].values()), sum(now["profile"]["self"].values())
    for lib in sorted(set(base["profile"]["self"]) | set(now["profile"]["self"]),
                      key=lambda k: -base["profile"]["self"].get(k, 0)):
        b, n = base["profile"]["self"].get(lib, 0.0), now["profile"]["self"].get(lib, 0.0)
        lines.append(f"| {lib} | {b:.2f} | {100 * b / total_b:.0f}% | {n:.2f} | {100 * n / total_n:.0f}% |")
    lines += [f"| total | {total_b:.2f} | | {total_n:.2f} | |", ""]
    if base.get("sampled") and now.get("sampled"):
        sb, sn = base["sampled"], now["sampled"]
        tb, tn = sum(sb.values()), sum(sn.values())
        lines += ["Self time by library, the same build sampled by py-spy at 250 Hz (no per-call cost: the "
                  "unbiased shares; C extensions count for their Python caller):", "",
                  "| library | before (samples) | share | this revision (samples) | share |", "|---|---:|---:|---:|---:|"]
        for lib in sorted(set(sb) | set(sn), key=lambda k: -sb.get(k, 0)):
            lines.append(f"| {lib} | {sb.get(lib, 0)} | {100 * sb.get(lib, 0) / tb:.0f}% | {sn.get(lib, 0)} | "
                         f"{100 * sn.get(lib, 0) / tn:.0f}% |")
        lines += [f"| total | {tb} | | {tn} | |", ""]
    lines += [
              "Seconds per derivation as the build reports them (one process, under the profiler):", "",
              "| derivation | before | this revision |", "|---|---:|---:|"]
    for name, seconds in base["profile"]["derivations"].items():
        lines.append(f"| {name} | {seconds:.2f} | {now['profile']['derivations'].get(name, float('nan')):.2f} |")
    lines += ["", "Outputs of the two revisions compared file by file (volatile timing files excluded):", ""]
    for key, differing in data["identical"].items():
        lines.append(f"- {key}: " + ("byte-identical" if not differing else "differ in " + ", ".join(differing)))
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--base", default=BASE, help=f"the revision to compare with (default {BASE})")
    ap.add_argument("--revision", default="HEAD", help="the revision measured against the base (default HEAD)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--pmax", type=int, nargs="*", default=[], help="also compare outputs (and time) at these pmax")
    ap.add_argument("--name", default="build_profile", help="results file name in bench/results (default build_profile)")
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="bench-build-profile-") as tmp_name:
        tmp = Path(tmp_name)
        trees = {"base": tmp / "base", "this": tmp / "this"}
        for name, revision in (("base", args.base), ("this", args.revision)):
            subprocess.run(["git", "worktree", "add", "--detach", "-q", str(trees[name]), revision], cwd=ROOT,
                           check=True)
        try:
            data = {"machine": cpu_name(), "cores": os.cpu_count(), "python": platform.python_version(),
                    "base_revision": args.base, "repeat": args.repeat,
                    "revision": subprocess.run(["git", "rev-parse", "--short", args.revision], cwd=ROOT,
                                               capture_output=True, text=True).stdout.strip(),
                    "base": measure("base", trees["base"], tmp, args.repeat, args.pmax),
                    "this": measure("this", trees["this"], tmp, args.repeat, args.pmax)}
            data["identical"] = {"default pmax": same_tree(tmp / "base-a0", tmp / "this-a0")}
            for pmax in args.pmax:
                data["identical"][f"pmax {pmax}"] = same_tree(tmp / f"base-p{pmax}", tmp / f"this-p{pmax}")
        finally:
            for tree in trees.values():
                subprocess.run(["git", "worktree", "remove", "--force", str(tree)], cwd=ROOT, check=False)
    write_results(args.name, data, report(data))
    print(report(data))
    return 0 if not any(data["identical"].values()) else 1


if __name__ == "__main__":
    sys.exit(main())
