"""README's and the guide pages' Python blocks run as written (pasted into a fresh interpreter, outside the repository).

The guide pages (``docs/*.md``) are built by Sphinx with ``-W`` in ``tests/test_docs.py``; their code is
run here, like the README's.  The README stays a front door: at most 200 lines.
"""
import re
import subprocess
import sys

import pytest

from derivations.output.pipeline import ROOT

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
BLOCKS = [(page.name, block) for page in PAGES
          for block in re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"), flags=re.S)]


def test_readme_has_python_blocks_and_is_short():
    assert any(name == "README.md" for name, _ in BLOCKS)
    assert (ROOT / "README.md").read_text(encoding="utf-8").count("\n") <= 200


@pytest.mark.parametrize("index", range(len(BLOCKS)), ids=[f"{name}-{i}" for i, (name, _) in enumerate(BLOCKS)])
def test_python_block_runs_as_pasted(tmp_path, index):
    result = subprocess.run([sys.executable, "-c", BLOCKS[index][1]], cwd=tmp_path, capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stderr


BENCHMARKS = ROOT / "docs" / "benchmarks.md"   # the measurements' page; the README quotes its current numbers


def test_build_table_is_the_committed_measurement():
    """The cold-build table (docs/benchmarks.md since issue 47 moved the history out of the README) quotes
    bench/results/build.json (the medians of the default build alternating with the baseline, --verify, the
    pmax runs and the warm rebuild), not a memory of it."""
    import json

    data = json.loads((ROOT / "bench/results/build.json").read_text(encoding="utf-8"))
    page = BENCHMARKS.read_text(encoding="utf-8")
    paired = data["interleaved"]
    assert data["baseline"]["revision"] in page
    assert (f"| default pmax, both cores | {paired['median_baseline']:.1f} s | {paired['median_ours']:.1f} s |"
            in page)
    assert (f"| `--verify generated` | {paired['median_verify_baseline']:.1f} s | "
            f"{paired['median_verify_ours']:.1f} s |") in page
    walls = {r["pmax"]: r["wall_seconds"] for r in data["runs"] if r["jobs"] == "all cores"}
    for pmax in (51, 101):
        assert f"| `--pmax {pmax}`, both cores | | {walls[pmax]:.1f} s |" in page, pmax
    assert f"| a rebuild with nothing changed (from the cache) | | {data['warm']['15']:.1f} s |" in page


def test_readme_build_times_are_the_committed_measurement():
    """The README's one sentence of build times quotes the same file (and points to the page that has the rest)."""
    import json

    data = json.loads((ROOT / "bench/results/build.json").read_text(encoding="utf-8"))
    readme = " ".join((ROOT / "README.md").read_text(encoding="utf-8").split())
    walls = {r["pmax"]: r["wall_seconds"] for r in data["runs"] if r["jobs"] == "all cores"}
    assert (f"{data['interleaved']['median_ours']:.1f} s at the default pmax, {walls[51]:.1f} s at `--pmax 51`, "
            f"{walls[101]:.1f} s at `--pmax 101`") in readme
    assert f"and {data['warm']['15']:.1f} s from the cache" in readme
    assert "(docs/benchmarks.md)" in readme


def test_pmax_201_sentence_is_the_committed_measurement():
    """The --pmax 201 sentence of docs/benchmarks.md quotes bench/results/build_profile_201.json."""
    import json

    data = json.loads((ROOT / "bench/results/build_profile_201.json").read_text(encoding="utf-8"))
    page = " ".join(BENCHMARKS.read_text(encoding="utf-8").split())
    assert (f"At `--pmax 201` (both cores) the build took {data['this']['pmax 201']:.1f} s, beside "
            f"{data['base']['pmax 201']:.1f} s for the revision before ({data['base_revision']})") in page
    assert data["identical"]["pmax 201"] == []
