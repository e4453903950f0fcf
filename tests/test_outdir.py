"""Output directories: refused unless the program's, replaced crash-safely, no leftovers (suslov/outdir.py).

Issue 27, findings 1-3 and 12: the build's ``--out`` deleted a user's directory, turned a file into a
directory and failed on ``.``; a kill inside the rename window lost the output; interrupted runs
left staging directories and live worker processes behind.  The kill test sends SIGKILL at random
instants of a process that swaps trees in a loop and checks, after each kill, that the path holds one
complete tree (the exchange route: at every instant; the journal route: after the next run's
:func:`recover`).
"""
import json
import os
import random
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from suslov import outdir
from suslov.outdir import OutputRefused, claim, recover, remove_stale

ROOT = Path(__file__).resolve().parent.parent
FILES = 20


def user_directory(path: Path) -> dict:
    (path / "sub").mkdir(parents=True)
    (path / "thesis.txt").write_text("three years")
    (path / "sub" / "notes.md").write_text("notes")
    return snapshot(path)


def snapshot(path: Path) -> dict:
    return {str(p.relative_to(path)): p.read_bytes() for p in sorted(path.rglob("*")) if p.is_file()}


def test_foreign_directory_file_and_cwd_are_refused(tmp_path, monkeypatch):
    mine = tmp_path / "mine"
    before = user_directory(mine)
    with pytest.raises(OutputRefused, match="thesis.txt"):
        claim(mine, "tool")
    (tmp_path / "afile").write_text("data")
    with pytest.raises(OutputRefused, match="not a directory"):
        claim(tmp_path / "afile", "tool")
    with pytest.raises(OutputRefused, match="not a directory"):
        claim(tmp_path / "afile" / "out", "tool")
    monkeypatch.chdir(mine)
    with pytest.raises(OutputRefused, match="current directory"):
        claim(".", "tool")
    assert snapshot(mine) == before and (tmp_path / "afile").read_text() == "data"


def test_own_marker_empty_and_new_paths_are_accepted(tmp_path):
    (tmp_path / "empty").mkdir()
    assert claim(tmp_path / "empty", "tool") == tmp_path / "empty"
    assert claim(tmp_path / "a" / "b", "tool") == tmp_path / "a" / "b"
    with outdir.staged(tmp_path / "out", "tool") as staging:
        (staging / "x.txt").write_text("1")
    with outdir.staged(tmp_path / "out", "tool") as staging:   # the tool's own output: replaced
        (staging / "y.txt").write_text("2")
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == [outdir.MARKER, "y.txt"]
    with pytest.raises(OutputRefused):   # another tool's output is not this tool's to replace
        claim(tmp_path / "out", "other")
    legacy = tmp_path / "legacy"
    legacy.mkdir()
    (legacy / "report.md").write_text("old run")
    assert claim(legacy, "tool", signature="report.md") == legacy


def test_outputs_follow_the_umask(tmp_path):
    old = os.umask(0o022)
    try:
        with outdir.staged(tmp_path / "shared" / "out", "tool") as staging:
            (staging / "x.txt").write_text("1")
    finally:
        os.umask(old)
    assert (tmp_path / "shared" / "out").stat().st_mode & 0o777 == 0o755
    assert (tmp_path / "shared").stat().st_mode & 0o777 == 0o755
    assert (tmp_path / "shared" / "out" / "x.txt").stat().st_mode & 0o777 == 0o644


def test_stale_staging_of_dead_processes_is_removed_and_nothing_else(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    target = tmp_path / "out"
    stale = tmp_path / f".out.suslov-new-{dead}-abcd"
    live = tmp_path / f".out.suslov-new-{os.getpid()}-abcd"
    foreign = tmp_path / ".out.mine-123"
    for d in (stale, live, foreign):
        d.mkdir()
        (d / "f").write_text("x")
    recover(target)
    assert not stale.exists() and live.exists() and foreign.exists()
    assert remove_stale(tmp_path, ".out.suslov-new") == []


SWAPPER = textwrap.dedent("""
    import sys
    from pathlib import Path
    from suslov import outdir
    outdir._EXCHANGE_ENABLED = sys.argv[2] == "exchange"
    target, generation = Path(sys.argv[1]), 0
    print("ready", flush=True)
    while True:
        generation += 1
        staging = outdir.new_staging(target, "tool")
        for i in range({files}):
            (staging / f"f{{i}}.txt").write_text(str(generation) * 1000)
        outdir.swap_in(staging, target)
""").format(files=FILES)


def complete_tree(target: Path) -> bool:
    names = sorted(p.name for p in target.iterdir())
    contents = {(target / f"f{i}.txt").read_text() for i in range(FILES) if (target / f"f{i}.txt").exists()}
    return names == sorted([outdir.MARKER] + [f"f{i}.txt" for i in range(FILES)]) and len(contents) == 1


@pytest.mark.parametrize("route", ["exchange", "journal"])
def test_kill_at_random_instants_of_the_swap_leaves_one_complete_tree(tmp_path, route):
    target = tmp_path / "out"
    seeded = random.Random(27)
    script = tmp_path / "swapper.py"
    script.write_text(SWAPPER)
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    interrupted = 0
    for _ in range(12):
        proc = subprocess.Popen([sys.executable, str(script), str(target), route], stdout=subprocess.PIPE, env=env)
        assert proc.stdout.readline().strip() == b"ready"
        time.sleep(seeded.uniform(0.05, 0.4))
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait()
        proc.stdout.close()
        if route == "exchange":
            # at every instant the path holds a complete tree: checked before any recovery
            assert target.is_dir() and complete_tree(target)
        else:
            interrupted += not target.exists()
            recover(target)
            assert target.is_dir() and complete_tree(target)
        leftovers = [p.name for p in tmp_path.iterdir() if p.name not in ("out", "swapper.py")]
        recover(target)
        assert [p.name for p in tmp_path.iterdir() if p.name not in ("out", "swapper.py")] == [], leftovers


def test_journal_recovery_finishes_or_rolls_back(tmp_path):
    target = tmp_path / "out"
    for staging_there, expected in ((True, "finished"), (False, "rolled back")):
        staging, backup = tmp_path / ".out.suslov-new-1-x", tmp_path / ".out.suslov-old-1-y"
        backup.mkdir()
        (backup / "which").write_text("old")
        if staging_there:
            staging.mkdir()
            (staging / "which").write_text("new")
        (tmp_path / ".out.suslov-swap").write_text(json.dumps({"staging": staging.name, "backup": backup.name}))
        assert recover(target) == expected
        assert (target / "which").read_text() == ("new" if staging_there else "old")
        assert not (tmp_path / ".out.suslov-swap").exists()
        import shutil
        shutil.rmtree(target)
        shutil.rmtree(backup, ignore_errors=True)


def run_build(*args, cwd=ROOT):
    return subprocess.run([sys.executable, str(ROOT / "build_formulas.py"), "--quiet", *map(str, args)],
                          cwd=cwd, capture_output=True, text=True)


def test_build_refuses_foreign_out_before_any_work(tmp_path):
    mine = tmp_path / "mine"
    before = user_directory(mine)
    done = subprocess.run([sys.executable, str(ROOT / "build_formulas.py"), "--out", str(mine)],
                          cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 2 and "thesis.txt" in done.stderr and "refusing" in done.stderr
    assert "[1/" not in done.stderr and "certificates" not in done.stderr   # refused before any derivation ran
    assert snapshot(mine) == before
    (tmp_path / "afile").write_text("data")
    done = run_build("--out", tmp_path / "afile")
    assert done.returncode == 2 and (tmp_path / "afile").read_text() == "data"
    done = run_build("--out", ".", cwd=mine)
    assert done.returncode == 2 and "current directory" in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "mine"]   # no staging left anywhere


def test_simulator_refuses_foreign_out_before_any_work(tmp_path, monkeypatch):
    import suslov.simulator.cli
    from suslov.cli import main

    mine = tmp_path / "mine"
    before = user_directory(mine)
    monkeypatch.setattr(suslov.simulator.cli, "simulate", lambda *a, **k: pytest.fail("computed before refusing"))
    assert main(["simulate", str(ROOT / "scenes" / "fig1_omega.toml"), "--out", str(mine), "--quiet"]) == 2
    assert snapshot(mine) == before


WORKERS = textwrap.dedent("""
    import os, time
    from suslov import executor
    if __name__ == "__main__":
        pool = executor._local_pool(2)
        print(" ".join(str(f.result()) for f in [pool.submit(os.getpid) for _ in range(8)]), flush=True)
        time.sleep(60)
""")


def test_workers_die_with_their_parent(tmp_path):
    script = tmp_path / "workers.py"
    script.write_text(WORKERS)
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                            env=dict(os.environ, PYTHONPATH=str(ROOT)))
    workers = {int(pid) for pid in proc.stdout.readline().split()}
    assert workers and proc.pid not in workers
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    proc.stdout.close()
    deadline = time.time() + 120   # a hang guard, not a timing: each worker polls its parent every 0.5 s
    alive = workers
    while alive and time.time() < deadline:
        time.sleep(0.2)
        alive = {pid for pid in alive if Path(f"/proc/{pid}").exists()
                 and "Z" not in Path(f"/proc/{pid}/stat").read_text().split()[2]}
    for pid in alive:   # a failing run (the mutation suite's seeded fault) must not leave them behind either
        os.kill(pid, signal.SIGKILL)
    assert not alive, f"workers {alive} outlived their parent"


def test_cache_and_chunk_leftovers_of_dead_processes_are_removed(tmp_path):
    from derivations.core.cache import TreeCache
    from suslov.executor import TMP_PREFIX, ChunkStore

    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    store = ChunkStore(tmp_path / "per-p")
    (tmp_path / "per-p").mkdir()
    stale_file = tmp_path / "per-p" / f"{TMP_PREFIX}-{dead}-abc"
    stale_file.write_text("half")
    store.put("key", {"x": 1})
    assert store.get("key") == {"x": 1} and not stale_file.exists()
    tree = tmp_path / "tree"
    tree.mkdir()
    (tree / "a.txt").write_text("a")
    (tmp_path / "cache" / "builds").mkdir(parents=True)
    stale_dir = tmp_path / "cache" / "builds" / f"{TMP_PREFIX}-{dead}-key"
    stale_dir.mkdir()
    cache = TreeCache(tmp_path / "cache")
    cache.store("key", tree)
    assert cache.lookup("key") is not None and not stale_dir.exists()
