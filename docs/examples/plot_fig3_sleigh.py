"""
Fig. 3: the contact point of the Chaplygin sleigh
=================================================

The paper's Fig. 3: *a generic trajectory of the contact point of the blade on the plane
(x, y)* (section 4 compares the Suslov problem with I13 = 0 and the Chaplygin sleigh).  The scene
``scenes/fig3_sleigh.toml`` gives the sleigh's mass, inertia and blade offset; its velocities
are closed forms and the path of the contact point is one quadrature.  Between its two
straight-line asymptotes the blade turns by a fixed angle.
"""
import json
from pathlib import Path

import suslov
from suslov.simulator.engine import execute
from suslov.simulator.figures import figure
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import load_scene

REPO = Path(suslov.__file__).resolve().parents[1]
scene = load_scene(REPO / "scenes" / "fig3_sleigh.toml")
plan = make_plan(scene)
print(plan.explain())
run = execute(plan)
print(json.dumps(run.results, indent=1))
fig = figure("sleigh_path", run)
