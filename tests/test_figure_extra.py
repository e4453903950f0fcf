"""Figures on a core install (issue 47): ``Result.plot()`` / ``save()`` name the extra to install.

A core install has no matplotlib; ``result.plot()`` used to end in a bare ``ModuleNotFoundError: No module
named 'matplotlib'`` from inside the figure module.  Simulated here by ``sys.modules["matplotlib"] = None``
(what ``import`` and ``importlib.util.find_spec`` then see as "not installed"): every route that draws a
figure raises an ``ImportError`` naming the [sim] extra and its install command before any work, nothing
is written, and what needs no figure still works.
"""
import sys

import pytest

import suslov
from suslov import extras

HINT = "pip install 'suslov-certified[sim]'"
BODY = {"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 7},
        "effects": {"compute": ["omega", "scattering_angle"], "figures": ["omega_plane"]}}
PLAIN = {"body": {"p": 2.5, "d": 0.7}, "motion": {"time": [-3, 3], "samples": 7},
         "effects": {"compute": ["omega", "scattering_angle"]}}
SWEEP = {"sweep": {"I11": 1.25, "I22": 1.0, "I33": 1.5, "I13": [0.0, 0.3], "I23": [-0.5, 0.5]},
         "effects": {"compute": ["scattering_angle"], "figures": ["map"]}}


@pytest.fixture
def no_matplotlib(monkeypatch):
    """matplotlib "not installed", and the figure modules not yet imported (so nothing cached hides it)."""
    for name in [n for n in sys.modules if n == "matplotlib" or n.startswith("matplotlib.")]:
        monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.delitem(sys.modules, "suslov.simulator.figures", raising=False)


def assert_names_the_extra(error):
    text = str(error.value)
    assert isinstance(error.value, ImportError)
    assert HINT in text and "[sim] extra" in text and "matplotlib not installed" in text, text


def test_plot_names_the_extra(no_matplotlib):
    result = suslov.simulate(BODY)   # the closed forms need no matplotlib
    with pytest.raises(ImportError) as error:
        result.plot()
    assert_names_the_extra(error)
    assert "Result.plot()" in str(error.value)


def test_save_names_the_extra_and_writes_nothing(no_matplotlib, tmp_path):
    result = suslov.simulate(BODY)
    with pytest.raises(ImportError) as error:
        result.save(tmp_path / "out")
    assert_names_the_extra(error)
    assert "Result.save()" in str(error.value) and not (tmp_path / "out").exists()


def test_simulate_with_out_names_the_extra_before_any_work(no_matplotlib, tmp_path):
    with pytest.raises(ImportError) as error:
        suslov.simulate(BODY, out=tmp_path / "out")
    assert_names_the_extra(error)
    assert not (tmp_path / "out").exists()


def test_sweep_plot_and_save_name_the_extra(no_matplotlib, tmp_path):
    result = suslov.simulate(SWEEP, workers=1)
    for call in (lambda: result.plot("map"), lambda: result.save(tmp_path / "out")):
        with pytest.raises(ImportError) as error:
            call()
        assert_names_the_extra(error)
    assert not (tmp_path / "out").exists()


def test_a_scene_without_figures_saves_without_matplotlib(no_matplotlib, tmp_path):
    files = suslov.simulate(PLAIN).save(tmp_path / "out")
    assert "results.json" in files and not [f for f in files if f.endswith((".png", ".pdf", ".svg"))]
    assert sys.modules["matplotlib"] is None   # nothing imported it behind the test's back


def test_require_checks_only_the_libraries_asked_for(monkeypatch):
    """A figure needs matplotlib of [sim], not heyoka: a partial install is refused only for what it lacks."""
    monkeypatch.setitem(sys.modules, "heyoka", None)
    if not extras.missing("sim", extras.FIGURES):   # matplotlib here: heyoka's absence does not stop a figure
        extras.require("sim", "a figure", extras.FIGURES)
    with pytest.raises(ModuleNotFoundError, match=r"needs the \[sim\] extra \(heyoka not installed\)") as error:
        extras.require("sim", "Taylor integration", ("heyoka",))
    assert error.value.name == "heyoka"
    assert "heyoka" in extras.missing("sim")
