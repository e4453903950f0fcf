"""What a build's output tree holds, and the build's claim on an output directory (no SymPy here).

The names of the files a build writes (``OUTPUTS``: template, file, the derivations it needs), the volatile
ones that the manifest and ``--check`` leave out, the derivations the generated module needs, and
:func:`claim_output`, which decides before any work whether a directory is the build's to replace.  They live
apart from :mod:`derivations.output.pipeline` (which re-exports them) so that the command line can refuse a bad
``--out`` or ``--pdf`` path, or a bad option, in a tenth of a second, before it imports SymPy and the derivations
(about 0.7 s of CPU per run: ``bench/bench_cli_startup.py``).
"""
from __future__ import annotations

import filecmp
import shutil
from pathlib import Path

from derivations.output.pdf import is_byproduct
from suslov import manifest, outdir
from suslov.formula_catalog import FILENAME as CATALOG_FILENAME

ROOT = Path(__file__).resolve().parents[2]   # the repository (derivations/<layer>/this file)
GENERATED = ROOT / "generated"
VOLATILE = ("certificate_costs.json", "certificate_costs.tex", "certificate_measurements.json", "cache_report.json")

# the derivations the generated module's formulas come from (and --verify runs)
MODULE_NEEDS = ("model", "special_case", "kovalevskaya", "meromorphic", "first_integrals", "scattering", "gauss",
                "general_angle")
# the derivations whose formulas the figures draw (derivations.output.figures)
FIGURES_NEEDS = ("scattering", "general_angle", "general_galois", "pole_theorem")
# (template, output file, derivations the output needs)
OUTPUTS = (
    ("init.py.j2", "__init__.py", ()),
    ("suslov_formulas.py.j2", "suslov_formulas.py", MODULE_NEEDS),
    ("suslov-preamble.tex.j2", "suslov-preamble.tex", ()),
    ("suslov_formulas.tex.j2", "suslov_formulas.tex", ()),
    ("formulas_body.tex.j2", "formulas_body.tex", ()),
    ("notation.tex.j2", "notation.tex", ()),
    ("figures.tex.j2", "figures.tex", FIGURES_NEEDS),
    ("certificates.tex.j2", "certificates.tex", ()),
    ("certificates_table.tex.j2", "certificates_table.tex", ()),
    ("errata_table.tex.j2", "errata_table.tex", ()),
    ("per_p_table.tex.j2", "per_p_table.tex", ("special_case",)),
    ("integrals_table.tex.j2", "integrals_table.tex", ("first_integrals",)),
    ("basis_tables.tex.j2", "basis_tables.tex", ("meromorphic",)),
    ("monodromy_tables.tex.j2", "monodromy_tables.tex", ("residue",)),
    ("galois_tables.tex.j2", "galois_tables.tex", ("galois",)),
    ("galois_group_table.tex.j2", "galois_group_table.tex", ("fuchsian",)),
    ("certificate_costs.tex.j2", "certificate_costs.tex", ()),
)

BUILD_TOOL = "build_formulas.py"
BUILD_SIGNATURE = "certificates.json"   # recognises build outputs written before the marker existed


def claim_output(target: Path) -> Path:
    """``target`` as an absolute path the build may replace (:func:`suslov.outdir.claim`: refuses a file,
    a foreign directory or an unwritable place with :class:`suslov.outdir.OutputRefused`).

    A previous build output is replaced only when it holds nothing but what the build wrote: the files its
    manifest ``SHA256SUMS`` lists (a tree without a readable one: the names the build writes), the manifest,
    the volatile files, the TeX by-products a rebuild keeps (``pipeline.swap_in``) and a ``__pycache__/`` of
    ``*.pyc`` only (Python's, remade on import).  Any other file or directory is the user's: refused, named.
    """
    def written(directory: Path) -> set[str]:
        try:   # leniently: a --only build's manifest lacks the module that manifest.read requires
            lines = (directory / manifest.MANIFEST).read_text(encoding="utf-8").splitlines()
            names = {line.partition("  ")[2] for line in lines if "  " in line} - {""}
        except (OSError, UnicodeDecodeError):
            names = {filename for _, filename, _ in OUTPUTS} | {BUILD_SIGNATURE, CATALOG_FILENAME}
        names |= {manifest.MANIFEST, *VOLATILE}
        for entry in directory.iterdir():
            if entry.is_file() and is_byproduct(entry.name):
                names.add(entry.name)
            elif (entry.name == "__pycache__" and entry.is_dir() and not entry.is_symlink()
                  and all(f.is_file() and not f.is_symlink() and f.suffix == ".pyc" for f in entry.iterdir())):
                names.add(entry.name)
        return names

    return outdir.claim(target, BUILD_TOOL, BUILD_SIGNATURE, written)


def write_manifest(directory: Path) -> Path:
    """The tree's last file (:mod:`suslov.manifest`): the SHA-256 of every emitted, non-volatile file, so the
    loader can refuse a tree changed after the build.  Written into the staging directory, before the swap."""
    names = [p.name for p in Path(directory).iterdir()
             if p.is_file() and p.name not in VOLATILE + (manifest.MANIFEST, outdir.MARKER) and not is_byproduct(p.name)]
    return manifest.write(directory, names)


def install_tree(source: Path, target: Path) -> None:
    """Copy the files of ``source`` (a cached build) into ``target``, swapped in like a fresh build."""
    target = claim_output(target)
    outdir.make_dir(target.parent)
    staging = outdir.new_staging(target, BUILD_TOOL)
    try:
        for item in Path(source).iterdir():
            if item.is_file() and item.name not in ("manifest.json", outdir.MARKER):
                shutil.copyfile(item, staging / item.name)
        write_manifest(staging)
        claim_output(target)   # again: a file a user put into the previous output meanwhile is not lost
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    swap_in(staging, target)


def swap_in(staging: Path, target: Path) -> None:
    """Replace ``target`` by ``staging`` (:func:`suslov.outdir.swap_in`); TeX by-products of ``target`` are kept."""
    if target.is_dir():  # a user's PDF (and the other TeX by-products) survives the rebuild
        for item in target.iterdir():
            if item.is_file() and is_byproduct(item.name) and not (staging / item.name).exists():
                shutil.copyfile(item, staging / item.name)
    outdir.swap_in(staging, target)


def compare_trees(expected: Path, actual: Path) -> list[str]:
    """Files that differ, are missing or are extra (volatile files and TeX by-products ignored)."""
    def files(root: Path) -> set[str]:
        if not root.exists():
            return set()
        return {str(p.relative_to(root)) for p in root.rglob("*")
                if p.is_file() and p.name not in VOLATILE and "__pycache__" not in p.parts and not is_byproduct(p.name)}

    left, right = files(expected), files(actual)
    differing = sorted(left ^ right)
    differing += sorted(f for f in left & right if not filecmp.cmp(expected / f, actual / f, shallow=False))
    return differing
