"""
Fig. 1: omega(t) of a general body
==================================

The paper's Fig. 1: *a generic trajectory omega(t) on the plane (omega1, omega2); black and
white dots indicate stable and unstable equilibria.*  The scene ``scenes/fig1_omega.toml``
takes a general inertia tensor (I13 and I23 both non-zero); the planner chooses the certified
closed form ``omega_general`` (no integration): omega runs along half of the energy ellipse,
from the unstable equilibrium (t -> -oo) to the stable one (t -> +oo), both on the line
I13 omega1 + I23 omega2 = 0.
"""
from pathlib import Path

import suslov
from suslov.simulator.engine import execute
from suslov.simulator.figures import figure
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import load_scene

REPO = Path(suslov.__file__).resolve().parents[1]
scene = load_scene(REPO / "scenes" / "fig1_omega.toml")
plan = make_plan(scene)
print(plan.explain())

# %%
# Compute what the plan asks for (here: omega only), then draw the figure the scene names.
run = execute(plan)
w = run.data["omega_paper"]
print(f"{len(run.data['t'])} samples; omega (paper frame) at the ends of the window:")
print(w[0], "->", w[-1])
fig = figure("omega_plane", run)

# %%
# The generated module classifies the body: I13 does not vanish in the constraint frame, so
# there is no meromorphic case and no closed-form basis of Poisson solutions.
print(suslov.meromorphy(scene.body["inertia"]))
print("Kovalevskaya exponents:", suslov.kovalevskaya_exponents(scene.body["inertia"]))
