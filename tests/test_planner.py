"""The planner as a declarative effect graph (issue 15): minimal subgraph, needs first, explained."""
import pytest

from suslov.simulator import planner
from suslov.simulator.engine import STEPS, execute
from suslov.simulator.planner import ORDER, PROVIDERS, make_plan
from suslov.simulator.scene import load_scene


def scene(tmp_path, body, compute, extra=""):
    path = tmp_path / "s.toml"
    path.write_text(f"[body]\n{body}\n[motion]\ntime = [-3.0, 3.0]\nsamples = 7\n"
                    f"[effects]\ncompute = {compute}\n{extra}")
    return load_scene(path)


def test_every_provider_is_a_step_and_its_needs_come_first():
    for provider in PROVIDERS:
        assert provider.step in STEPS, provider.step
        assert provider.effect in ORDER
        for need in provider.needs:
            assert ORDER.index(need) < ORDER.index(provider.effect), (provider.step, need)


def test_needs_are_pulled_in_with_their_reason(tmp_path):
    plan = make_plan(scene(tmp_path, "p = 2.5\nd = 0.7", '["integral_drift"]'))
    assert plan.names() == ["omega", "gamma_gauss", "integrals"]
    reasons = {s.name: s.reason for s in plan.steps}
    assert reasons["omega"] == reasons["gamma_gauss"] == "needed by integral_drift"
    assert reasons["integrals"] == "integral_drift requested"
    run = execute(plan)
    assert run.results["integral_drift"]["F2"]["max_abs_drift"] < 1e-10


def test_sleigh_contact_point_needs_the_velocities(tmp_path):
    sleigh = 'kind = "sleigh"\nmass = 1.0\ninertia = 0.2\noffset = 0.5'
    plan = make_plan(scene(tmp_path, sleigh, '["contact_point"]'))
    assert plan.names() == ["sleigh_velocities", "sleigh_path"]
    run = execute(plan)
    assert run.data["sleigh"]["x"].shape == (7,)


@pytest.mark.parametrize("body, chosen, refused", [
    ("p = 3\nd = 0.5", "gamma_closed_form", None),
    ("p = 2.5\nd = 0.7", "gamma_gauss", "gamma_closed_form"),
    ("inertia = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]", "gamma_gauss", "gamma_closed_form"),
])
def test_explain_shows_the_graph_and_the_providers_not_chosen(tmp_path, body, chosen, refused):
    text = make_plan(scene(tmp_path, body, '["gamma"]')).explain()
    assert f"gamma <- {chosen} [" in text
    if refused:
        assert f"not {refused} [I13 = 0 and p an odd integer with a certified basis]: does not apply" in text
    else:
        assert "not gamma_" not in text


@pytest.mark.parametrize("body, chosen", [
    ("p = 2.5\nd = 0.7", "angle_closed_form"),
    ("inertia = [[2.0, 0.1, 0.2], [0.1, 1.0, -0.3], [0.2, -0.3, 1.5]]", "angle_general_closed_form"),
])
def test_the_angle_is_a_closed_form_and_the_integration_is_asked_for_by_name(tmp_path, body, chosen):
    plan = make_plan(scene(tmp_path, body, '["scattering_angle"]'))
    assert plan.names() == [chosen]
    both = make_plan(scene(tmp_path, body, '["scattering_angle", "scattering_angle_integrated"]'))
    assert both.names() == [chosen, "angle_integrate"]
    assert "heyoka Taylor" in both.steps[1].method and "scattering_angle_integrated requested" == both.steps[1].reason


def test_scipy_method_is_planned_and_named(tmp_path):
    integrate = '[numerics]\ngamma_route = "integrate"\n'
    plan = make_plan(scene(tmp_path, "p = 2.5\nd = 0.7", '["gamma"]', integrate + 'method = "DOP853"\n'))
    assert plan.scene.method == "scipy:DOP853"
    assert "SciPy DOP853" in plan.steps[0].method
    taylor_plan = make_plan(scene(tmp_path, "p = 2.5\nd = 0.7", '["gamma"]', integrate))
    assert "heyoka Taylor" in taylor_plan.steps[0].method
    gauss_plan = make_plan(scene(tmp_path, "p = 2.5\nd = 0.7", '["gamma"]', '[numerics]\nmethod = "DOP853"\n'))
    assert gauss_plan.names() == ["gamma_gauss"] and "gauss_2f1" in gauss_plan.steps[0].method


def test_unknown_effect_for_a_body_has_no_provider(tmp_path):
    sleigh = planner.build_body(scene(tmp_path, 'kind = "sleigh"\nmass = 1.0\ninertia = 0.2\noffset = 0.5',
                                      '["omega"]'))
    with pytest.raises(ValueError, match="no provider"):
        planner.choose("gamma", None, sleigh)
