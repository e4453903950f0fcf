"""Scene figures (issue 14, item 4): titles from the scene, every artist in a legend, windows that reach the
limits, vector output beside PNG, byte-identical files across runs; the enclosure effect (issue 16).

Each scene is computed once per test session (``run_scene`` is cached): the tests check what the figures
draw, not the integrators, and the general body's integration is the slow part.
"""
import functools
import json
import re
from pathlib import Path

import numpy as np
import pytest

from suslov.simulator import engine, figures
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import SceneError, load_scene

SCENES = [p for p in sorted(Path(__file__).resolve().parent.parent.joinpath("scenes").glob("*.toml"))
          if not load_scene(p).is_sweep]   # sweep figures: tests/test_sweep.py
SCENE = {p.stem: p for p in SCENES}


@functools.cache
def run_scene(path):
    return engine.execute(make_plan(load_scene(path)))


def vector_files(directory):
    return {p.name: p.read_bytes() for p in directory.iterdir() if p.suffix in (".png", ".pdf", ".svg")}


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_png_and_pdf_byte_identical_across_runs(path, tmp_path):
    run = run_scene(path)
    assert run.plan.scene.figures_format == ("png", "pdf")
    engine.write_outputs(run, tmp_path / "a")
    engine.write_outputs(run, tmp_path / "b")
    first, second = vector_files(tmp_path / "a"), vector_files(tmp_path / "b")
    assert set(first) == {f"{f}.{x}" for f in run.plan.scene.figures for x in ("png", "pdf")}
    assert first == second
    for figure in run.plan.scene.figures:
        assert first[f"{figure}.png"][:8] == b"\x89PNG\r\n\x1a\n"
        assert first[f"{figure}.pdf"][:5] == b"%PDF-"
        assert b"CreationDate" not in first[f"{figure}.pdf"] and b"Producer" not in first[f"{figure}.pdf"]


def test_a_fresh_computation_gives_the_same_bytes(tmp_path):
    """Not only the drawing: a second execution of the scene (new integration) writes the same files."""
    path = SCENE["fig3_sleigh"]
    engine.write_outputs(run_scene(path), tmp_path / "a")
    engine.write_outputs(engine.execute(make_plan(load_scene(path))), tmp_path / "b")
    assert vector_files(tmp_path / "a") == vector_files(tmp_path / "b")


def test_svg_is_byte_identical_too(tmp_path):
    """SVG element ids are salted with a random uuid by default; the figures fix the salt."""
    run = run_scene(SCENE["fig4_basis_p1"])
    for sub in ("a", "b"):
        (tmp_path / sub).mkdir()
        assert figures.draw("basis_sphere", run, tmp_path / sub, ("svg",)) == ["basis_sphere.svg"]
    assert (tmp_path / "a" / "basis_sphere.svg").read_bytes() == (tmp_path / "b" / "basis_sphere.svg").read_bytes()


def legend_problems(fig):
    """Artists of ``fig`` that a reader cannot identify from a legend (an empty list when all are)."""
    problems = []
    for ax in fig.axes:
        artists = ax.lines + ax.collections
        if not artists:
            continue
        if ax.get_legend() is None:
            problems.append(f"axes {ax.get_title()!r} draws {len(artists)} artists and has no legend")
            continue
        handles, labels = ax.get_legend_handles_labels()
        colours = {str(h.get_color()) for h in handles if hasattr(h, "get_color")}
        for artist in artists:
            label = artist.get_label()
            if label and not label.startswith("_"):
                if label not in labels:
                    problems.append(f"{label!r} is not in the legend")
            # an unlabelled line may only repeat a legend entry (same colour): the blade at other instants,
            # the mirror branch of the energy level; an unlabelled collection (wireframe, arrows) never
            elif not hasattr(artist, "get_color") or str(artist.get_color()) not in colours:
                problems.append(f"unlabelled {type(artist).__name__} in axes {ax.get_title()!r}")
    return problems


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_titles_from_the_scene_mathtext_and_every_artist_in_a_legend(path):
    run = run_scene(path)
    for name in run.plan.scene.figures:
        fig = figures.figure(name, run)
        try:
            texts = [ax.get_title() for ax in fig.axes] + [fig._suptitle.get_text() if fig._suptitle else ""]
            assert run.plan.scene.title and any(run.plan.scene.title in t for t in texts), texts
            labels = [t.get_text() for ax in fig.axes if ax.get_legend() for t in ax.get_legend().get_texts()]
            for text in texts + labels:   # mathtext, not ASCII stand-ins (outside the $...$ segments)
                plain = re.sub(r"\$[^$]*\$", "", text)
                assert not any(ascii in plain for ascii in ("^", "oo", "deg", "->", "omega", "gamma", "psi")), text
            assert legend_problems(fig) == []
        finally:
            figures.plt.close(fig)


def test_titles_are_not_hard_coded(tmp_path):
    """The same figure function under another scene title shows that title and no figure number."""
    scene = tmp_path / "mine.toml"
    scene.write_text('title = "My own $\\\\gamma$ plot"\n[body]\np = 2.5\nd = 0.7\n[motion]\ntime = [-2.0, 2.0]\n'
                     'samples = 201\ninitial = "ss"\n[effects]\ncompute = ["scattering_angle"]\n'
                     'figures = ["gamma_components", "gamma_sphere"]\n')
    run = engine.execute(make_plan(load_scene(scene)))
    for name in ("gamma_components", "gamma_sphere"):
        fig = figures.figure(name, run)
        try:
            title = fig.axes[0].get_title()
            assert title.startswith(r"My own $\gamma$ plot") and "Fig." not in title and " ss" not in title
        finally:
            figures.plt.close(fig)
    scene.write_text(scene.read_text().replace('title = "My own $\\\\gamma$ plot"\n', ""))
    fig = figures.figure("gamma_sphere", engine.execute(make_plan(load_scene(scene))))
    try:
        assert fig.axes[0].get_title().startswith("mine")   # no title: the scene's name (its file name)
    finally:
        figures.plt.close(fig)


def test_fig1_arc_reaches_both_equilibria():
    """The window is long enough: omega(t0), omega(t1) are the two equilibria, computed here from the tensor.

    Equilibria of the Suslov problem with a = e3: omega3 = 0 and (I omega)_3 = I13 w1 + I23 w2 = 0, on the
    energy level (1/2) <I omega, omega> = E; tolerance 1e-3 of |omega| is below one pixel of the figure.
    """
    scene = load_scene(SCENE["fig1_omega"])
    run = run_scene(SCENE["fig1_omega"])
    tensor = np.asarray(scene.body["inertia"], dtype=float)
    n = np.array([tensor[1, 2], -tensor[0, 2], 0.0])
    n /= np.linalg.norm(n)
    equilibrium = np.sqrt(2 * scene.energy / (n @ tensor @ n)) * n
    w = run.data["omega"]
    scale = np.linalg.norm(equilibrium)
    ends = sorted([w[0], w[-1]], key=lambda x: x @ equilibrium)
    assert np.linalg.norm(ends[0] + equilibrium) < 1e-3 * scale
    assert np.linalg.norm(ends[1] - equilibrium) < 1e-3 * scale
    assert w[0] @ w[-1] < 0   # from one equilibrium to the other, not back


def test_general_angle_window_lets_the_axis_component_settle():
    run = run_scene(SCENE["general_angle"])
    body = run.plan.body
    along = run.data["gamma"] @ body.to_scene(body.limit_axis())
    angle = run.results["scattering_angle"]["radians"]
    assert abs(along[0] + 1) < 1e-6 and abs(along[-1] + np.cos(angle)) < 1e-5


def test_sleigh_draws_the_blade_and_direction_in_a_square_equal_aspect_frame():
    run = run_scene(SCENE["fig3_sleigh"])
    fig = figures.figure("sleigh_path", run)
    try:
        ax = fig.axes[0]
        assert ax.get_aspect() == 1.0
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        assert abs((x1 - x0) - (y1 - y0)) < 1e-9 * (y1 - y0)   # square, not a narrow strip
        s = run.data["sleigh"]
        assert x0 < s["x"].min() and s["x"].max() < x1 and y0 < s["y"].min() and s["y"].max() < y1
        blades = [line for line in ax.lines if str(line.get_color()) == "C3"]
        assert len(blades) >= 5
        _, labels = ax.get_legend_handles_labels()
        assert "direction of motion" in labels
        arrows = next(c for c in ax.collections if c.get_label() == "direction of motion")
        # each arrow points along the velocity of the contact point (sign of v times the heading)
        i = [int(np.argmin(np.hypot(s["x"] - px, s["y"] - py))) for px, py in arrows.get_offsets()]
        velocity = np.stack([s["v"][i] * np.cos(s["theta"][i]), s["v"][i] * np.sin(s["theta"][i])], axis=-1)
        assert np.all(np.einsum("ij,ij->i", velocity, np.stack([arrows.U, arrows.V], axis=-1)) > 0)
    finally:
        figures.plt.close(fig)


def test_enclosure_effect_contains_the_float_angle_within_its_estimate():
    run = run_scene(SCENE["general_angle"])
    ball = run.results["scattering_angle_enclosure"]
    float_angle = run.results["scattering_angle"]
    assert ball["radius"] < 1e-18
    # the DOP853 estimate is an estimate: allow a factor 10 (the ball is the reference)
    assert abs(float_angle["radians"] - ball["midpoint"]) <= 10 * float_angle["error_estimate"] + ball["radius"]
    json.dumps(ball)


@pytest.mark.parametrize("value,message", [('["png", "jpeg"]', "unknown format 'jpeg'"), ('[]', "non-empty list"),
                                           ('"pdf"', "non-empty list"), ('[1]', "non-empty list")])
def test_bad_figures_format_names_the_field(tmp_path, value, message):
    scene = tmp_path / "bad.toml"
    scene.write_text(f'[body]\np = 1\nd = 0.5\n[motion]\ntime = [-1.0, 1.0]\n[effects]\nfigures = ["omega_plane"]\n'
                     f'figures_format = {value}\n')
    with pytest.raises(SceneError, match="effects.figures_format") as error:
        load_scene(scene)
    assert message in str(error.value) and str(scene) in str(error.value)
