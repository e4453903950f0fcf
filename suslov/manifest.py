"""Verified loading of a generated formula tree: a SHA-256 manifest, checked before anything runs (issue 38).

A generated tree (``generated/``, ``build_formulas.py --out DIR``, a store entry ``pmax-N``, the wheel's
``suslov.formulas``) is code: ``suslov_formulas.py`` is executed when it is loaded.  The build writes,
last and inside its atomic swap (``derivations/output/pipeline.py``, :mod:`suslov.outdir`), the file
:data:`MANIFEST` (``SHA256SUMS``): one line ``<sha256>  <name>`` per emitted file (the module, its
package ``__init__.py``, ``certificates.json``, the LaTeX documents), sorted by name -- the format of
``sha256sum``, so ``sha256sum -c SHA256SUMS`` checks a tree without this package.

Before a tree's module is executed, :func:`verify`

* refuses a tree that other users can write: the directory, its files and every directory above it
  must belong to the current user or root and be writable by nobody else (a group-writable entry is
  accepted only when the group is the user's private group; a world-writable ancestor only with the
  sticky bit, as ``/tmp``) -- whoever can write there can rewrite the manifest too;
* refuses a tree without a manifest, a manifest that omits the module, ``__init__.py`` or
  ``certificates.json``, a listed file that is missing or whose digest differs (naming the file, the
  expected and the found digest), and a Python file that the manifest does not list;
* returns the bytes it checked, and :func:`load_module` executes exactly those bytes (never a cached
  ``.pyc``, never a second read of the file).

What this does and does not protect is written up in ``docs/trust.md``.  Standard library only: the
loader imports this module before NumPy or SymPy.
"""
from __future__ import annotations

import hashlib
import importlib.abc
import importlib.util
import os
import stat
import sys
from pathlib import Path
from types import ModuleType

__all__ = ["MANIFEST", "REQUIRED", "ManifestError", "UntrustedTree", "digest", "write", "read", "verify",
           "load_module", "import_verified"]

MANIFEST = "SHA256SUMS"
MODULE = "suslov_formulas.py"
REQUIRED = ("__init__.py", "certificates.json", MODULE)
# Set by build_formulas.py to the checkout's generated/ when that tree does not match its manifest (after a
# merge, or an edit the build is about to replace): the build evaluates the previous module in its validated
# certificates and then certifies the module it emits (round trip).  Only that directory, only for digest
# mismatches: the permission check still holds.
REBUILD_ENV = "SUSLOV_REBUILDING"


class ManifestError(ImportError):
    """A tree whose manifest is missing, malformed or does not match its files; nothing was executed."""


class UntrustedTree(ManifestError):
    """A tree that users other than its owner (or root) can write; nothing was executed."""


def digest(data: bytes) -> str:
    """The SHA-256 of ``data``, as the manifest writes it (64 lowercase hex digits)."""
    return hashlib.sha256(data).hexdigest()


def write(directory, names) -> Path:
    """Write ``directory/SHA256SUMS`` for the files ``names`` (the build's last write); returns its path."""
    directory = Path(directory)
    lines = [f"{digest((directory / name).read_bytes())}  {name}\n" for name in sorted(set(names))]
    path = directory / MANIFEST
    path.write_text("".join(lines), encoding="utf-8")
    return path


def read(directory) -> dict[str, str]:
    """The manifest of ``directory`` as ``{name: sha256}`` (raises :class:`ManifestError` naming the line)."""
    path = Path(directory) / MANIFEST
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ManifestError(f"{Path(directory)}: no {MANIFEST} (the manifest every build writes last); a tree "
                            "without one is not executed -- rebuild it with build_formulas.py (--out DIR or "
                            "--pmax N --install)") from None
    except (OSError, UnicodeDecodeError) as error:
        raise ManifestError(f"{path}: cannot be read ({error})") from None
    entries = {}
    for number, line in enumerate(text.splitlines(), 1):
        value, sep, name = line.partition("  ")
        if (not sep or len(value) != 64 or any(c not in "0123456789abcdef" for c in value) or not name
                or "/" in name or name in (".", "..") or name in entries):
            raise ManifestError(f"{path}, line {number}: {line[:100]!r} is not '<sha256>  <file name>' (or repeats "
                                "a name); the manifest is damaged")
        entries[name] = value
    missing = [name for name in REQUIRED if name not in entries]
    if missing:
        raise ManifestError(f"{path}: does not list {', '.join(missing)}; refusing the tree")
    return entries


def _private_group(gid: int, uid: int) -> bool:
    """True when group ``gid`` holds the user ``uid`` alone (a user-private group, umask 002 systems)."""
    try:
        import grp
        import pwd

        group, user = grp.getgrgid(gid), pwd.getpwuid(uid)
        if any(member != user.pw_name for member in group.gr_mem):
            return False
        return all(entry.pw_gid != gid or entry.pw_uid == uid for entry in pwd.getpwall())
    except (ImportError, KeyError):
        return False


def _writable_by_others(info: os.stat_result, ancestor: bool) -> str | None:
    """Why an entry with ``info`` can be changed by another user, or None."""
    uid = os.getuid()
    if info.st_uid not in (uid, 0):
        return f"belongs to user id {info.st_uid}, not to you ({uid}) or root"
    mode = info.st_mode
    if mode & stat.S_IWOTH and not (ancestor and mode & stat.S_ISVTX):
        return f"is writable by every user (mode {stat.filemode(mode)})"
    if mode & stat.S_IWGRP and not (ancestor and mode & stat.S_ISVTX) and not _private_group(info.st_gid, uid):
        return f"is writable by its group, gid {info.st_gid} (mode {stat.filemode(mode)})"
    return None


def _refuse_shared(directory: Path, checked: dict[str, os.stat_result]) -> None:
    if os.name != "posix":   # ownership and mode bits mean something else there; the digests are still checked
        return
    for name, info in [(str(directory), os.stat(directory))] + [(str(directory / n), i) for n, i in checked.items()]:
        why = _writable_by_others(info, ancestor=False)
        if why:
            raise UntrustedTree(f"{name}: {why}; a tree other users can write is not executed (its manifest could "
                                f"have been rewritten too) -- fix with: chmod go-w {name}")
    for parent in directory.parents:
        why = _writable_by_others(os.stat(parent), ancestor=True)
        if why:
            raise UntrustedTree(f"{directory}: the directory above it, {parent}, {why}; another user could replace "
                                f"the tree, so it is not executed -- fix with: chmod go-w {parent} (or move the tree)")


def verify(directory) -> dict[str, bytes]:
    """Check ``directory`` against its manifest and its permissions; the verified bytes of its Python files.

    Raises :class:`UntrustedTree` or :class:`ManifestError` (a subclass of ``ImportError``) naming the path,
    the file and, for a changed file, the expected and the found SHA-256.
    """
    directory = Path(os.path.realpath(Path(directory).expanduser()))
    entries = read(directory)
    # who can write comes first: it holds even where the digests are waived (REBUILD_ENV)
    _refuse_shared(directory, {name: os.stat(directory / name) for name in [MANIFEST, *sorted(entries)]
                               if (directory / name).exists()})
    contents = {}
    for name, expected in sorted(entries.items()):
        path = directory / name
        try:
            with open(path, "rb") as handle:   # read once: the bytes checked are the bytes executed
                data = handle.read()
        except OSError as error:
            raise ManifestError(f"{directory}: {name} is listed in {MANIFEST} but cannot be read "
                                f"({error.strerror or error}); refusing the tree") from None
        found = digest(data)
        if found != expected:
            raise ManifestError(f"{path}: SHA-256 {found} where {MANIFEST} records {expected}: the file was changed "
                                "after the build; refusing to execute the tree (rebuild it, or restore the file)")
        if name.endswith(".py"):
            contents[name] = data
    extra = sorted(p.name for p in directory.iterdir() if p.suffix == ".py" and p.name not in entries)
    if extra:
        raise ManifestError(f"{directory}: {', '.join(extra)} is not listed in {MANIFEST}; a tree with unlisted "
                            "Python files is not executed")
    return contents


class _Verified(importlib.abc.Loader):
    """Executes source bytes that :func:`verify` checked."""

    def __init__(self, source: bytes, path: Path):
        self.source, self.path = source, path

    def create_module(self, spec):
        return None

    def exec_module(self, module):
        exec(compile(self.source, str(self.path), "exec", dont_inherit=True), module.__dict__)

    def get_source(self, name):
        return self.source.decode("utf-8")


def _execute(name: str, path: Path, source: bytes, package: bool = False) -> ModuleType:
    spec = importlib.util.spec_from_file_location(name, path, loader=_Verified(source, path),
                                                  submodule_search_locations=[str(path.parent)] if package else None)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        sys.modules.pop(name, None)
        raise
    return module


def load_module(directory, name: str) -> ModuleType:
    """``directory/suslov_formulas.py`` as the module ``name``, after :func:`verify` (its checked bytes)."""
    directory = Path(os.path.realpath(Path(directory).expanduser()))
    contents = verify(directory)
    return _execute(name, directory / MODULE, contents[MODULE])


def import_verified(name: str) -> ModuleType:
    """``importlib.import_module(name)`` for ``PACKAGE.suslov_formulas`` (``generated`` of a checkout,
    ``suslov.formulas`` of a wheel), with the package's tree verified before its ``__init__`` runs.

    Raises ``ModuleNotFoundError`` (with ``.name``) when the package does not exist, like an import.
    """
    if name in sys.modules:
        return sys.modules[name]
    package, _, leaf = name.rpartition(".")
    if leaf + ".py" != MODULE:
        raise ValueError(f"{name}: only a package's {MODULE} is loaded this way")
    spec = importlib.util.find_spec(package)   # imports the package's parents, not the package itself
    if spec is None or not spec.submodule_search_locations:
        raise ModuleNotFoundError(f"No module named {package!r}", name=package)
    directory = Path(list(spec.submodule_search_locations)[0])
    if not (directory / MODULE).is_file():
        raise ModuleNotFoundError(f"No module named {name!r}", name=name)
    directory = Path(os.path.realpath(directory))
    try:
        contents = verify(directory)
    except UntrustedTree:
        raise
    except ManifestError as error:
        if os.environ.get(REBUILD_ENV) != str(directory):
            raise
        _refuse_shared(directory, {n: os.stat(directory / n) for n in ("__init__.py", MODULE)})
        contents = {n: (directory / n).read_bytes() for n in ("__init__.py", MODULE)}
        print(f"suslov: {error}; loaded anyway for the build that rewrites it ({REBUILD_ENV})", file=sys.stderr)
    parent = sys.modules.get(package) or _execute(package, directory / "__init__.py", contents["__init__.py"],
                                                  package=True)
    module = _execute(name, directory / MODULE, contents[MODULE])
    setattr(parent, leaf, module)
    return module
