"""Run ``--verify``'s checks on many seeded copies in one process (used by tests/test_verify_faults.py).

``build_formulas.py --verify`` derives what the module needs (about 7 s), then runs the round trip on the tree.  One
subprocess per seeded fault paid that derivation 47 times (about 9 minutes of the suite on 2 cores).  Here the
derivation runs once; then, for each seeded copy, every ``suslov`` module and every module of the checking layers
(``derivations.output``, ``derivations.proofs``) is dropped from ``sys.modules`` and the copy is put first on
``sys.path``, so the emitted module, the run-time code it imports and the checks that import run-time code
themselves (``basis_proof``'s phase, ``float_paths``) all come from the copy, as in a ``--verify`` subprocess started
there; :func:`derivations.output.roundtrip.verify` then gives the first discrepancy or None.  The derivation's own
results (``derivations.sections``, ``derivations.core``) are exact objects computed before any fault was seeded.
The real command line's ``--verify`` runs in ``tests/test_roundtrip.py`` (on the committed tree and on a mutated
copy).

Usage: ``python tests/verify_faults_batch.py TREES...`` (each a directory holding ``suslov/`` and ``generated/``);
prints one JSON object: tree -> the discrepancy, or null when the tree passes.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

FRESH = ("suslov", "derivations.output", "derivations.proofs")


def _fresh(name: str) -> bool:
    return any(name == prefix or name.startswith(prefix + ".") for prefix in FRESH)


def main(trees: list[str]) -> dict:
    from derivations.core.options import BuildOptions
    from derivations.output.pipeline import MODULE_NEEDS, derive

    build = derive(BuildOptions(jobs=1), list(MODULE_NEEDS))   # no pool: the suite runs on every core already
    saved = {name: module for name, module in sys.modules.items() if _fresh(name)}
    outcome = {}
    for tree in trees:
        for name in [n for n in sys.modules if _fresh(n)]:
            del sys.modules[name]
        sys.path.insert(0, tree)
        try:
            from derivations.output.roundtrip import (
                verify,  # fresh: its lazy imports resolve in the copy
            )

            outcome[tree] = verify(build, Path(tree) / "generated", jobs=1)   # the copy is on this process's path
        except Exception as error:   # a check that crashes on a fault is a rejection, named as --verify would
            outcome[tree] = f"the module in {tree} cannot be checked: {type(error).__name__}: {error}"
        finally:
            sys.path.remove(tree)
            for name in [n for n in sys.modules if _fresh(n)]:
                del sys.modules[name]
            sys.modules.update(saved)
    return outcome


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1:])))
