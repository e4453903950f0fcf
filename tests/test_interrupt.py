"""Ctrl-C stops any run within 5 s, leaves the output as it was and no process behind (issue 36).

A build of ``--pmax 201`` (twelve minutes of work) is interrupted 15 s in, a sweep a few seconds in, both
started as a non-interactive shell starts a background job (SIGINT inherited as ignored: the case in
which a ``kill -INT`` used to do nothing).  Every process of the run's session must be gone when it
ends, and the output directory must be absent (a build writes by an atomic swap) or hold only the
sweep's resumable chunk store.
"""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LIMIT = 5.0


def _session_members(sid: int) -> list[str]:
    members = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
                # fields 3 and 6 of /proc/PID/stat: the state (a zombie computes nothing and waits only for
                # its reaper) and the session id
                if int(fields[3]) == sid and fields[0] != "Z":
                    members.append((entry / "cmdline").read_text().replace("\0", " ")[:120])
            except (OSError, IndexError, ValueError):
                continue
    return members


def _interrupt(command: list[str], after: float, env: dict, ignored: bool = True) -> tuple[int, float, list, str]:
    ignore = lambda: signal.signal(signal.SIGINT, signal.SIG_IGN)   # noqa: E731 (as `sh -c 'cmd &'` does)
    process = subprocess.Popen(command, cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True, start_new_session=True, preexec_fn=ignore if ignored else None)
    time.sleep(after)
    assert process.poll() is None, "the run ended before it could be interrupted: " + process.stderr.read()
    process.send_signal(signal.SIGINT)
    start = time.monotonic()
    try:
        process.wait(timeout=60)
    finally:
        if process.poll() is None:
            os.killpg(process.pid, signal.SIGKILL)
    elapsed = time.monotonic() - start
    time.sleep(0.5)   # workers killed by the parent's exit get this long to be reaped
    left = _session_members(process.pid)
    if left:
        os.killpg(process.pid, signal.SIGKILL)
    return process.returncode, elapsed, left, process.stderr.read()


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads sessions from /proc (Linux)")
def test_sigint_stops_a_large_build_within_5_s(tmp_path):
    env = dict(os.environ, SUSLOV_CACHE_DIR=str(tmp_path / "cache"))
    out = tmp_path / "out"
    code, elapsed, left, stderr = _interrupt([sys.executable, "build_formulas.py", "--pmax", "201", "--no-cache",
                                              "--out", str(out)], 15, env)
    assert code == 130, stderr[-2000:]
    assert elapsed < LIMIT, f"took {elapsed:.1f} s to stop"
    assert left == [], left
    assert "interrupted; nothing was replaced" in stderr
    assert not out.exists() or not any(out.iterdir())


SWEEP = """
name = "interrupted"
[sweep]
I11 = 2.0
I22 = 1.0
I33 = 1.5
I13 = {linear = [-0.4, 0.4], count = 61}
I23 = {linear = [-0.4, 0.4], count = 61}
energy = [0.5, 1.0, 2.0]
[effects]
compute = ["scattering_angle", "scattering_angle_integrated"]
"""


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads sessions from /proc (Linux)")
def test_sigint_stops_a_sweep_within_5_s(tmp_path):
    scene, out = tmp_path / "sweep.toml", tmp_path / "out"
    scene.write_text(SWEEP)
    code, elapsed, left, stderr = _interrupt([sys.executable, "-m", "suslov", "simulate", str(scene), "--out", str(out),
                                              "--yes"], 12, dict(os.environ))
    assert code == 130, stderr[-2000:]
    assert elapsed < LIMIT, f"took {elapsed:.1f} s to stop"
    assert left == [], left
    assert "suslov: interrupted" in stderr and not out.exists()


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads sessions from /proc (Linux)")
def test_sigint_stops_load_formulas_and_its_build_within_5_s(tmp_path):
    env = dict(os.environ, SUSLOV_DATA_DIR=str(tmp_path / "store"), SUSLOV_CACHE_DIR=str(tmp_path / "cache"))
    code, elapsed, left, stderr = _interrupt([sys.executable, "-c", "import suslov; suslov.load_formulas(pmax=61)"],
                                             15, env, ignored=False)
    assert code != 0 and "KeyboardInterrupt" in stderr, stderr[-2000:]
    assert elapsed < LIMIT, f"took {elapsed:.1f} s to stop"
    assert left == [], left
    store = tmp_path / "store"
    assert not store.exists() or not [p for p in store.iterdir() if p.name.startswith("pmax-")]
