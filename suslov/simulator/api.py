"""The simulator from Python: ``suslov.simulate(scene)`` returns a :class:`Result` (issue 36).

The heyoka / PyDy habit: a scene goes in as a dict (the TOML file's tables as nested dicts), a TOML path
or a parsed :class:`~suslov.simulator.scene.Scene`; the requested effects come back as NumPy arrays and
numbers, ``.plot()`` draws a figure, ``.save(DIR)`` writes the same directory ``suslov simulate SCENE
--out DIR`` writes.  The command line (:mod:`suslov.simulator.cli`) is a thin layer over this module:
one route for both.  Effects, figures and the schema: ``scenes/README.md``; the planner computes only
what the scene asks for (DESIGN notes in ``docs/simulator.md``).

>>> import suslov
>>> result = suslov.simulate({"body": {"p": 2, "d": 0.5},
...                           "motion": {"time": [-4, 4], "samples": 5},
...                           "effects": {"compute": ["omega", "scattering_angle"]}})
>>> result["omega"].shape
(5, 3)
>>> angle = result["scattering_angle"]
>>> round(angle["radians"], 6), angle["method"]
(3.134123, 'closed form (Theorem 5.4, corrected: q = d)')
>>> fig = result.plot("omega_plane")      # a matplotlib Figure
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from suslov.extras import FIGURES as FIGURE_LIBRARIES
from suslov.extras import missing, require
from suslov.simulator.scene import FIGURES, Scene, SceneError, load_scene, parse_scene

__all__ = ["Result", "check_extras", "simulate"]


@dataclass
class Result:
    """What :func:`simulate` computed.

    ``data``: arrays by effect (``t``, ``omega`` (n, 3), ``gamma`` (n, 3), ``orientation`` (n, 3, 3), ...);
    ``results``: the scalar effects (``scattering_angle``, ``galois_group``, ...); ``table``: a sweep's columns
    (one entry per point); ``steps``: what ran, with its method and seconds; ``files``: what was
    written.  ``result[name]`` looks in
    ``data``, then ``results``, then ``table``.
    """
    scene: Scene
    data: dict = field(default_factory=dict)
    results: dict = field(default_factory=dict)
    table: dict = field(default_factory=dict)
    steps: list = field(default_factory=list)
    files: list = field(default_factory=list)   # written by simulate(..., out=DIR) or save()
    _run: object = field(default=None, repr=False)
    _plan: object = field(default=None, repr=False)

    def __getitem__(self, name: str):
        for source in (self.data, self.results, self.table):
            if name in source:
                value = source[name]
                return np.asarray(value) if source is self.table else value
        raise KeyError(f"{name!r}: not computed by scene {self.scene.name!r}; available: {', '.join(self.keys())}")

    def keys(self) -> list[str]:
        return list(dict.fromkeys([*self.data, *self.results, *self.table]))

    def figures(self) -> list[str]:
        """The figures :meth:`plot` can draw for this result."""
        if self.scene.is_sweep:
            return ["map", "histogram"] if len(self.scene.sweep.varying) == 2 else ["histogram"]
        effects = set(self.scene.effects)
        allowed = [n for n, effect in FIGURES.items() if effect in effects]
        from suslov.simulator.scene import SLEIGH_FIGURES
        return [n for n in allowed if (n in SLEIGH_FIGURES) == self.scene.is_sleigh]

    def plot(self, name: str | None = None):
        """A matplotlib ``Figure`` of ``name`` (default: the scene's first figure, else the first one
        :meth:`figures` lists); the caller shows, saves or closes it.  Needs matplotlib: without it (a core
        install) an ``ImportError`` says to install the [sim] extra."""
        choices = self.figures()
        if name is None:
            name = (self.scene.figures or choices or [None])[0]
        if name not in choices:
            raise ValueError(f"figure {name!r}: not drawable from scene {self.scene.name!r} (its effects: "
                             f"{', '.join(self.scene.effects)}); available: {', '.join(choices) or 'none'}")
        needs_figures("Result.plot()", [name])
        if self.scene.is_sweep:
            from suslov.simulator.sweep_outputs import sweep_figure
            return sweep_figure(name, self.scene, self.table)
        from suslov.simulator import figures
        return figures.figure(name, self._run)

    def save(self, out, progress=None) -> list[str]:
        """Write the scene's outputs (data, figures, results.json, report.md) into ``out`` atomically, as
        ``suslov simulate SCENE --out DIR`` does; returns the file names.  A scene with figures needs
        matplotlib (else an ``ImportError`` naming the [sim] extra, before anything is written)."""
        from suslov.simulator.outputs import check_out

        needs_figures("Result.save()", self.scene.figures)
        check_out(out)
        if self.scene.is_sweep:
            from suslov.simulator.sweep_outputs import write_sweep_outputs
            self.files = write_sweep_outputs(self.scene, self._plan, self.table, Path(out),
                                             sum(s["seconds"] for s in self.steps), len(self.steps), progress)
        else:
            from suslov.simulator.engine import write_outputs
            self.files = write_outputs(self._run, out, progress)
        return self.files

    def __repr__(self) -> str:
        shown = ", ".join(self.keys())
        return f"<suslov Result of scene {self.scene.name!r}: {shown}>"

    def _repr_html_(self) -> str:
        """Notebooks: the results (value first, then method), the arrays, the steps and the scene's figures inline
        as PNG (:mod:`suslov.simulator.result_display`; without matplotlib a line naming the [sim] extra)."""
        from suslov.simulator.result_display import result_html
        return result_html(self)


def needs_figures(what: str, names) -> None:
    """The one check before figures ``names`` are drawn (plot, save, simulate with ``out``): a core install
    (no matplotlib) gets an ``ImportError`` naming the [sim] extra, before any work, instead of ``No module
    named 'matplotlib'`` from inside the drawing (the figure modules import it on first use); no figure
    needs nothing."""
    if names:
        require("sim", f"{what}, drawing {', '.join(names)},", FIGURE_LIBRARIES)


def check_extras(what: str, scene: Scene, plan=None, *, figures: bool = True, workers: int | None = None,
                 scheduler: str | None = None) -> int | None:
    """The one check of the [sim] extra per scene (issue 47): a ``ModuleNotFoundError`` (an ``ImportError``) naming
    the extra, the missing libraries and the steps that need them, before any work, when a planned step needs a
    library that is not installed (:meth:`suslov.simulator.planner.Plan.libraries`: an integration its integrator, a
    figure matplotlib when ``figures``); a closed-form scene passes with NumPy, mpmath and python-flint alone.

    A sweep (``plan`` None) needs what its effects and figures need, and loky for local worker processes: without
    loky and without a scheduler, ``workers=None`` (all cores) becomes 1 (this process), which is returned;
    otherwise ``workers`` is returned unchanged."""
    from suslov.simulator.planner import sweep_libraries

    needs = plan.libraries(figures) if plan is not None else sweep_libraries(scene, figures)
    if plan is None and scheduler is None and missing("sim", ("loky",)):
        if workers is None:
            workers = 1           # the default: all cores, in loky's processes; one core needs no process
        elif workers > 1:
            needs[f"{workers} worker processes"] = ("loky",)
    lacking = {step: tuple(lib for lib in libraries if missing("sim", (lib,))) for step, libraries in needs.items()}
    lacking = {step: libraries for step, libraries in lacking.items() if libraries}
    if lacking:
        libraries = tuple(dict.fromkeys(lib for libs in lacking.values() for lib in libs))
        require("sim", f"{what} ({', '.join(map(_need_label, lacking))})", libraries)
    return workers


def _need_label(step: str) -> str:
    """``figure:map`` -> ``figure map``; an integrating step or effect says so."""
    if step.startswith("figure:"):
        return "figure " + step.split(":", 1)[1]
    if step.endswith(("_integrate", "_integrated")):
        return f"{step}: a numerical integration"
    return step


def as_scene(scene) -> Scene:
    """A :class:`Scene` from a dict, a TOML path or a Scene; :class:`SceneError` otherwise."""
    if isinstance(scene, Scene):
        return scene
    if isinstance(scene, dict):
        return parse_scene(scene)
    if isinstance(scene, (str, os.PathLike)):
        return load_scene(scene)
    raise SceneError(Path("<argument>"), "scene", f"{type(scene).__name__}: give a dict, a TOML path or a Scene")


def _reporter(progress):
    if progress is True:
        return lambda message: print(message, file=sys.stderr, flush=True)
    if progress in (None, False) or callable(progress):
        return progress or None
    raise ValueError(f"progress={progress!r}: give None, True (lines on stderr) or a callable taking one string")


def simulate(scene, *, out=None, workers: int | None = None, scheduler: str | None = None, progress=None,
             confirmed: bool = False) -> Result:
    """Run ``scene`` (a dict, a TOML path or a :class:`Scene`) and return its :class:`Result`.

    ``out``: also write the outputs there (atomically; a sweep keeps finished chunks beside it and resumes
    from them when interrupted).  ``workers`` / ``scheduler``: where a sweep's chunks run (local processes,
    default all cores, or a dask.distributed address).  ``progress``: ``True`` for lines on stderr, or a
    callable taking one string.  A sweep above 200000 points or an hour of estimated work runs only with
    ``confirmed=True``.  Bad input raises :class:`~suslov.simulator.scene.SceneError` naming the field.  A step
    that needs the [sim] extra (an integration, a figure drawn for ``out``) raises an ``ImportError`` naming it when
    a library is missing, before any work (:func:`check_extras`); closed forms need the core install only.
    """
    scene = as_scene(scene)
    report = _reporter(progress)
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise ValueError(f"workers={workers!r}: must be a positive integer")
    if out is not None:
        needs_figures(f"simulate(..., out={str(out)!r})", scene.figures)
    if scene.is_sweep:
        workers = check_extras(f"simulate(scene {scene.name!r})", scene, figures=out is not None, workers=workers,
                               scheduler=scheduler)
        return _sweep(scene, out, workers, scheduler, report, confirmed)
    from suslov.simulator.engine import execute, write_outputs
    from suslov.simulator.planner import make_plan

    try:
        plan = make_plan(scene)
    except ValueError as exc:
        raise SceneError(scene.path, "body", str(exc)) from None
    check_extras(f"simulate(scene {scene.name!r})", scene, plan, figures=out is not None)
    if out is not None:
        from suslov.simulator.outputs import check_out
        check_out(out)
    run = execute(plan, report)
    result = Result(scene, dict(run.data), dict(run.results), {}, run.executed, [], run, plan)
    if out is not None:
        result.files = write_outputs(run, out, report)
    return result


def _sweep(scene, out, workers, scheduler, report, confirmed) -> Result:
    from suslov.simulator.sweep import check_size, compute_sweep, plan_sweep, run_sweep

    if out is not None:
        table, plan, seconds, computed = run_sweep(scene, out, scheduler=scheduler, workers=workers, progress=report,
                                                   confirmed=confirmed)
    else:
        plan = plan_sweep(scene, workers, scheduler)
        check_size(scene, plan, confirmed)
        table, seconds, computed = compute_sweep(scene, plan, None, report)
    steps = [{"step": "sweep", "method": f"{plan.chunks} chunks, {computed} computed", "seconds": seconds}]
    files = sorted(p.name for p in Path(out).iterdir()) if out is not None else []
    return Result(scene, {}, {}, table, steps, files, None, plan)
