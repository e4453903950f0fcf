"""The command line refuses bad options and paths before it imports SymPy and the derivations (issue 43).

A refusal used to cost the imports of a whole build (about 0.8 s of CPU: SymPy, symengine, every derivation); now
``derivations.output.cli`` imports them only when a build starts (``bench/bench_cli_startup.py`` measures the
difference).  Checked here by what a refused run leaves in ``sys.modules``, not by timing it; and the registry's
names, known without importing the derivations, are the modules' own.
"""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PROBE = """
import contextlib, io, sys
from derivations.output import cli
err = io.StringIO()
with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
    try:
        status = cli.run(sys.argv[1:])
    except SystemExit as exit:
        status = exit.code
heavy = sorted(m for m in ("sympy", "symengine", "derivations.core.certificates", "derivations.output.pipeline",
                           "derivations.sections.model") if m in sys.modules)
print(status, heavy, err.getvalue().strip().splitlines()[-1:])
"""


@pytest.mark.parametrize("args, status, said", [
    (["--pmax", "0"], 2, "--pmax 0: must be between 1 and"),
    (["--only", "nonsense"], 2, "--only 'nonsense': unknown derivation"),
    (["--out", "/proc/x", "--only", "special_case", "--pmax", "3"], 2, "nothing was done"),
    (["--check", "--only", "model"], 2, "--check compares a full build"),
])
def test_a_refusal_imports_no_sympy_and_no_derivation(args, status, said):
    done = subprocess.run([sys.executable, "-c", PROBE, *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    code, heavy, message = done.stdout.strip().split(" ", 2)
    assert int(code) == status and heavy == "[]", done.stdout
    assert said in message, done.stdout


def test_the_registry_names_are_the_modules_names_in_order():
    from derivations import registry

    assert list(registry.DERIVATIONS) == list(registry.NAMES)
    assert all(module.NAME == name for name, module in registry.DERIVATIONS.items())
    assert registry.resolve(["gauss"])[-1] == "gauss" and set(registry.resolve(None)) == set(registry.NAMES)


def test_help_still_lists_every_derivation_with_its_title():
    from derivations.output.cli import parser
    from derivations.registry import DERIVATIONS

    text = " ".join(parser().format_help().split())
    assert all(name in text for name in DERIVATIONS)
    assert "general_galois (The differential Galois group of every body, exactly" in text
