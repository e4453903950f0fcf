"""A sweep's outputs: the results table (CSV, Parquet), its figures, a summary and a report.

``results.csv`` holds every point in point order (floats with 17 significant digits, so the table
round-trips exactly and is byte-identical whatever executor computed it); ``results.parquet`` is
the same table when pyarrow is importable.  Figures (paper section 5.1: the scattering angle over
a family of bodies): ``map`` draws each scalar effect over the sweep's two varying fields (at the
first energy; and the energy spread when there are several), ``histogram`` its distribution.
Points that are no body or no scattering motion (the equilibrium ``I13 = I23 = 0``) are drawn
hatched as *undefined*, apart from the white *unknown* cells; colours keep distinct lightness, so
the maps read in grey print; the title is wrapped inside the canvas (constrained layout).
"""
from __future__ import annotations

import csv
import json
import math
import textwrap

import numpy as np

from suslov.simulator.outputs import REPORT, staged

SCALARS = ("scattering_angle", "scattering_angle_integrated", "scattering_angle_enclosure", "galois_group",
           "local_behaviour", "energy_spread")
LABELS = {"scattering_angle": r"$\Delta\psi$ (rad)", "scattering_angle_integrated": r"$\Delta\psi$ integrated (rad)",
          "scattering_angle_enclosure": r"$\Delta\psi$ ball midpoint (rad)",
          "energy_spread": r"energy spread $\Delta\psi_{\max} - \Delta\psi_{\min}$ (rad)",
          "galois_group": "Galois group (0: reducible, Liouvillian; 1: SO(3,C), not; white: unknown)",
          "local_behaviour": r"At the poles of $\omega$ (0: meromorphic; 1: logarithmic; 2: branching)"}
SPREAD_FLOOR = 1e-17   # a spread of exactly 0 (equal in every bit) is drawn at this value on the log scale
AXIS_LABELS = {"I11": "$I_{11}$", "I22": "$I_{22}$", "I33": "$I_{33}$", "I12": "$I_{12}$", "I13": "$I_{13}$",
               "I23": "$I_{23}$", "p": "$p$", "d": "$d$"}


def _cell(value) -> str:
    if isinstance(value, float):
        return "" if math.isnan(value) else repr(value)
    return str(value)


def write_csv(path, table: dict):
    names = list(table)
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(names)
        for row in zip(*(table[n] for n in names)):
            writer.writerow([_cell(v) for v in row])


def write_parquet(path, table: dict) -> bool:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        return False
    pq.write_table(pa.table(table), path)
    return True


def summary(scene, table: dict) -> dict:
    """Counts and ranges per scalar column (finite values only)."""
    errors = [e for e in table["error"] if e]
    out = {"points": len(table["error"]), "refused_or_failed": len(errors),
           "first_errors": errors[:5], "columns": {}}
    for name in SCALARS:
        if name in table:
            values = np.array(table[name], dtype=float)
            finite = values[np.isfinite(values)]
            if finite.size:
                out["columns"][name] = {"min": float(finite.min()), "max": float(finite.max()),
                                        "finite": int(finite.size)}
                if f"{name}_error" in table:
                    err = np.array(table[f"{name}_error"], dtype=float)
                    out["columns"][name]["largest_error_estimate"] = float(np.nanmax(err))
    return out


def _first_energy(scene, values: np.ndarray) -> np.ndarray:
    return values[::scene.sweep.energies]


# two classes with distinct lightness (dark blue, light yellow: told apart in grey print too)
GALOIS_COLOURS = ("#1f3b73", "#f2c14e")
LOCAL_COLOURS = ("#1f3b73", "#c8553d", "#f2c14e")   # meromorphic, logarithmic, branching: distinct in grey too
UNDEFINED = dict(facecolor="0.85", edgecolor="0.25", hatch="///", linewidth=0.0)


def _cells(centres: np.ndarray) -> np.ndarray:
    """Edges of the cells around ``centres`` (``pcolormesh(shading="nearest")``'s cells)."""
    if centres.size == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mid = (centres[1:] + centres[:-1]) / 2
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def _mark_undefined(ax, x, y, undefined) -> bool:
    """Hatch the cells of points that are no body or no scattering motion (the equilibrium I13 = I23 = 0):
    undefined there, not "unknown"."""
    from matplotlib.patches import Rectangle
    xe, ye = _cells(x), _cells(y)
    for j, i in zip(*np.nonzero(undefined)):
        ax.add_patch(Rectangle((xe[i], ye[j]), xe[i + 1] - xe[i], ye[j + 1] - ye[j], label="_undefined", **UNDEFINED))
    if undefined.any():
        ax.legend(handles=[Rectangle((0, 0), 1, 1, **UNDEFINED)], labels=["undefined (equilibrium, not a body)"],
                  loc="upper right", fontsize=7, framealpha=0.9)
    return bool(undefined.any())


def map_figure(scene, table: dict):
    """The ``map`` figure (a matplotlib Figure): each scalar effect over the two varying fields, refused
    points hatched as undefined, the title wrapped inside the canvas (constrained layout)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sw = scene.sweep
    if len(sw.varying) != 2:
        raise ValueError(f"figure 'map' needs a grid sweep with exactly two varying fields (besides energy); "
                         f"this sweep varies {', '.join(sw.varying) or 'none'}: use 'histogram'")
    xname, yname = sw.varying
    x = np.unique(_first_energy(scene, np.array(table[xname])))
    y = np.unique(_first_energy(scene, np.array(table[yname])))
    panels = [n for n in SCALARS if n in table]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.8), squeeze=False, layout="constrained")
    xi = np.searchsorted(x, _first_energy(scene, np.array(table[xname])))
    yi = np.searchsorted(y, _first_energy(scene, np.array(table[yname])))
    undefined = np.zeros((len(y), len(x)), dtype=bool)
    undefined[yi, xi] = [bool(e) for e in _first_energy(scene, np.array(table.get("error", [""] * len(table[xname]))))]
    for ax, name in zip(axes[0], panels):
        grid = np.full((len(y), len(x)), np.nan)
        grid[yi, xi] = _first_energy(scene, np.array(table[name], dtype=float))
        norm = None
        label = LABELS[name]
        if name == "energy_spread":
            from matplotlib.colors import LogNorm
            grid = np.where(np.isfinite(grid), np.maximum(grid, SPREAD_FLOOR), np.nan)
            finite = grid[np.isfinite(grid)]
            norm = LogNorm(finite.min(), max(finite.max(), 10 * SPREAD_FLOOR)) if finite.size else None
            label += f"; 0 drawn at {SPREAD_FLOOR:g}"
        if name == "galois_group":   # two classes; unknown masked (white), undefined hatched
            from matplotlib.colors import BoundaryNorm, ListedColormap
            mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(grid), shading="nearest",
                                 cmap=ListedColormap(GALOIS_COLOURS), norm=BoundaryNorm([-0.5, 0.5, 1.5], 2))
            fig.colorbar(mesh, ax=ax, ticks=[0, 1], label="0 reducible (Liouvillian), 1 SO(3,C); white: unknown")
        elif name == "local_behaviour":   # three classes
            from matplotlib.colors import BoundaryNorm, ListedColormap
            mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(grid), shading="nearest",
                                 cmap=ListedColormap(LOCAL_COLOURS), norm=BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3))
            fig.colorbar(mesh, ax=ax, ticks=[0, 1, 2], label="0 meromorphic, 1 logarithmic, 2 branching")
        else:   # viridis: lightness rises monotonically, so the scale reads in grey
            mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(grid), shading="nearest", norm=norm, cmap="viridis")
            fig.colorbar(mesh, ax=ax, label=label)
        _mark_undefined(ax, x, y, undefined)
        ax.set_xlabel(AXIS_LABELS.get(xname, xname))
        ax.set_ylabel(AXIS_LABELS.get(yname, yname))
        title = LABELS[name].rsplit(" (", 1)[0]
        ax.set_title(title + (f" (energy {table['energy'][0]:g})" if sw.energies > 1 and name != "energy_spread"
                              else ""), fontsize=10)
    # about 11 characters of 11 pt text per inch: wrap the scene's title to the canvas
    fig.suptitle(textwrap.fill(scene.title or scene.name, width=int(11 * fig.get_figwidth())), fontsize=11)
    return fig


def draw_map(scene, table: dict, staging, formats) -> list[str]:
    return _save(map_figure(scene, table), "map", staging, formats)


def draw_histogram(scene, table: dict, staging, formats) -> list[str]:
    return _save(histogram_figure(scene, table), "histogram", staging, formats)


def histogram_figure(scene, table: dict):
    """The ``histogram`` figure of every scalar effect of the sweep, not saved."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = [n for n in SCALARS if n in table]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.4), squeeze=False, layout="constrained")
    for ax, name in zip(axes[0], panels):
        values = np.array(table[name], dtype=float)
        values = values[np.isfinite(values)]
        ax.hist(values, bins=min(50, max(5, int(np.sqrt(values.size)))), color="tab:blue",
                label=f"{values.size} points")
        ax.set_xlabel(LABELS[name])
        ax.set_ylabel("points")
        ax.legend()
    fig.suptitle(textwrap.fill(scene.title or scene.name, width=int(11 * fig.get_figwidth())), fontsize=11)
    return fig


def sweep_figure(name: str, scene, table: dict):
    """Figure ``name`` (``map`` or ``histogram``) of a sweep's table, not saved (``suslov.simulate(...).plot()``)."""
    return map_figure(scene, table) if name == "map" else histogram_figure(scene, table)


def _save(fig, name, staging, formats) -> list[str]:
    import matplotlib.pyplot as plt

    from suslov.simulator.figures import save_formats
    written = save_formats(fig, staging / name, formats)
    plt.close(fig)
    return written


def _report(scene, plan, files, seconds, computed, stats) -> str:
    lines = [f"# Sweep {scene.name}", "", scene.description or "", "", f"Scene file: `{scene.path.name}`", "",
             "## Plan", "", "```", plan.explain(), "```", "",
             f"Computed {computed} of {plan.chunks} chunks in {seconds:.2f} s "
             f"({plan.chunks - computed} resumed from a previous run).", "",
             "## Summary", "", "```json", json.dumps(stats, indent=1, sort_keys=True), "```", "",
             "## Files", ""] + [f"- `{f}`" for f in files]
    return "\n".join(lines) + "\n"


def spread_source(effects) -> str | None:
    """The angle whose energy spread is reported: the integrated one when asked for (the closed forms
    never see the energy: their spread is 0 by construction), else the closed form; None without an angle."""
    return next((e for e in ("scattering_angle_integrated", "scattering_angle") if e in effects), None)


def columns_of(scene) -> list[str]:
    """The table's columns: the inputs, three per effect (value, _error, _method), energy_spread, error."""
    names = list(scene.sweep.columns)
    for effect in scene.effects:
        names += [effect, f"{effect}_error", f"{effect}_method"]
    if scene.sweep.energies > 1 and spread_source(scene.effects):
        names.append("energy_spread")
    return names + ["error"]


def write_sweep_outputs(scene, plan, table: dict, out, seconds: float, computed: int, progress=None) -> list[str]:
    """Write the table, figures, results.json and report.md into ``out`` atomically."""
    assert list(table) == columns_of(scene)
    with staged(out) as staging:
        write_csv(staging / "results.csv", table)
        files = ["results.csv"]
        if write_parquet(staging / "results.parquet", table):
            files.append("results.parquet")
        for name in scene.figures:
            if progress:
                progress(f"figure {name}")
            draw = draw_map if name == "map" else draw_histogram
            files += draw(scene, table, staging, scene.figures_format)
        stats = summary(scene, table)
        (staging / "results.json").write_text(json.dumps({"scene": scene.name, "summary": stats}, indent=1,
                                                         sort_keys=True) + "\n", encoding="utf-8")
        files.append("results.json")
        (staging / REPORT).write_text(_report(scene, plan, files, seconds, computed, stats), encoding="utf-8")
    return files
