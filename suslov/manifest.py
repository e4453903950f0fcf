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
  sticky bit, as ``/tmp``) -- whoever can write there can rewrite the manifest too.  "Writable" reads
  the POSIX access ACL as well as the mode bits (:mod:`suslov.acl`: ``setfacl -m u:nobody:rw`` leaves
  a mode that looks private), and an ACL that cannot be read is a refusal;
* opens only regular files (a FIFO as ``SHA256SUMS`` or ``certificates.json`` would block the read
  forever): :class:`NotRegularFile`, a ``ValueError`` naming the file;
* refuses a tree without a manifest, a manifest that omits the module, ``__init__.py`` or
  ``certificates.json``, a listed file that is missing or whose digest differs (naming the file, the
  expected and the found digest), and a Python file that the manifest does not list;
* returns the bytes it checked, each file read once: :func:`load_module` executes exactly those bytes
  (never a cached ``.pyc``, never a second read of the file), and :func:`verified_files` gives the
  loader the checked ``certificates.json`` to parse.

:func:`refuse_shared_cache` applies the same rule to the certificate cache (``$SUSLOV_CACHE_DIR``),
whose pickles and whole trees a build installs and runs.

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
import weakref
from pathlib import Path
from types import ModuleType

import suslov.acl as acl

__all__ = ["MANIFEST", "REQUIRED", "ManifestError", "UntrustedTree", "UntrustedCache", "NotRegularFile", "digest",
           "write", "read", "read_regular", "verify", "verified_files", "load_module", "import_verified",
           "refuse_shared_cache"]

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


class UntrustedCache(UntrustedTree, ValueError):
    """A certificate cache (``$SUSLOV_CACHE_DIR``) that other users can write; no build used it."""


class NotRegularFile(ManifestError, ValueError):
    """A tree's file that is a FIFO, device, socket or directory; it was not read (a FIFO would block)."""


# the verified bytes of every module loaded here, for the loader's certificates.json (one read, issue 44)
_VERIFIED: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


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
    return _parse(path, _read_manifest(path, check=False))


def _read_manifest(path: Path, check: bool) -> bytes:
    try:
        return read_regular(path, check=check)
    except FileNotFoundError:
        raise ManifestError(f"{path.parent}: no {MANIFEST} (the manifest every build writes last); a tree "
                            "without one is not executed -- rebuild it with build_formulas.py (--out DIR or "
                            "--pmax N --install)") from None
    except OSError as error:
        raise ManifestError(f"{path}: cannot be read ({error.strerror or error})") from None


def _parse(path: Path, data: bytes) -> dict[str, str]:
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
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


_KINDS = ((stat.S_ISFIFO, "a FIFO (named pipe)"), (stat.S_ISCHR, "a character device"),
          (stat.S_ISBLK, "a block device"), (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a directory"))


def _not_regular(path, info: os.stat_result) -> NotRegularFile:
    kind = next((name for test, name in _KINDS if test(info.st_mode)), "a special file")
    return NotRegularFile(f"{path}: is {kind} (mode {stat.filemode(info.st_mode)}), not a regular file; a generated "
                          "tree holds regular files only, so it is refused without reading it (a FIFO would block)")


def read_regular(path, check: bool = False) -> bytes:
    """The bytes of ``path``, read once, if it is a regular file; :class:`NotRegularFile` otherwise.

    Never blocks on a FIFO: the file is examined (``stat``) before it is opened, opened non-blocking, and
    examined again on the open descriptor (``fstat``: it may have been swapped in between).  With
    ``check``, the open file must also be writable by no other user (:class:`UntrustedTree`), checked on
    the descriptor whose bytes are returned.  ``OSError`` (``FileNotFoundError`` ...) passes through.
    """
    path = Path(path)
    info = os.stat(path)
    if not stat.S_ISREG(info.st_mode):
        raise _not_regular(path, info)
    flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
    fd = os.open(path, flags)
    with open(fd, "rb", closefd=True) as handle:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise _not_regular(path, info)
        if check and os.name == "posix":
            _refuse(path, _writable_by_others(info, False, fd))
        return handle.read()


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


def _writable_by_others(info: os.stat_result, ancestor: bool, target) -> tuple[str, str] | None:
    """Why an entry with ``info`` (at ``target``: a path or a descriptor) can be changed by another user, and
    the command that fixes it; or None."""
    uid = os.getuid()
    if info.st_uid not in (uid, 0):
        return f"belongs to user id {info.st_uid}, not to you ({uid}) or root", f"chown {uid}"
    mode = info.st_mode
    if ancestor and mode & stat.S_ISVTX:
        return None   # sticky (as /tmp): others may add entries but not replace ours, whatever may write it
    if mode & stat.S_IWOTH:
        return f"is writable by every user (mode {stat.filemode(mode)})", "chmod go-w"
    try:
        entries = acl.access_acl(target)
    except (acl.AclUnreadable, acl.AclError) as error:
        # an ACL we cannot read could grant anyone write: refuse rather than trust the mode bits
        text = error.strerror if isinstance(error, OSError) else f"its access ACL cannot be parsed: {error}"
        return f"{text} (mode {stat.filemode(mode)}), so who may write it is unknown", "setfacl -b"
    if entries is None:
        if mode & stat.S_IWGRP and not _private_group(info.st_gid, uid):
            return f"is writable by its group, gid {info.st_gid} (mode {stat.filemode(mode)})", "chmod go-w"
        return None
    for entry in acl.writers(entries):
        if entry.tag == acl.USER and entry.id not in (info.st_uid, uid, 0):
            who = f"user id {entry.id}"
        elif entry.tag == acl.GROUP_OBJ and not _private_group(info.st_gid, uid):
            who = f"its group, gid {info.st_gid}"
        elif entry.tag == acl.GROUP and not _private_group(entry.id, uid):
            who = f"group id {entry.id}"
        elif entry.tag == acl.OTHER:
            who = "every user"
        else:
            continue
        return (f"is writable by {who} through its POSIX access ACL ({acl.XATTR}; mode {stat.filemode(mode)})",
                "setfacl -b")
    return None


def _refuse(name, found: tuple[str, str] | None) -> None:
    if found:
        why, fix = found
        raise UntrustedTree(f"{name}: {why}; a tree other users can write is not executed (its manifest could "
                            f"have been rewritten too) -- fix with: {fix} {name}")


def _refuse_shared(directory: Path) -> None:
    """The directory itself and every directory above it (the files are checked as they are read)."""
    if os.name != "posix":   # ownership and mode bits mean something else there; the digests are still checked
        return
    _refuse(directory, _writable_by_others(os.stat(directory), False, str(directory)))
    for parent in directory.parents:
        found = _writable_by_others(os.stat(parent), True, str(parent))
        if found:
            why, fix = found
            raise UntrustedTree(f"{directory}: the directory above it, {parent}, {why}; another user could replace "
                                f"the tree, so it is not executed -- fix with: {fix} {parent} (or move the tree)")


def verify(directory) -> dict[str, bytes]:
    """Check ``directory`` against its manifest and its permissions; the verified bytes of every listed file.

    Each file is read once, on a descriptor checked to be a regular file nobody else can write; the bytes
    returned are the bytes hashed.  Raises :class:`UntrustedTree`, :class:`NotRegularFile` or
    :class:`ManifestError` (subclasses of ``ImportError``) naming the path, the file and, for a changed file,
    the expected and the found SHA-256.
    """
    directory = Path(os.path.realpath(Path(directory).expanduser()))
    # who can write comes first: it holds even where the digests are waived (REBUILD_ENV)
    _refuse_shared(directory)
    entries = _parse(directory / MANIFEST, _read_manifest(directory / MANIFEST, check=True))
    contents, unreadable = {}, {}
    for name in sorted(entries):
        try:   # read once: the bytes checked are the bytes executed (and parsed: certificates.json)
            contents[name] = read_regular(directory / name, check=True)
        except OSError as error:   # reported after every file's permissions were checked
            unreadable[name] = error
    for name, error in unreadable.items():
        raise ManifestError(f"{directory}: {name} is listed in {MANIFEST} but cannot be read "
                            f"({error.strerror or error}); refusing the tree") from None
    for name, expected in sorted(entries.items()):
        found = digest(contents[name])
        if found != expected:
            raise ManifestError(f"{directory / name}: SHA-256 {found} where {MANIFEST} records {expected}: the file "
                                "was changed after the build; refusing to execute the tree (rebuild it, or restore "
                                "the file)")
    extra = sorted(p.name for p in directory.iterdir() if p.suffix == ".py" and p.name not in entries)
    if extra:
        raise ManifestError(f"{directory}: {', '.join(extra)} is not listed in {MANIFEST}; a tree with unlisted "
                            "Python files is not executed")
    return contents


def verified_files(module: ModuleType) -> dict[str, bytes] | None:
    """The bytes :func:`verify` checked for the tree ``module`` was executed from (by :func:`load_module` or
    :func:`import_verified`), or None (a module imported another way, or under the rebuild waiver)."""
    return _VERIFIED.get(module)


def refuse_shared_cache(root, label: str = "the certificate cache") -> None:
    """Refuse (:class:`UntrustedCache`, a ``ValueError``) a cache directory that another user can write.

    The rule of the store: ``root``, everything inside it and every directory above it belong to you or root
    and nobody else can write them (mode bits and access ACL; a sticky world-writable ancestor as /tmp is
    fine).  A cache that does not exist yet is checked through the directories above it (the build creates
    it, private).  Symbolic links inside are checked at their target and not followed into.
    """
    if os.name != "posix":
        return
    root = Path(os.path.realpath(Path(root)))

    def refuse(name, found, above=False):
        if found:
            why, fix = found
            place = f"the directory above it, {name}," if above else (name if name != root else "it")
            raise UntrustedCache(f"{label} {root}: {place} {why}; a build installs and runs the trees and pickles "
                                 f"it holds, so a cache other users can write is not used -- fix with: {fix} {name} "
                                 "(or point SUSLOV_CACHE_DIR at a private directory, or set SUSLOV_NO_CACHE=1)")

    for parent in root.parents:
        if os.path.lexists(parent):
            refuse(parent, _writable_by_others(os.stat(parent), True, str(parent)), above=True)
    if not os.path.lexists(root):
        return
    if not root.is_dir():
        raise UntrustedCache(f"{label} {root}: is not a directory; refusing to build with it")
    todo = [root]
    while todo:
        current = todo.pop()
        try:
            refuse(current, _writable_by_others(os.stat(current), False, str(current)))
            if current is root or current.is_dir() and not current.is_symlink():
                todo.extend(sorted(Path(e.path) for e in os.scandir(current)))
        except FileNotFoundError:
            continue   # removed meanwhile (a concurrent build's staging): nothing left to trust
        except OSError as error:
            raise UntrustedCache(f"{label} {root}: {current} cannot be examined ({error.strerror or error}); "
                                 "refusing to build with a cache whose permissions are unknown") from None


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


def load_module(directory, name: str, contents: dict[str, bytes] | None = None) -> ModuleType:
    """``directory/suslov_formulas.py`` as the module ``name``, after :func:`verify` (its checked bytes).

    ``contents``: what :func:`verify` returned for ``directory`` when the caller has just called it (the loader
    looks at ``certificates.json`` first); the files are then not read again.
    """
    directory = Path(os.path.realpath(Path(directory).expanduser()))
    if contents is None:
        contents = verify(directory)
    module = _execute(name, directory / MODULE, contents[MODULE])
    _VERIFIED[module] = dict(contents)
    return module


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
    if not os.path.lexists(directory / MODULE):   # present but not a regular file: verify names it
        raise ModuleNotFoundError(f"No module named {name!r}", name=name)
    directory = Path(os.path.realpath(directory))
    verified = None
    try:
        contents = verified = verify(directory)
    except (UntrustedTree, NotRegularFile):
        raise
    except ManifestError as error:
        if os.environ.get(REBUILD_ENV) != str(directory):
            raise
        _refuse_shared(directory)
        contents = {n: read_regular(directory / n, check=True) for n in ("__init__.py", MODULE)}
        print(f"suslov: {error}; loaded anyway for the build that rewrites it ({REBUILD_ENV})", file=sys.stderr)
    parent = sys.modules.get(package) or _execute(package, directory / "__init__.py", contents["__init__.py"],
                                                  package=True)
    module = _execute(name, directory / MODULE, contents[MODULE])
    if verified is not None:
        _VERIFIED[module] = verified
    setattr(parent, leaf, module)
    return module
