"""
The scattering angle of a general body, over (I13, I23)
=======================================================

The paper's open case (its Conclusion): for I13 != 0 the paper has no closed form for the scattering
angle; the project derives one (Gauss's equation in s = sinh t).  A sweep scene names many bodies;
the planner evaluates that certified closed form for each (Theorem 5.4 on the line I13 = 0) and, where
the scene asks for ``scattering_angle_integrated``, integrates the ss solution with heyoka's Taylor
method as the independent check, one row per body.  Here a coarser copy of ``scenes/general_body_study.toml`` (21 x 21 bodies, 3 energies)
runs in one process; the shipped scene (41 x 41) runs the same way with
``suslov simulate scenes/general_body_study.toml --out out/study``.
"""
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

import suslov
from suslov.simulator.scene import load_scene
from suslov.simulator.sweep import plan_sweep, run_sweep

REPO = Path(suslov.__file__).resolve().parents[1]
text = (REPO / "scenes" / "general_body_study.toml").read_text().replace("count = 41", "count = 21")
work = Path(tempfile.mkdtemp())
(work / "study.toml").write_text(text.replace('figures = ["map"]', "figures = []"))
scene = load_scene(work / "study.toml")
print(plan_sweep(scene, workers=1).explain())

# %%
# Run it: one table, one row per (body, energy), refused points named in the ``error`` column.
table, plan, seconds, _ = run_sweep(scene, work / "out", workers=1)
print(f"{len(table['error'])} points in {seconds:.2f} s;", sum(bool(e) for e in table["error"]), "refused:",
      next(e for e in table["error"] if e))

# %%
# The angle at the first energy, and the largest difference between the three energies of each
# body: at rounding level everywhere, as the scaling symmetry of the equations predicts
# (c omega(c t) solves them at energy c^2 E, and gamma(c t) then solves the Poisson equations).
i13 = np.array(table["I13"])[::3]
i23 = np.array(table["I23"])[::3]
angle = np.array(table["scattering_angle"])[::3]
spread = np.array(table["energy_spread"])[::3]
x, y = np.unique(i13), np.unique(i23)
grid = np.full((len(y), len(x)), np.nan)
grid[np.searchsorted(y, i23), np.searchsorted(x, i13)] = angle
fig, ax = plt.subplots(figsize=(5.5, 4.5))
mesh = ax.pcolormesh(x, y, np.ma.masked_invalid(grid), shading="nearest")
fig.colorbar(mesh, ax=ax, label=r"$\Delta\psi$ (rad)")
ax.set_xlabel("$I_{13}$")
ax.set_ylabel("$I_{23}$")
ax.set_title(r"$I_{11}=2$, $I_{22}=1$, $I_{33}=3/2$; the centre (a principal axis) is refused")
print(f"angle from {np.nanmin(angle):.4f} to {np.nanmax(angle):.6f}; largest energy spread {np.nanmax(spread):.1e} rad")
