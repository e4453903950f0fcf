"""The simulator's output directories (docs/design.md, "Scenes"): all of a run's files or none.

Files go into a staging directory beside ``--out`` and are exchanged into place only when
everything succeeded (:mod:`suslov.outdir`: crash-safe at every instant, stale staging of dead
runs removed, the user's umask kept); a failed or interrupted run leaves the output directory as
it was.  A path that is a file, a directory of someone else's (neither empty, nor marked as a
simulator output, nor a pre-marker output with ``report.md``) or an unwritable place is refused
before any work.
"""
from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

import suslov.outdir as outdir

REPORT = "report.md"
TOOL = "suslov"


def check_out(out) -> Path:
    """``out`` as an absolute Path; :class:`suslov.outdir.OutputRefused` (a ``ValueError``) if the
    simulator may not replace it."""
    return outdir.claim(out, TOOL, REPORT)


@contextmanager
def staged(out):
    """Yield a staging directory; on success it replaces ``out``, on any exception it is removed."""
    with outdir.staged(out, TOOL, REPORT) as staging:
        yield staging
