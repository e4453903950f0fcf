"""A researcher's first hour (issue 26): any p without touching the checkout.

The out-of-range message is followed literally: the code it names is executed as written, and
must end with a certified module for p = 21 and an unchanged ``git status`` of the checkout.
"""
import os
import subprocess
import sys

import numpy as np
import pytest

from derivations.output.pipeline import ROOT

SCRIPT = r'''
import re, sys
import numpy as np
import suslov
try:
    suslov.gamma_basis(0.1, 21, 0.5)
except ValueError as error:
    message = str(error)
print(message)
code = re.search(r"sf = suslov\.load_formulas\(pmax=\d+\)", message).group(0)
exec(code)                      # exactly what the message says
B = sf.gamma_basis(0.1, 21, 0.5)
assert sf.PMAX >= 21 and B.shape == (3, 3) and np.allclose(B @ B.T, np.eye(3), atol=1e-12)
sf2 = suslov.load_formulas(pmax=21)     # the second time: from the store, no build
assert sf2 is sf
suslov.use_formulas(sf)
assert suslov.gamma_basis(0.1, 21, 0.5).shape == (3, 3)   # import suslov now uses it
print("OK", sf.PMAX)
'''


def git_status():
    return subprocess.run(["git", "status", "--porcelain", "--untracked-files=all"], cwd=ROOT, capture_output=True,
                          text=True).stdout


@pytest.mark.skipif(not (ROOT / ".git").exists(), reason="needs the git checkout")
def test_following_the_out_of_range_message_gives_p21_and_a_clean_checkout(tmp_path, cli_build):
    before = git_status()
    # the per-p cache of this session's default build (conftest.cli_build): p > 15 computed here
    env = dict(cli_build[1], SUSLOV_DATA_DIR=str(tmp_path / "store"))
    done = subprocess.run([sys.executable, "-c", SCRIPT], cwd=tmp_path, env=env, capture_output=True, text=True,
                          timeout=900)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "outside the certified range" in done.stdout and "OK 21" in done.stdout
    assert git_status() == before
    stored = tmp_path / "store" / "pmax-21"
    assert (stored / "suslov_formulas.py").is_file() and (stored / ".suslov-output").is_file()


def test_load_formulas_from_an_out_directory(tmp_path):
    import suslov
    from suslov import loader

    module = suslov.load_formulas(path=ROOT / "generated")
    assert module.PMAX == loader.active_formulas().PMAX
    assert np.allclose(module.gamma_basis(0.3, 3, 0.5), loader.active_formulas().gamma_basis(0.3, 3, 0.5))
    with pytest.raises(FileNotFoundError, match="not a generated tree"):
        suslov.load_formulas(path=tmp_path)
    with pytest.raises(ValueError, match="exactly one"):
        suslov.load_formulas()
    with pytest.raises(ValueError, match="pmax=0"):
        suslov.load_formulas(pmax=0)
