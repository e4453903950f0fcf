"""Every effect combination the scene schema allows runs (issue 38): a clear SceneError or a result.

For each kind of body (Theorem 5.4's case with a non-integer and an odd p, a general body, the
Chaplygin sleigh) the schema is asked which effects and figures it accepts; then every subset of the
accepted effects is planned (the planner's graph, cheap), and every single effect, every single figure
and the whole set are run and saved.  The failures this catches were ``KeyError: 'omega_paper'`` and
``KeyError: 't'`` from combinations the schema accepted.
"""
import itertools

import numpy as np
import pytest

import suslov
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import EFFECTS, FIGURES, SceneError, parse_scene

BODIES = {
    "p non-integer": {"p": 2.5, "d": 0.7},
    "p odd": {"p": 3, "d": 0.5},
    "general": {"inertia": [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]},
    "sleigh": {"kind": "sleigh", "mass": 1.0, "inertia": 0.2, "offset": 0.5},
}
MOTION = {"time": [-3.0, 3.0], "samples": 21}


def scene(body, compute=(), figures=()):
    effects = {"compute": list(compute)} | ({"figures": list(figures)} if figures else {})
    return {"body": dict(body), "motion": dict(MOTION), "effects": effects}


def accepted(body, kind: str) -> list:
    names = []
    for name in (EFFECTS if kind == "compute" else FIGURES):
        try:
            parse_scene(scene(body, **{kind if kind == "compute" else "figures": [name]}))
        except SceneError:
            continue
        names.append(name)
    return names


@pytest.mark.parametrize("kind", sorted(BODIES))
def test_the_schema_accepts_something_for_every_body(kind):
    assert accepted(BODIES[kind], "compute") and accepted(BODIES[kind], "figures")


@pytest.mark.parametrize("kind", sorted(BODIES))
def test_every_accepted_subset_of_effects_is_planned(kind):
    body = BODIES[kind]
    effects = accepted(body, "compute")
    planned = 0
    for size in range(1, len(effects) + 1):
        for subset in itertools.combinations(effects, size):
            plan = make_plan(parse_scene(scene(body, subset)))
            assert plan.steps, subset
            planned += 1
    assert planned == 2 ** len(effects) - 1


def _finite(result):
    for name, value in result.data.items():
        if isinstance(value, np.ndarray) and value.dtype.kind == "f":
            assert np.all(np.isfinite(value)), name


@pytest.mark.parametrize("kind", sorted(BODIES))
def test_every_single_effect_every_figure_and_all_together_run(kind, tmp_path):
    body = BODIES[kind]
    effects, figures = accepted(body, "compute"), accepted(body, "figures")
    runs = [scene(body, [e]) for e in effects] + [scene(body, (), [f]) for f in figures]
    runs.append(scene(body, effects, figures))
    for index, spec in enumerate(runs):
        result = suslov.simulate(spec)
        _finite(result)
        assert result.keys() and result.steps, spec
        files = result.save(tmp_path / str(index))
        for figure in spec["effects"].get("figures", []):
            assert f"{figure}.png" in files, (spec, files)
