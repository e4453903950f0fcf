"""The content-keyed certificate cache (issue 13): hits, misses after a source change, corrupt entries.

Each test gets its own cache directory (``SUSLOV_CACHE_DIR``) and turns the session-wide
``SUSLOV_NO_CACHE`` off.  "Recomputed" is observed, not assumed: the volatile cache_report.json says
how many per-p results came from the cache, and the work function is counted in-process.
"""
import json

import pytest

import build_formulas
from derivations.core import cache
from derivations.core.certificates import CertificateLog
from derivations.core.options import BuildOptions
from derivations.output.pipeline import compare_trees, derive, write_atomically
from derivations.sections import residue


@pytest.fixture
def cache_dir(tmp_path, monkeypatch):
    monkeypatch.setenv("SUSLOV_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("SUSLOV_NO_CACHE", raising=False)
    return tmp_path / "cache"


def test_per_p_results_hit_and_give_the_same_build(tmp_path, cache_dir):
    cold = derive(BuildOptions(pmax=10, jobs=1, cache=True), ["residue"])
    warm = derive(BuildOptions(pmax=10, jobs=1, cache=True), ["residue"])
    assert cold.log.cache_report[0]["from_cache"] == 0 and warm.log.cache_report[0]["from_cache"] == 10
    assert [c.deterministic_record() for c in cold.log.certificates] == \
        [c.deterministic_record() for c in warm.log.certificates]
    write_atomically(cold, tmp_path / "cold")
    write_atomically(warm, tmp_path / "warm")
    assert compare_trees(tmp_path / "cold", tmp_path / "warm") == []
    report = json.loads((tmp_path / "warm" / "cache_report.json").read_text())
    assert report[0]["phase"] == "Frobenius logarithms at t0" and report[0]["from_cache"] == 10


def test_a_source_change_misses(cache_dir, monkeypatch):
    log = CertificateLog(cache=True)
    log.map_per_p("logs", [2, 3], residue.logarithm_verdict)
    before = cache.per_p_key(residue.logarithm_verdict, 2)
    # the key follows the sources: residue imports physical_bodies, so editing it (simulated by a
    # different digest) must change residue's keys, while a module residue does not import must not
    monkeypatch.setattr(cache, "module_digest", lambda name, real=cache.module_digest: real(name) + "x")
    assert cache.per_p_key(residue.logarithm_verdict, 2) != before
    monkeypatch.undo()
    assert "derivations.sections.physical_bodies" in cache._imports("derivations.sections.residue", cache._module_file("derivations.sections.residue"))
    assert "derivations.sections.galois" not in cache._imports("derivations.sections.residue", cache._module_file("derivations.sections.residue"))


def test_corrupt_and_foreign_entries_are_recomputed(cache_dir):
    calls = []
    work = residue.logarithm_verdict
    log = CertificateLog(cache=True)
    first = log.map_per_p("logs", [2, 3], work)
    store = cache.per_p_store()
    key2, key3 = cache.per_p_key(work, 2), cache.per_p_key(work, 3)
    path2 = store.directory / f"{key2}.pkl"
    path2.write_bytes(path2.read_bytes()[:-7])                                  # truncated
    (store.directory / f"{key3}.pkl").write_bytes((store.directory / f"{key3}.pkl").read_bytes()
                                                  .replace(key3.encode(), b"0" * len(key3), 1))   # foreign key
    assert store.get(key2) is None and store.get(key3) is None
    again = CertificateLog(cache=True)
    second = again.map_per_p("logs", [2, 3], lambda p: calls.append(p) or work(p))
    assert sorted(calls) == [2, 3]   # both recomputed
    assert [r[:4] for r in first] == [r[:4] for r in second]


def test_whole_build_from_the_cache_and_no_cache(tmp_path, cache_dir, capsys):
    out = tmp_path / "out"
    assert build_formulas.main(["--pmax", "3", "--out", str(out), "--quiet"]) == 0
    first = {p.name: p.read_bytes() for p in out.iterdir()}
    assert build_formulas.main(["--pmax", "3", "--out", str(out), "--quiet"]) == 0
    assert "from the certificate cache" in capsys.readouterr().out
    for name, data in first.items():
        if name not in ("certificate_costs.json", "certificate_costs.tex", "cache_report.json",
                        "certificate_measurements.json"):
            assert (out / name).read_bytes() == data, name
    # a corrupted cached tree is not trusted: the next build recomputes
    entry = next((cache_dir / "builds").iterdir())
    (entry / "suslov_formulas.py").write_text("# tampered\n")
    assert build_formulas.main(["--pmax", "3", "--out", str(out), "--quiet"]) == 0
    assert "from the certificate cache" not in capsys.readouterr().out
    assert (out / "suslov_formulas.py").read_bytes() == first["suslov_formulas.py"]
    assert build_formulas.main(["--pmax", "3", "--out", str(out), "--quiet", "--no-cache"]) == 0
    assert "from the certificate cache" not in capsys.readouterr().out
