"""The core install and the extras, from the wheel, in a fresh virtual environment (issue 36).

``pip install suslov-certified`` must give the generated module, the run-time formulas and the balls
with NumPy, mpmath, python-flint and platformdirs only (under 150 MB), import no extra, and say which
extra a feature needs; ``[build]`` added to the same environment must let ``load_formulas(pmax=17)``
certify a module from the derivations shipped in the wheel (``suslov.build``), outside the repository.
The environment is made with ``python -m venv`` and filled by pip from the configured indexes (the
machine's mirrors), as a user's would be; expected values are computed here from the formulas' own
definitions with the standard library, not by the package.
"""
import json
import math
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from suslov.extras import EXTRAS

pytest.importorskip("build")
LIMIT_MB = 150
PIP_OWN = ("pip", "setuptools", "_distutils_hack", "pkg_resources", "distutils-precedence.pth")


@pytest.fixture(scope="module")
def venv(wheel, tmp_path_factory):
    root = tmp_path_factory.mktemp("core")
    subprocess.run([sys.executable, "-m", "venv", str(root / "env")], check=True, timeout=300)
    python = root / "env" / "bin" / "python"
    done = subprocess.run([str(python), "-m", "pip", "install", "-q", str(wheel)], capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    return python, root


def run(python, code: str, cwd, **env) -> subprocess.CompletedProcess:
    clean = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SUSLOV_FORMULAS")}
    return subprocess.run([str(python), "-c", code], cwd=cwd, env=dict(clean, **env), capture_output=True, text=True,
                          timeout=900)


def site_packages_mb(python) -> float:
    site = Path(subprocess.run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                               capture_output=True, text=True, check=True).stdout.strip())
    total = 0
    for entry in site.iterdir():
        if entry.name.split("-")[0] in PIP_OWN or entry.name in PIP_OWN:
            continue   # the installer itself, present in every venv
        files = [entry] if entry.is_file() else [f for f in entry.rglob("*") if f.is_file()]
        total += sum(f.stat().st_size for f in files)
    return total / 2**20


def test_the_wheel_ships_the_build_and_the_scenes(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    assert "suslov/build/derivations/registry.py" in names and "suslov/build/templates/suslov_formulas.py.j2" in names
    assert "suslov/scenes/fig1_omega.toml" in names and "suslov/scenes/README.md" in names
    assert not [n for n in names if n.startswith(("derivations/", "generated/", "templates/"))]


def test_core_install_is_light_imports_no_extra_and_evaluates(venv, tmp_path):
    python, _ = venv
    assert site_packages_mb(python) < LIMIT_MB
    extras = sorted({name for names in EXTRAS.values() for name in names})
    code = f"""
import importlib.util, math, sys
import suslov
assert [n for n in {extras!r} if importlib.util.find_spec(n) is not None] == [], "an extra is installed"
w1, w2 = suslov.omega(0.3, 3, 0.5)
B1, B3 = suslov.gamma_basis(0.7, 1, 0.5), suslov.gamma_basis(0.7, 3, 0.5)
angle = float(suslov.scattering_angle(2.5, 0.7))
print(float(w1), float(w2), float(B1[0, 0]), float(abs(B3 @ B3.T - __import__('numpy').eye(3)).max()), angle)
print([n for n in {extras!r} if n in sys.modules])
print(suslov.__version__)
"""
    done = run(python, code, tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    numbers, loaded, version = done.stdout.strip().splitlines()
    w1, w2, b00, orthogonality, angle = map(float, numbers.split())
    assert abs(w1 - 6 * math.tanh(0.3)) < 1e-14 and abs(w2 + 6 * math.sqrt(1.25) / math.cosh(0.3)) < 1e-14
    assert abs(b00 - math.tanh(0.7)) < 1e-14 and orthogonality < 1e-13   # p = 1: gamma^(1)_1 = tanh t
    x = math.pi * 2.5 / (2 * 0.7)   # Theorem 5.4 (corrected): cos(angle/2) = |cos(pi p/2)| / cosh(pi p/(2d))
    assert abs(angle - 2 * math.acos(abs(math.cos(math.pi * 2.5 / 2)) / math.cosh(x))) < 1e-12
    assert loaded == "[]" and version == "0.1.0"


def test_core_command_line_and_missing_extras_say_what_to_install(venv, tmp_path):
    python, _ = venv
    suslov = python.parent / "suslov"
    version = subprocess.run([str(suslov), "--version"], capture_output=True, text=True, timeout=120)
    assert version.returncode == 0 and version.stdout.strip() == "suslov-certified 0.1.0"
    scenes = subprocess.run([str(suslov), "scenes"], capture_output=True, text=True, timeout=120)
    assert scenes.returncode == 0 and "fig1_omega" in scenes.stdout and "8 scenes" in scenes.stdout
    sim = subprocess.run([str(suslov), "simulate", "fig1_omega", "--out", str(tmp_path / "o")], capture_output=True,
                         text=True, timeout=120)
    assert sim.returncode == 2 and "pip install 'suslov-certified[sim]'" in sim.stderr
    done = run(python, "import suslov; suslov.load_formulas(pmax=17)", tmp_path,
               SUSLOV_DATA_DIR=str(tmp_path / "store"))
    assert done.returncode == 1 and "pip install 'suslov-certified[build]'" in done.stderr
    assert not (tmp_path / "o").exists() and not (tmp_path / "store").exists()


def test_build_extra_certifies_a_larger_range_from_the_wheel(venv, wheel, tmp_path):
    python, _ = venv
    done = subprocess.run([str(python), "-m", "pip", "install", "-q", f"{wheel}[build]"], capture_output=True,
                          text=True, timeout=900)
    assert done.returncode == 0, done.stderr[-3000:]
    code = """
import json, suslov
sf = suslov.load_formulas(pmax=17, quiet=True)
B = sf.gamma_basis(0.4, 17, 0.5)
print(sf.PMAX, sf.__file__, float(abs(B @ B.T - __import__('numpy').eye(3)).max()))
"""
    done = run(python, code, tmp_path, SUSLOV_DATA_DIR=str(tmp_path / "store"), SUSLOV_CACHE_DIR=str(tmp_path / "c"))
    assert done.returncode == 0, done.stderr[-3000:]
    pmax, path, orthogonality = done.stdout.split()
    assert int(pmax) >= 17 and path.startswith(str(tmp_path / "store")) and float(orthogonality) < 1e-12
    certificates = json.loads((Path(path).parent / "certificates.json").read_text())
    assert certificates["pmax"] == 17 and sorted(p.name for p in (tmp_path / "store").iterdir()) == ["pmax-17"]
