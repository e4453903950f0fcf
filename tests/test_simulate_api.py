"""``suslov.simulate``: the simulator from Python, the command line a thin layer over it (issue 36).

Expected values come from the closed forms written out here with NumPy (omega of eq. omegas) and from
the command line's own output files (the CLI must write what ``Result.save`` writes, byte for byte).
"""
import json
import math
from pathlib import Path

import numpy as np
import pytest

import suslov
from suslov.cli import main
from suslov.simulator.api import Result
from suslov.simulator.scene import SceneError

ROOT = Path(__file__).resolve().parents[1]
BODY = {"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 7},
        "effects": {"compute": ["omega", "scattering_angle"]}}


def test_a_dict_scene_gives_arrays_and_numbers():
    result = suslov.simulate(BODY)
    assert isinstance(result, Result) and set(result.keys()) >= {"t", "omega", "scattering_angle"}
    t, (p, d) = result["t"], (2.5, 0.7)
    assert np.allclose(result["omega"][:, 0], (p / d) * np.tanh(t), rtol=1e-14, atol=1e-14)
    assert np.allclose(result["omega"][:, 1], -(p / d) * math.sqrt(d * d + 1) / np.cosh(t), rtol=1e-14, atol=1e-14)
    x = math.pi * p / (2 * d)   # Theorem 5.4 (corrected)
    expected = 2 * math.acos(abs(math.cos(math.pi * p / 2)) / math.cosh(x))
    assert abs(result["scattering_angle"]["radians"] - expected) < 1e-12
    with pytest.raises(KeyError, match="'gamma': not computed"):
        result["gamma"]


def test_plot_returns_a_figure_and_refuses_what_was_not_computed():
    result = suslov.simulate(BODY)
    figure = result.plot()
    assert figure.axes and result.figures() == ["omega_plane"]
    with pytest.raises(ValueError, match="basis_sphere.*available: omega_plane"):
        result.plot("basis_sphere")


def test_the_command_line_writes_what_save_writes(tmp_path):
    scene = ROOT / "scenes" / "fig4_basis_p1.toml"
    assert main(["simulate", str(scene), "--out", str(tmp_path / "cli"), "--quiet"]) == 0
    suslov.simulate(scene).save(tmp_path / "api")
    files = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert files == sorted(p.name for p in (tmp_path / "api").iterdir()) and "results.json" in files
    for name in files:
        if name != "report.md":   # the report carries each run's seconds
            assert (tmp_path / "api" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name


def test_a_sweep_from_a_dict_returns_its_table_and_plots():
    scene = {"sweep": {"I11": 1.25, "I22": 1.0, "I33": 1.5, "I13": [0.0, 0.3], "I23": [-0.5, 0.5]},
             "effects": {"compute": ["scattering_angle", "galois_group"], "figures": ["map"]}}
    result = suslov.simulate(scene, workers=1)
    angles = result["scattering_angle"]
    assert angles.shape == (4,) and np.all(np.isfinite(angles))
    expected = suslov.general_scattering_angle(1.25, 1.0, result["I13"], result["I23"])
    assert np.allclose(angles, expected, rtol=1e-13)
    assert result.figures() == ["map", "histogram"] and result.plot("map").axes


@pytest.mark.parametrize("scene, field", [
    (42, "scene"),
    ({"body": {"p": 2, "d": 0.5}, "motion": {"time": [0, 1]}, "effects": {"compute": ["nope"]}}, "effects.compute"),
    ({"body": {"p": 2, "d": -0.5}, "motion": {"time": [0, 1]}, "effects": {"compute": ["omega"]}}, "body"),
])
def test_bad_scenes_name_the_field(scene, field):
    with pytest.raises(SceneError, match=field.replace(".", r"\.")):
        suslov.simulate(scene)


def test_progress_lines_and_bad_progress():
    lines = []
    suslov.simulate(BODY, progress=lines.append)
    assert lines and all(isinstance(line, str) for line in lines)
    with pytest.raises(ValueError, match="progress=3"):
        suslov.simulate(BODY, progress=3)
    assert json.dumps(suslov.simulate(BODY).results, default=float)
