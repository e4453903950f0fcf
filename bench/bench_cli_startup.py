"""What the build's command line costs before it does any work: refused options and paths, and --help.

``build_formulas.py`` refuses a bad option (``--pmax 0``), an unknown derivation (``--only nonsense``) and an output
path it may not replace (``--out /proc/x``) before any derivation runs.  Since the command line imports SymPy and
the derivations only when a build starts (``derivations.output.tree``, ``derivations.registry.NAMES``), a refusal
takes about 0.1 s of CPU instead of 0.8 s; the test suite starts about thirty such processes.  ``--help`` still
imports the derivations (its last paragraph lists their titles).

Each command runs ``--repeat`` times in this checkout and in a git worktree of ``--baseline`` (alternating, in one
run); the table gives the median CPU seconds (user + system of the child) and wall seconds.

Usage::

    python bench/bench_cli_startup.py --baseline 1224cdb --repeat 7
"""
from __future__ import annotations

import argparse
import os
import platform
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
COMMANDS = {
    "--pmax 0 (refused option)": ["--pmax", "0"],
    "--only nonsense (unknown derivation)": ["--only", "nonsense"],
    "--out /proc/x (refused path)": ["--out", "/proc/x", "--only", "special_case", "--pmax", "3"],
    "--help": ["--help"],
}


def cost(tree: Path, args: list[str]) -> tuple[float, float]:
    """(CPU seconds, wall seconds) of one ``build_formulas.py ARGS`` in ``tree``."""
    before = os.times()
    start = time.perf_counter()
    subprocess.run([sys.executable, str(tree / "build_formulas.py"), *args], cwd=tree, capture_output=True,
                   env=dict(os.environ, PYTHONPATH=str(tree)), check=False)
    wall = time.perf_counter() - start
    after = os.times()
    return (after.children_user - before.children_user) + (after.children_system - before.children_system), wall


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--baseline", required=True, help="git revision to compare with (a worktree, in the same run)")
    ap.add_argument("--repeat", type=int, default=7)
    args = ap.parse_args()
    samples = {name: {"this": [], "baseline": []} for name in COMMANDS}
    with tempfile.TemporaryDirectory(prefix="bench-cli-") as tmp, worktree(args.baseline, Path(tmp) / "base") as base:
        trees = {"this": ROOT, "baseline": base}
        for name, command in COMMANDS.items():
            for tree in trees.values():   # one warm-up each: the first import reads the files from disk
                cost(tree, command)
            for _ in range(args.repeat):
                for which, tree in trees.items():
                    samples[name][which].append(cost(tree, command))
    rows = []
    for name, runs in samples.items():
        this_cpu = statistics.median(c for c, _ in runs["this"])
        base_cpu = statistics.median(c for c, _ in runs["baseline"])
        rows.append({"command": name, "cpu": this_cpu, "wall": statistics.median(w for _, w in runs["this"]),
                     "baseline_cpu": base_cpu, "baseline_wall": statistics.median(w for _, w in runs["baseline"]),
                     "ratio": this_cpu / base_cpu if base_cpu else None})
    machine = f"{cpu_name()}, Python {platform.python_version()}, {os.cpu_count()} cores (shared)"
    lines = ["# The command line's cost before any work", "",
             f"Machine: {machine}. Command: `python bench/bench_cli_startup.py --baseline {args.baseline} "
             f"--repeat {args.repeat}`. Medians of {args.repeat} runs each, alternating with the baseline revision "
             "in one run; CPU is user + system of the `build_formulas.py` process.", "",
             f"| command | CPU (s) | wall (s) | {args.baseline} CPU (s) | {args.baseline} wall (s) | CPU ratio |",
             "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for row in rows:
        lines.append(f"| `{row['command']}` | {row['cpu']:.2f} | {row['wall']:.2f} | {row['baseline_cpu']:.2f} | "
                     f"{row['baseline_wall']:.2f} | {row['ratio']:.2f} |")
    write_results("cli_startup", {"machine": machine, "baseline": args.baseline, "repeat": args.repeat, "rows": rows},
                  "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
