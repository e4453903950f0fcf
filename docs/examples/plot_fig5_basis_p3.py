"""
Fig. 5: the Poisson basis for p = 3, d = 1/2
============================================

The paper's Fig. 5: *independent and orthogonal vector solutions gamma^(1) and gamma^(2) for
p = 3 and d = 1/2 in the body frame* (Theorem 6.1).  p is an odd integer, so the planner uses
the certified closed form ``gamma_basis`` (nothing is integrated); the scene
``scenes/fig5_basis_p3.toml`` also asks for the drift of the first integrals F1 (energy),
``F2 = |gamma|^2`` and the polynomial integral F3 of Theorem 6.2 along gamma^(1).
"""
import json
from pathlib import Path

import numpy as np

import suslov
from suslov.simulator.engine import execute
from suslov.simulator.figures import figure
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import load_scene

REPO = Path(suslov.__file__).resolve().parents[1]
scene = load_scene(REPO / "scenes" / "fig5_basis_p3.toml")
plan = make_plan(scene)
print(plan.explain())
run = execute(plan)
print(json.dumps(run.results, indent=1))
fig = figure("basis_sphere", run)

# %%
# The rows of ``gamma_basis`` form a rotation at every t: orthonormal, determinant +1.
B = suslov.gamma_basis(np.linspace(-8, 8, 5), 3, 0.5)
print("max |B B^T - I| =", np.abs(B @ B.transpose(0, 2, 1) - np.eye(3)).max())
print("det B =", np.linalg.det(B))
