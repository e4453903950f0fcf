"""The derivations the build knows, in dependency order.

Each entry names a module with ``NAME``, ``TITLE``, optional ``REQUIRES`` and
``run(log, options, *required_results) -> DerivationResult``; optional ``PREFETCH``, a tuple of
``(label, values, work)`` for numeric certificates that need no other result: the build starts
them in its worker processes before any derivation runs, and ``run`` collects them with
``log.map_per_p(label, values, work)`` where it records them (``CertificateLog.prefetch``).  Later issues add
their modules here; ``--only`` resolves names against this table.
"""
from __future__ import annotations

from types import ModuleType

from derivations.sections import (
    first_integrals,
    fuchsian,
    galois,
    gauss,
    general_angle,
    general_galois,
    hypergeometric,
    kovalevskaya,
    meromorphic,
    model,
    pole_theorem,
    residue,
    scattering,
    special_case,
)

DERIVATIONS: dict[str, ModuleType] = {m.NAME: m for m in (model, special_case, kovalevskaya, residue, hypergeometric,
                                                   meromorphic, first_integrals, scattering, galois,
                                                   fuchsian, gauss, general_angle, general_galois,
                                                   pole_theorem)}


def requirements(name: str) -> tuple[str, ...]:
    return tuple(getattr(DERIVATIONS[name], "REQUIRES", ()))


def resolve(only: list[str] | None) -> list[str]:
    """Names to run, requirements first, in registry order.

    Raises ``KeyError`` with the unknown name and the known ones.
    """
    if not only:
        return list(DERIVATIONS)
    wanted: set[str] = set()

    def add(name: str):
        if name not in DERIVATIONS:
            raise KeyError(f"unknown derivation {name!r}; known: {', '.join(DERIVATIONS)}")
        if name not in wanted:
            wanted.add(name)
            for req in requirements(name):
                add(req)

    for name in only:
        add(name)
    return [name for name in DERIVATIONS if name in wanted]
