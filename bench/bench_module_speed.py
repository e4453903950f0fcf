"""Speed of the generated module's float paths, side by side with an earlier version, in one run.

Issue 12's targets, on 1e6 points, float64, p = 15: ``gamma_basis`` <= 150 ns per point,
``first_integral`` <= 100 ns, ``omega`` <= 20 ns; the first call for a new (p, d) (the
coefficients of the basis) <= 5 ms at p = 15 and <= 50 ms at p = 51; import <= 0.3 s.

The earlier version is the committed ``generated/suslov_formulas.py`` of a git revision
(``--old REV``, default the last commit before the module became the certified artifact),
loaded from a temporary file; both modules run in the same process on the same inputs.
Times are medians of ``--repeat`` runs after a warm-up (the machine has 2 shared cores:
compare ratios).  The first-call time calls the module's coefficient routine
(``suslov.runtime.basis.series_float``) for a fresh d each repeat, since a p = 51 basis is beyond the default
build's public range.

Run:  python bench/bench_module_speed.py      (writes bench/results/module_speed.{md,json})
"""
from __future__ import annotations

import argparse
import importlib.util
import json
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.machine_info import cpu_name  # noqa: E402
from bench.timing import median_seconds  # noqa: E402
from suslov.runtime.basis import series_float  # noqa: E402

OLD_REVISION = "082128f"  # generated/ before the round trip (the hand-written template)
TARGETS_NS = {"omega": 20.0, "gamma_basis": 150.0, "first_integral": 100.0}
TARGETS_FIRST_CALL_MS = {15: 5.0, 51: 50.0}


def load_module_from_git(revision: str, directory: Path):
    text = subprocess.run(["git", "show", f"{revision}:generated/suslov_formulas.py"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout
    certificates = subprocess.run(["git", "show", f"{revision}:generated/certificates.json"], cwd=ROOT, check=True,
                                  capture_output=True, text=True).stdout
    (directory / "suslov_formulas.py").write_text(text)
    (directory / "certificates.json").write_text(certificates)
    return load_module(directory / "suslov_formulas.py", f"old_{revision}")


def load_module(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def per_point(module, n: int, repeat: int) -> dict:
    rng = np.random.default_rng(12)
    t = rng.uniform(-20, 20, n)
    p, d = 15, 0.5
    w1, w2 = module.omega(t, p, d)
    g = rng.normal(size=(3, n))
    g /= np.linalg.norm(g, axis=0)
    calls = {"omega": lambda: module.omega(t, p, d),
             "gamma_basis": lambda: module.gamma_basis(t, p, d),
             "first_integral": lambda: module.first_integral(p, d, w1, w2, *g)}
    return {name: median_seconds(call, repeat) / n * 1e9 for name, call in calls.items()}


def first_call(module, p: int, repeat: int) -> float:
    rng = np.random.default_rng(p)
    times = []
    for _ in range(repeat):
        d = float(rng.uniform(0.2, 3.0))  # a fresh d: nothing cached
        start = time.perf_counter()
        series_float(module._basis_core, p, d)
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1e3


def import_seconds(path: Path, repeat: int) -> float:
    code = (f"import importlib.util, time; s = time.perf_counter(); "
            f"spec = importlib.util.spec_from_file_location('m', {str(path)!r}); m = importlib.util.module_from_spec(spec); "
            f"spec.loader.exec_module(m); print(time.perf_counter() - s)")
    times = [float(subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True, capture_output=True,
                                  text=True).stdout) for _ in range(repeat)]
    return statistics.median(times)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", default=OLD_REVISION, help="git revision of the earlier module (default %(default)s)")
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "bench" / "results")
    args = ap.parse_args(argv)
    new_path = ROOT / "generated" / "suslov_formulas.py"
    new = load_module(new_path, "new_module")
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        old = load_module_from_git(args.old, Path(tmp))
        for label, module, path in (("old", old, Path(tmp) / "suslov_formulas.py"), ("new", new, new_path)):
            print(f"[{label}] per-point times ...", file=sys.stderr)
            row = per_point(module, args.points, args.repeat)
            print(f"[{label}] first calls ...", file=sys.stderr)
            row.update({f"first_call_p{p}_ms": first_call(module, p, args.repeat) for p in TARGETS_FIRST_CALL_MS})
            row["import_s"] = import_seconds(path, args.repeat)
            rows[label] = row
    machine = f"{cpu_name()}, {platform.python_implementation()} {platform.python_version()}, NumPy {np.__version__}"
    doc = {"machine": machine, "points": args.points, "repeat": args.repeat, "old_revision": args.old, "rows": rows,
           "targets_ns": TARGETS_NS, "targets_first_call_ms": TARGETS_FIRST_CALL_MS, "target_import_s": 0.3}
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "module_speed.json").write_text(json.dumps(doc, indent=1, sort_keys=True) + "\n")
    lines = ["# Speed of the generated module (float64, p = 15, d = 0.5)", "",
             f"Machine: {machine} (2 shared cores; medians of {args.repeat} runs after a warm-up).",
             f"Command: `python bench/bench_module_speed.py` (old = `generated/` at git revision {args.old}).", "",
             "| quantity | old | new | new/old | target | met |", "|---|---|---|---|---|---|"]
    for name, target in TARGETS_NS.items():
        o, n = rows["old"][name], rows["new"][name]
        lines.append(f"| `{name}` (ns per point, {args.points:.0e} points) | {o:.0f} | {n:.0f} | {n / o:.2f} | "
                     f"<= {target:.0f} | {'yes' if n <= target else 'no'} |")
    for p, target in TARGETS_FIRST_CALL_MS.items():
        key = f"first_call_p{p}_ms"
        o, n = rows["old"][key], rows["new"][key]
        lines.append(f"| first call, new (p, d), p = {p} (ms) | {o:.1f} | {n:.1f} | {n / o:.2f} | <= {target:.0f} | "
                     f"{'yes' if n <= target else 'no'} |")
    o, n = rows["old"]["import_s"], rows["new"]["import_s"]
    lines.append(f"| import (s) | {o:.3f} | {n:.3f} | {n / o:.2f} | <= 0.3 | {'yes' if n <= 0.3 else 'no'} |")
    (args.out / "module_speed.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
