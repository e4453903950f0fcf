"""One executor for chunks of independent work: local processes by default, a Dask cluster on request.

Used by sweep scenes (:mod:`suslov.simulator.sweep`); the work is a picklable top-level function applied to
each chunk.  Guarantees, whatever runs the chunks:

* **Same results, same order.**  Results come back indexed by chunk, so the caller assembles rows
  in point order; the work function is deterministic (seeds are drawn by the caller, before
  chunking), so local processes, one process and a Dask cluster give identical tables.
* **Resumable.**  With a :class:`ChunkStore`, every finished chunk is written at once (atomically:
  a temporary file renamed into place) under a key that hashes the chunk's inputs and the code
  that computes it; a rerun after an interruption loads what is there and computes only the rest.
  A truncated or foreign file fails its checksum and is recomputed, never trusted.
* **Clear failures.**  An unreachable scheduler is reported within ``CONNECT_TIMEOUT`` seconds
  (:class:`SchedulerError`); Ctrl-C stops the pool and leaves the finished chunks in the store.

Local processes are loky's (``loky.ProcessPoolExecutor``, joblib's pool; ``loky`` start method: a fresh
interpreter per worker, since a forked child would inherit LLVM's state from a parent that already compiled
a Taylor integrator, which is not fork-safe).  loky, not ``concurrent.futures``, because an interrupted run
must end now: ``concurrent.futures`` can only cancel what has not started, and its exit hook then waits
for the running chunks (a Ctrl-C'd ``--pmax 401`` build ran on for 41 minutes), while loky's
``shutdown(kill_workers=True)`` ends them.  The waits poll (``POLL`` seconds) so that a SIGINT which the
kernel delivered to another thread of this process is still handled at once by the main thread.
Workers also ask the kernel to kill them when their parent dies (``PR_SET_PDEATHSIG``, Linux), with a
watching thread as the portable fallback.
"""
from __future__ import annotations

import atexit
import hashlib
import json
import math
import os
import pickle
import signal
import socket
import threading
import time
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, wait
from pathlib import Path

from suslov.interrupts import die_with_parent
from suslov.outdir import make_dir, remove_stale

CONNECT_TIMEOUT = 10.0
POLL = 0.25   # seconds between checks for a pending signal while waiting for workers
TMP_PREFIX = ".suslov-tmp"   # in-flight files: TMP_PREFIX-PID-KEY; those of dead processes are removed
SCHEDULER_ENV = "SUSLOV_SCHEDULER"


class SchedulerError(RuntimeError):
    """The Dask scheduler cannot be reached or is not usable."""


class ChunkStore:
    """Finished results on disk: ``DIR/<key>.<codec>``, a header line ``<key> <sha256>`` and the payload.

    ``key`` must change whenever the result could (inputs, options, code version); the checksum
    covers the payload, so a truncated, edited or foreign file is detected and reads as missing.
    ``codec``: "json" (sweep chunks: plain data, the default) or "pkl" (the build's per-p results,
    which hold certificate records; never unpickled before the checksum matched).
    """

    def __init__(self, directory, codec: str = "json"):
        if codec not in ("json", "pkl"):
            raise ValueError(f"codec={codec!r}: must be 'json' or 'pkl'")
        self.directory, self.codec = Path(directory), codec
        self._swept = False

    def _path(self, key: str) -> Path:
        return self.directory / f"{key}.{self.codec}"

    def _dumps(self, value) -> bytes:
        if self.codec == "json":
            return json.dumps(value, sort_keys=True).encode()
        return pickle.dumps(value, protocol=4)

    def get(self, key: str):
        try:
            header, payload = self._path(key).read_bytes().split(b"\n", 1)
            stored_key, checksum = header.decode().split(" ")
            if stored_key != key or hashlib.sha256(payload).hexdigest() != checksum:
                return None
            return json.loads(payload) if self.codec == "json" else pickle.loads(payload)
        except (OSError, ValueError, UnicodeDecodeError, pickle.UnpicklingError, EOFError, AttributeError):
            return None

    def put(self, key: str, value) -> None:
        payload = self._dumps(value)
        make_dir(self.directory)
        if not self._swept:   # once per store: leftovers of killed runs
            remove_stale(self.directory, TMP_PREFIX)
            self._swept = True
        tmp = self.directory / f"{TMP_PREFIX}-{os.getpid()}-{key}"
        tmp.write_bytes(f"{key} {hashlib.sha256(payload).hexdigest()}\n".encode() + payload)
        tmp.replace(self._path(key))


def default_workers() -> int:
    """Worker processes when none are asked for: the cores this process may run on (:func:`cores`, its CPU
    affinity), so that ``taskset -c 0 python build_formulas.py`` or a container limited to one CPU runs the per-p
    work in line instead of starting processes that only compete for that core (``os.cpu_count()`` counts the
    machine's cores, usable or not)."""
    return cores()


WORKER_MEMORY = 300 * 2**20   # resident memory of one worker with NumPy, mpmath and python-flint (measured: ~160 MB)


def available_memory() -> int | None:
    """Bytes of memory available to new processes (``MemAvailable`` of /proc/meminfo), None where unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def cores() -> int:
    """Cores this process may run on (its affinity mask where the system has one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def worker_limit(requested: int | None, option: str = "--workers") -> tuple[int, str | None]:
    """``(n, message)``: the worker processes to start for ``requested`` (None: all cores), at most the
    cores and what the available memory holds at :data:`WORKER_MEMORY` each (at least 1); ``message``
    says why when ``requested`` was lowered (issue 38: ``--workers 1000`` started 128 processes, 20 GB)."""
    limit, why = cores(), f"{cores()} cores"
    memory = available_memory()
    if memory is not None and memory // WORKER_MEMORY < limit:
        limit = max(1, memory // WORKER_MEMORY)
        why = f"{memory / 2**30:.1f} GB available at about {WORKER_MEMORY / 2**30:.2f} GB per worker"
    if requested is None:
        return limit, None
    if requested <= limit:
        return requested, None
    return limit, f"{option} {requested}: capped at {limit} ({why}); more processes would only compete"


def scheduler_address(cli_value: str | None) -> str | None:
    """The scheduler from ``--scheduler`` or, failing that, the ``SUSLOV_SCHEDULER`` environment variable."""
    return cli_value or os.environ.get(SCHEDULER_ENV) or None


class _Progress:
    """'k/n chunks, elapsed, about T left' lines, at most one a second."""

    def __init__(self, total: int, report: Callable[[str], None] | None):
        self.total, self.report, self.done = total, report, 0
        self.start = self.last = time.perf_counter()
        self.first = None   # when the first chunk finished: the time before it is mostly worker start-up

    def left(self, now: float) -> float | None:
        """Seconds left from the completion rate *after* the first chunk (the start-up of the workers, about
        2 s, made a 2 s study announce 35 s when it was spread over the chunks); None before two chunks."""
        if self.first is None or self.done < 2:
            return None
        return (now - self.first) / (self.done - 1) * (self.total - self.done)

    def tick(self, computed: bool = True):
        self.done += 1
        now = time.perf_counter()
        if self.first is None:
            self.first = now
        if self.report and (now - self.last >= 1.0 or self.done == self.total):
            self.last = now
            left = self.left(now)
            estimate = "estimating" if left is None else f"about {left:.0f} s left"
            self.report(f"chunks {self.done}/{self.total}, {now - self.start:.1f} s, {estimate}")


def run_chunks(work: Callable, chunks: list, keys: list[str], *, store: ChunkStore | None = None,
               scheduler: str | None = None, workers: int | None = None,
               progress: Callable[[str], None] | None = None,
               on_finish: Callable[[int], None] | None = None,
               meanwhile: Callable[[], None] | None = None) -> tuple[list, int]:
    """``[work(c) for c in chunks]`` in chunk order, computing only what ``store`` lacks.

    Returns (results, number of chunks computed now).  ``scheduler`` is a dask.distributed
    address (``tcp://host:port``); otherwise ``workers`` local processes (default: all cores;
    1 runs in this process).  ``on_finish(i)`` is called as chunk i completes (any order).
    ``meanwhile()``, if given, runs exactly once in this process while the workers compute (before
    the chunks when there are no workers), so this process's own work does not leave them idle.
    Used by sweeps (:mod:`suslov.simulator.sweep`) and by the build's per-p certificates
    (``derivations.core.certificates.CertificateLog.map_per_p``).
    """
    results: list = [None] * len(chunks)
    pending = []
    for i, key in enumerate(keys):
        cached = store.get(key) if store is not None else None
        if cached is None:
            pending.append(i)
        else:
            results[i] = cached
    meter = _Progress(len(pending), progress)
    if progress and len(pending) < len(chunks):
        progress(f"resuming: {len(chunks) - len(pending)} of {len(chunks)} chunks already computed")

    def finish(i, value):
        results[i] = value
        if store is not None:
            store.put(keys[i], value)
        meter.tick()
        if on_finish is not None:
            on_finish(i)

    meanwhile = meanwhile or (lambda: None)
    if not pending:
        meanwhile()
        return results, 0
    if scheduler:
        _run_dask(work, chunks, keys, pending, scheduler, finish, meanwhile)
    else:
        workers = worker_limit(workers)[0]   # never more processes than cores or memory hold
        if workers <= 1 or len(pending) == 1:
            meanwhile()
            for i in pending:
                finish(i, work(chunks[i]))
        else:
            _run_local(work, chunks, pending, workers, finish, meanwhile)
    return results, len(pending)


def wait_first(futures) -> set:
    """The futures of ``futures`` that are done, waiting for at least one; returns to the interpreter every
    ``POLL`` seconds so that Ctrl-C is handled even when the kernel delivered it to a helper thread.

    Ctrl-C is never raised *inside* ``concurrent.futures.wait``: that function acquires every future's lock
    in a Python loop, and a KeyboardInterrupt between two acquisitions left locks held for ever, so the
    pool's manager thread, setting the futures' exceptions at shutdown, waited on them and the interrupted
    sweep never exited (seen once in a few runs of tests/test_interrupt.py).  While waiting, SIGINT only
    sets a flag; the program's own handler runs right after."""
    while True:
        done = _wait_deferring_sigint(set(futures))
        if done:
            return done


def _wait_deferring_sigint(futures: set) -> set:
    if threading.current_thread() is not threading.main_thread():
        return wait(futures, timeout=POLL, return_when=FIRST_COMPLETED)[0]
    caught = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(frame))
    try:
        done = wait(futures, timeout=POLL, return_when=FIRST_COMPLETED)[0]
    finally:
        signal.signal(signal.SIGINT, previous)
    if caught:
        if callable(previous):
            previous(signal.SIGINT, caught[0])
        elif previous == signal.SIG_DFL:
            raise KeyboardInterrupt
    return done


class Ahead:
    """Chunks submitted to the local worker processes *now*, collected later (:func:`submit_ahead`).

    The build starts its long numeric certificates (monodromy balls, enclosures) before the symbolic
    derivations and collects them where they are recorded, so the two kinds of work overlap on the
    cores; the results are the ones :func:`run_chunks` would return, in chunk order."""

    def __init__(self, work, chunks, keys, store, workers):
        self.work, self.chunks, self.keys, self.store = work, list(chunks), list(keys), store
        self.results = [store.get(key) if store is not None else None for key in self.keys]
        self.pool = _local_pool(workers)
        self.workers = workers
        self.futures = {self.pool.submit(work, chunk): i for i, chunk in enumerate(self.chunks)
                        if self.results[i] is None}

    def collect(self, on_finish=None) -> tuple[list, int]:
        """(results in chunk order, number computed now): waits for the chunks still running."""
        computed = len(self.futures)
        try:
            while self.futures:
                done = wait_first(self.futures)
                for future in sorted(done, key=self.futures.get):
                    i = self.futures.pop(future)
                    self.results[i] = future.result()
                    if self.store is not None:
                        self.store.put(self.keys[i], self.results[i])
                    if on_finish is not None:
                        on_finish(i)
        except BaseException:
            self.cancel()
            raise
        return self.results, computed

    def cancel(self) -> None:
        """Drop the chunks not collected: a pool with any of them unfinished is killed (no orphan computes on;
        cancelling them one by one first would leave loky's shutdown tripping over cancelled futures)."""
        unfinished = [future for future in self.futures if not future.done()]
        self.futures = {}
        if unfinished:
            _kill(self.workers, self.pool)


def submit_ahead(work: Callable, chunks: list, keys: list[str], *, store: ChunkStore | None = None,
                 workers: int | None = None) -> Ahead:
    """Start ``[work(c) for c in chunks]`` in the kept local worker processes and return at once
    (the chunks ``store`` already holds are not recomputed); :meth:`Ahead.collect` gets the results."""
    return Ahead(work, chunks, keys, store, worker_limit(workers)[0])


_POOLS: dict = {}
LEAK_ALLOWANCE = 4 * 10**9   # bytes a worker may grow before loky restarts it (its default: 3e8)


def _local_pool(workers: int):
    """The process pool for ``workers`` spawned processes, kept for the life of this process.

    Phases that follow each other (the build's residue, meromorphic, galois and round-trip
    phases; sweeps run one after another) reuse warm workers instead of paying the start-up
    (about 2 s of imports per process) every time.  A pool that fails is shut down and forgotten.
    """
    pool = _POOLS.get(workers)
    if pool is None:
        # loky restarts a worker whose memory grew by 300 MB, taking it for a leak; the build's large-p work
        # (the exact basis at p = 201) grows a worker by more than that and keeps its high-water mark without
        # leaking (measured: six bases at p = 101 in one process, RSS 160 MB after the first, 168 MB after each
        # of the others), and each restart re-imports everything: the workers inherit a larger allowance
        os.environ.setdefault("LOKY_MAX_MEMORY_LEAK_SIZE", str(LEAK_ALLOWANCE))
        from loky import ProcessPoolExecutor
        from loky.backend.context import get_context

        pool = _POOLS[workers] = ProcessPoolExecutor(max_workers=workers, context=get_context("loky"),
                                                     initializer=_worker_init, initargs=(os.getpid(),))
    return pool


def _kill(workers: int, pool) -> None:
    """Forget ``pool`` and end its processes now, running chunks included."""
    if _POOLS.get(workers) is pool:
        del _POOLS[workers]
    pool.shutdown(wait=False, kill_workers=True)


# the workers' scheduling priority below their parent's (``nice``): on a machine with as many cores as workers,
# work the parent does meanwhile (the build's symbolic derivations while the workers run prefetched ball checks)
# is its critical path, and at equal priority the workers took a share of its core; work nobody competes
# for runs as fast as before
WORKER_NICENESS = 5


def _worker_init(parent: int) -> None:
    """In each worker: Ctrl-C is the parent's to handle (no traceback per worker), and the worker ends
    itself within half a second once its parent is gone (``kill -9`` of a build or a sweep leaves no
    orphans computing, and with them the resource tracker, whose pipe they hold, ends too); it runs at
    ``WORKER_NICENESS`` below its parent's priority."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    die_with_parent()
    try:
        os.nice(WORKER_NICENESS)
    except (AttributeError, OSError):   # no nice on this platform, or not permitted: equal priority then
        pass

    def watch():
        while os.getppid() == parent:
            time.sleep(0.5)
        os._exit(1)

    threading.Thread(target=watch, name="parent-watch", daemon=True).start()


def release_pools() -> None:
    """End every kept worker process now, without waiting for them (a finished build's workers are idle, and
    loky's own exit hook then joins them at interpreter exit: measured 0.6 s of a 9 s build)."""
    while _POOLS:
        _POOLS.popitem()[1].shutdown(wait=False, kill_workers=True)


@atexit.register
def shutdown_pools() -> None:
    """Stop every kept worker process (at exit, or to release them earlier)."""
    while _POOLS:
        _POOLS.popitem()[1].shutdown(wait=True)


# chunks submitted ahead: enough that the caller's ``meanwhile`` work (the build's serial checks) never
# leaves the workers idle, bounded so that the queue never holds a whole large sweep
IN_FLIGHT = 64


def _run_local(work, chunks, pending, workers, finish, meanwhile):
    pool = _local_pool(workers)
    try:
        queue, futures = iter(pending), {}

        def submit_more():
            for i in queue:
                futures[pool.submit(work, chunks[i])] = i
                if len(futures) >= max(IN_FLIGHT, 4 * workers):
                    return

        submit_more()
        meanwhile()
        while futures:
            for future in sorted(wait_first(futures), key=futures.get):
                finish(futures.pop(future), future.result())
            submit_more()
    except BaseException:
        # an interrupted or failed run leaves no worker behind and no pool in an unknown state
        _kill(workers, pool)
        raise


def check_reachable(address: str, timeout: float = CONNECT_TIMEOUT) -> None:
    """:class:`SchedulerError` at once if nothing listens at ``address`` (``tcp://host:port``)."""
    from urllib.parse import urlsplit

    parts = urlsplit(address if "://" in address else f"tcp://{address}")
    try:
        host, port = parts.hostname, parts.port
    except ValueError:
        host = port = None
    if parts.scheme not in ("tcp", "tls") or not host or not port:
        raise SchedulerError(f"--scheduler {address}: not a scheduler address (expected tcp://host:port)")
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except OSError as exc:
        raise SchedulerError(f"--scheduler {address}: cannot reach a Dask scheduler ({type(exc).__name__}: "
                             f"{exc})") from None


def connect(address: str, timeout: float = CONNECT_TIMEOUT):
    """A ``distributed.Client`` for ``address``, or :class:`SchedulerError` within about ``timeout`` seconds.

    The client is built in a daemon thread with a deadline: a port that accepts connections but
    does not speak Dask's protocol (a proxy answering HTTP, say) would otherwise fail late or hang.
    """
    check_reachable(address, timeout)
    try:
        from distributed import Client
    except ImportError as exc:
        raise SchedulerError(f"--scheduler {address}: dask.distributed is not importable ({exc}); "
                             "pip install 'suslov-certified[dask]'") from None
    outcome: dict = {}

    def attempt():
        try:
            outcome["client"] = Client(address, timeout=f"{math.ceil(timeout)}s", set_as_default=False)
        except BaseException as exc:   # anything the handshake raises becomes one clear error below
            outcome["error"] = exc

    thread = threading.Thread(target=attempt, name="suslov-dask-connect", daemon=True)
    thread.start()
    thread.join(timeout + 1.0)
    if "client" in outcome:
        return outcome["client"]
    reason = outcome.get("error")
    if reason is not None:
        _discard_half_built_clients(reason, Client)
    why = f"{type(reason).__name__}: {reason}" if reason is not None else f"no answer within {timeout:g} s"
    raise SchedulerError(f"--scheduler {address}: something listens there but does not answer as a Dask "
                         f"scheduler ({why})"[:400])


def _discard_half_built_clients(error: BaseException, client_type) -> None:
    """Close the Client a failed handshake left behind, quickly.

    Its finaliser would otherwise wait twice the connect timeout at interpreter exit for a
    scheduler that never answered; the half-built client is found in the traceback's frames.
    """
    tb = error.__traceback__
    while tb is not None:
        for value in list(tb.tb_frame.f_locals.values()):
            if isinstance(value, client_type):
                try:
                    value.close(timeout=1)
                except Exception:   # the loop may be dead already: marking it closed is what matters
                    pass
                value.status = "closed"
        tb = tb.tb_next


def _run_dask(work, chunks, keys, pending, address, finish, meanwhile):
    from distributed import as_completed

    client = connect(address)
    try:
        futures = [client.submit(work, chunks[i], key=f"suslov-{keys[i]}", pure=False) for i in pending]
        meanwhile()
        index = {f.key: i for f, i in zip(futures, pending)}
        for future in as_completed(futures, loop=client.loop):
            finish(index[future.key], future.result())
    finally:
        client.close()
