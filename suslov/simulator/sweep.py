"""Sweep scenes: the scattering angle (paper section 5.1, Theorem 5.4, eq:o12) over many bodies and energies.

A sweep scene (:mod:`suslov.simulator.sweep_spec`) names points; each point is a body.  The method per
point comes from the planner's provider table (:func:`suslov.simulator.planner.point_steps`): for
``scattering_angle`` the closed form of Theorem 5.4 when I13 = 0 and the closed form of every body
(``general_scattering_angle``) otherwise, never an integration; for ``scattering_angle_integrated``
(the cross-check) Taylor integration of the ss solution (SciPy on request) at every point; for
``scattering_angle_enclosure`` a ball of the closed form of every body.  The exact effects (``galois_group``,
``scattering_angle_enclosure``) are for the point's numbers as written (:mod:`suslov.simulator.exact`: a
decimal string in the scene or a CSV cell exactly, a float its binary value), never for the det-normalised
float entries of the numerics; their ``_method`` column says which.  Points are cut into chunks and run by
:mod:`suslov.executor` (local processes or Dask); finished chunks are kept beside the output
directory (``.NAME.chunks``) until the whole sweep succeeded, so an interrupted sweep resumes.

The scattering angle of a general body (I13 != 0) is the spatial angle between the limit
positions of the body axis ``n = u/|u|`` about which the body rotates at t -> -oo and t -> +oo:
with gamma the ss solution (gamma(-oo) = -n), ``cos(Delta psi) = -<gamma(+oo), n>``.  For I13 = 0
this is Theorem 5.4's angle, ``scattering_angle(p, d)``; for every body the closed form and the
integration agree (both checked in tests/test_sweep.py).

Output (written atomically into ``--out``): ``results.csv`` (``results.parquet`` too when pyarrow
is importable) with one row per point in point order: the input columns, one column per scalar
effect, ``<effect>_error`` (the error estimate or the ball's radius), ``<effect>_method``,
``energy_spread`` (largest difference of the angle between the energies of one body, when the
sweep lists several energies: of ``scattering_angle_integrated`` when the sweep asks for it, else of
``scattering_angle``, whose closed forms never see the energy, so that spread is 0) and ``error``
(why a point was refused; empty otherwise); the
figures; ``results.json`` (summary) and ``report.md``.
"""
from __future__ import annotations

import hashlib
import json
import math
import os
import shutil
import time
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import suslov.executor as executor
from suslov.loader import gf
from suslov.simulator import exact
from suslov.simulator.body import make_body
from suslov.simulator.engine import general_angle, numeric_angle
from suslov.simulator.exact import from_pd, from_tensor
from suslov.simulator.planner import point_steps
from suslov.simulator.sweep_cost import output_seconds
from suslov.simulator.sweep_outputs import columns_of, spread_source, write_sweep_outputs
from suslov.simulator.sweep_spec import tensor_of

SAMPLE_FOR_EXPLAIN = 20_000
# seconds per point and step (evaluate_point, warm, one process) on the 2-core machine under load 3, rounded up:
# Theorem 5.4 48 us, the closed form of every body 158 us, a refused point 37 us, Taylor with the closed form
# 511 us, the exact Galois group 174-247 us, the ball 274 us (issue 44; the last two were 0.3 s when they were
# monodromy balls).  --explain and --quiet use them; a sweep with progress lines times its own points.
COST = {"galois_monodromy": 3e-4, "local_behaviour": 2e-4, "angle_closed_form": 5e-5, "angle_general_closed_form": 2e-4,
        "angle_integrate:taylor": 5e-4, "angle_integrate:scipy": 2.0, "angle_enclosure": 4e-4, "refused": 4e-5}
CALIBRATION_SECONDS = 1.5   # at most this long timing sample points before a sweep with progress lines
CALIBRATION_POINTS = 3      # timed per class of points at least (budget allowing) ...
CALIBRATION_MAX = 50        # ... and up to this many while a class has taken less than CALIBRATION_CLASS seconds:
CALIBRATION_CLASS = 0.1     # three calls of 50 us time the clock and the caches, not the point
WORKER_START = 1.0   # seconds to start a worker process (imports 0.4 s, Taylor compilation 0.5 s)
ENCLOSURE_DIGITS = 15
GALOIS_DIGITS = 20
# the galois_group column: 0 solvable in Liouvillian functions (reducible), 1 not (SO(3,C)), NaN not decided
GALOIS_CODES = {"reducible": 0.0, "SO(3,C)": 1.0, "unknown": math.nan, "imprimitive": 0.0, "finite": 0.0}
# the local_behaviour column (at the poles of omega): 0 meromorphic, 1 logarithmic, 2 branching
LOCAL_CODES = {"meromorphic": 0.0, "logarithmic": 1.0, "branching": 2.0}


@dataclass
class SweepPlan:
    scene: object
    classes: dict          # tuple of step names (or ("refused",)) -> number of points
    sampled: bool
    chunk: int
    chunks: int
    workers: int
    scheduler: str | None
    measured: dict | None = None   # class -> seconds per point, timed on sample points (measure_costs)
    startup: float = WORKER_START  # seconds before a worker's first chunk finishes its first point
    free_cores: float | None = None   # cores not busy with other work when measured (os.getloadavg)
    outputs: bool = True   # the outputs are written (suslov simulate --out): their cost is part of the estimate
    classified: dict | None = None   # point index -> its class, for the points plan_sweep classified (its sample)

    def point_cost(self, steps: tuple) -> float:
        if self.measured and steps in self.measured:
            return self.measured[steps]
        return sum(COST[_cost_key(s, self.scene.method)] for s in steps)

    def compute_estimate(self) -> float:
        """Seconds to compute the points (in parallel on the workers), worker start-up included."""
        total = 0.0
        for steps, count in self.classes.items():
            total += count * self.point_cost(steps)
        parallel = 1 if self.scheduler else self.workers
        if self.free_cores is not None and not self.scheduler:
            parallel = max(1.0, min(parallel, self.free_cores))
        return total / parallel + (self.startup if self.workers > 1 or self.scheduler else 0.0)

    def output_estimate(self) -> float:
        """Seconds to write the outputs in this process (:mod:`suslov.simulator.sweep_cost`); 0 without outputs.
        The figures' undefined cells dominate a sweep of refused points (60x the computation, issue 44)."""
        return output_seconds(self.scene, self.classes.get(("refused",), 0)) if self.outputs else 0.0

    def estimate(self) -> float:
        """Seconds of the whole sweep from here: computing the points, then writing the outputs."""
        return self.compute_estimate() + self.output_estimate()

    def estimate_text(self) -> str:
        """"about 12.3 s", with its parts when writing the outputs takes half a second and a fifth of the computing
        or more."""
        compute, output = self.compute_estimate(), self.output_estimate()
        shown = output >= max(0.5, 0.2 * compute)
        parts = f" (computing {compute:.1f} s, writing the outputs {output:.1f} s)" if shown else ""
        return f"about {compute + output:.1f} s{parts}"

    def explain(self) -> str:
        sw = self.scene.sweep
        axes = ", ".join(f"{c} ({len(np.unique(sw.values[:, i]))})" for i, c in enumerate(sw.columns)
                         if len(np.unique(sw.values[:, i])) > 1) or "one point"
        lines = [f"scene {self.scene.name!r} ({self.scene.path})",
                 f"sweep: {len(sw)} points ({'grid over ' + axes if sw.source == 'grid' else sw.source})",
                 f"effects: {', '.join(self.scene.effects)}",
                 "point classes (steps per point from the effect graph)"
                 + (f", estimated from a sample of {SAMPLE_FOR_EXPLAIN}" if self.sampled else "") + ":"]
        for steps, count in sorted(self.classes.items(), key=lambda kv: -kv[1]):
            lines.append(f"  {count} points: {' + '.join(steps)}")
        where = (f"Dask scheduler {self.scheduler}" if self.scheduler
                 else f"local processes, {self.workers} worker{'s' if self.workers > 1 else ''}")
        lines.append(f"executor: {where}; {self.chunks} chunks of up to {self.chunk} points")
        lines.append(f"estimated cost: {self.estimate_text()}")
        return "\n".join(lines)


def _cost_key(step: str, method: str) -> str:
    if step == "angle_integrate":
        return "angle_integrate:taylor" if method == "taylor" else "angle_integrate:scipy"
    return step


def _options(scene) -> dict:
    return {"effects": list(scene.effects), "method": scene.method, "kind": scene.sweep.kind,
            "columns": list(scene.sweep.columns)}


EXACT_EFFECTS = ("galois_group", "scattering_angle_enclosure", "local_behaviour")


def point_body(point: dict, kind: str, with_exact: bool = False, written: dict | None = None):
    """The body of one sweep point; ValueError (with the reason) when it cannot be a body.

    ``with_exact``: also the body as written (``body.exact``, :mod:`suslov.simulator.exact`), the exact effects'
    body: the point's numbers as written (``written``: column -> the string the scene or the CSV gave, where
    one did) or else its float64 values, exactly (their binary values)."""
    numbers = dict(point, **{k: v for k, v in (written or {}).items() if v is not None})
    if kind == "pd":
        body = from_pd(numbers["p"], numbers["d"]) if with_exact else None
        return make_body(None, point["p"], point["d"], point.get("energy"), exact=body)
    body = from_tensor(tensor_of(numbers, exact=True)) if with_exact else None
    return make_body(tensor_of(point), energy=point.get("energy"), exact=body)


def classify(point: dict, options: dict) -> tuple:
    try:
        body = point_body(point, options["kind"])
    except ValueError:
        return ("refused",)
    return tuple(point_steps(options["effects"], SimpleNamespace(method=options["method"]), body))


def plan_sweep(scene, workers: int | None = None, scheduler: str | None = None) -> SweepPlan:
    """Classes of points, chunking and cost (no integration: bodies are built, nothing more)."""
    sw, options = scene.sweep, _options(scene)
    n = len(sw)
    index = np.arange(n)
    sampled = n > SAMPLE_FOR_EXPLAIN
    if sampled:
        index = np.sort(np.random.default_rng(0).choice(n, SAMPLE_FOR_EXPLAIN, replace=False))
    classes: dict = {}
    classified = {int(i): classify(sw.point(int(i)), options) for i in index}
    for key in classified.values():
        classes[key] = classes.get(key, 0) + 1
    if sampled:
        classes = {k: round(v * n / len(index)) for k, v in classes.items()}
    auto = workers is None
    workers = executor.default_workers() if auto else max(1, workers)
    plan = SweepPlan(scene, classes, sampled, 1, 1, 1, scheduler, classified=classified)
    if auto and not scheduler and plan.compute_estimate() < 2 * WORKER_START:
        workers = 1   # starting processes would cost more than the work
    parallel = 4 if scheduler else workers
    chunk = sw.chunk or max(min(n, 16), min(2000, math.ceil(n / (8 * parallel))))
    return SweepPlan(scene, classes, sampled, chunk, math.ceil(n / chunk), workers, scheduler, classified=classified)


def _angle(body, steps, point):
    """(angle, error, method) by the closed form the effect graph chose: Theorem 5.4 or that of every body."""
    if "angle_closed_form" in steps:
        # a (p, d) point is evaluated at its own p, d (the body's are recomputed from a tensor, to rounding)
        p, d = (point["p"], point["d"]) if "p" in point else (body.p, body.d)
        return float(gf.scattering_angle(p, d)), 1e-13 * math.pi, "closed form (Theorem 5.4)"
    angle, bound = general_angle(body)
    return angle, bound, "closed form of every body (Gauss's equation in s = sinh t)"


def _integrated(body, method):
    """(angle, error estimate, method) by integrating ss: the cross-check, the one-body scenes' integrator."""
    angle, error, _ = numeric_angle(SimpleNamespace(method=method), body)
    return angle, error, ("heyoka Taylor" if method == "taylor" else "SciPy DOP853") + " (ss, lam t = 40)"


def _columns(effect: str, value, error, method) -> dict:
    return {effect: value, f"{effect}_error": error, f"{effect}_method": method}


def evaluate_point(point: dict, options: dict, written: dict | None = None) -> dict:
    """The scalar effects of one point; a point that is not a body gets its reason in ``error``.

    The exact effects (galois_group, scattering_angle_enclosure, local_behaviour) are computed for the point's numbers as
    written (``written``, else its float64 values, exactly): never for the det-normalised float entries."""
    try:
        body = point_body(point, options["kind"], any(e in EXACT_EFFECTS for e in options["effects"]), written)
    except ValueError as exc:
        return {"error": f"refused: {exc}"}
    steps = point_steps(options["effects"], SimpleNamespace(method=options["method"]), body)
    row: dict = {}
    try:
        if "scattering_angle" in options["effects"]:
            row |= _columns("scattering_angle", *_angle(body, steps, point))
        if "angle_integrate" in steps:
            row |= _columns("scattering_angle_integrated", *_integrated(body, options["method"]))
        if "galois_monodromy" in steps:
            result = exact.galois_group(body.exact)   # exact: Kimura's theorem on the body's Gauss equation
            row |= {"galois_group": GALOIS_CODES[result.group], "galois_group_error": 0.0,
                    "galois_group_method": f"{result.group} (exact: Kimura's theorem, {_whose(body.exact)})"}
        if "local_behaviour" in steps:
            decided = exact.local_behaviour(body.exact)   # exact: the meromorphy theorem for every p
            row |= {"local_behaviour": LOCAL_CODES[decided.kind], "local_behaviour_error": 0.0,
                    "local_behaviour_method": f"{decided.kind} (exact: the meromorphy theorem, {_whose(body.exact)})"}
        if "angle_enclosure" in steps:
            ball = exact.enclosure(body.exact, dps=ENCLOSURE_DIGITS).angle
            row |= {"scattering_angle_enclosure": float(ball.mid()),
                    "scattering_angle_enclosure_error": float(ball.rad()),
                    "scattering_angle_enclosure_method": "closed form of every body in ball arithmetic, "
                                                         f"{_whose(body.exact)} (rigorous)"}
    except (RuntimeError, ArithmeticError, ValueError) as exc:
        return {"error": f"failed: {type(exc).__name__}: {exc}"}
    return row


def _whose(body) -> str:
    """Which body an exact column is for, short (one CSV cell)."""
    if body.floats:
        return "for the point's float64 entries (their binary values, not the decimals they print as)"
    return "for the point's numbers as written (exact)"


def evaluate_chunk(task) -> list:
    """Executor work: ``task = (options, rows)`` or ``(options, rows, written)``, rows as lists of floats in
    ``options['columns']`` order, ``written`` the strings the cells were written as (``Sweep.written``)."""
    options, rows = task[0], task[1]
    written = task[2] if len(task) > 2 else [None] * len(rows)
    columns = options["columns"]
    return [evaluate_point(dict(zip(columns, row)), options, None if w is None else dict(zip(columns, w)))
            for row, w in zip(rows, written)]


def _code_version() -> str:
    """A hash of the code a chunk's result depends on (the runtime and the generated module)."""
    root = Path(__file__).resolve().parents[1]   # the whole suslov package (simulator, runtime, kernel)
    files = sorted(root.rglob("*.py")) + [Path(gf.__file__).resolve()]
    digest = hashlib.sha256()
    for f in files:
        digest.update(f.name.encode() + f.read_bytes())
    return digest.hexdigest()[:16]


class ChunkTasks:
    """The chunks of a sweep as a lazy sequence: ``tasks[i] = (options, rows)`` is built when asked for.

    Rows are never materialised as Python lists for the whole sweep (a 10^7-point sweep spent 40 s
    and 3.8 GB that way before its first chunk); the executor asks for a chunk when it submits it.
    """

    def __init__(self, scene, chunk: int):
        self.options, self.values, self.chunk = _options(scene), scene.sweep.values, chunk
        self.written = scene.sweep.written

    def __len__(self) -> int:
        return math.ceil(len(self.values) / self.chunk)

    def __getitem__(self, i: int):
        if not 0 <= i < len(self):
            raise IndexError(i)
        rows = self.values[i * self.chunk:(i + 1) * self.chunk].tolist()
        if self.written is None:
            return self.options, rows
        return self.options, rows, self.written[i * self.chunk:(i + 1) * self.chunk].tolist()


def chunk_tasks(scene, chunk: int) -> tuple[ChunkTasks, list]:
    """(tasks, keys): the key hashes the chunk's rows (their float64 bytes, and the strings they were written as
    where the sweep keeps them: "0.3" and 0.3 are different bodies), the options and the code version."""
    tasks = ChunkTasks(scene, chunk)
    prefix = json.dumps([tasks.options, _code_version()], sort_keys=True).encode()
    values = np.ascontiguousarray(tasks.values, dtype="<f8")
    written = tasks.written

    def key(start: int) -> str:
        data = prefix + values[start:start + chunk].tobytes()
        if written is not None:
            data += json.dumps(written[start:start + chunk].tolist()).encode()
        return hashlib.sha256(data).hexdigest()[:32]

    return tasks, [key(start) for start in range(0, len(values), chunk)]


def assemble(scene, rows: list) -> dict:
    """Column name -> list of values, in point order (inputs first, ``error`` last)."""
    sw = scene.sweep
    table = {c: sw.values[:, i].tolist() for i, c in enumerate(sw.columns)}
    for name in columns_of(scene)[len(sw.columns):]:
        if name == "energy_spread":
            continue
        empty = "" if name.endswith("_method") or name == "error" else math.nan
        table[name] = [r.get(name, empty) for r in rows]
    if "energy_spread" in columns_of(scene):
        angles = np.array(table[spread_source(scene.effects)], dtype=float).reshape(-1, sw.energies)
        spread = angles.max(axis=1) - angles.min(axis=1)   # NaN when any energy of the body failed
        table["energy_spread"] = np.repeat(spread, sw.energies).tolist()
        table = {c: table[c] for c in columns_of(scene)}
    return table


def chunk_dir(out: Path) -> Path:
    return out.parent / f".{out.name}.chunks"


class LargeSweep(ValueError):
    """A sweep above :data:`CONFIRM_ABOVE` points or :data:`CONFIRM_SECONDS` of estimated work, not confirmed."""


CONFIRM_ABOVE = 200_000     # points; beyond, or beyond CONFIRM_SECONDS, a sweep runs only when confirmed
CONFIRM_SECONDS = 3600.0


def run_sweep(scene, out, *, scheduler: str | None = None, workers: int | None = None, progress=None,
              confirmed: bool = False):
    """Compute every point and write the outputs atomically; returns (table, plan, seconds, chunks computed).

    A sweep of more than ``CONFIRM_ABOVE`` points, or estimated above ``CONFIRM_SECONDS``, raises
    :class:`LargeSweep` (with the size and the estimate) before any work unless ``confirmed``
    (``suslov simulate --yes``).
    """
    from suslov.simulator.outputs import check_out

    out = Path(out)
    check_out(out)
    plan = plan_sweep(scene, workers, scheduler)
    check_size(scene, plan, confirmed)
    table, seconds, computed = compute_sweep(scene, plan, executor.ChunkStore(chunk_dir(out)), progress)
    write_sweep_outputs(scene, plan, table, out, seconds, computed, progress)
    shutil.rmtree(chunk_dir(out), ignore_errors=True)
    return table, plan, seconds, computed


def check_size(scene, plan: SweepPlan, confirmed: bool) -> None:
    """:class:`LargeSweep` unless ``confirmed`` when the sweep is above ``CONFIRM_ABOVE`` points or
    ``CONFIRM_SECONDS`` of estimated work."""
    if not confirmed and (len(scene.sweep) > CONFIRM_ABOVE or plan.estimate() > CONFIRM_SECONDS):
        raise LargeSweep(f"{scene.path}: {len(scene.sweep)} points, estimated {plan.estimate():.0f} s on "
                         f"{plan.workers} worker(s): above {CONFIRM_ABOVE} points or {CONFIRM_SECONDS:.0f} s, "
                         "so it runs only when confirmed: add --yes (suslov simulate ... --yes; "
                         "suslov.simulate(..., confirmed=True))")


def measure_costs(scene, budget: float = CALIBRATION_SECONDS, classified: dict | None = None) -> tuple[dict, int, float]:
    """(class -> seconds per point, points timed, seconds of the first calls): each class of points timed
    here on ``CALIBRATION_POINTS`` sample points at least, and on up to ``CALIBRATION_MAX`` while the class has
    taken less than ``CALIBRATION_CLASS`` seconds (cheap points vary more than their mean), after one untimed call
    (compilation, caches: what every worker pays once), within about ``budget`` seconds after those.  The table
    ``COST`` is a guess from another machine and another load; a sweep of 5043 integrations announced 19 s and
    took 112 s.  Writing the outputs is not timed here: :mod:`suslov.simulator.sweep_cost` counts it.

    ``classified``: the classes :func:`plan_sweep` found (point index -> class, ``SweepPlan.classified``); the
    sample points are then drawn from those points, in a random order, and not classified a second time (each
    class takes building the point's body: 20000 of them took about 4 s)."""
    sw, options = scene.sweep, _options(scene)
    samples: dict = {}
    rng = np.random.default_rng(0)
    if classified:
        order = [int(i) for i in rng.permutation(np.fromiter(classified, dtype=np.int64, count=len(classified)))]
    else:
        order = [int(i) for i in rng.permutation(len(sw))[:SAMPLE_FOR_EXPLAIN]]
    for i in order:
        key = classified[i] if classified else classify(sw.point(i), options)
        indices = samples.setdefault(key, [])
        if len(indices) < CALIBRATION_MAX + 1:
            indices.append(int(i))
    measured, timed, first, start = {}, 0, 0.0, time.perf_counter()
    for steps, indices in samples.items():
        if time.perf_counter() - start - first > budget:
            break
        begin = time.perf_counter()
        evaluate_point(sw.point(indices[0]), options, sw.written_point(indices[0]))
        first += time.perf_counter() - begin
        begin, count = time.perf_counter(), 0
        for i in indices[1:]:
            evaluate_point(sw.point(i), options, sw.written_point(i))
            count += 1
            if time.perf_counter() - start - first > budget:
                break
            if count >= CALIBRATION_POINTS and time.perf_counter() - begin > CALIBRATION_CLASS:
                break
        if count:
            measured[steps] = (time.perf_counter() - begin) / count
            timed += count
    return measured, timed, first


def free_cores() -> float | None:
    """Cores not busy with other processes (the 1-minute load average, this process's own share added
    back), None where the platform has no load average."""
    try:
        return (os.cpu_count() or 1) - os.getloadavg()[0] + 1.0
    except (AttributeError, OSError):
        return None


def compute_sweep(scene, plan: SweepPlan, store=None, progress=None) -> tuple[dict, float, int]:
    """Every point of ``plan`` (chunks ``store`` holds are not recomputed): (table, seconds, chunks computed).

    The chunk store lives beside the output directory (:func:`chunk_dir`): without one (``suslov.simulate``
    without ``out``) no outputs follow, and the announced estimate leaves them out."""
    plan.outputs = store is not None
    if progress:
        plan.measured, timed, first = measure_costs(scene, classified=plan.classified)
        plan.startup, plan.free_cores = WORKER_START + first, free_cores()
        busy = "" if plan.free_cores is None else f", {max(0.0, plan.free_cores):.1f} of {os.cpu_count()} cores free"
        basis = f"points timed on {timed} samples here{busy}" if timed else "points from the cost table"
        progress(f"{len(scene.sweep)} points in {plan.chunks} chunks; estimated {plan.estimate_text()} ({basis})")
    tasks, keys = chunk_tasks(scene, plan.chunk)
    start = time.perf_counter()
    results, computed = executor.run_chunks(evaluate_chunk, tasks, keys, store=store, scheduler=plan.scheduler,
                                            workers=plan.workers, progress=progress)
    return assemble(scene, [row for chunk in results for row in chunk]), time.perf_counter() - start, computed
