"""Which optional extra a feature needs, and one clear error when it is missing (issue 36).

The core install (``pip install suslov-certified``: NumPy, mpmath, python-flint, platformdirs) evaluates
the generated module, the run-time formulas and the balls.  The rest comes in extras, NumPy/SciPy
style: ``[build]`` (the derivations: SymPy, symengine, Jinja2), ``[sim]`` (the simulator: SciPy,
matplotlib, heyoka), ``[dask]`` (sweeps on a cluster), ``[catalog]`` (SymPy: the formula catalog's
expressions), ``[docs]``, ``[test]``.  A feature that needs an extra calls :func:`require` first, so a
core install gets ``pip install 'suslov-certified[sim]'`` instead of a traceback from deep inside an
import.  Standard library only: every layer may import it.

>>> missing("build") in ([], ["sympy"], ["symengine"], ["jinja2"], ["sympy", "symengine", "jinja2"]) or True
True
"""
from __future__ import annotations

import importlib.util

__all__ = ["EXTRAS", "FIGURES", "missing", "require", "install_hint"]

EXTRAS = {
    "build": ("sympy", "symengine", "jinja2", "loky"),
    "sim": ("scipy", "matplotlib", "heyoka", "loky"),
    "dask": ("dask", "distributed"),
    "catalog": ("sympy",),
}
# what drawing or saving a simulator figure needs of [sim] (Result.plot, Result.save, simulate(out=...))
FIGURES = ("matplotlib",)


def install_hint(extra: str) -> str:
    return f"pip install 'suslov-certified[{extra}]'"


def missing(extra: str, libraries: tuple[str, ...] | None = None) -> list[str]:
    """The libraries of ``extra`` (or only ``libraries`` of it) that cannot be imported here (empty when
    they are installed).  A name set to ``None`` in ``sys.modules`` counts as missing, as ``import`` says."""
    return [name for name in (EXTRAS[extra] if libraries is None else libraries)
            if importlib.util.find_spec(name) is None]


def require(extra: str, what: str, libraries: tuple[str, ...] | None = None) -> None:
    """``ModuleNotFoundError`` (an ``ImportError``) naming ``extra`` and the missing libraries when ``what``
    cannot run here.  ``libraries``: the part of the extra ``what`` needs (a figure needs matplotlib, not
    heyoka: :data:`FIGURES`), so a partial install is refused only for what it lacks."""
    absent = missing(extra, libraries)
    if absent:
        raise ModuleNotFoundError(f"{what} needs the [{extra}] extra ({', '.join(absent)} not installed): "
                                  f"{install_hint(extra)}", name=absent[0])
