"""Nothing lost (issue 44): a rebuild never deletes what the program did not write, and output paths are
checked before any work.

A user's file or directory inside a previous build output (``build_formulas.py --out prev``) or
simulator output (``suslov simulate SCENE --out prev``) used to vanish in the atomic swap.  Now the
run refuses before any work (exit 2, naming them, the tree unchanged byte for byte), and again just
before the swap when one appears while the run works; a previous output holding only what the program
wrote (plus the TeX by-products the build keeps, and Python's ``__pycache__``) is replaced as before.
``--out /proc/x``, ``--pdf`` naming a file and ``~nosuchuser/x`` are refused in one line before any
derivation ran (no progress line ``[1/`` on stderr).  Builds here are ``--only special_case --pmax 3``.
"""
import os
import pwd
import subprocess
import sys
from pathlib import Path

import pytest

from derivations.core.options import BuildOptions
from derivations.output import pipeline
from derivations.output.pipeline import derive, write_atomically
from suslov import outdir
from suslov.outdir import OutputRefused

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "fig1_omega.toml"
SMALL = ("--only", "special_case", "--pmax", "3")
NO_USER = "nosuchuser"


def build(*args, quiet=True):
    return subprocess.run([sys.executable, str(ROOT / "build_formulas.py"), *(("--quiet",) if quiet else ()),
                           *map(str, args)], cwd=ROOT, capture_output=True, text=True)


def simulate(*args):
    return subprocess.run([sys.executable, "-m", "suslov", "simulate", str(SCENE), *map(str, args)], cwd=ROOT,
                          capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(ROOT)))


def tree(root: Path) -> dict:
    """Every entry under ``root`` (and the root's siblings, so leftover staging shows): bytes of files, "dir"."""
    entries = {str(p.relative_to(root.parent)): "dir" if p.is_dir() else p.read_bytes()
               for p in sorted(root.rglob("*"))}
    entries["siblings"] = sorted(p.name for p in root.parent.iterdir())
    return entries


def add_users_things(out: Path) -> None:
    (out / "my_notes.txt").write_text("three weeks of notes")
    (out / "figures").mkdir()
    (out / "figures" / "sketch.png").write_bytes(b"\x89PNG mine")


def refused_naming_them(done) -> None:
    assert done.returncode == 2, done.stderr
    assert "my_notes.txt" in done.stderr and "figures/" in done.stderr and "refusing" in done.stderr
    assert "Traceback" not in done.stderr and len(done.stderr.strip().splitlines()) == 1, done.stderr


@pytest.fixture(scope="module")
def small_build():
    return derive(BuildOptions(pmax=3), ["special_case"])


def test_users_file_and_directory_in_a_previous_build_survive_a_rebuild(tmp_path):
    prev = tmp_path / "prev"
    assert build("--out", prev, *SMALL).returncode == 0
    add_users_things(prev)
    before = tree(prev)
    done = build("--out", prev, *SMALL, quiet=False)
    refused_naming_them(done)
    assert "[1/" not in done.stderr   # refused before any derivation ran
    assert tree(prev) == before


def test_users_file_and_directory_in_a_previous_simulator_output_survive(tmp_path):
    prev = tmp_path / "prev"
    assert simulate("--out", prev, "--quiet").returncode == 0
    add_users_things(prev)
    before = tree(prev)
    refused_naming_them(simulate("--out", prev))
    assert tree(prev) == before
    import suslov
    with pytest.raises(OutputRefused, match="my_notes.txt"):   # the Python route too
        suslov.simulate(str(SCENE), out=prev)
    assert tree(prev) == before


def test_a_clean_previous_output_is_replaced_as_before(tmp_path):
    prev = tmp_path / "prev"
    assert build("--out", prev, *SMALL).returncode == 0
    fresh = (prev / "certificates.tex").read_bytes()
    (prev / "certificates.tex").write_text("edited by hand: the build's file, replaced")
    for name in ("suslov_formulas.pdf", "suslov_formulas.aux", "certificates.log"):   # compiled in place: kept
        (prev / name).write_text(f"the user's {name}")
    (prev / "__pycache__").mkdir()
    (prev / "__pycache__" / "__init__.cpython-311.pyc").write_bytes(b"bytecode")   # Python's: remade on import
    done = build("--out", prev, *SMALL)
    assert done.returncode == 0, done.stderr
    assert (prev / "certificates.tex").read_bytes() == fresh
    assert (prev / "suslov_formulas.pdf").read_text() == "the user's suslov_formulas.pdf"
    assert (prev / "certificates.log").read_text() == "the user's certificates.log"
    assert not (prev / "__pycache__").exists()
    (prev / "SHA256SUMS").unlink()   # a tree without its manifest: the names the build writes are its own
    assert build("--out", prev, *SMALL).returncode == 0 and (prev / "SHA256SUMS").is_file()
    sim = tmp_path / "sim"
    assert simulate("--out", sim, "--quiet").returncode == 0
    assert simulate("--out", sim, "--quiet").returncode == 0
    assert {p.name for p in sim.iterdir()} >= {"report.md", "results.json", "omega.csv", outdir.MARKER}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prev", "sim"]   # no staging left


def test_a_file_put_there_while_the_build_works_is_not_lost(tmp_path, small_build, monkeypatch):
    prev = tmp_path / "prev"
    write_atomically(small_build, prev)
    original = pipeline.write_manifest

    def meanwhile(directory):
        (prev / "my_notes.txt").write_text("written during the build")
        return original(directory)

    monkeypatch.setattr(pipeline, "write_manifest", meanwhile)
    with pytest.raises(OutputRefused, match="my_notes.txt"):
        write_atomically(small_build, prev)
    assert (prev / "my_notes.txt").read_text() == "written during the build"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prev"]   # the staging tree is gone
    # the simulator's route (suslov.outdir.staged) checks again before its swap too
    from suslov.simulator.outputs import staged
    sim = tmp_path / "sim"
    with staged(sim) as staging:
        (staging / "report.md").write_text("# run\n\n## Files\n\n- `a.csv`\n")
        (staging / "a.csv").write_text("1")
    with pytest.raises(OutputRefused, match="figures/"):
        with staged(sim) as staging:
            (staging / "report.md").write_text("# run\n\n## Files\n\n- `a.csv`\n")
            (sim / "figures").mkdir()
    assert (sim / "figures").is_dir() and (sim / "a.csv").read_text() == "1"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["prev", "sim"]


def refused_before_any_work(done, option: str, path: str, why: str) -> None:
    assert done.returncode == 2, done.stderr
    assert "[1/" not in done.stderr and "Traceback" not in done.stderr, done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and f"{option} {path}" in lines[0] and why in lines[0], done.stderr


@pytest.mark.skipif(not Path("/proc/self").is_dir(), reason="no /proc")
def test_out_in_proc_is_refused_before_any_work():
    refused_before_any_work(build("--out", "/proc/x", *SMALL, quiet=False), "--out", "/proc/x", "cannot write")
    done = simulate("--out", "/proc/x")
    assert done.returncode == 2 and "cannot write in /proc" in done.stderr and "Traceback" not in done.stderr


def test_pdf_naming_an_existing_file_is_refused_before_any_work(tmp_path):
    (tmp_path / "afile").write_text("data")
    done = build("--out", tmp_path / "out", "--pdf", tmp_path / "afile", *SMALL, quiet=False)
    refused_before_any_work(done, "--pdf", str(tmp_path / "afile"), "not a directory")
    assert (tmp_path / "afile").read_text() == "data" and sorted(p.name for p in tmp_path.iterdir()) == ["afile"]


def test_tilde_of_no_user_is_refused_before_any_work(tmp_path):
    try:
        pwd.getpwnam(NO_USER)
        pytest.skip(f"a user {NO_USER} exists here")
    except KeyError:
        pass
    path = f"~{NO_USER}/x"
    refused_before_any_work(build("--out", path, *SMALL, quiet=False), "--out", path, "no such user")
    refused_before_any_work(build("--out", tmp_path / "out", "--pdf", path, *SMALL, quiet=False), "--pdf", path,
                            "no such user")
    done = simulate("--out", path)
    assert done.returncode == 2 and "no such user" in done.stderr and "Traceback" not in done.stderr
    assert list(tmp_path.iterdir()) == []
