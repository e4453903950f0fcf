"""The build's certificate cache, keyed by content (issue 13: warm rebuilds).

Two levels, both keyed by what the result depends on and nothing else:

* **Per-p results** of ``CertificateLog.map_per_p`` (the Frobenius logarithms at t0, the logarithms
  at s1..s4 of section 5.2, the meromorphic bases of Theorem 6.1): the key hashes the work
  function's name, the source of its module and of every module of ``derivations`` and ``suslov``
  it imports (transitively), the versions of the libraries, and p.  Changing galois.py recomputes
  the galois phase; residue's entries stay valid.
* **Whole builds**: the key hashes every source the build reads (``derivations/``, ``suslov/``,
  ``templates/``, ``build_formulas.py``), the library versions and the options; a hit installs the
  stored tree (the same files a cold build writes) in about a second.

Per-p entries live in the executor's ``ChunkStore`` (pickles with the key and a SHA-256 of the
payload in a header; whole trees carry a manifest of SHA-256 per file): a truncated, edited or
foreign entry fails the check and is recomputed, never trusted (and never unpickled before its
checksum matched).  Location: ``$SUSLOV_CACHE_DIR``, else the platform's per-user cache directory
(``platformdirs``: ``$XDG_CACHE_HOME/suslov-certified`` or ``~/.cache/suslov-certified`` on Linux); deleting it is always safe.  ``--no-cache`` bypasses it.
Which results came from the cache is recorded in the volatile ``cache_report.json``: the
committed outputs are byte-identical cold or warm.

Why not ``diskcache`` (issue 36 asked): it stores pickles in SQLite and unpickles what it reads, with
no checksum of the payload, so an edited or foreign entry would be executed by ``pickle.loads``
before anything could reject it; here nothing is unpickled before its SHA-256 matched the key's, and
the store is plain files a user can inspect and delete.  The two levels share that mechanism
(``ChunkStore`` for per-p results and sweep chunks, a manifest of the same digests for trees).
"""
from __future__ import annotations

import ast
import functools
import hashlib
import importlib.metadata
import importlib.util
import json
import os
import platform
import shutil
from pathlib import Path


from suslov.executor import TMP_PREFIX
from suslov.outdir import make_dir, remove_stale

ROOT = Path(__file__).resolve().parents[2]   # the build tree: the checkout, or suslov/build/ in a wheel
SUSLOV_PARENT = Path(importlib.util.find_spec("suslov").origin).resolve().parents[1]   # the checkout, or site-packages
PACKAGES = {"derivations": ROOT, "suslov": SUSLOV_PARENT}
LIBRARIES = ("sympy", "symengine", "mpmath", "python-flint", "numpy", "jinja2", "scipy", "heyoka")
BUILD_SOURCES = ((ROOT, "derivations"), (SUSLOV_PARENT, "suslov"), (ROOT, "templates"), (ROOT, "build_formulas.py"))


_TRUSTED_ROOTS: set = set()


def cache_root() -> Path:
    """``$SUSLOV_CACHE_DIR``, else the platform's per-user cache directory (platformdirs).

    Refused (``suslov.manifest.UntrustedCache``, a ValueError naming the path) when another user can write it, its
    contents or a directory above it: the build unpickles per-p results and installs trees from it (the rule of
    the per-user store, docs/trust.md).  Checked once per directory and process.
    """
    from suslov.loader import cache_dir   # one definition: the loader checks the same directory before a build
    from suslov.manifest import refuse_shared_cache

    root = cache_dir()
    if root not in _TRUSTED_ROOTS:
        refuse_shared_cache(root)
        _TRUSTED_ROOTS.add(root)
    return root


@functools.cache
def library_versions() -> tuple:
    versions = [("python", platform.python_version())]
    for name in LIBRARIES:
        try:
            versions.append((name, importlib.metadata.version(name)))
        except importlib.metadata.PackageNotFoundError:
            versions.append((name, None))
    return tuple(versions)


def _module_file(name: str) -> Path | None:
    parts = name.split(".")
    if parts[0] not in PACKAGES:
        return None
    path = PACKAGES[parts[0]].joinpath(*parts)
    for candidate in (path.with_suffix(".py"), path / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _imports(name: str, path: Path) -> set:
    """Modules of our packages that ``name`` imports (absolute and relative forms)."""
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[:len(anchor) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            found.add(base)
            found.update(f"{base}.{a.name}" for a in node.names)
    return {m for m in found if _module_file(m) is not None}


@functools.cache
def module_digest(name: str) -> str:
    """SHA-256 over the source of ``name`` and of every module of ours it imports, transitively."""
    seen, todo = {}, [name]
    while todo:
        current = todo.pop()
        path = _module_file(current)
        if current in seen or path is None:
            continue
        seen[current] = path
        todo.extend(_imports(current, path))
    digest = hashlib.sha256()
    for module in sorted(seen):
        digest.update(module.encode() + b"\0" + seen[module].read_bytes() + b"\0")
    return digest.hexdigest()


def per_p_key(work, value) -> str:
    blob = json.dumps([work.__module__, work.__qualname__, module_digest(work.__module__), library_versions(),
                       repr(value)])
    return hashlib.sha256(blob.encode()).hexdigest()[:40]


def build_key(options, only) -> str:
    digest = hashlib.sha256()
    for base, source in BUILD_SOURCES:
        path = base / source
        files = sorted(p for p in path.rglob("*") if p.is_file() and "__pycache__" not in p.parts) \
            if path.is_dir() else [path] if path.is_file() else []   # a wheel has no build_formulas.py
        for f in files:
            digest.update(str(f.relative_to(base)).encode() + b"\0" + f.read_bytes() + b"\0")
    digest.update(json.dumps([options.pmax, options.ball_checks, options.cross_check_pmax, sorted(only or []),
                               library_versions()]).encode())
    return digest.hexdigest()[:40]


def per_p_store():
    """The per-p results: the executor's checksummed store (one mechanism for sweeps and the build)."""
    from suslov.executor import ChunkStore

    return ChunkStore(cache_root() / "per-p", codec="pkl")


class TreeCache:
    """Whole output trees: ``builds/<key>/`` with a manifest of SHA-256 per file."""

    def __init__(self, root: Path | None = None):
        self.root = (root or cache_root()) / "builds"

    def lookup(self, key: str) -> Path | None:
        entry = self.root / key
        try:
            manifest = json.loads((entry / "manifest.json").read_text(encoding="utf-8"))
            files = {p.name for p in entry.iterdir() if p.name != "manifest.json"}
            if manifest["key"] != key or files != set(manifest["files"]):
                return None
            for name, checksum in manifest["files"].items():
                if hashlib.sha256((entry / name).read_bytes()).hexdigest() != checksum:
                    return None
        except (OSError, ValueError, KeyError, TypeError):
            return None
        return entry

    def store(self, key: str, tree: Path, keep=lambda name: True) -> None:
        make_dir(self.root)
        remove_stale(self.root, TMP_PREFIX)
        staging = self.root / f"{TMP_PREFIX}-{os.getpid()}-{key}"
        shutil.rmtree(staging, ignore_errors=True)
        os.mkdir(staging, 0o777)
        try:
            files = {}
            for item in sorted(Path(tree).iterdir()):
                if item.is_file() and keep(item.name):
                    shutil.copyfile(item, staging / item.name)
                    files[item.name] = hashlib.sha256(item.read_bytes()).hexdigest()
            (staging / "manifest.json").write_text(json.dumps({"key": key, "files": files}, indent=1,
                                                              sort_keys=True))
            final = self.root / key
            if final.exists():
                shutil.rmtree(final, ignore_errors=True)
            try:
                staging.rename(final)
            except OSError:
                if self.lookup(key) is None:   # not a concurrent build's equal entry: a real failure
                    raise
                shutil.rmtree(staging, ignore_errors=True)
        except BaseException:
            shutil.rmtree(staging, ignore_errors=True)
            raise
