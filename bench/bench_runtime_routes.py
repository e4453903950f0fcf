"""What the round trip's run-time route certificates cost (``derivations/output/runtime_routes.py``).

Every public function of the emitted module is checked through its run-time route at listed points (float paths
against balls, mp twins, ``finite.repair``); those checks run in every build and every ``--verify``, first in
``--verify`` (a faulty route is named after them).  Their cost was asserted in ``tests/test_runtime_routes.py``
(under 1 s); a test does not time the machine, so it is measured here: ``--repeat`` runs of
``routes.certify`` on the committed module after a first run that pays the imports and fills the caches, as a
build's does (reported on its own); median and extremes of the sum of the certificates' seconds and of the wall time.

Usage::

    python bench/bench_runtime_routes.py --repeat 5
"""
from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(Path(__file__).resolve().parent))
from machine_info import cpu_name  # noqa: E402
from results_io import write_results  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    from derivations.core.certificates import CertificateLog
    from derivations.core.options import BuildOptions
    from derivations.output import runtime_routes as routes
    from derivations.output.pipeline import GENERATED, MODULE_NEEDS, derive
    from derivations.output.roundtrip import load_module

    build = derive(BuildOptions(jobs=1), list(MODULE_NEEDS))
    module = load_module(GENERATED)
    start = time.perf_counter()   # the first run pays the imports and fills the module's caches, as a build's does
    first = routes.certify(CertificateLog(derivation="roundtrip"), module, build)
    first_wall, first_sum = time.perf_counter() - start, sum(c.seconds for c in first)
    summed, walls = [], []
    for _ in range(args.repeat):
        start = time.perf_counter()
        certificates = routes.certify(CertificateLog(derivation="roundtrip"), module, build)
        walls.append(time.perf_counter() - start)
        summed.append(sum(c.seconds for c in certificates))
    machine = f"{cpu_name()}, Python {platform.python_version()}, {os.cpu_count()} cores (shared)"
    lines = ["# The run-time route certificates", "",
             f"Machine: {machine}. Command: `python bench/bench_runtime_routes.py --repeat {args.repeat}`. "
             f"{len(certificates)} certificates on the committed module: the first run, then {args.repeat} more.", "",
             "| run | sum of the certificates' seconds | wall (s) |", "| --- | ---: | ---: |",
             f"| first (as in a build) | {first_sum:.3f} | {first_wall:.3f} |",
             f"| later, median of {args.repeat} | {statistics.median(summed):.3f} | {statistics.median(walls):.3f} |",
             f"| later, largest | {max(summed):.3f} | {max(walls):.3f} |"]
    write_results("runtime_routes", {"machine": machine, "repeat": args.repeat, "first_sum": first_sum,
                                     "first_wall": first_wall, "summed": summed, "wall": walls,
                                     "certificates": len(certificates)}, "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
