"""The build: deterministic, committed tree up to date, fails loudly and atomically."""
import hashlib
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

import build_formulas
from derivations.core.certificates import CertificationFailure
from derivations.core.differential import T
from derivations.core.options import BuildOptions
from derivations.core.symbols import w1
from derivations.output.pipeline import (
    GENERATED,
    ROOT,
    VOLATILE,
    compare_trees,
    derive,
    write_atomically,
)
from derivations.sections import model


def tree_digest(root: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
        h.update(str(path.relative_to(root)).encode())
        h.update(path.read_bytes())
    return h.hexdigest()


def test_two_builds_are_byte_identical(tmp_path, default_build, cli_build):
    """Two cold builds, one in this process and one by the command line in another, byte for byte."""
    write_atomically(default_build, tmp_path / "a")
    assert compare_trees(tmp_path / "a", cli_build[0]) == []


def test_committed_generated_equals_default_build(tmp_path, default_build):
    write_atomically(default_build, tmp_path / "fresh")
    assert compare_trees(tmp_path / "fresh", GENERATED) == [], "run: python build_formulas.py"


def test_volatile_costs_are_written_but_not_compared(tmp_path, default_build):
    write_atomically(default_build, tmp_path / "out")
    for name in VOLATILE:
        assert (tmp_path / "out" / name).exists()
        (tmp_path / "out" / name).write_text("changed")
    assert compare_trees(tmp_path / "out", GENERATED) == []


def test_perturbed_omega_fails_the_build_and_leaves_output_untouched(tmp_path, monkeypatch, capsys):
    out = tmp_path / "generated"
    write_atomically(derive(BuildOptions(pmax=3), ["special_case"]), out)
    before = tree_digest(out)
    original = model.derive_general_solution

    def perturbed():
        solution = dict(original())
        solution[w1] = solution[w1] * (1 + sp.Rational(1, 1000) * T)
        return solution

    monkeypatch.setattr(model, "derive_general_solution", perturbed)
    with pytest.raises(CertificationFailure, match="derived omega"):
        derive(BuildOptions(pmax=3))
    status = build_formulas.main(["--pmax", "3", "--out", str(out), "--quiet"])
    assert status == 1
    assert "derived omega(t) solves the reduced Euler equations" in capsys.readouterr().err
    assert tree_digest(out) == before


def test_failure_while_rendering_leaves_output_untouched(tmp_path, monkeypatch):
    out = tmp_path / "generated"
    build = derive(BuildOptions(pmax=2), ["special_case"])
    write_atomically(build, out)
    before = tree_digest(out)
    import derivations.output.pipeline as pipeline

    def broken(template, context):
        if template.startswith("errata"):
            raise RuntimeError("template exploded")
        return "partial"

    monkeypatch.setattr(pipeline, "render", broken)
    with pytest.raises(RuntimeError):
        write_atomically(build, out)
    assert tree_digest(out) == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["generated"]  # no staging left behind


def run_cli(*args, env=None):
    return subprocess.run([sys.executable, "build_formulas.py", *args], cwd=ROOT, capture_output=True, text=True,
                          env=env)


@pytest.mark.parametrize("args, needle", [
    (["--pmax", "0"], "--pmax"),
    (["--pmax", "seven"], "--pmax"),
    (["--pmax", "100000"], "--pmax"),
    (["--only", "nonsense"], "nonsense"),
    (["--frobnicate"], "--frobnicate"),
])
def test_bad_command_line_is_one_clear_line_and_touches_nothing(args, needle):
    before = tree_digest(GENERATED)
    proc = run_cli(*args)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and needle in lines[0]
    assert tree_digest(GENERATED) == before


def test_check_passes_on_committed_tree(cli_build):
    # compared with this session's command-line build (from its cache): the committed tree is a fresh build's
    proc = run_cli("--check", "--quiet", env=cli_build[1])
    assert proc.returncode == 0, proc.stderr
    assert "identical" in proc.stdout


def test_check_detects_a_difference(tmp_path, default_build, cli_build, monkeypatch):
    write_atomically(default_build, tmp_path / "g")
    (tmp_path / "g" / "errata_table.tex").write_text("tampered\n")
    for name, value in cli_build[1].items():
        if name.startswith("SUSLOV"):
            monkeypatch.setenv(name, value)
    monkeypatch.delenv("SUSLOV_NO_CACHE", raising=False)
    assert build_formulas.main(["--check", "--quiet", "--out", str(tmp_path / "g")]) == 3


def test_only_certifies_requirements_and_writes_nothing():
    before = tree_digest(GENERATED)
    proc = run_cli("--only", "special_case")
    assert proc.returncode == 0, proc.stderr
    assert "model" in proc.stdout and "special_case" in proc.stdout
    quiet = run_cli("--only", "special_case", "--quiet")
    assert quiet.returncode == 0 and "certificates" not in quiet.stdout and not quiet.stderr
    assert tree_digest(GENERATED) == before


def test_pmax_splits_parities():
    options = BuildOptions(pmax=8)
    assert options.odd_p_values() == [1, 3, 5, 7] and options.even_p_values() == [2, 4, 6, 8]
    rows = derive(options, ["special_case"]).results["special_case"].exports["per_p"]
    assert [r["p"] for r in rows] == list(range(1, 9))
    assert [r["parity"] for r in rows[:2]] == ["odd", "even"]


def test_costliest_list_shows_each_outcome(default_build):
    """The console's "costliest" list showed refuted claims as if they were proved."""
    from derivations.output.pipeline import summary

    text = summary(default_build, top=len(default_build.log.certificates))
    costly = text.split("costliest", 1)[1].splitlines()[1:]
    refuted = [c for c in default_build.log.certificates if c.expected.value == "fail"]
    assert refuted and all(line.rstrip().endswith(")") for line in costly)
    assert sum("refuted" in line for line in costly) == len(refuted)


@pytest.mark.parametrize("pmax", [1, 2])
def test_smallest_pmax_certifies_the_galois_verdicts(pmax):
    """--pmax 1 and 2 are allowed: the agreement with the exact Frobenius analysis uses the p it ran
    (it asked for p = 2 and 3 whatever pmax was, and failed the build)."""
    build = derive(BuildOptions(pmax=pmax), ["fuchsian"])
    agree = next(c for c in build.log.certificates if "agree with the exact Frobenius" in c.claim)
    assert agree.outcome.value == "pass"
