"""Output directories written atomically (DESIGN.md, "Scenes"): all of a run's files or none.

Files go into a staging directory beside ``--out`` and are moved into place only when everything
succeeded; a failed or interrupted run leaves the output directory as it was.  A directory that
is neither empty nor a previous suslov output (no ``report.md``) is never overwritten.
"""
from __future__ import annotations

import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

REPORT = "report.md"


def check_out(out) -> Path:
    """``out`` as a Path; FileExistsError if it is a file or a foreign non-empty directory."""
    out = Path(out)
    if out.exists() and (not out.is_dir() or (any(out.iterdir()) and not (out / REPORT).exists())):
        raise FileExistsError(f"{out}: exists and is not an empty directory or a previous suslov output "
                              f"(no {REPORT}); refusing to overwrite")
    return out


@contextmanager
def staged(out):
    """Yield a staging directory; on success it replaces ``out``, on any exception it is removed."""
    out = check_out(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    staging = Path(tempfile.mkdtemp(prefix=f".{out.name}.", dir=out.parent))
    try:
        yield staging
        if out.exists():
            shutil.rmtree(out)
        staging.rename(out)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
