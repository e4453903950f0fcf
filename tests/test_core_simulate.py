"""``suslov simulate`` on the core install: the [sim] extra is asked for per scene, by what its plan needs (issue 47).

The core install (NumPy, mpmath, python-flint) evaluates every closed form, ball and exact decision; only a
numerical integration (heyoka or SciPy), the sleigh's quadrature (SciPy), a figure (matplotlib) and a sweep on
several local processes (loky) need the [sim] extra.  Here every extra's libraries (``suslov.extras.EXTRAS``:
SciPy, matplotlib, heyoka, loky, SymPy, ...) are hidden from a fresh interpreter (``sys.modules[name] = None``,
which ``import`` and ``importlib.util.find_spec`` both read as "not installed") before ``suslov`` is imported, and
the ``suslov`` command runs there: a closed-form scene runs and writes its outputs, whose numbers agree with
``general_scattering_angle_mp`` and the exact Galois group computed here with everything installed; a scene that
integrates, draws or spreads over processes exits 2 with one line naming [sim], the missing library and the steps
that need it, and writes nothing.  ``suslov.simulate`` raises the same as an ``ImportError``.
"""
import json
import os
import subprocess
import sys
from pathlib import Path

import mpmath
import pytest

import suslov
from suslov import validated
from suslov.extras import EXTRAS

ROOT = Path(__file__).resolve().parents[1]
HIDDEN = sorted({name for names in EXTRAS.values() for name in names})
HINT = "pip install 'suslov-certified[sim]'"
CORE = f"""
import sys
for name in {HIDDEN!r}:
    sys.modules[name] = None          # "not installed", for import and for importlib.util.find_spec
from suslov.cli import main
status = main(sys.argv[1:])
print("imported:", sorted(n for n in {HIDDEN!r} if sys.modules.get(n) is not None))
sys.exit(status)
"""
CLOSED = """
name = "closed_forms"
description = "A general body: omega, the angle, its ball, the Galois group, the local behaviour; no integration, no figure"
[body]
inertia = [["5/4", 0, "3/10"], [0, 1, "-1/2"], ["3/10", "-1/2", "3/2"]]
[motion]
time = [-5.0, 5.0]
samples = 21
[effects]
compute = ["omega", "scattering_angle", "scattering_angle_enclosure", "galois_group", "local_behaviour"]
"""
ODD_P = """
name = "odd_p"
description = "p = 3, d = 1: gamma from the certified basis, a closed form"
[body]
p = 3
d = 1
[motion]
time = [-4.0, 4.0]
samples = 21
[effects]
compute = ["omega", "gamma", "orientation", "integral_drift", "scattering_angle"]
"""
INTEGRATE = """
name = "integrate"
description = "p = 2.5: gamma integrated on request (the cross-check of the Gauss route)"
[body]
p = 2.5
d = 0.7
[motion]
time = [-5.0, 5.0]
samples = 21
[effects]
compute = ["gamma", "scattering_angle"]
[numerics]
gamma_route = "integrate"
{numerics}
"""
SWEEP = """
name = "sweep_closed"
description = "Closed forms over a small grid"
[sweep]
I11 = 2.0
I22 = 1.0
I33 = 1.5
I13 = [0.0, 0.3]
I23 = [-0.5, 0.4]
[effects]
compute = ["scattering_angle", "galois_group", "local_behaviour"]
"""


def core(tmp_path, *args) -> subprocess.CompletedProcess:
    """``suslov ARGS`` in a fresh interpreter without any extra's libraries, in ``tmp_path``."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), *filter(None, [os.environ.get("PYTHONPATH")])]))
    env.pop("SUSLOV_FORMULAS", None)
    return subprocess.run([sys.executable, "-c", CORE, *map(str, args)], cwd=tmp_path, env=env, capture_output=True,
                          text=True, timeout=300, check=False)


def scene(tmp_path, name: str, text: str) -> Path:
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return path


def one_error_line(done) -> str:
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1 and lines[0].startswith("suslov: error: "), done.stderr
    return lines[0]


def test_a_closed_form_scene_runs_on_the_core_install_and_writes_its_outputs(tmp_path):
    out = tmp_path / "out"
    done = core(tmp_path, "simulate", scene(tmp_path, "closed", CLOSED), "--out", out, "--quiet")
    assert done.returncode == 0, done.stderr
    assert "imported: []" in done.stdout
    assert {"omega.csv", "report.md", "results.json"} <= {p.name for p in out.iterdir()}
    results = json.loads((out / "results.json").read_text(encoding="utf-8"))["results"]
    body = ("5/4", 1, "3/10", "-1/2")
    with mpmath.workdps(50):
        reference = suslov.general_scattering_angle_mp(*body, dps=50)
        angle = results["scattering_angle"]
        assert abs(angle["radians"] - reference) <= angle["error_estimate"]
        ball = results["scattering_angle_enclosure"]
        assert abs(mpmath.mpf(ball["ball"].strip("[]").split(" +/- ")[0]) - reference) <= ball["radius"] < 1e-19
    assert results["galois_group"]["verdict"] == validated.galois_group(*body).group == "SO(3,C)"
    assert results["local_behaviour"]["kind"] == "branching"
    assert len((out / "omega.csv").read_text().splitlines()) == 22


def test_the_certified_basis_needs_no_integrator(tmp_path):
    out = tmp_path / "out"
    done = core(tmp_path, "simulate", scene(tmp_path, "odd_p", ODD_P), "--out", out, "--quiet")
    assert done.returncode == 0, done.stderr
    assert {"gamma.csv", "orientation.csv", "integrals.csv", "results.json"} <= {p.name for p in out.iterdir()}
    assert json.loads((out / "results.json").read_text())["results"]["gamma"]["method"] == "closed form gamma_basis"


@pytest.mark.parametrize("numerics, library", [("", "heyoka"), ('method = "scipy:DOP853"', "scipy")])
def test_a_scene_that_integrates_exits_2_naming_the_extra_and_writes_nothing(tmp_path, numerics, library):
    out = tmp_path / "out"
    done = core(tmp_path, "simulate", scene(tmp_path, "integrate", INTEGRATE.format(numerics=numerics)), "--out", out)
    assert done.returncode == 2
    line = one_error_line(done)
    assert "[sim] extra" in line and f"({library} not installed)" in line and HINT in line, line
    assert "gamma_integrate: a numerical integration" in line and "integrate.toml" in line
    assert not out.exists()


def test_the_plan_is_explained_without_the_extra(tmp_path):
    done = core(tmp_path, "simulate", scene(tmp_path, "integrate", INTEGRATE.format(numerics="")), "--explain")
    assert done.returncode == 0, done.stderr
    assert "gamma_integrate" in done.stdout and "heyoka Taylor" in done.stdout


def test_figures_and_the_sleigh_name_what_they_lack(tmp_path):
    figure = core(tmp_path, "simulate", "fig1_omega", "--out", tmp_path / "fig1")   # omega: a closed form; a figure
    line = one_error_line(figure)
    assert figure.returncode == 2 and "(figure omega_plane)" in line and "(matplotlib not installed)" in line, line
    sleigh = core(tmp_path, "simulate", "fig3_sleigh", "--out", tmp_path / "fig3")
    line = one_error_line(sleigh)
    assert sleigh.returncode == 2 and "sleigh_path, figure sleigh_path" in line, line
    assert "(scipy, matplotlib not installed)" in line and HINT in line
    assert not (tmp_path / "fig1").exists() and not (tmp_path / "fig3").exists()


def test_a_closed_form_sweep_runs_in_this_process_without_loky(tmp_path):
    path = scene(tmp_path, "sweep", SWEEP)
    done = core(tmp_path, "simulate", path, "--out", tmp_path / "out", "--quiet")
    assert done.returncode == 0, done.stderr
    rows = (tmp_path / "out" / "results.csv").read_text().splitlines()
    assert len(rows) == 5 and "galois_group" in rows[0]
    several = core(tmp_path, "simulate", path, "--out", tmp_path / "out2", "--workers", "2")
    line = one_error_line(several)
    assert several.returncode == 2 and "(2 worker processes)" in line and "(loky not installed)" in line, line
    assert not (tmp_path / "out2").exists()


def test_simulate_from_python_raises_naming_the_extra(monkeypatch):
    """The same check in ``suslov.simulate``: an ImportError before any work; closed forms still run."""
    monkeypatch.setitem(sys.modules, "heyoka", None)
    integrating = {"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 5},
                   "effects": {"compute": ["gamma"]}, "numerics": {"gamma_route": "integrate"}}
    with pytest.raises(ImportError) as error:
        suslov.simulate(integrating)
    assert "[sim] extra (heyoka not installed)" in str(error.value) and HINT in str(error.value)
    closed = suslov.simulate({"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 5},
                              "effects": {"compute": ["omega", "scattering_angle"]}})
    assert closed["omega"].shape == (5, 3)
