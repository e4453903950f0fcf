"""Verified loading (issue 38, suslov/manifest.py): a tree changed after the build is refused, never run.

The tampering of the audit is reproduced literally: one line of ``scattering_angle`` in a stored
``suslov_formulas.py`` gets a factor 1.001 (and, to show that nothing of the file runs, a line that would
create a file at import).  The expected digests come from ``hashlib`` over the copied files (and, for the
committed tree, from coreutils' ``sha256sum -c``), not from the code under test.
"""
import hashlib
import json
import os
import re
import shutil
import stat
import subprocess
import sys

import pytest

from derivations.output.pipeline import GENERATED, ROOT, VOLATILE
from suslov import manifest
from suslov.manifest import MANIFEST, ManifestError, UntrustedTree

ANGLE_LINE = "def scattering_angle("


def copy_tree(target):
    shutil.copytree(GENERATED, target, ignore=shutil.ignore_patterns("__pycache__", *VOLATILE))
    return target


def tamper(tree, sentinel):
    """One line of scattering_angle multiplied by 1.001, plus an import-time side effect."""
    path = tree / "suslov_formulas.py"
    lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
    start = next(i for i, line in enumerate(lines) if line.startswith(ANGLE_LINE))
    ret = next(i for i in range(start, len(lines)) if lines[i].lstrip().startswith("return "))
    indent = lines[ret][:len(lines[ret]) - len(lines[ret].lstrip())]
    lines[ret] = lines[ret].replace("return ", "return 1.001 * ", 1)
    lines.append(f"\nopen({str(sentinel)!r}, 'w').write('ran')\n")
    path.write_text("".join(lines), encoding="utf-8")
    assert indent   # the line really was inside the function
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_committed_tree_matches_its_manifest_by_sha256sum():
    assert shutil.which("sha256sum")
    done = subprocess.run(["sha256sum", "--check", "--strict", MANIFEST], cwd=GENERATED, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    tracked = subprocess.run(["git", "ls-files", "generated"], cwd=ROOT, capture_output=True, text=True).stdout.split()
    if tracked:   # every committed file of the tree, except the manifest itself, is listed
        listed = {line.split("  ", 1)[1] for line in (GENERATED / MANIFEST).read_text().splitlines()}
        assert listed == {os.path.basename(t) for t in tracked} - {MANIFEST, ".suslov-output"}


def test_intact_copy_loads_and_agrees(tmp_path):
    from suslov import loader

    tree = copy_tree(tmp_path / "tree")
    module = loader.load_formulas(path=tree)
    assert module.scattering_angle(3, 0.5) == loader.active_formulas().scattering_angle(3, 0.5)


def test_tampered_store_module_is_refused_never_run(tmp_path, monkeypatch):
    """The audit's case: a per-user store entry whose module was edited after the build."""
    from suslov import loader

    store = tmp_path / "store"
    entry = copy_tree(store / "pmax-99")
    document = json.loads((entry / "certificates.json").read_text())
    document["pmax"] = 99   # a consistent stored tree for a larger range (manifest rewritten by hand below)
    (entry / "certificates.json").write_text(json.dumps(document))
    names = [line.split("  ", 1)[1] for line in (entry / MANIFEST).read_text().splitlines()]
    (entry / MANIFEST).write_text("".join(f"{hashlib.sha256((entry / n).read_bytes()).hexdigest()}  {n}\n"
                                          for n in sorted(names)))
    expected = hashlib.sha256((entry / "suslov_formulas.py").read_bytes()).hexdigest()
    sentinel = tmp_path / "ran"
    found = tamper(entry, sentinel)
    monkeypatch.setenv(loader.DATA_ENV, str(store))
    with pytest.raises(ManifestError) as caught:
        loader.load_formulas(pmax=99, build=False)
    message = str(caught.value)
    assert str(entry / "suslov_formulas.py") in message and expected in message and found in message
    assert not sentinel.exists()


def test_tampered_tree_named_by_environment_is_refused_in_a_fresh_process(tmp_path):
    tree = copy_tree(tmp_path / "tree")
    sentinel = tmp_path / "ran"
    found = tamper(tree, sentinel)
    env = dict(os.environ, SUSLOV_FORMULAS=str(tree), PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-c", "import suslov; print(suslov.scattering_angle(3, 0.5))"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert done.returncode != 0 and "ManifestError" in done.stderr and found in done.stderr
    assert not sentinel.exists()


def test_use_formulas_refuses_a_tampered_certificates_file(tmp_path):
    from suslov import loader

    tree = copy_tree(tmp_path / "tree")
    with open(tree / "certificates.json", "a") as handle:
        handle.write(" ")
    with pytest.raises(ManifestError, match=r"certificates\.json: SHA-256 [0-9a-f]{64} where SHA256SUMS records"):
        loader.use_formulas(tree)
    assert loader.active_formulas().__name__ == "generated.suslov_formulas"


@pytest.mark.parametrize("damage", ["no manifest", "unlisted python file", "module not listed", "garbled line"])
def test_incomplete_or_extended_trees_are_refused(tmp_path, damage):
    tree = copy_tree(tmp_path / "tree")
    if damage == "no manifest":
        (tree / MANIFEST).unlink()
    elif damage == "unlisted python file":
        (tree / "helper.py").write_text("raise SystemExit('ran')\n")
    else:
        lines = (tree / MANIFEST).read_text().splitlines(keepends=True)
        if damage == "module not listed":
            lines = [line for line in lines if not line.endswith("  suslov_formulas.py\n")]
        else:
            lines[0] = "zz" + lines[0][2:]   # not hexadecimal
        (tree / MANIFEST).write_text("".join(lines))
    with pytest.raises(ManifestError, match={"no manifest": "no SHA256SUMS", "unlisted python file": "helper.py",
                                             "module not listed": "does not list suslov_formulas.py",
                                             "garbled line": "line 1"}[damage]):
        manifest.load_module(tree, "suslov_formulas_damaged")


@pytest.mark.skipif(os.name != "posix", reason="POSIX permissions")
@pytest.mark.parametrize("where", ["tree", "module", "parent"])
def test_a_tree_others_can_write_is_refused(tmp_path, where):
    parent = tmp_path / "shared"
    tree = copy_tree(parent / "tree")
    victim = {"tree": tree, "module": tree / "suslov_formulas.py", "parent": parent}[where]
    victim.chmod(victim.stat().st_mode | stat.S_IWOTH)
    with pytest.raises(UntrustedTree, match=re.escape(str(victim)) + ".*writable by every user.*chmod go-w"):
        manifest.load_module(tree, "suslov_formulas_shared")
    parent.chmod(parent.stat().st_mode | stat.S_IWOTH | stat.S_ISVTX)   # a sticky parent (as /tmp) is fine
    if where == "parent":
        manifest.load_module(tree, "suslov_formulas_sticky")


def test_the_default_import_checks_the_package_before_its_init_runs(tmp_path, monkeypatch):
    package = copy_tree(tmp_path / "gencopy")
    sentinel = tmp_path / "ran"
    with open(package / "__init__.py", "a") as handle:
        handle.write(f"open({str(sentinel)!r}, 'w').write('ran')\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    with pytest.raises(ManifestError, match="__init__.py: SHA-256"):
        manifest.import_verified("gencopy.suslov_formulas")
    assert not sentinel.exists() and "gencopy" not in sys.modules


def test_verify_command_checks_the_manifest_first(tmp_path, capsys):
    from derivations.output.cli import main

    tree = copy_tree(tmp_path / "tree")
    found = tamper(tree, tmp_path / "ran")
    assert main(["--verify", str(tree), "--quiet"]) == 1
    error = capsys.readouterr().err
    assert "suslov_formulas.py: SHA-256 " + found in error and "--verify" in error


def test_build_writes_the_manifest_last_over_the_emitted_files(tmp_path):
    from derivations.output.pipeline import write_manifest

    tree = copy_tree(tmp_path / "tree")
    (tree / MANIFEST).unlink()
    (tree / "certificate_costs.json").write_text("{}")   # volatile: never listed
    write_manifest(tree)
    assert (tree / MANIFEST).read_bytes() == (GENERATED / MANIFEST).read_bytes()


def test_the_build_may_load_its_own_stale_generated_tree_and_nothing_else(tmp_path, monkeypatch, capsys):
    """After a merge generated/ may not match its manifest; the build (which rewrites it) loads it with a note,
    through SUSLOV_REBUILDING naming that one directory.  Another tree, or a tree others can write, is still refused."""
    from derivations.output import cli

    package = copy_tree(tmp_path / "genstale")
    with open(package / "suslov_formulas.py", "a") as handle:
        handle.write("\nSTALE = True\n")
    monkeypatch.setattr(cli, "GENERATED", package)
    monkeypatch.delenv(manifest.REBUILD_ENV, raising=False)
    cli.allow_rebuilding_generated(quiet=False)
    assert os.environ[manifest.REBUILD_ENV] == os.path.realpath(package)
    monkeypatch.syspath_prepend(str(tmp_path))
    module = manifest.import_verified("genstale.suslov_formulas")
    assert module.STALE and "loaded anyway for the build" in capsys.readouterr().err
    other = copy_tree(tmp_path / "other")
    with open(other / "suslov_formulas.py", "a") as handle:
        handle.write("\nSTALE = True\n")
    with pytest.raises(ManifestError):
        manifest.import_verified("other.suslov_formulas")
    for name in ("genstale", "genstale.suslov_formulas"):
        sys.modules.pop(name, None)
    package.chmod(package.stat().st_mode | stat.S_IWOTH)
    with pytest.raises(UntrustedTree):
        manifest.import_verified("genstale.suslov_formulas")


def test_the_rebuild_waiver_still_refuses_a_shared_tree_without_manifest(tmp_path, monkeypatch):
    package = copy_tree(tmp_path / "genbare")
    (package / MANIFEST).unlink()
    monkeypatch.setenv(manifest.REBUILD_ENV, os.path.realpath(package))
    monkeypatch.syspath_prepend(str(tmp_path))
    package.chmod(package.stat().st_mode | stat.S_IWOTH)
    with pytest.raises(UntrustedTree):
        manifest.import_verified("genbare.suslov_formulas")
