"""
What accuracy costs: the work-precision diagram
===============================================

Median wall time against the error at the end point, for the Poisson equations of the Suslov
problem (ss solution on [-40, 40]) solved by several methods side by side: the certified closed
forms of the generated module (float64 and mpmath), SciPy's ``solve_ivp`` (RK45, DOP853, Radau,
LSODA) over a sweep of tolerances, heyoka's Taylor integrator with and without a step cap, a
4th-order Magnus method and ``mpmath.odefun``.  The reference values are independent of every
method timed (a Taylor integrator in mpmath started from the ss power series).

This page only *plots* the committed results, ``bench/results/work_precision.json``; the study
itself (``python bench/bench_work_precision.py``, 4-6 minutes) is not rerun by the docs build.
Crosses mark runs that failed the benchmark's rule (error above 100 x the tolerance, or above
1e-2): LSODA and uncapped heyoka can jump over the dynamics from a start next to the limit axis.
Errors below 1e-20 (the mpmath closed forms) are drawn at the grey left edge.
"""
import json
import sys
from pathlib import Path

import suslov

REPO = Path(suslov.__file__).resolve().parents[1]
data = json.loads((REPO / "bench" / "results" / "work_precision.json").read_text())
meta = data["meta"]
print("machine:", meta["machine"]["cpu"], f"({meta['machine']['cpu_count']} CPUs);",
      ", ".join(f"{k} {v}" for k, v in meta["machine"]["versions"].items()))

sys.path.insert(0, str(REPO / "bench"))
from work_precision_plot import draw  # noqa: E402  (the benchmark's own drawing of the diagram)

fig = draw(data["runs"], meta, data["settings"]["problems"], data.get("references"))

# %%
# Which method for which accuracy: the cheapest successful run of each method reaching 1e-9 in
# the generic case (p = 2.5, no closed form).
generic = [r for r in data["runs"] if r["problem"] == "2_generic" and not r["failed"]
           and r.get("time_median_s") is not None and r["error"] <= 1e-9 and "window" not in r]
best = {}
for r in generic:
    if r["method"] not in best or r["time_median_s"] < best[r["method"]]["time_median_s"]:
        best[r["method"]] = r
for method, r in sorted(best.items(), key=lambda kv: kv[1]["time_median_s"]):
    print(f"{method:24s} {r['setting']:32s} error {r['error']:.1e}  time {r['time_median_s'] * 1e3:9.3f} ms")
