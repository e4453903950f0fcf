#!/usr/bin/env python3
"""Build the certified formulas: derive -> certify -> render into generated/.

Usage examples::

    python build_formulas.py                 # full build into generated/
    python build_formulas.py --pmax 51       # per-p tables up to p = 51
    python build_formulas.py --pmax 201 --cross-check-pmax 201   # every p's logarithm recursions (default: p <= 101, a sample above)
    python build_formulas.py --check         # compare generated/ with the build (cache or rebuild), exit 3 if it differs
    python build_formulas.py --only model    # certify one derivation (generated/ untouched)
    python build_formulas.py --verify generated   # check the tree's SHA256SUMS, certify its module, rewrite nothing
    python build_formulas.py --pdf           # build, then pdflatex into build/pdf/ (generated/ untouched)
    python build_formulas.py --diff HEAD~3   # what changed since a revision (or a directory), latexdiff PDF

Every build certifies the generated module as emitted (``derivations/output/roundtrip.py``):
it is imported from the staging directory and checked against the certified objects
before anything is moved into place.  The last file written is the manifest ``SHA256SUMS``
(``suslov/manifest.py``), which the loader checks before executing a tree (``docs/trust.md``).

Exit status: 0 success; 1 a certificate failed (the claim is named; the output
directory is left as it was) or ``--verify`` found a discrepancy (or unreadable certificates);
2 bad command line, or an output path that is not the build's to replace (a file, a directory
with other content, an unwritable place: refused before any work, see ``suslov/outdir.py``), or an output or
the certificate cache that cannot be written (a full disk: one line naming the path and the reason, the previous
output intact); 3 ``--check`` found differences; 130 interrupted (Ctrl-C, from the first line on).
"""
from __future__ import annotations

import signal
import sys

# the line derivations.output.cli.run prints for a Ctrl-C during the build, here for one during the imports
INTERRUPTED = "build_formulas.py: interrupted; nothing was replaced (an output is swapped in whole or not at all)"


def main(argv: list[str] | None = None) -> int:
    """Run the build (``derivations.output.cli.main``) with the command-line arguments ``argv``."""
    from derivations.output.cli import main as build

    return build(argv)


def run(argv: list[str] | None = None) -> int:
    """:func:`main`, with Ctrl-C reported in one line (``derivations.output.cli.run``), also during the imports
    (SymPy and the derivations take about a second): nothing has been written then either."""
    try:
        from derivations.output.cli import run as build
    except KeyboardInterrupt:
        print(INTERRUPTED, file=sys.stderr)
        return 130
    return build(argv)


if __name__ == "__main__":   # the build's worker processes import this file too: nothing heavy above
    # First, before any import that takes time: a background job (`cmd &` in a script) starts with SIGINT
    # ignored, and a `kill -INT` sent during the imports was lost (issue 44).  Standard library only here
    # (suslov.interrupts.listen_for_interrupts does the same after importing the suslov package).
    signal.signal(signal.SIGINT, signal.default_int_handler)
    sys.exit(run())
