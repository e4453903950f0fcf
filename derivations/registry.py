"""The derivations the build knows, in dependency order.

Each entry names a module with ``NAME``, ``TITLE``, optional ``REQUIRES`` and
``run(log, options, *required_results) -> DerivationResult``; optional ``PREFETCH``, a tuple of
``(label, values, work)`` for numeric certificates that need no other result: the build starts
them in its worker processes before any derivation runs, and ``run`` collects them with
``log.map_per_p(label, values, work)`` where it records them (``CertificateLog.prefetch``).  Later issues add
their modules here; ``--only`` resolves names against this table.
"""
from __future__ import annotations

import functools
import importlib
from types import ModuleType

# the derivation modules (derivations.sections.<name>, whose NAME is <name>), in dependency order: known without
# importing them, so that the command line checks ``--only`` before it loads SymPy and the derivations
NAMES = ("model", "special_case", "kovalevskaya", "residue", "hypergeometric", "meromorphic", "first_integrals",
         "scattering", "galois", "fuchsian", "gauss", "general_angle", "general_galois", "pole_theorem")


@functools.cache
def _table() -> dict[str, ModuleType]:
    table = {name: importlib.import_module(f"derivations.sections.{name}") for name in NAMES}
    wrong = [name for name, module in table.items() if module.NAME != name]
    if wrong:
        raise ImportError(f"derivations.sections.{wrong[0]} is registered as {wrong[0]!r} but names itself "
                          f"{table[wrong[0]].NAME!r}")
    return table


def __getattr__(name: str):
    """``DERIVATIONS`` (name -> module, in registry order), imported on first use."""
    if name == "DERIVATIONS":
        return _table()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def requirements(name: str) -> tuple[str, ...]:
    return tuple(getattr(_table()[name], "REQUIRES", ()))


def resolve(only: list[str] | None) -> list[str]:
    """Names to run, requirements first, in registry order.

    Raises ``KeyError`` with the unknown name and the known ones.
    """
    if not only:
        return list(NAMES)
    wanted: set[str] = set()

    def add(name: str):
        if name not in NAMES:
            raise KeyError(f"unknown derivation {name!r}; known: {', '.join(NAMES)}")
        if name not in wanted:
            wanted.add(name)
            for req in requirements(name):
                add(req)

    for name in only:
        add(name)
    return [name for name in NAMES if name in wanted]
