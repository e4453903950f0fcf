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
import math
from pathlib import Path

import matplotlib.pyplot as plt

import suslov

REPO = Path(suslov.__file__).resolve().parents[1]
data = json.loads((REPO / "bench" / "results" / "work_precision.json").read_text())
meta = data["meta"]
print("machine:", meta["machine"]["cpu"], f"({meta['machine']['cpu_count']} CPUs);",
      ", ".join(f"{k} {v}" for k, v in meta["machine"]["versions"].items()))

XMIN = 1e-20
STYLE = {  # method -> (colour, marker), in legend order
    "closed form (float64)": ("k", "*"),
    "closed form (mpmath)": ("0.45", "P"),
    "heyoka + max_delta_t": ("tab:purple", "D"),
    "heyoka": ("tab:pink", "d"),
    "Magnus-4 (NumPy)": ("tab:olive", "v"),
    "DOP853": ("tab:blue", "o"),
    "RK45": ("tab:orange", "s"),
    "Radau": ("tab:green", "^"),
    "LSODA": ("tab:red", "<"),
    "mpmath odefun": ("tab:cyan", "p"),
}

fig, axes = plt.subplots(2, 2, figsize=(11, 9), sharex=True)
for ax, (problem, (title, _case, _quantity)) in zip(axes.flat, data["settings"]["problems"].items()):
    runs = [r for r in data["runs"] if r["problem"] == problem and r.get("time_median_s") is not None
            and "grid" not in r and "window" not in r]
    for method, (color, marker) in STYLE.items():
        mine = sorted((r for r in runs if r["method"] == method), key=lambda r: r["sort_key"])
        good = [r for r in mine if not r["failed"]]
        bad = [r for r in mine if r["failed"]]
        if good:
            ax.plot([max(r["error"], XMIN) for r in good], [r["time_median_s"] for r in good],
                    color=color, marker=marker, ls="-" if len(good) > 1 else "none", ms=6, label=method)
        if bad:
            ax.plot([min(max(r["error"], XMIN), 10.0) if math.isfinite(r["error"]) else 10.0 for r in bad],
                    [r["time_median_s"] for r in bad], color=color, marker="X", ls="none", ms=10, mec="k", mew=0.7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(XMIN / 3, 30)
    ax.axvspan(XMIN / 3, XMIN, color="0.9")
    ax.grid(True, alpha=0.4)
    ax.set_title(title, fontsize=10)
for ax in axes[1]:
    ax.set_xlabel("error at the end point")
for ax in axes[:, 0]:
    ax.set_ylabel("median wall time [s]")
handles, labels = [], []
for ax in axes.flat:
    for h, label in zip(*ax.get_legend_handles_labels()):
        if label not in labels:
            handles.append(h)
            labels.append(label)
handles.append(plt.Line2D([], [], color="gray", marker="X", ls="none", ms=9, mec="k"))
labels.append("failed (colour of its method)")
fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, frameon=False)
fig.suptitle("Work-precision, Poisson equations, ss solution on [-40, 40] (bench/results/work_precision.json)",
             fontsize=11)
fig.tight_layout(rect=(0, 0.08, 1, 0.96))

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
