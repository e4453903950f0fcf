"""``suslov simulate SCENE --out DIR [--explain] [--workers N] [--scheduler ADDRESS]``: a thin layer over
``suslov.simulate`` (:mod:`suslov.simulator.api`).

The parser is :mod:`suslov.cli` (the ``suslov`` command, also ``python -m suslov``).  A sweep scene
(``[sweep]``) runs its points in chunks on local processes (``--workers``, default all cores) or on a
dask.distributed cluster (``--scheduler tcp://host:port``, or the environment variable
``SUSLOV_SCHEDULER``); an interrupted sweep resumes from its finished chunks.

Exit codes: 0 success, 2 bad input (scene file, output directory, a missing extra), 1 a
computation failed, 130 interrupted.  Errors are one line naming the file, the field and the
reason; nothing is written to ``--out`` unless the whole scene succeeded.  The [sim] extra (SciPy, heyoka,
matplotlib, loky) is asked for per scene, by what its plan needs (:func:`suslov.simulator.api.check_extras`): a
scene of closed forms, balls and exact decisions without figures runs on the core install (NumPy, mpmath,
python-flint).
"""
from __future__ import annotations

import sys
from pathlib import Path

from suslov.executor import TMP_PREFIX, SchedulerError, scheduler_address, worker_limit
from suslov.interrupts import listen_for_interrupts
from suslov.outdir import OutputRefused, discard_own, write_failure
from suslov.simulator.api import check_extras, simulate
from suslov.simulator.outputs import check_out
from suslov.simulator.planner import make_plan
from suslov.simulator.scene import SceneError, load_scene
from suslov.simulator.sweep import LargeSweep, chunk_dir, plan_sweep


def simulate_command(args) -> int:
    """Run ``suslov simulate`` with the parsed ``args`` (:func:`suslov.cli.parser`)."""
    listen_for_interrupts()
    if args.workers is not None and args.workers < 1:
        print(f"suslov: error: --workers {args.workers}: must be at least 1", file=sys.stderr)
        return 2
    if args.workers is not None:
        args.workers, capped = worker_limit(args.workers)
        if capped:
            print(f"suslov: note: {capped}", file=sys.stderr)
    progress = None if args.quiet else (lambda msg: print(msg, file=sys.stderr, flush=True))
    try:
        scene = load_scene(args.scene)
        if scene.is_sweep:
            return _sweep(scene, args, progress)
        try:
            plan = make_plan(scene)
        except ValueError as exc:
            raise SceneError(scene.path, "body", str(exc)) from None
    except SceneError as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    if args.explain:
        print(plan.explain())
        return 0
    if not args.out:
        print("suslov: error: --out DIR is required (or --explain)", file=sys.stderr)
        return 2
    try:
        check_extras(f"suslov simulate {scene.path}", scene, plan)
    except ModuleNotFoundError as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    try:
        check_out(args.out)
    except OutputRefused as exc:
        print(f"suslov: error: --out {exc}", file=sys.stderr)
        return 2
    files = []
    try:
        status = _guarded(f"scene {scene.path}",
                          lambda: files.extend(simulate(scene, out=args.out, progress=progress).files), args.out)
    except KeyboardInterrupt:
        print("suslov: interrupted; nothing was written", file=sys.stderr)
        return 130
    if status == 0 and progress:
        progress(f"wrote {len(files)} files to {args.out}")
    return status


def _guarded(what: str, action, out) -> int:
    """Run ``action``; map bad output directories (``out``) and schedulers to 2, failed computations to 1."""
    try:
        action()
    except (OutputRefused, SchedulerError, LargeSweep) as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:   # the output cannot be written (read-only file system, disk full): bad output place
        # one line naming the path (the file the system named, else --out) and the reason; the output is staged
        # and swapped in whole (suslov.outdir), so a previous output at --out is unchanged
        kept = f" (the previous output {out} is unchanged)" if Path(out).is_dir() else ""
        print(f"suslov: error: {what}: cannot write the output: {write_failure(exc, out)}; nothing was written{kept}",
              file=sys.stderr)
        return 2
    except (RuntimeError, ArithmeticError, ValueError) as exc:
        print(f"suslov: error: {what}: computation failed: {exc}", file=sys.stderr)
        return 1
    return 0


def _sweep(scene, args, progress) -> int:
    scheduler = scheduler_address(args.scheduler)
    if args.explain:
        print(plan_sweep(scene, args.workers, scheduler).explain())
        return 0
    if not args.out:
        print("suslov: error: --out DIR is required (or --explain)", file=sys.stderr)
        return 2
    try:
        args.workers = check_extras(f"suslov simulate {scene.path}", scene, workers=args.workers, scheduler=scheduler)
    except ModuleNotFoundError as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    outcome = []
    try:
        status = _guarded(f"sweep {scene.path}", lambda: outcome.append(
            simulate(scene, out=args.out, scheduler=scheduler, workers=args.workers, progress=progress,
                     confirmed=args.yes)), args.out)
    except KeyboardInterrupt:
        print(f"suslov: interrupted: {_kept(chunk_dir(Path(args.out)))}", file=sys.stderr)
        return 130
    if status:
        _tidy_chunks(chunk_dir(Path(args.out)))
    if status == 0 and progress:
        progress(f"sweep of {len(scene.sweep)} points done in {outcome[0].steps[0]['seconds']:.1f} s; "
                 f"wrote {args.out}")
    return status


def _tidy_chunks(chunks: Path) -> None:
    """After a failed sweep (a full disk): no half-written chunk file of this run, no empty chunk store; the
    finished chunks stay for the resumed run."""
    if not chunks.is_dir():
        return
    discard_own(chunks, TMP_PREFIX)
    try:
        chunks.rmdir()   # only when empty
    except OSError:
        pass


def _kept(chunks: Path) -> str:
    """One line saying what an interrupted sweep kept (the resumable chunks, or nothing)."""
    kept = len(list(chunks.glob("*.json"))) if chunks.is_dir() else 0
    if kept == 0:
        return "no chunk had finished; nothing was kept"
    return f"{kept} finished chunk{'s' if kept > 1 else ''} kept in {chunks}; run the same command again to resume"

