"""The work-precision diagram (bench/bench_work_precision.py): one drawing, used by the benchmark
(which saves it as bench/results/work_precision.png) and by the docs gallery (which draws it from the
committed bench/results/work_precision.json)."""
from __future__ import annotations

import math

import matplotlib.pyplot as plt

METHOD_ORDER = ["closed form (float64)", "closed form (mpmath)", "RK45", "DOP853", "Radau", "LSODA",
                "heyoka", "heyoka + max_delta_t", "Magnus-4 (NumPy)", "mpmath odefun"]

METHOD_STYLE = {
    "closed form (float64)": ("black", "*"),
    "closed form (mpmath)": ("dimgray", "P"),
    "RK45": ("tab:blue", "o"),
    "DOP853": ("tab:orange", "s"),
    "Radau": ("tab:green", "^"),
    "LSODA": ("tab:red", "v"),
    "heyoka": ("tab:purple", "D"),
    "heyoka + max_delta_t": ("tab:cyan", "d"),
    "Magnus-4 (NumPy)": ("tab:brown", "h"),
    "mpmath odefun": ("tab:pink", "p"),
}
XMIN = 1e-20


def draw(runs, meta, problems, refs=None):
    """The work-precision diagram of ``runs`` (the benchmark's records) as a matplotlib Figure."""
    fig, axes = plt.subplots(2, 2, figsize=(14, 11))
    for ax, (problem, (title, _, _)) in zip(axes.flat, problems.items()):
        rs = [r for r in runs if r["problem"] == problem and r["time_median_s"] is not None and "grid" not in r]
        for method in METHOD_ORDER:
            mr = sorted([r for r in rs if r["method"] == method and "window" not in r], key=lambda r: r["sort_key"])
            if not mr:
                continue
            color, marker = METHOD_STYLE[method]
            good = [r for r in mr if not r["failed"]]
            bad = [r for r in mr if r["failed"]]
            xs = [max(r["error"], XMIN) for r in good]
            ys = [r["time_median_s"] for r in good]
            ls = "-" if len(good) > 1 and not method.startswith("closed") else "none"
            ax.plot(xs, ys, color=color, marker=marker, ls=ls, ms=7, label=method)
            if bad:
                bx = [min(max(r["error"], XMIN), 10.0) if math.isfinite(r["error"]) else 10.0 for r in bad]
                ax.plot(bx, [r["time_median_s"] for r in bad], color=color, marker="X", ls="none", ms=12,
                        mec="black", mew=0.8)
        clipped = sorted([r for r in rs if not r["failed"] and r["error"] < XMIN], key=lambda r: r["time_median_s"])
        last_y, stack = None, 0
        for r in clipped:  # points beyond the left edge: label them with their error, staggered
            y = math.log10(r["time_median_s"])
            stack = stack + 1 if last_y is not None and y - last_y < 0.35 else 0
            last_y = y if stack == 0 else last_y
            color = METHOD_STYLE[r["method"]][0]
            label = r["setting"].replace("cos(Dpsi/2) formula, ", "").replace("gamma_basis_mp ", "gamma_basis_mp ")
            ax.annotate(f"{label}: {r['error']:.0e}" if r["error"] > 0 else f"{label}: 0 (exact to ref.)",
                        (XMIN, r["time_median_s"]), xytext=(8, 11 * stack), textcoords="offset points",
                        fontsize=7, va="center", color=color,
                        arrowprops={"arrowstyle": "-", "color": color, "lw": 0.5} if stack else None)
        win = [r for r in rs if "window" in r]
        for r in win:
            ax.plot([max(r["error"], XMIN)], [r["time_median_s"]], marker="p", mfc="none", mec="tab:pink",
                    ls="none", ms=9)
            ax.annotate(f"odefun {r['setting'].split(',')[0]}, [-5,5] only",
                        (max(r["error"], XMIN), r["time_median_s"]),
                        xytext=(6, -3), textcoords="offset points", fontsize=7, color="tab:pink")
        if refs is not None and problems[problem][2] == "dpsi":
            tr = abs(refs[problems[problem][1]]["info"]["dpsi_integrated_T40_minus_closed"])
            ax.axvline(tr, color="0.5", ls=":", lw=1)
            ax.annotate("|Dpsi(40) - Dpsi(oo)|", (tr, 0.5), xycoords=("data", "axes fraction"), rotation=90,
                        fontsize=7, color="0.4", xytext=(3, 0), textcoords="offset points", va="bottom")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(XMIN / 3, 30)
        ax.set_title(title, fontsize=11)
        ax.set_xlabel("error at the end point (|gamma(40) - ref|_max, or |Dpsi - Dpsi_ref|)")
        ax.set_ylabel("median wall time [s]")
        ax.grid(True, which="major", alpha=0.4)
        ax.axvspan(XMIN / 3, XMIN, color="0.9")
    handles, labels = [], []
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    handles.append(plt.Line2D([], [], color="gray", marker="X", ls="none", ms=10, mec="black"))
    labels.append("FAILED (same colour as its method)")
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=9, frameon=False)
    fig.suptitle("Work-precision: Poisson equations of the Suslov problem, ss solution on [-40, 40]\n"
                 f"{meta['machine']['cpu']}, {meta['machine']['cpu_count']} CPUs; errors < 1e-20 drawn at the "
                 "grey left edge with their value", fontsize=11)
    fig.tight_layout(rect=(0, 0.06, 1, 0.95))
    return fig


