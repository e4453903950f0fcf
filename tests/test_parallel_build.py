"""Per-p certificates through the simulator's executor (issues 13 and 15): same log, same files.

The build's per-p work (Frobenius logarithms at t0, logarithms at s1..s4) runs through
``suslov.executor`` like a sweep: in this process, in local worker processes, or on a Dask
cluster.  Whatever ran it, the certificate log and every output must be identical.
"""
import pytest

from derivations.core.options import BuildOptions
from derivations.output.pipeline import compare_trees, derive, write_atomically
from derivations.sections import meromorphic


def records(build):
    return [c.deterministic_record() for c in build.log.certificates]


def test_per_p_work_is_identical_in_one_process_and_in_workers(tmp_path):
    serial = derive(BuildOptions(pmax=10, jobs=1), ["residue"])
    parallel = derive(BuildOptions(pmax=10, jobs=2), ["residue"])
    assert records(serial) == records(parallel)
    assert sum(1 for c in serial.log.certificates if c.label == "Theorem 3.5" and c.claim.startswith("p = ")) >= 10
    write_atomically(serial, tmp_path / "serial")
    write_atomically(parallel, tmp_path / "parallel")
    assert compare_trees(tmp_path / "serial", tmp_path / "parallel") == []


def test_per_p_work_on_a_dask_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    serial = derive(BuildOptions(pmax=10, jobs=1), ["residue"])
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, host="127.0.0.1", dashboard_address=None,
                                  processes=True) as cluster:
        remote = derive(BuildOptions(pmax=10, scheduler=cluster.scheduler_address), ["residue"])
    assert records(serial) == records(remote)


def test_jobs_must_be_positive():
    with pytest.raises(ValueError, match="jobs=0"):
        BuildOptions(jobs=0)


def test_bases_beyond_15_are_left_to_the_round_trip_and_certified_without_one():
    """p = 17..31: the meromorphic derivation checks only genhip there (in workers) and leaves the bases pending,
    with the sigma of its general certificate; a build that emits no module certifies them from the recipe
    (``certify_pending``, in workers), completing the rows.  The logs are the same in one process and in
    workers, and the rows' term counts are those of the basis constructed here, in this process."""
    serial = derive(BuildOptions(pmax=31, jobs=1), ["meromorphic"])
    parallel = derive(BuildOptions(pmax=31, jobs=2), ["meromorphic"])
    assert records(serial) == records(parallel)
    exports = parallel.results["meromorphic"].exports
    assert "digests" not in exports and exports["pending"] == list(range(17, 32, 2))
    assert sorted(exports["objects"]) == list(range(1, 16, 2))
    later = [row for row in exports["rows"] if row["p"] > 15]
    assert [row["p"] for row in later] == list(range(17, 32, 2))
    assert all(row["sigma"] == -1 and len(row["certificates"]) == 1 and row["terms"] == [] for row in later)
    theorem = [c for c in parallel.log.certificates if c.claim.startswith("for every odd p")]
    assert len(theorem) == 1 and theorem[0].label == "asymp" and theorem[0].derivation == "meromorphic"
    for build in (serial, parallel):
        meromorphic.certify_pending(build.log, build.results["meromorphic"])
        assert build.results["meromorphic"].exports["pending"] == []
    assert records(serial) == records(parallel)
    rows = {row["p"]: row for row in exports["rows"]}
    by_key = {c.key: c for c in parallel.log.certificates}
    for p in (17, 31):
        real, cplx = meromorphic.construct(p)
        assert rows[p]["terms"] == [len(m) for m in real.M + cplx.M]
        labels = [by_key[k].label for k in rows[p]["certificates"]]
        assert labels == ["pol_sol", "eq:gam3", "F_23_pol", "eq:ps", "gam1, gam2, gam3", "asymp"]
        assert all(by_key[k].derivation == "meromorphic" and by_key[k].claim.startswith(f"p = {p}:")
                   for k in rows[p]["certificates"])


def test_round_trip_refuses_an_emitted_core_with_another_fingerprint():
    """The fingerprint by which a worker's float-path check of a kept basis takes the emitted core's numerators
    (``float_check``: the certified ones are in the main process): the committed module's core at p = 17 matches
    the fingerprint of the basis constructed here and is refused against any other."""
    from pathlib import Path

    from derivations.core.certificates import (
        CertificateLog,
        CertificationFailure,
        Outcome,
    )
    from derivations.output import roundtrip

    generated = Path(__file__).resolve().parent.parent / "generated"
    module = roundtrip.load_module(generated)
    real, cplx = meromorphic.construct(17)
    right = meromorphic.numerators_digest(real.M, cplx.M)
    cert, numerators = roundtrip.basis_core_by_digest(module, 17, right)
    assert cert.outcome is Outcome.PASS and "SHA-256" in cert.method and numerators == (real.M, cplx.M)
    wrong = meromorphic.numerators_digest(cplx.M, real.M)      # the same polynomials, in another order
    assert roundtrip.basis_core_by_digest(module, 17, wrong)[0].outcome is Outcome.FAIL
    with pytest.raises(CertificationFailure):                  # and recorded, it stops the build
        CertificateLog().record(roundtrip.basis_core_by_digest(module, 17, wrong)[0])


def test_round_trip_float_checks_are_identical_in_workers_and_in_one_process(default_build, tmp_path):
    """The round trip's float-path checks run in the worker processes while this process certifies the emitted
    formulas and the cores (``roundtrip.float_check``); recorded in their order, they make the log that one
    process makes with the checks in line (``float_paths.certify``), certificate for certificate."""
    from derivations.core.certificates import CertificateLog
    from derivations.output import float_paths, roundtrip
    from derivations.output.pipeline import render_into

    render_into(default_build, tmp_path, only=("__init__.py", "suslov_formulas.py"))
    logs = {jobs: CertificateLog(workers=jobs) for jobs in (1, 2)}
    for log in logs.values():
        roundtrip.certify_module(log, default_build, tmp_path)
    in_line, in_workers = ([c.deterministic_record() for c in log.certificates] for log in logs.values())
    assert in_line == in_workers
    # every check of the task list ran: the per-p gamma_basis proofs of every kept p among them
    module = roundtrip.load_module(tmp_path)
    names = [name for name, _ in float_paths.tasks(module, default_build)]
    assert names.count("gamma_basis") == len(module.BASIS_PS) and names.count("first_integral") == len(module.INTEGRAL_PS)
    assert sum(1 for c in in_workers if c["claim"].startswith("p = ") and "gamma_basis" in c["claim"]) >= 2 * len(module.BASIS_PS)


def test_a_fault_only_a_float_check_sees_stops_the_round_trip_in_workers_too(default_build, tmp_path):
    """A tree whose module says sigma = +1 for p = 3 (the certified sigma is -1) passes the exact checks of this
    process; the gamma_basis check finds it in the workers, and the round trip names it as one process does."""
    import shutil
    from pathlib import Path

    from derivations.output.roundtrip import verify

    tree = tmp_path / "tree"
    shutil.copytree(Path(__file__).resolve().parent.parent / "generated", tree)
    module = tree / "suslov_formulas.py"
    text = module.read_text(encoding="utf-8")
    assert text.count("_BASIS_SIGMA = {1: -1, 3: -1,") == 1
    module.write_text(text.replace("_BASIS_SIGMA = {1: -1, 3: -1,", "_BASIS_SIGMA = {1: -1, 3: 1,"), encoding="utf-8")
    in_workers, in_line = verify(default_build, tree, jobs=2), verify(default_build, tree, jobs=1)
    assert in_workers is not None and in_workers.startswith("p = 3: gamma_basis_mp")
    assert in_workers == in_line


def test_a_certificate_from_a_worker_prints_its_ring_as_made():
    """Certificates come back from the worker processes pickled: a method naming Q[x,d,i]/(i^2+1) (i the imaginary
    unit, the relation kept unevaluated) printed Q[x, d, i]/(0) after the trip (builds beyond p = 40)."""
    import pickle

    from derivations.core.statement import Statement, ring, say
    from derivations.sections.meromorphic_ring import DOMAIN

    for statement in (Statement("exact zero test in ", ring(DOMAIN)), say("exact zero test in $Q[x,d,i]/(i^2+1)$"),
                      say("in $Q(p,d,P0)[i]/(i^2+1)$")):
        back = pickle.loads(pickle.dumps(statement))
        assert back == statement and back.text() == statement.text() and back.tex() == statement.tex()
        assert "(i**2 + 1)" in back.text() and "/(0)" not in back.text()
