"""Sweep scenes (issue 15): points, per-point methods, one table, executors, resume, bad input.

Expected values come from independent routes: the certified closed form of Theorem 5.4 for
I13 = 0 and the validated ball integration (python-flint, 30 digits) for general bodies.
"""
import csv
import json
import socket
import threading
from pathlib import Path

import numpy as np
import pytest

import generated.suslov_formulas as gf
from suslov import executor
from suslov.simulator import sweep
from suslov.cli import main
from suslov.simulator.scene import SceneError, load_scene
from suslov.validated import scattering_angle_enclosure

GRID = """
name = "grid"
[sweep]
I11 = 2.0
I22 = 1.0
I33 = 1.5
I13 = {linear = [-0.3, 0.3], count = 3}
I23 = {linear = [-0.5, 0.5], count = 3}
energy = [0.5, 3.0]
chunk = 4
[effects]
compute = ["scattering_angle"]
figures = ["map"]
"""


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def read_csv(path):
    with path.open(newline="") as handle:
        rows = list(csv.reader(handle))
    return rows[0], [dict(zip(rows[0], row)) for row in rows[1:]]


def test_grid_points_methods_and_table(tmp_path):
    out = tmp_path / "out"
    assert main(["simulate", str(write(tmp_path, GRID)), "--out", str(out), "--quiet", "--workers", "1"]) == 0
    header, rows = read_csv(out / "results.csv")
    assert header[:7] == ["I11", "I22", "I33", "I12", "I13", "I23", "energy"]
    assert header[-1] == "error" and "scattering_angle_error" in header and "energy_spread" in header
    assert len(rows) == 18
    for row in rows:
        i13, i23 = float(row["I13"]), float(row["I23"])
        if i13 == 0 and i23 == 0:   # the constraint axis is principal: refused on its row, not the sweep
            assert row["error"].startswith("refused") and row["scattering_angle"] == ""
            continue
        assert row["error"] == ""
        angle = float(row["scattering_angle"])
        if i13 == 0:
            assert row["scattering_angle_method"] == "closed form (Theorem 5.4)"
        else:
            assert row["scattering_angle_method"].startswith("closed form of every body")
            assert float(row["scattering_angle_error"]) < 1e-12
        assert float(row["energy_spread"]) == 0.0   # the closed forms never see the energy (two per body)
        assert 0 < angle <= np.pi
    assert (out / "map.png").read_bytes()[:4] == b"\x89PNG"
    parquet = pytest.importorskip("pyarrow.parquet").read_table(out / "results.parquet").to_pydict()
    assert list(parquet) == header and parquet["I13"] == [float(r["I13"]) for r in rows]
    summary = json.loads((out / "results.json").read_text())["summary"]
    assert summary["points"] == 18 and summary["refused_or_failed"] == 2
    assert not sweep.chunk_dir(out).exists()


def test_sweep_angles_match_independent_enclosures():
    """Three seeded general bodies: the sweep's float angle (the closed form of every body) against a 30-digit
    rigorous ball of the validated integration, an independent route."""
    rng = np.random.default_rng(15)
    options = {"effects": ["scattering_angle"], "method": "taylor", "kind": "tensor",
               "columns": ["I11", "I22", "I33", "I12", "I13", "I23", "energy"]}
    rows = [[2.0, 1.0, 1.5, 0.0, float(rng.uniform(-0.5, 0.5)), float(rng.uniform(-0.5, 0.5)), 1.0]
            for _ in range(3)]
    for row, result in zip(rows, sweep.evaluate_chunk((options, rows))):
        body = sweep.point_body(dict(zip(options["columns"], row)), "tensor")
        ball = scattering_angle_enclosure(*body.entries, dps=30, method="integration").angle
        assert float(ball.rad()) < 1e-28
        assert abs(result["scattering_angle"] - float(ball.mid())) < 1e-12


def test_pd_sweep_uses_the_closed_form_everywhere(tmp_path):
    text = """
[sweep]
p = {log = [0.5, 8.0], count = 4}
d = {random = [0.1, 2.0], count = 3, seed = 4}
[effects]
compute = ["scattering_angle"]
figures = ["histogram"]
"""
    scene = load_scene(write(tmp_path, text))
    table, plan, _, _ = sweep.run_sweep(scene, tmp_path / "out", workers=1)
    assert list(plan.classes) == [("angle_closed_form",)]
    expected = gf.scattering_angle(np.array(table["p"]), np.array(table["d"]))
    assert np.array_equal(np.array(table["scattering_angle"]), expected)
    assert (tmp_path / "out" / "histogram.png").exists()


def test_results_identical_across_executors(tmp_path):
    """One process, two local processes and a Dask LocalCluster on loopback: byte-identical tables (the
    angle and the certified Galois verdict, issue 23)."""
    distributed = pytest.importorskip("distributed")
    scene = write(tmp_path, GRID.replace('figures = ["map"]', "").replace('compute = ["scattering_angle"]',
                                                                          'compute = ["scattering_angle", "galois_group"]'))
    assert main(["simulate", str(scene), "--out", str(tmp_path / "one"), "--quiet", "--workers", "1"]) == 0
    assert main(["simulate", str(scene), "--out", str(tmp_path / "two"), "--quiet", "--workers", "2"]) == 0
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        assert main(["simulate", str(scene), "--out", str(tmp_path / "dask"), "--quiet",
                     "--scheduler", cluster.scheduler_address]) == 0
    one = (tmp_path / "one" / "results.csv").read_bytes()
    assert one == (tmp_path / "two" / "results.csv").read_bytes() == (tmp_path / "dask" / "results.csv").read_bytes()


def test_unreachable_scheduler_fails_fast_and_writes_nothing(tmp_path, capsys):
    pytest.importorskip("distributed")
    out = tmp_path / "out"
    status = main(["simulate", str(write(tmp_path, GRID)), "--out", str(out), "--quiet",
                   "--scheduler", "tcp://127.0.0.1:9"])
    assert status == 2
    assert "cannot reach a Dask scheduler" in capsys.readouterr().err
    assert not out.exists()


def test_a_port_that_is_not_a_scheduler_fails_fast(tmp_path, capsys):
    """A service that accepts connections but answers HTTP (as a proxy does): a clear error, quickly."""
    pytest.importorskip("distributed")
    server = socket.create_server(("127.0.0.1", 0))
    port = server.getsockname()[1]

    def answer():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            conn.recv(64)
            conn.sendall(b"HTTP/1.1 400 Bad Request\r\ncontent-length: 0\r\n\r\n")
            conn.close()

    threading.Thread(target=answer, daemon=True).start()
    status = main(["simulate", str(write(tmp_path, GRID)), "--out", str(tmp_path / "out"), "--quiet",
                   "--scheduler", f"tcp://127.0.0.1:{port}"])
    server.close()
    assert status == 2
    assert "does not answer as a Dask scheduler" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_interrupted_sweep_resumes_from_finished_chunks(tmp_path, monkeypatch):
    scene = load_scene(write(tmp_path, GRID))
    out = tmp_path / "out"
    calls = []
    original = sweep.evaluate_chunk

    def interrupted(task):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(1)
        return original(task)

    monkeypatch.setattr(sweep, "evaluate_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        sweep.run_sweep(scene, out, workers=1)
    assert not out.exists() and len(list(sweep.chunk_dir(out).glob("*.json"))) == 2
    # a corrupted chunk is detected by its checksum and recomputed, never trusted
    first = sorted(sweep.chunk_dir(out).glob("*.json"))[0]
    first.write_text(first.read_text()[:-20])
    monkeypatch.setattr(sweep, "evaluate_chunk", original)
    table, plan, _, computed = sweep.run_sweep(scene, out, workers=1)
    assert plan.chunks == 5 and computed == 4
    fresh, _, _, _ = sweep.run_sweep(scene, tmp_path / "fresh", workers=1)
    assert json.dumps(table) == json.dumps(fresh)


def test_chunk_store_rejects_foreign_entries(tmp_path):
    store = executor.ChunkStore(tmp_path)
    store.put("abc", [{"x": 1.0}])
    assert store.get("abc") == [{"x": 1.0}]
    (tmp_path / "abc.json").rename(tmp_path / "def.json")     # right checksum, wrong key
    assert store.get("def") is None and store.get("missing") is None


def test_csv_bodies_refuse_bad_rows_not_the_sweep(tmp_path):
    (tmp_path / "bodies.csv").write_text("I11,I22,I33,I12,I13,I23,energy\n2,1,1.5,0,0.2,-0.3,1\n"
                                         "1,1,1,0,2,0,1\n2,1,1.5,0.1,0,-0.4,3\n")
    text = '[sweep]\nbodies = "bodies.csv"\n[effects]\ncompute = ["scattering_angle"]\n'
    table, _, _, _ = sweep.run_sweep(load_scene(write(tmp_path, text)), tmp_path / "out", workers=1)
    assert table["error"][0] == "" and table["error"][2] == ""
    assert table["error"][1].startswith("refused") and "positive definite" in table["error"][1]


@pytest.mark.parametrize("csv_text, where", [
    ("I11,I22,I33,I12,I13\n2,1,1.5,0,0.2\n", "missing column 'I23'"),
    ("I11,I22,I33,I12,I13,I23\n2,1,1.5,0,0.2,-0.3\n2,1,x,0,0.2,-0.3\n", "row 2, column I33"),
    ("I11,I22,I33,I12,I13,I23\n2,1,1.5,0,nan,-0.3\n", "row 1, column I13"),
    ("I11,I22,I33,I12,I13,I23\n", "no data rows"),
    ("I11,I22,I33,I12,I13,I23,I13\n2,1,1.5,0,0.2,-0.3,0.5\n", "column 'I13' appears 2 times"),
    ("I11,I22,I33,I12,I13,I23,mass\n2,1,1.5,0,0.2,-0.3,1\n", "unknown column 'mass'"),
])
def test_malformed_csv_is_rejected_naming_row_or_column(tmp_path, csv_text, where):
    (tmp_path / "bodies.csv").write_text(csv_text)
    path = write(tmp_path, '[sweep]\nbodies = "bodies.csv"\n[effects]\ncompute = ["scattering_angle"]\n')
    with pytest.raises(SceneError, match=where) as info:
        load_scene(path)
    assert "bodies.csv" in str(info.value)


@pytest.mark.parametrize("sweep_text, field, reason", [
    ("p = {linear = [1, 2], count = 0}\nd = 0.5", "sweep.p", "0 points"),
    ("p = {linear = [1, 2], count = -3}\nd = 0.5", "sweep.p.count", "cannot be negative"),
    ("p = {linear = [1, 2], count = 10000}\nd = {linear = [0.1, 1], count = 10000}", "sweep", "more than 10000000"),
    ("p = {log = [0, 2], count = 3}\nd = 0.5", "sweep.p.log", "both ends > 0"),
    ("p = 1.0", "sweep.d", "missing"),
    ("p = 1.0\nd = 0.5\nI11 = 2.0", "sweep", "exactly one of"),
    ("p = 1.0\nd = 0.5\nenergy = [1.0, -2.0]", "sweep.energy", "must be > 0"),
    ("p = {linear = [1, 2]}\nd = 0.5", "sweep.p.count", "must be an integer"),
])
def test_bad_sweep_is_rejected_and_nothing_written(tmp_path, capsys, sweep_text, field, reason):
    path = write(tmp_path, f"[sweep]\n{sweep_text}\n[effects]\ncompute = [\"scattering_angle\"]\n")
    out = tmp_path / "out"
    assert main(["simulate", str(path), "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert f": {field}: " in err and reason in err
    assert not out.exists()


def test_sweep_refuses_per_body_effects(tmp_path):
    path = write(tmp_path, '[sweep]\np = 1.0\nd = 0.5\n[effects]\ncompute = ["gamma"]\n')
    with pytest.raises(SceneError, match="not a scalar effect"):
        load_scene(path)


def test_explain_prints_the_plan_without_computing(tmp_path, monkeypatch, capsys):
    def boom(*args):
        raise AssertionError("--explain must not compute")
    monkeypatch.setattr(sweep, "evaluate_chunk", boom)
    assert main(["simulate", str(write(tmp_path, GRID)), "--explain", "--workers", "2"]) == 0
    text = capsys.readouterr().out
    assert "18 points" in text and "grid over I13 (3), I23 (3), energy (2)" in text
    assert "12 points: angle_general_closed_form" in text and "4 points: angle_closed_form" in text
    assert "2 points: refused" in text and "chunks of up to 4 points" in text and "estimated cost" in text


def test_enclosure_effect_in_a_sweep_contains_the_float_angle(tmp_path):
    """Both scalar effects per point: the rigorous ball (radius as its error) and the float angle
    (Theorem 5.4 on I13 = 0, the closed form of every body elsewhere) agree within the ball's radius plus the
    float bound."""
    text = ('[sweep]\nI11 = 2.0\nI22 = 1.0\nI33 = 1.5\nI13 = [0.0, 0.2]\nI23 = -0.3\n'
            '[effects]\ncompute = ["scattering_angle", "scattering_angle_enclosure"]\n')
    table, plan, _, _ = sweep.run_sweep(load_scene(write(tmp_path, text)), tmp_path / "out", workers=1)
    assert sorted(plan.classes.values()) == [1, 1]
    for i in range(2):
        radius = table["scattering_angle_enclosure_error"][i]
        assert 0 < radius < 1e-12 and table["scattering_angle_enclosure_method"][i].endswith("(rigorous)")
        gap = abs(table["scattering_angle"][i] - table["scattering_angle_enclosure"][i])
        assert gap <= radius + table["scattering_angle_error"][i]


def test_integrated_angle_column_agrees_with_the_closed_form(tmp_path):
    """scattering_angle_integrated (Taylor, every point, I13 = 0 included) beside scattering_angle (closed forms):
    own columns, agreement to 1e-10, and the energy spread is that of the integration (the closed forms' is 0)."""
    text = GRID.replace('figures = ["map"]', "").replace('compute = ["scattering_angle"]',
                                                          'compute = ["scattering_angle", "scattering_angle_integrated"]')
    scene = load_scene(write(tmp_path, text))
    table, plan, _, _ = sweep.run_sweep(scene, tmp_path / "out", workers=1)
    assert plan.classes == {("angle_general_closed_form", "angle_integrate"): 12,
                            ("angle_closed_form", "angle_integrate"): 4, ("refused",): 2}
    for name in ("scattering_angle_integrated", "scattering_angle_integrated_error", "scattering_angle_integrated_method"):
        assert name in table
    closed, integrated = np.array(table["scattering_angle"]), np.array(table["scattering_angle_integrated"])
    ok = np.isfinite(closed)
    assert ok.sum() == 16 and np.array_equal(ok, np.isfinite(integrated))
    assert np.max(np.abs(closed[ok] - integrated[ok])) < 1e-10
    assert all(m == "heyoka Taylor (ss, lam t = 40)" for m, e in zip(table["scattering_angle_integrated_method"],
                                                                     table["error"]) if not e)
    spread = np.array(table["energy_spread"])[ok]
    pairs = integrated.reshape(-1, 2)
    assert np.array_equal(spread, np.repeat(pairs.max(axis=1) - pairs.min(axis=1), 2)[ok])


def test_readme_quotes_the_general_body_study_as_it_is(tmp_path):
    """The study figures in docs/simulator.md (bodies, points, angle range, energy spread) are those of the study's own output:
    run it, compare with the committed summary (bench/results/general_body_study.json), then the page with both."""
    import json
    import re

    root = Path(__file__).resolve().parent.parent
    committed = json.loads((root / "bench" / "results" / "general_body_study.json").read_text())
    table, _, _, _ = sweep.run_sweep(load_scene(root / "scenes" / "general_body_study.toml"), tmp_path / "study")
    summary = json.loads((tmp_path / "study" / "results.json").read_text())["summary"]
    assert summary["points"] == committed["points"] and summary["refused_or_failed"] == committed["refused"]
    angles = summary["columns"]["scattering_angle"]
    assert angles["min"] == pytest.approx(committed["angle_min"], abs=1e-9)
    spread = summary["columns"]["energy_spread"]["max"]
    assert spread <= 4 * committed["energy_spread_max"]           # rounding-level, CPU-dependent in its digits
    readme = (root / "docs" / "simulator.md").read_text(encoding="utf-8")
    assert f"{committed['points']} points ({committed['bodies']} bodies at {committed['energies']} energies" in readme
    assert f"ranges from {committed['angle_min']:.2f} to pi" in readme
    quoted = float(re.search(r"largest spread ([0-9.e+-]+) rad over the (\d+) bodies", readme).group(1))
    assert quoted == pytest.approx(committed["energy_spread_max"], rel=0.05)


def test_galois_group_effect_maps_the_verdict(tmp_path):
    """The galois_group effect: one row per body, 1 (SO(3,C)) for a general body, 0 (reducible) for odd p with
    I13 = 0, the method naming the verdict; the map figure draws it (issue 23)."""
    text = ('name = "g"\n[sweep]\nI11 = 2.0\nI22 = 1.0\nI33 = 1.5\nI13 = [0.0, 0.3]\nI23 = [-0.2, 1.0]\n'
            '[effects]\ncompute = ["galois_group"]\nfigures = ["map"]\n')
    table, _, _, _ = sweep.run_sweep(load_scene(write(tmp_path, text)), tmp_path / "out", workers=1)
    rows = dict(zip(zip(table["I13"], table["I23"]), zip(table["galois_group"], table["galois_group_method"])))
    assert rows[(0.3, -0.2)][0] == 1.0 and rows[(0.3, -0.2)][1].startswith("SO(3,C)")
    assert (tmp_path / "out" / "map.png").is_file()
    from suslov.validated import monodromy
    # I13 = 0, I23 = -0.2 in the paper's frame after det I = 1 normalisation: whatever p is, the row agrees
    # with the API on the same tensor
    body = sweep.point_body({"I11": 2.0, "I22": 1.0, "I33": 1.5, "I12": 0.0, "I13": 0.0, "I23": -0.2}, "tensor")
    expected = {"SO(3,C)": 1.0, "reducible": 0.0}.get(monodromy(*body.entries, dps=20).verdict)
    got = rows[(0.0, -0.2)][0]
    assert (expected is None and got != got) or got == expected


def test_map_title_inside_the_canvas_equilibrium_undefined_and_grey_readable(tmp_path):
    """The Galois map (issue 35): every text of the figure lies inside the canvas (matplotlib bounding
    boxes), the equilibrium I13 = I23 = 0 is a hatched 'undefined' cell (not white 'unknown'), and the two
    classes differ in lightness, so the map reads in grey print."""
    import matplotlib.colors as mcolors

    from suslov.simulator.sweep_outputs import GALOIS_COLOURS, map_figure
    text = ('name = "g"\ntitle = "Differential Galois group of the Poisson equations over $(I_{13}, I_{23})$, '
            '$I_{11}=2$, $I_{22}=1$, a deliberately long title that must wrap inside the canvas"\n'
            '[sweep]\nI11 = 2.0\nI22 = 1.0\nI33 = 1.5\nI13 = [-0.3, 0.0, 0.3]\nI23 = [-0.2, 0.0, 0.4]\n'
            '[effects]\ncompute = ["galois_group"]\nfigures = ["map"]\n')
    scene = load_scene(write(tmp_path, text))
    table, _, _, _ = sweep.run_sweep(scene, tmp_path / "out", workers=1)
    assert [e for e in table["error"] if e] and (tmp_path / "out" / "map.png").is_file()
    fig = map_figure(scene, table)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    canvas = fig.bbox
    texts = [fig._suptitle] + [t for ax in fig.axes for t in (ax.title, ax.xaxis.label, ax.yaxis.label)]
    for artist in texts:
        box = artist.get_window_extent(renderer)
        assert box.x0 >= canvas.x0 - 0.5 and box.x1 <= canvas.x1 + 0.5, artist.get_text()
        assert box.y0 >= canvas.y0 - 0.5 and box.y1 <= canvas.y1 + 0.5, artist.get_text()
    ax = fig.axes[0]
    hatched = [patch for patch in ax.patches if patch.get_hatch()]
    assert len(hatched) == 1                                               # the equilibrium, and only it
    cell = hatched[0]
    assert cell.get_x() < 0 < cell.get_x() + cell.get_width() and cell.get_y() < 0 < cell.get_y() + cell.get_height()
    assert "undefined" in ax.get_legend().get_texts()[0].get_text()

    def grey(colour):
        r, g, b = mcolors.to_rgb(colour)
        return 0.2126 * r + 0.7152 * g + 0.0722 * b
    assert abs(grey(GALOIS_COLOURS[0]) - grey(GALOIS_COLOURS[1])) > 0.4
    import matplotlib.pyplot as plt
    plt.close(fig)
