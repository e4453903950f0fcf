"""The simulator's output directories (docs/design.md, "Scenes"): all of a run's files or none.

Files go into a staging directory beside ``--out`` and are exchanged into place only when
everything succeeded (:mod:`suslov.outdir`: crash-safe at every instant, stale staging of dead
runs removed, the user's umask kept); a failed or interrupted run leaves the output directory as
it was.  A path that is a file, a directory of someone else's (neither empty, nor marked as a
simulator output, nor a pre-marker output with ``report.md``) or an unwritable place is refused
before any work.  So is a previous output that holds anything the simulator did not write there (a
user's file or directory): what it wrote is ``report.md`` and the files its "Files" section lists
(:func:`written`); the refusal names the others, and the run would otherwise have deleted them.
"""
from __future__ import annotations

import re
from contextlib import contextmanager
from pathlib import Path

import suslov.outdir as outdir

REPORT = "report.md"
TOOL = "suslov"


def written(directory: Path) -> set[str]:
    """The names a previous simulator output in ``directory`` holds of the simulator's: ``report.md`` and the
    files listed in its last section, "## Files" (every file of a run but the report and the marker); none
    without a readable report."""
    try:
        text = (directory / REPORT).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return set()
    _, found, files = text.rpartition("\n## Files\n")
    return {REPORT, *re.findall(r"^- `([^`/]+)`$", files, flags=re.M)} if found else {REPORT}


def check_out(out) -> Path:
    """``out`` as an absolute Path; :class:`suslov.outdir.OutputRefused` (a ``ValueError``) if the
    simulator may not replace it (also a previous output holding files the simulator did not write)."""
    return outdir.claim(out, TOOL, REPORT, written)


@contextmanager
def staged(out):
    """Yield a staging directory; on success it replaces ``out``, on any exception it is removed."""
    with outdir.staged(out, TOOL, REPORT, written) as staging:
        yield staging
