"""Runtime package: the simulator (scenes, planner, guarded integration, figures) on the generated formulas.

Every public name of the generated module (its ``__all__``) is available here as ``suslov.NAME``;
the import is lazy (PEP 562), so ``suslov.kernel`` and ``suslov.recipes``, which the generated
module itself imports, can be loaded without a cycle and before ``generated/`` exists (the build
runs the recipes).  Which generated module: :func:`active_formulas` (the checkout's
``generated/``, the wheel's ``suslov.formulas``, ``$SUSLOV_FORMULAS`` or :func:`use_formulas`);
a larger p range without touching the checkout: :func:`load_formulas` (``load_formulas(pmax=101)``);
the simulator from Python: ``suslov.simulate(scene)`` (:mod:`suslov.simulator.api`); every certified
formula as an object (SymPy, Mathematica, Maple, JSON): ``suslov.catalog`` (:mod:`suslov.formula_catalog`).  ``suslov.__version__``
comes from the package metadata.

Precision follows mpmath's habits everywhere: every ``*_mp`` and ``*_ball`` function and every routine
of :mod:`suslov.validated` works at ``mpmath.mp.dps`` unless given ``dps=`` (decimal digits); the ball
routes also take ``prec=`` (bits, python-flint's unit).

Layers (docs/design.md, data flow): ``suslov.kernel`` (numerical machinery) and
``suslov.recipes`` (constructions written once, run by the build exactly and by the module
numerically) need neither SymPy nor ``generated``; the simulator modules import
``generated``, never ``derivations``.
"""
from __future__ import annotations

import importlib.metadata

from suslov.loader import active_formulas, load_formulas, use_formulas  # noqa: F401  (public re-exports)

try:
    __version__ = importlib.metadata.version("suslov-certified")
except importlib.metadata.PackageNotFoundError:   # a checkout used without installing it
    __version__ = "0+unknown"


_OWN = ["active_formulas", "load_formulas", "use_formulas", "simulate", "catalog"]


def _public_names() -> list[str]:
    return list(active_formulas().__all__) + _OWN


def __getattr__(name: str):
    if name == "__all__":
        return _public_names()
    if name.startswith("__"):
        raise AttributeError(name)
    if name == "simulate":   # the simulator's Python entry point (suslov.simulator.api), loaded on first use
        from suslov.simulator.api import simulate

        return simulate
    if name == "catalog":    # the formula catalog of the module in use (suslov.formula_catalog)
        from suslov.formula_catalog import catalog_of

        try:
            return catalog_of(active_formulas())
        except FileNotFoundError as error:   # a tree built before the catalog: no attribute, and why
            raise AttributeError(f"suslov.catalog: {error}") from error
    module = active_formulas()
    if name in module.__all__:
        return getattr(module, name)
    raise AttributeError(f"module 'suslov' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_public_names()))
