"""Shared fixtures: one certified build in this process and one by the command line per test session
(about ten seconds each, cold), the committed documents compiled and the Sphinx pages built once per run
(:func:`once_per_run`: one directory for all xdist workers), and the ``slow`` marker of the quick loop
(``pytest -m "not slow"``).

The build's certificate cache is off for the whole session (``SUSLOV_NO_CACHE``, inherited by the
``build_formulas.py`` subprocesses): tests that perturb a derivation at run time must not be
answered from a cache keyed by unchanged sources.  tests/test_cache.py turns it on in its own
temporary cache directory, and :func:`cli_build` in its own, for the read-only ``--check`` tests.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from filelock import FileLock

os.environ["SUSLOV_NO_CACHE"] = "1"

from derivations.core.options import BuildOptions
from derivations.output.pipeline import derive

ROOT = Path(__file__).resolve().parents[1]


SLOW_FIXTURES = {"default_build", "cli_build", "wheel", "venv"}   # a whole build, or a package installed


def _listed_slow() -> set[str]:
    listed = (ROOT / "tests" / "slow_tests.txt").read_text(encoding="utf-8").splitlines()
    return {line.strip() for line in listed if line.strip() and not line.startswith("#")}


def pytest_collection_modifyitems(config, items):
    """Mark ``slow`` what ``tests/slow_tests.txt`` lists (``bench/slow_tests.py``: 0.3 s or more in a timed run)
    and every test that needs a whole build: ``pytest -m "not slow"`` is the developer's quick loop; the
    README's test command runs everything."""
    listed = _listed_slow()
    for item in items:
        if item.nodeid in listed or SLOW_FIXTURES & set(getattr(item, "fixturenames", ())):
            item.add_marker(pytest.mark.slow)
    items[:] = sorted(items, key=_session_builds_first)


def _session_builds_first(item) -> tuple:
    """The tests that use a session-scoped build (SLOW_FIXTURES) first, grouped by the builds they use, the others
    in collection order (a stable sort).  Why: each pytest-xdist worker builds a session fixture for itself when it
    runs a test that needs it; ``--dist worksteal`` hands each worker a contiguous half of this list at the start,
    so these tests all go to the first worker, which builds each fixture once for the whole run (the second
    worker's copy of ``default_build`` cost about 11 CPU-seconds, in tests/test_notation_index.py's setup)."""
    used = tuple(sorted(SLOW_FIXTURES & set(getattr(item, "fixturenames", ()))))
    return (0, used) if used else (1, ())


@pytest.fixture(scope="session")
def default_build():
    """The default build in this process, with no worker processes (``jobs=1``): the suite already runs on every
    core, and a pool's start costs CPU the other pytest worker needs (7.6 CPU-s against 5.5 for the module's
    derivations, measured).  The command-line build (:func:`cli_build`) uses workers; tests/test_build.py compares
    the two trees byte for byte."""
    return derive(BuildOptions(jobs=1))


@pytest.fixture(scope="session")
def cli_build(tmp_path_factory):
    """``(out, env)``: one cold default build by the command line, as a user runs it (a second process,
    independent of :func:`default_build`), into ``out``, filling a whole-build cache of its own; ``env``
    points at that cache with the cache on, so that ``--check`` in this session compares against this
    build instead of building again (tests that perturb derivations never use it)."""
    root = tmp_path_factory.mktemp("cli_build")
    env = {k: v for k, v in os.environ.items() if k != "SUSLOV_NO_CACHE"}
    env["SUSLOV_CACHE_DIR"] = str(root / "cache")
    done = subprocess.run([sys.executable, str(ROOT / "build_formulas.py"), "--quiet", "--out", str(root / "out")],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return root / "out", env


def once_per_run(tmp_path_factory, worker_id: str, name: str, make) -> Path:
    """A directory ``make(directory)`` fills once per test run, whichever xdist worker asks first; the others wait
    for it and read the same files (pytest-xdist's recipe: a file lock in the run's base directory, which is new for
    every run).  A session fixture is otherwise made once per worker, and with the tests of one module spread
    over both workers the Sphinx pages were built twice (about 16 CPU-s).  The directory is complete when its
    marker file is there; if ``make`` fails, nothing is marked and the next worker tries again (and fails alike).
    Callers treat the directory as read-only.  Without xdist (``-n 0``) the directory is this session's own."""
    if worker_id == "master":
        root = tmp_path_factory.mktemp(name)
        make(root)
        return root
    root = tmp_path_factory.getbasetemp().parent / name
    done = root / ".made"
    with FileLock(str(root) + ".lock"):
        if not done.is_file():
            shutil.rmtree(root, ignore_errors=True)   # a failed attempt of another worker
            root.mkdir()
            make(root)
            done.write_text("complete\n")
    return root


@pytest.fixture(scope="session")
def generated_pdfs(tmp_path_factory, worker_id) -> list:
    """The committed tree's documents compiled once per run (:func:`derivations.output.pdf.compile_pdfs`, the
    order it returns them in), for the tests that read them (tests/test_latex.py, tests/test_pdf_text.py)."""
    from derivations.output import pdf
    from derivations.output.pipeline import GENERATED

    require_tools("pdflatex")
    directory = once_per_run(tmp_path_factory, worker_id, "generated-pdf",
                             lambda root: (root / "order.txt").write_text(
                                 "\n".join(p.name for p in pdf.compile_pdfs(GENERATED, root / "pdf")) + "\n"))
    return [directory / "pdf" / line for line in (directory / "order.txt").read_text().split()]


def working_tree(target: Path) -> None:
    """Copy the files git tracks or would track (the working tree, uncommitted edits included) to ``target``."""
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout.split("\0")
    for name in filter(None, files):
        if (ROOT / name).is_file():
            (target / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(ROOT / name, target / name)


@pytest.fixture(scope="session")
def wheel(tmp_path_factory):
    """The project's wheel, built once per session from a copy of the working tree (no build/ left here)."""
    pytest.importorskip("build")
    tmp = tmp_path_factory.mktemp("wheel")
    working_tree(tmp / "src")
    done = subprocess.run([sys.executable, "-m", "build", "--wheel", "--no-isolation", "--outdir", str(tmp / "dist"),
                           str(tmp / "src")], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    (path,) = (tmp / "dist").glob("*.whl")
    return path


def circle_monodromy(matrix, center, radius, dim):
    """Monodromy of Y' = matrix(t) Y around the circle |t - center| = radius (SciPy DOP853, complex state).

    Shared by the logarithm tests: an independent numerical route to local monodromy.
    """
    import numpy as np
    from scipy.integrate import solve_ivp

    def rhs(th, y):
        t = center + radius * np.exp(1j * th)
        return (matrix(t) @ y.reshape(dim, dim) * 1j * radius * np.exp(1j * th)).ravel()

    sol = solve_ivp(rhs, (0, 2 * np.pi), np.eye(dim, dtype=complex).ravel(), method="DOP853", rtol=1e-12, atol=1e-12)
    return sol.y[:, -1].reshape(dim, dim)


def mutated_function(module, name: str, old: str, new: str):
    """``module.name`` recompiled with one text change (a seeded fault), in the module's namespace; for
    ``monkeypatch.setattr(module, name, ...)``.  The original text must be in the source."""
    import inspect

    source = inspect.getsource(getattr(module, name))
    assert old in source, f"mutation site not in {module.__name__}.{name}: {old!r}"
    namespace = dict(vars(module))
    exec(source.replace(old, new), namespace)
    return namespace[name]


@pytest.fixture
def forget_loaded():
    """Undo what a test loaded through ``suslov.loader`` (its cache of verified trees and the modules it imported:
    the generated module under its private names, and the ``gen44`` test packages)."""
    from suslov import loader

    before, modules = dict(loader._loaded), set(sys.modules)
    yield
    loader._loaded.clear()
    loader._loaded.update(before)
    for name in set(sys.modules) - modules:
        if "suslov_formulas" in name or name.startswith("gen44"):
            del sys.modules[name]


def require_tools(*tools: str) -> None:
    """Skip when a command-line tool the test needs is missing; under CI (``$CI`` set) fail instead: ``.ci/run``
    installs them (texlive-latex-base, latexdiff, poppler-utils), so a missing one there is a broken set-up."""
    import shutil

    missing = [tool for tool in tools if shutil.which(tool) is None]
    if missing and os.environ.get("CI"):
        pytest.fail(f"{', '.join(missing)} not found under CI: .ci/run must install it")
    if missing:
        pytest.skip(f"{', '.join(missing)} not installed")
