"""What a sweep costs besides computing its points: writing its outputs, in the main process (issue 44).

A sweep of 200,000 points announced 3 s and took 198 s.  The announced figure counted the points'
computations only (2e-5 s for a point that is no body), but the ``map`` figure draws every undefined
cell (no body, the equilibrium, a failed point) as a hatched rectangle of its own, one artist per cell
and panel, built once and drawn again for every format: about 1 ms per such cell, 60 times the
computation.  Writing the table costs some 10 us per point, a figure a fixed 0.5 s.  :func:`output_seconds`
counts that phase from the scene alone (what the plan knows before any work): points, undefined points
(the plan's ``refused`` class), figures, formats and panels (one per scalar effect).

``OUTPUT_COST`` was measured with ``sweep_outputs.write_sweep_outputs`` in a fresh process per case on the
project's 2-core machine (grids of 2,000 and 8,000 points, all defined or all refused, map and histogram in
PNG, PDF and both, one and two panels), rounded up; another machine scales it by a constant factor.
No timing runs here: planning stays free of work.
"""
from __future__ import annotations

from suslov.simulator.sweep_outputs import SCALARS, columns_of

OUTPUT_COST = {
    "fixed": 0.05,              # results.json, report.md, the swap of the output directory
    "row": 1.5e-5,              # per point: assembling the table, results.csv (17 digits), results.parquet
    "figure": 0.45,             # per figure: building it and saving its first format
    "format": 0.25,             # per further format of a figure
    "panel": 0.3,               # per further panel of the map (one per scalar effect)
    "cell_raster": 1e-5,        # per map cell, panel and raster format (PNG)
    "cell_vector": 3e-5,        # per map cell, panel and vector format (PDF, SVG: every cell is a path)
    "undefined": 5e-4,          # per undefined map cell and panel: building its hatched rectangle
    "undefined_format": 3e-4,   # per undefined map cell, panel and format: drawing it
}
VECTOR_FORMATS = ("pdf", "svg")


def map_panels(scene) -> int:
    """Panels of the ``map`` figure: one per scalar effect of the table (energy spread included)."""
    columns = columns_of(scene)
    return max(1, sum(name in columns for name in SCALARS))


def output_seconds(scene, undefined: int) -> float:
    """Estimated seconds to write the outputs of ``scene``'s sweep (table, figures, summary) in one process,
    ``undefined`` of its points being no body (the plan's ``refused`` class)."""
    cost = OUTPUT_COST
    sweep = scene.sweep
    points = len(sweep)
    energies = max(1, sweep.energies)
    seconds = cost["fixed"] + cost["row"] * points
    formats = list(scene.figures_format) or ["png"]
    for name in scene.figures:
        seconds += cost["figure"] + cost["format"] * (len(formats) - 1)
        if name != "map":   # a histogram: a fixed cost, whatever the number of points
            continue
        panels = map_panels(scene)
        cells, holes = points / energies, undefined / energies   # the map draws the first energy of each body
        seconds += cost["panel"] * (panels - 1)
        for fmt in formats:
            per_cell = cost["cell_vector"] if fmt in VECTOR_FORMATS else cost["cell_raster"]
            seconds += panels * (per_cell * cells + cost["undefined_format"] * holes)
        seconds += panels * cost["undefined"] * holes
    return seconds
