"""Per-p certificates through the simulator's executor (issues 13 and 15): same log, same files.

The build's per-p work (Frobenius logarithms at t0, logarithms at s1..s4) runs through
``suslov.executor`` like a sweep: in this process, in local worker processes, or on a Dask
cluster.  Whatever ran it, the certificate log and every output must be identical.
"""
import pytest

from derivations import meromorphic
from derivations.options import BuildOptions
from derivations.pipeline import compare_trees, derive, write_atomically


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


def test_bases_beyond_15_come_back_from_workers_intact(tmp_path):
    """p = 17..31: the meromorphic bases are certified in workers and their numerators rebuilt here;
    the round trip of the emitted module (which compares its exact cores with these numerators for
    every p) and the log are the same as in one process."""
    serial = derive(BuildOptions(pmax=31, jobs=1), ["meromorphic"])
    parallel = derive(BuildOptions(pmax=31, jobs=2), ["meromorphic"])
    assert records(serial) == records(parallel)
    objects = parallel.results["meromorphic"].exports["objects"]
    assert sorted(objects) == list(range(1, 32, 2))
    for p in (17, 31):   # rebuilt from the workers' dicts == constructed here, in this process
        real, cplx = meromorphic.construct(p)
        assert list(objects[p][0]) == list(real.M) and list(objects[p][1]) == list(cplx.M)
