"""The wheel: one clean namespace, no volatile files, certified module inside, the README example runs.

Issue 26, item 2: ``pip install .`` used to install top-level ``generated`` and ``derivations`` and ship
the per-build timing files.  Here the wheel is built from a copy of the working tree (no ``build/``
left in the checkout), checked with ``twine check``, installed with ``pip install --no-deps --target``
(its dependencies are those of the test environment), and the README's module example is run from
outside the repository with only the installed package on the path before site-packages.
"""
import hashlib
import os
import re
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from derivations.output.pipeline import ROOT, VOLATILE

pytest.importorskip("build")


def test_wheel_has_one_namespace_and_no_volatile_files(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    top = {n.split("/")[0] for n in names}
    assert {t for t in top if not t.endswith(".dist-info")} == {"suslov"}
    assert "suslov/formulas/suslov_formulas.py" in names and "suslov/formulas/certificates.json" in names
    assert not [n for n in names if Path(n).name in VOLATILE]
    # the manifest ships and matches what the wheel holds (issue 38: the installed module is verified on import)
    archive = zipfile.ZipFile(wheel)
    listed = dict(line.split("  ")[::-1] for line in archive.read("suslov/formulas/SHA256SUMS").decode().splitlines())
    assert {"__init__.py", "suslov_formulas.py", "certificates.json"} <= set(listed)
    for name, expected in listed.items():
        assert hashlib.sha256(archive.read(f"suslov/formulas/{name}")).hexdigest() == expected, name
    done = subprocess.run([sys.executable, "-m", "twine", "check", "--strict", str(wheel)], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr


def test_installed_wheel_runs_the_readme_example_outside_the_repository(wheel, tmp_path):
    site = tmp_path / "site"
    done = subprocess.run([sys.executable, "-m", "pip", "install", "--no-deps", "--no-index", "--target", str(site),
                           str(wheel)], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    example = re.findall(r"```python\n(.*?)```", (ROOT / "README.md").read_text(encoding="utf-8"), flags=re.S)[0]
    check = example + textwrap_check(site)
    env = dict(os.environ, PYTHONPATH=str(site))
    run = subprocess.run([sys.executable, "-c", check], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    assert "from the wheel" in run.stdout


def textwrap_check(site: Path) -> str:
    return (f"\nimport suslov as _s, importlib.util as _u\n"
            f"assert _s.__file__.startswith({str(site)!r}), _s.__file__\n"
            f"assert _s.active_formulas().__file__.startswith({str(site)!r})\n"
            f"assert _u.find_spec('generated') is None and _u.find_spec('derivations') is None\n"
            # issue 47: the catalog's formulas from the wheel's own verified catalog.json
            f"_P = _s.catalog['first_integrals'](p=5).expr\n"
            f"assert [str(e.lhs) for e in _P] == ['P1', 'P2', 'P3'], _P\n"
            f"assert _s.catalog['general_angle'].expr is not None\n"
            f"print('from the wheel')\n")
