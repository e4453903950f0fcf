"""Output directories that are the program's or refused, replaced crash-safely (docs/design.md, "Generated outputs").

Used by the build (``build_formulas.py``: ``generated/`` or ``--out DIR``) and by the simulator
(``suslov simulate`` / sweeps: ``--out DIR``).  No dependency beyond the standard library, so the
build and the run-time package share it.

Rules
-----
* **Ownership.**  A run writes only into a path that does not exist, an empty directory, or a
  directory carrying the tool's marker file ``.suslov-output`` (a previous output of the same tool;
  outputs written before the marker existed are recognised by their signature file:
  ``certificates.json`` for the build, ``report.md`` for the simulator).  Anything else (a file, a
  user's directory, the current directory of a checkout, a path whose parent cannot be written) is
  refused with :class:`OutputRefused` *before any work*, naming the path and what is in it.
* **Nothing lost.**  When the tool says what it wrote (``claim(..., written=...)``: the build from its
  manifest ``SHA256SUMS``, the simulator from its ``report.md``), a previous output that also holds
  anything else (a user's file or directory) is refused, naming those entries, before any work and
  again just before the swap (a file put there while the run worked).  Nothing foreign is moved or
  kept: the user moves it or chooses another path.
* **Writable place.**  The nearest existing ancestor of the path must be a directory in which a
  directory can be created (tried, then removed: ``/proc``, a read-only mount, or root's view of a
  mode-0555 directory are told apart only by trying); ``~user`` must name a user.  Checked before any work.
* **Replacement at every instant.**  The new tree is written into a staging directory beside the
  target, then exchanged with the old one in a single ``renameat2(RENAME_EXCHANGE)`` system call
  (Linux >= 3.15): at any instant, a kill leaves either the complete old or the complete new tree at
  the path.  Where the exchange is not available (another OS, a file system without it), a journal
  ``.NAME.suslov-swap`` is written before the two renames; the next run that touches the path
  finishes the swap (the new tree is complete) or rolls it back (see :func:`recover`).
* **Failed writes.**  A write that fails half-way (a full disk: ``ENOSPC``) removes its staging tree; the
  path keeps the previous tree; :func:`write_failure` is the command lines' one-line report of it.
* **Stale staging.**  Staging and discarded trees are named ``.NAME.suslov-{new,old}-PID-XXXX``; a run
  removes those of processes that no longer exist (never another live run's, never a foreign name).
* **Permissions.**  Directories are created with mode 0o777 and files by ``open``: the user's
  umask decides (``tempfile.mkdtemp`` would make them owner-only).
* Concurrent runs serialise their swaps with ``flock`` on the parent directory (no lock file).
"""
from __future__ import annotations

import ctypes
import errno
import fcntl
import json
import os
import secrets
import shutil
from contextlib import contextmanager
from pathlib import Path

MARKER = ".suslov-output"
_KINDS = ("new", "old")
_RENAME_EXCHANGE = 2
_AT_FDCWD = -100

__all__ = ["MARKER", "OutputRefused", "claim", "writable_directory", "recover", "new_staging", "swap_in", "staged",
           "remove_stale", "make_dir", "discard_own", "discard_own_staging",
           "write_failure"]


class OutputRefused(ValueError):
    """The output path is not the program's to replace (a file, a foreign directory, unwritable)."""


def _describe(path: Path, limit: int = 5) -> str:
    return _listing(list(path.iterdir()), limit)


def _listing(entries, limit: int = 5) -> str:
    names = sorted(p.name + ("/" if p.is_dir() else "") for p in entries)
    shown = ", ".join(names[:limit]) + (f", ... ({len(names)} entries)" if len(names) > limit else "")
    return shown


def _owned(path: Path, tool: str, signature: str | None) -> bool:
    try:
        return json.loads((path / MARKER).read_text(encoding="utf-8")).get("tool") == tool
    except (OSError, ValueError, AttributeError):
        return signature is not None and (path / signature).is_file()


def _absolute(target) -> Path:
    """``target`` with ``~`` expanded, made absolute (not resolved: a symlinked output stays refused)."""
    try:
        return Path(os.path.abspath(Path(target).expanduser()))
    except RuntimeError:   # pathlib: "Could not determine home directory." for ~nosuchuser (or no $HOME)
        head = str(target).split("/", 1)[0]
        raise OutputRefused(f"{target}: {head} is no user's home directory (no such user, or no home); "
                            "give the path in full") from None


def _cannot_create_in(directory: Path) -> str | None:
    """Why nothing can be created in ``directory``, or None.  Tried with a directory made and removed at once:
    permission bits do not tell (root passes ``os.access`` in ``/proc`` and on some read-only mounts)."""
    if not os.access(directory, os.W_OK | os.X_OK):
        return "read-only or not permitted"
    probe = directory / f".suslov-probe-{os.getpid()}-{secrets.token_hex(4)}"
    try:
        os.mkdir(probe, 0o700)
    except OSError as error:
        return f"creating a directory there fails: {error.strerror}"
    try:
        os.rmdir(probe)
    except OSError:
        pass
    return None


def _writable_place(target, path: Path, inside: bool = False) -> None:
    """Refuse ``path`` when its nearest existing ancestor (``path`` itself with ``inside``) is not a directory
    one can create entries in."""
    parent = path if inside else path.parent
    while not parent.exists() and not parent.is_symlink():
        parent = parent.parent
    if not parent.is_dir():
        raise OutputRefused(f"{target}: {parent} is not a directory")
    why = _cannot_create_in(parent)
    if why:
        raise OutputRefused(f"{target}: cannot write in {parent} ({why})")


def claim(target, tool: str, signature: str | None = None, written=None) -> Path:
    """The absolute output path, after checking that ``tool`` may replace it.

    Raises :class:`OutputRefused` naming the path and its contents when it is a file, a non-empty
    directory without ``tool``'s marker (or the legacy ``signature`` file), a directory that contains
    the current working directory, or a path whose parent cannot be created or written (or whose
    ``~user`` names no user).  ``written``, when given, is a function of a previous output's directory
    returning the names of its entries the tool wrote (or keeps): a previous output holding any other
    entry is refused too, naming them (the marker file is always the tool's).

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp()); (d / "thesis.txt").write_text("mine")
    4
    >>> claim(d, "demo")
    Traceback (most recent call last):
    ...
    suslov.outdir.OutputRefused: ...: a directory with other content (thesis.txt), not a previous demo output; refusing to replace it
    """
    path = _absolute(target)
    if path.exists() or path.is_symlink():
        if path.is_symlink() or not path.is_dir():
            raise OutputRefused(f"{target}: exists and is not a directory; refusing to replace it")
        if Path.cwd() == path or path in Path.cwd().parents:
            raise OutputRefused(f"{target}: is (or contains) the current directory; choose a new or empty "
                                "directory for the output")
        if any(path.iterdir()):
            if not _owned(path, tool, signature):
                raise OutputRefused(f"{target}: a directory with other content ({_describe(path)}), not a previous "
                                    f"{tool} output; refusing to replace it")
            if written is not None:
                own = set(written(path)) | {MARKER}
                foreign = [entry for entry in path.iterdir() if entry.name not in own]
                if foreign:
                    raise OutputRefused(f"{target}: a previous {tool} output that also holds what {tool} did not "
                                        f"write ({_listing(foreign, 10)}); refusing to replace it (that would delete "
                                        "them): move them elsewhere or choose another output directory")
    _writable_place(target, path)
    return path


def writable_directory(target) -> Path:
    """The absolute path of a directory that files are written into (not replaced whole: the build's
    ``--pdf OUTDIR``), after checking that it is one or can be created: :class:`OutputRefused` naming the
    path when it is a file, lies under a file, cannot be written or has a ``~user`` that names no user."""
    path = _absolute(target)
    if path.exists() or path.is_symlink():
        if not path.is_dir():
            raise OutputRefused(f"{target}: exists and is not a directory")
        _writable_place(target, path, inside=True)
    else:
        _writable_place(target, path)
    return path


def make_dir(path: Path) -> Path:
    """``mkdir -p`` with mode 0o777 (the umask decides), returning ``path``."""
    os.makedirs(path, mode=0o777, exist_ok=True)
    return path


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def remove_stale(directory: Path, prefix: str) -> list[Path]:
    """Remove ``directory/PREFIX-PID-*`` entries whose process no longer exists; returns them.

    Only names of exactly that form are touched; entries of live processes are left alone.
    """
    removed = []
    try:
        entries = list(Path(directory).iterdir())
    except OSError:
        return removed
    for entry in entries:
        rest = entry.name[len(prefix):] if entry.name.startswith(prefix + "-") else None
        if rest is None:
            continue
        pid = rest[1:].split("-", 1)[0].split(".", 1)[0]
        if not pid.isdigit() or _pid_alive(int(pid)):
            continue
        _remove(entry)
        removed.append(entry)
    return removed


def _remove(entry: Path) -> None:
    """A directory tree or a file (a symbolic link itself, never its target)."""
    if entry.is_dir() and not entry.is_symlink():
        shutil.rmtree(entry, ignore_errors=True)
    else:
        entry.unlink(missing_ok=True)


def _name(target: Path, kind: str) -> Path:
    return target.parent / f".{target.name}.suslov-{kind}-{os.getpid()}-{secrets.token_hex(4)}"


def _journal(target: Path) -> Path:
    return target.parent / f".{target.name}.suslov-swap"


@contextmanager
def _locked(target: Path):
    make_dir(target.parent)
    fd = os.open(target.parent, os.O_RDONLY)   # the parent directory itself: no lock file left behind
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)


def recover(target) -> str | None:
    """Finish or roll back an interrupted swap of ``target`` and remove stale staging trees.

    Returns what was done ("finished", "rolled back", None).  Safe to call at any time; called by
    :func:`new_staging` and :func:`swap_in`.
    """
    target = Path(os.path.abspath(target))
    if not target.parent.exists():
        return None
    with _locked(target):
        return _recover_locked(target)


def _recover_locked(target: Path) -> str | None:
    done = None
    journal = _journal(target)
    try:
        entry = json.loads(journal.read_text(encoding="utf-8"))
        staging, backup = target.parent / entry["staging"], target.parent / entry["backup"]
    except FileNotFoundError:
        entry = None
    except (OSError, ValueError, KeyError, TypeError):
        entry = None   # a journal torn while being written: the swap had not started (written before the renames)
        journal.unlink(missing_ok=True)
    if entry is not None:
        if not target.exists():
            if staging.is_dir():
                os.rename(staging, target)
                done = "finished"
            elif backup.is_dir():
                os.rename(backup, target)
                done = "rolled back"
        journal.unlink(missing_ok=True)
    for kind in _KINDS:
        remove_stale(target.parent, f".{target.name}.suslov-{kind}")
    return done


def new_staging(target, tool: str) -> Path:
    """A fresh staging directory beside ``target`` (created with the umask's mode) holding ``tool``'s marker."""
    target = Path(os.path.abspath(target))
    recover(target)
    staging = _name(target, "new")
    os.mkdir(staging, 0o777)
    try:
        (staging / MARKER).write_text(json.dumps({"tool": tool}) + "\n", encoding="utf-8")
    except BaseException:   # a full disk fails already here, before the callers' clean-up starts
        shutil.rmtree(staging, ignore_errors=True)
        raise
    return staging


def discard_own(directory, prefix: str) -> list[Path]:
    """Remove ``directory/PREFIX-PID-*`` of this process (a write that failed half-way, e.g. on a full disk, where
    no clean-up block removed it); returns them.  Other processes' entries are left alone."""
    start = f"{prefix}-{os.getpid()}-"
    removed = []
    try:
        entries = [entry for entry in Path(directory).iterdir() if entry.name.startswith(start)]
    except OSError:
        return removed
    for entry in entries:
        _remove(entry)
        removed.append(entry)
    return removed


def discard_own_staging(target) -> list[Path]:
    """Remove the staging trees this process made beside ``target`` and left there (:func:`discard_own`)."""
    target = Path(os.path.abspath(target))
    return discard_own(target.parent, f".{target.name}.suslov-new")


def write_failure(error: OSError, path) -> str:
    """One line for ``error`` met while writing ``path``: the file the system named (else ``path``) and the
    reason with its errno, e.g. ``/data/out: No space left on device [Errno 28 ENOSPC]``; no traceback.

    Of two files (a copy's or a rename's source and destination) the destination is named: that is the one
    written."""
    where = next((name for name in (error.filename2, error.filename) if name is not None), path)
    reason = error.strerror or str(error) or type(error).__name__
    code = f" [Errno {error.errno} {errno.errorcode.get(error.errno, '?')}]" if error.errno is not None else ""
    return f"{where}: {reason}{code}"


def _exchange(a: Path, b: Path) -> bool:
    """Atomically exchange two paths (Linux renameat2); False where the system cannot."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    if renameat2(_AT_FDCWD, os.fsencode(a), _AT_FDCWD, os.fsencode(b), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP, errno.ENOTSUP):
        return False
    raise OSError(code, os.strerror(code), str(b))


_EXCHANGE_ENABLED = True   # tests switch it off to exercise the journal route


def swap_in(staging: Path, target) -> None:
    """Put the complete tree ``staging`` at ``target``; the old tree (if any) is removed afterwards."""
    target = Path(os.path.abspath(target))
    staging = Path(staging)
    with _locked(target):
        _recover_locked(target)
        if not target.exists():
            os.rename(staging, target)
            return
        if _EXCHANGE_ENABLED and _exchange(staging, target):
            old = staging   # the old tree now sits at the staging name
        else:
            old = _name(target, "old")
            journal = _journal(target)
            tmp = _name(target, "new")   # a torn journal of a killed run is stale staging like any other
            tmp.write_text(json.dumps({"staging": staging.name, "backup": old.name}), encoding="utf-8")
            os.replace(tmp, journal)
            os.rename(target, old)
            os.rename(staging, target)
            journal.unlink()
        discard = _name(target, "old") if old == staging else old
        if old == staging:
            os.rename(staging, discard)
        shutil.rmtree(discard, ignore_errors=True)


@contextmanager
def staged(out, tool: str, signature: str | None = None, written=None):
    """Yield a staging directory; on success it replaces ``out``, on any exception it is removed.

    ``out`` is checked with :func:`claim` first, so a refused path fails before any work, and again before
    the swap (files a user put into the previous output meanwhile are not lost: :class:`OutputRefused`).
    """
    out = claim(out, tool, signature, written)
    make_dir(out.parent)
    staging = new_staging(out, tool)
    try:
        yield staging
        claim(out, tool, signature, written)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise
    swap_in(staging, out)
