"""
Fig. 2: a Poisson solution with the boundary condition ss
=========================================================

The paper's Fig. 2: *a generic trajectory gamma(t) = (g1, g2, g3) with the boundary condition
(ss)*, i.e. gamma -> (-1, 0, 0) as t -> -oo.  The scene ``scenes/fig2_gamma_ss.toml`` takes
p = 2.5, d = 0.7: p is not an odd integer, so there is no closed-form solution and the planner
integrates the Poisson equations (DOP853 with a bounded step, started from the ss power series
so that a start on the limit axis cannot jump the transition).  The scattering angle between the
limit axes is the closed form of Theorem 5.4 (corrected), valid for every real p.
"""
import json
from pathlib import Path

import suslov
from suslov.simulator.engine import execute
from suslov.simulator.figures import figure
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import load_scene

REPO = Path(suslov.__file__).resolve().parents[1]
scene = load_scene(REPO / "scenes" / "fig2_gamma_ss.toml")
plan = make_plan(scene)
print(plan.explain())
run = execute(plan)
print(json.dumps(run.results, indent=1))

# %%
# The components of gamma(t); the dotted line is the limit -cos(Delta psi) of g1 as t -> +oo.
fig = figure("gamma_components", run)

# %%
# The same curve on the unit sphere (the Poisson equations preserve ``|gamma| = 1``).
fig = figure("gamma_sphere", run)

# %%
# The angle from the generated module directly: float64, 30 digits, and a rigorous ball.
print(suslov.scattering_angle(2.5, 0.7))
print(suslov.scattering_angle_mp(2.5, "0.7", dps=30))
print(suslov.scattering_angle_ball("5/2", "7/10", prec=100))
