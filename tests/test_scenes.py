"""Scenes, planner and simulator (issue 5): the planner computes only what a scene asks for.

"What ran" is observed, not assumed: the engine's ``executed`` log and spies on the
integrator and the closed forms (monkeypatched to fail if touched).
"""
import json
from pathlib import Path

import numpy as np
import pytest

import generated.suslov_formulas as gf
from suslov.cli import main
from suslov.simulator import engine, integrate, taylor
from suslov.simulator.engine import execute
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import SceneError, load_scene
from suslov.simulator.sleigh import Sleigh
from suslov.validated import scattering_angle_enclosure

ROOT = Path(__file__).resolve().parents[1]
SCENES = sorted((ROOT / "scenes").glob("*.toml"))


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def forbid(monkeypatch, *targets):
    def boom(*args, **kwargs):
        raise AssertionError("this computation must not run")
    for module, name in targets:
        monkeypatch.setattr(module, name, boom)


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_every_scene_runs_and_draws(scene, tmp_path):
    out = tmp_path / "out"
    assert main(["simulate", str(scene), "--out", str(out), "--quiet"]) == 0
    parsed = load_scene(scene)
    for fig in parsed.figures:
        png = out / f"{fig}.png"
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    results = json.loads((out / "results.json").read_text())
    if parsed.is_sweep:   # tests/test_sweep.py checks sweeps in detail
        assert results["summary"]["points"] == len(parsed.sweep)
        assert (out / "results.csv").read_text().count("\n") == len(parsed.sweep) + 1
        return
    assert results["steps"] == [s.name for s in make_plan(parsed).steps]
    assert "Plan and what ran" in (out / "report.md").read_text()


OMEGA_ONLY = """
[body]
p = 2.5
d = 0.7
[motion]
time = [-5.0, 5.0]
samples = 11
[effects]
compute = ["omega"]
"""


def test_omega_only_never_touches_poisson(tmp_path, monkeypatch):
    forbid(monkeypatch, (integrate, "solve_poisson"), (gf, "gamma_basis"))
    run = execute(make_plan(load_scene(write(tmp_path, OMEGA_ONLY))))
    assert [e["step"] for e in run.executed] == ["omega"]
    w1, w2 = gf.omega(run.data["t"], 2.5, 0.7)
    assert np.allclose(run.data["omega"][:, :2], np.stack([w1, w2], -1), rtol=0, atol=1e-15)


def test_closed_form_angle_integrates_nothing(tmp_path, monkeypatch):
    forbid(monkeypatch, (integrate, "solve_poisson"), (integrate, "numeric_angle"), (gf, "omega"))
    scene = write(tmp_path, OMEGA_ONLY.replace('["omega"]', '["scattering_angle"]'))
    run = execute(make_plan(load_scene(scene)))
    assert [e["step"] for e in run.executed] == ["angle_closed_form"]
    assert run.results["scattering_angle"]["radians"] == pytest.approx(float(gf.scattering_angle_mp(2.5, 0.7)),
                                                                       rel=1e-14)


GENERAL = OMEGA_ONLY.replace("p = 2.5\nd = 0.7", "inertia = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]")


def test_general_body_angle_is_the_closed_form_and_integrates_nothing(tmp_path, monkeypatch):
    """scattering_angle of a general body (I13 != 0) is the closed form of every body: no integrator runs, and
    it agrees with the validated integration (an independent route, python-flint balls)."""
    forbid(monkeypatch, (integrate, "solve_poisson"), (integrate, "numeric_angle"), (taylor, "taylor_angle"),
           (taylor, "solve_poisson_taylor"), (gf, "scattering_angle"), (gf, "gamma_basis"))
    plan = make_plan(load_scene(write(tmp_path, GENERAL.replace('["omega"]', '["scattering_angle"]'))))
    assert "not angle_closed_form [I13 = 0 (any real p)]: does not apply" in plan.explain()
    run = execute(plan)
    assert [e["step"] for e in run.executed] == ["angle_general_closed_form"]
    result = run.results["scattering_angle"]
    assert result["method"].startswith("closed form of every body") and 0 < result["error_estimate"] < 1e-12
    ball = scattering_angle_enclosure(*run.plan.body.entries, dps=20, method="integration").angle
    assert abs(result["radians"] - float(ball.mid())) < 1e-12


@pytest.mark.parametrize("method, module, function", [("taylor", taylor, "taylor_angle"),
                                                      ("scipy:DOP853", integrate, "solve_poisson")])
def test_general_body_is_integrated(tmp_path, monkeypatch, method, module, function):
    """The integration is asked for by name (scattering_angle_integrated): Taylor by default, SciPy on request;
    both agree with the rigorous ball of the validated integration."""
    calls = []
    original = getattr(module, function)
    monkeypatch.setattr(module, function, lambda *a, **k: calls.append(1) or original(*a, **k))
    forbid(monkeypatch, (gf, "scattering_angle"), (gf, "general_scattering_angle"), (gf, "gamma_basis"))
    text = GENERAL.replace('["omega"]', '["scattering_angle_integrated"]') + f'[numerics]\nmethod = "{method}"\n'
    run = execute(make_plan(load_scene(write(tmp_path, text))))
    assert [e["step"] for e in run.executed] == ["angle_integrate"] and calls
    assert "scattering_angle" not in run.results
    result = run.results["scattering_angle_integrated"]
    assert result["error_estimate"] < 1e-10
    ball = scattering_angle_enclosure(*run.plan.body.entries, dps=20, method="integration").angle
    assert abs(result["radians"] - float(ball.mid())) < 1e-10


def test_closed_form_and_integrated_angle_side_by_side(tmp_path):
    """Both effects in one scene: two steps, two results, agreeing within the integration's estimate."""
    text = GENERAL.replace('["omega"]', '["scattering_angle_integrated", "scattering_angle"]')
    run = execute(make_plan(load_scene(write(tmp_path, text))))
    assert [e["step"] for e in run.executed] == ["angle_general_closed_form", "angle_integrate"]
    closed, integrated = run.results["scattering_angle"], run.results["scattering_angle_integrated"]
    assert abs(closed["radians"] - integrated["radians"]) <= integrated["error_estimate"] + closed["error_estimate"]


def test_odd_p_gamma_uses_closed_form_and_matches_integration(tmp_path, monkeypatch):
    text = OMEGA_ONLY.replace("p = 2.5", "p = 3").replace('["omega"]', '["gamma", "integral_drift"]')
    forbid(monkeypatch, (integrate, "solve_poisson"))
    run = execute(make_plan(load_scene(write(tmp_path, text))))
    assert [e["step"] for e in run.executed] == ["omega", "gamma_closed_form", "integrals"]
    drift = run.results["integral_drift"]
    assert drift["F3"]["max_abs_drift"] <= 1e-12 * max(1.0, abs(drift["F3"]["initial"]))
    monkeypatch.undo()
    body = run.plan.body
    t_start, g0 = integrate.ss_initial(body, -5.0)
    numeric = integrate.solve_poisson(body, run.data["t"], g0, 1e-12, 1e-14, t_start=t_start)
    assert np.max(np.abs(body.to_scene(numeric.values[:, 0]) - run.data["gamma"])) < 1e-9


def test_integrator_started_on_the_limit_axis_is_guarded():
    """gamma0 = (-1, 0, 0) at t0 = -30 (the field is ~1e-13 there): the bounded step still follows the
    transition; reference: the certified ss solution (differs from this start by ~e^-30)."""
    from suslov.simulator.body import make_body
    body = make_body(p=3, d=0.5)
    t = np.linspace(-30, 30, 7)
    for method in ("RK45", "DOP853", "LSODA"):
        sol = integrate.solve_poisson(body, t, [-1.0, 0.0, 0.0], 1e-10, 1e-12, method)
        exact = gf.gamma_basis(t, 3, 0.5)[:, 0, :]
        assert np.max(np.abs(sol.values[:, 0] - exact)) < 1e-6, method
        assert sol.error_estimate < 1e-6


def test_sleigh_closed_form_solves_its_equations():
    s = Sleigh(mass=1.3, inertia=0.2, offset=0.4, speed=0.8)
    t = np.linspace(-3, 3, 13)
    h = 1e-5
    v, w, th = s.velocities(t)
    vp = (s.velocities(t + h)[0] - s.velocities(t - h)[0]) / (2 * h)
    wp = (s.velocities(t + h)[1] - s.velocities(t - h)[1]) / (2 * h)
    thp = (s.velocities(t + h)[2] - s.velocities(t - h)[2]) / (2 * h)
    assert np.allclose(vp, s.offset * w**2, atol=1e-8)
    assert np.allclose(s.inertia_contact * wp, -s.mass * s.offset * v * w, atol=1e-8)
    assert np.allclose(thp, w, atol=1e-8)
    assert np.ptp(s.energy(t)) < 1e-15 * 10
    far = s.velocities(np.array([-60.0, 60.0]))[2]
    assert far[1] - far[0] == pytest.approx(s.turning_angle(), rel=1e-12)


def test_outputs_are_deterministic(tmp_path):
    scene = SCENES[0]
    a, b = tmp_path / "a", tmp_path / "b"
    assert main(["simulate", str(scene), "--out", str(a), "--quiet"]) == 0
    assert main(["simulate", str(scene), "--out", str(b), "--quiet"]) == 0
    for f in a.iterdir():
        if f.name != "report.md":  # the report carries timings
            assert f.read_bytes() == (b / f.name).read_bytes(), f.name


BAD = {
    "malformed": ("[body\np = 1", "file", "TOML"),
    "unknown_effect": (OMEGA_ONLY.replace('["omega"]', '["omega", "spin"]'), "effects.compute", "unknown effect"),
    "not_pd": (OMEGA_ONLY.replace("p = 2.5\nd = 0.7", "inertia = [[1, 0, 0.5], [0, 1, 0.3], [0.5, 0.3, -1]]"),
               "body.inertia", "positive definite"),
    "window": (OMEGA_ONLY.replace("[-5.0, 5.0]", "[5.0, -5.0]"), "motion.time", "t0 < t1"),
    "samples": (OMEGA_ONLY.replace("samples = 11", "samples = 1"), "motion.samples", "integer"),
    "gamma0": (OMEGA_ONLY.replace("samples = 11", "samples = 11\ngamma0 = [1, 1, 0]"), "motion.gamma0", "unit"),
    "unknown_field": (OMEGA_ONLY.replace("[motion]", "[motion]\nspeeed = 2"), "motion.speeed", "unknown field"),
    "negative_d": (OMEGA_ONLY.replace("d = 0.7", "d = -0.7"), "body.d", "> 0"),
    "sleigh_effect": (OMEGA_ONLY.replace("p = 2.5\nd = 0.7", 'kind = "sleigh"\nmass = 1\ninertia = 1\noffset = 1')
                      .replace('["omega"]', '["gamma"]'), "effects", "sleigh"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_scene_is_rejected_and_nothing_written(case, tmp_path, capsys):
    text, field, reason = BAD[case]
    path = write(tmp_path, text)
    with pytest.raises(SceneError) as info:
        load_scene(path)
    assert info.value.field == field and reason in info.value.reason
    out = tmp_path / "out"
    assert main(["simulate", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert str(path) in err and field in err
    assert not out.exists()


def test_failed_run_leaves_output_untouched(tmp_path, monkeypatch):
    out = tmp_path / "out"
    assert main(["simulate", str(SCENES[0]), "--out", str(out), "--quiet"]) == 0
    before = {f.name: f.read_bytes() for f in out.iterdir()}
    monkeypatch.setattr(engine.STEPS["omega"].__globals__["np"], "savetxt",
                        lambda *a, **k: (_ for _ in ()).throw(RuntimeError("disk full")))
    assert main(["simulate", str(SCENES[0]), "--out", str(out), "--quiet"]) == 1
    assert {f.name: f.read_bytes() for f in out.iterdir()} == before
    assert [p.name for p in tmp_path.iterdir()] == ["out"]  # no staging left behind


def test_refuses_to_overwrite_foreign_directory(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    assert main(["simulate", str(SCENES[0]), "--out", str(out), "--quiet"]) == 2
    assert (out / "thesis.tex").read_text() == "precious"


def test_explain_prints_plan_without_running(tmp_path, monkeypatch, capsys):
    import suslov.simulator.cli
    forbid(monkeypatch, (suslov.simulator.cli, "simulate"))
    assert main(["simulate", str(SCENES[0]), "--explain"]) == 0
    assert "omega" in capsys.readouterr().out


def test_sleigh_scene_text_and_title_give_the_same_angle():
    """Fig. 3: the formula in the scene's description, evaluated with the scene's own fields, is the angle the
    figure title prints (the description once quoted Ic where the field is the inertia about the centre of mass)."""
    import math
    import tomllib

    from suslov.simulator.sleigh import TURNING_FORMULA, Sleigh

    scene = tomllib.loads((Path(__file__).resolve().parent.parent / "scenes" / "fig3_sleigh.toml").read_text(encoding="utf-8"))
    body = scene["body"]
    assert TURNING_FORMULA in scene["description"]
    expression = TURNING_FORMULA.replace("pi sqrt", "math.pi * math.sqrt").replace("^2", "**2").replace(
        "mass offset", "mass * offset")
    from_text = eval(expression, {"math": math}, dict(body))
    sleigh = Sleigh(body["mass"], body["inertia"], body["offset"], 1.0)
    assert from_text == pytest.approx(sleigh.turning_angle(), rel=1e-14)
    assert math.degrees(from_text) == pytest.approx(241.50, abs=0.01)


def test_one_method_vocabulary_in_scenes_and_docs():
    """Scenes and their docs write methods as the error message lists them (taylor, scipy:NAME)."""
    import re
    import tomllib

    from suslov.simulator.scene import METHODS

    root = Path(__file__).resolve().parent.parent
    for path in SCENES:
        method = tomllib.loads(path.read_text(encoding="utf-8")).get("numerics", {}).get("method")
        assert method is None or method in METHODS, (path.name, method)
    for doc in (root / "README.md", root / "docs" / "simulator.md", root / "scenes" / "README.md"):
        for method in re.findall(r'method = "([^"]+)"', doc.read_text(encoding="utf-8")):
            assert method in METHODS, (doc.name, method)


def test_help_is_plain_text(capsys):
    """``suslov --help`` printed raw reST (double backquotes) from the module docstring."""
    with pytest.raises(SystemExit):
        main(["--help"])
    text = capsys.readouterr().out
    assert "``" not in text and ":func:" not in text and "simulate" in text


def test_report_table_survives_a_pipe_in_a_cell():
    """report.md's step table broke on an unescaped '|' in a method text."""
    from types import SimpleNamespace

    from suslov.simulator.engine import _report

    scene = SimpleNamespace(name="s", description="", path=Path("s.toml"))
    plan = SimpleNamespace(scene=scene, explain=lambda: "plan")
    run = SimpleNamespace(plan=plan, executed=[{"step": "angle", "method": "closed form, |p| < 1e3", "seconds": 0.1}],
                          results={})
    rows = [line for line in _report(run, []).splitlines() if line.startswith("| angle")]
    cells = [c for c in __import__("re").split(r"(?<!\\)\|", rows[0])[1:-1]]
    assert len(cells) == 3 and cells[1].strip() == r"closed form, \|p\| < 1e3"


def test_sleigh_scene_refuses_a_suslov_figure_by_name(tmp_path):
    """A sleigh with figures = ["omega_plane"] ended in KeyError: 'omega_paper' (issue 38): now a SceneError."""
    text = (ROOT / "scenes" / "fig3_sleigh.toml").read_text().replace('figures = ["sleigh_path"]',
                                                                        'figures = ["omega_plane"]')
    with pytest.raises(SceneError, match="effects.figures.*omega_plane.*sleigh_path"):
        load_scene(write(tmp_path, text))


def test_orientation_of_a_general_body_draws_its_basis_sphere(tmp_path):
    """A general tensor with figures = ["basis_sphere"] ended in KeyError: 't' (issue 38): the integrated
    orientation now carries its times; the rows stay a rotation."""
    text = ('name = "b"\n[body]\ninertia = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]\n'
            '[motion]\ntime = [-5.0, 5.0]\nsamples = 101\n[effects]\ncompute = ["orientation"]\n'
            'figures = ["basis_sphere"]\nfigures_format = ["png"]\n')
    out = tmp_path / "out"
    assert main(["simulate", str(write(tmp_path, text)), "--out", str(out)]) == 0
    assert (out / "basis_sphere.png").is_file()
    rows = np.loadtxt(out / "orientation.csv", delimiter=",", skiprows=1)[:, 1:].reshape(-1, 3, 3)
    assert np.allclose(np.einsum("nij,nkj->nik", rows, rows), np.eye(3), atol=1e-9)


def test_omega_at_one_instant_is_the_public_omega_bit_for_bit():
    """The integrators' per-step ``Body.omega_at`` (the emitted kernel called directly) against ``Body.omega`` (the
    public, validated function): the same float64 values, special and general bodies, near 0 and where tanh and
    sech saturate (t = +-700), for a body with p/d = 1e305."""
    from suslov.simulator.body import make_body

    rng = np.random.default_rng(11)
    bodies = [make_body(p=3, d=0.5), make_body(p=7.3, d=2.0, energy=4.0), make_body(p=1e300, d=1e-5)]
    for _ in range(8):
        a = rng.normal(size=(3, 3))
        bodies.append(make_body(tensor=(a @ a.T + np.eye(3)) * 10.0 ** rng.integers(-4, 4), energy=1.7))
    for body in bodies:
        for t in (-700.0, -30.0, -1.0, 0.0, 0.3, 25.0, 710.0):
            assert np.array_equal(body.omega_at(t), body.omega(np.asarray(t))), (body.describe(), t)
            with np.errstate(over="ignore"):   # p/d = 1e305: an energy beyond float64 is inf on both routes
                w = body.omega_scene(np.asarray(t))   # the energy through the public route, as it was computed before
                assert body.energy(t) == float(0.5 * w @ body.tensor @ w), (body.describe(), t)
