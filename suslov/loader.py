"""Which generated module the run-time package uses, and certified modules for any p range (issue 26).

The build emits one module, ``suslov_formulas.py`` (certified as emitted: ``derivations/output/roundtrip.py``),
with the per-p objects up to its ``PMAX``.  This module finds the one in use and loads others:

* :func:`active_formulas` -- the active module, in this order: the one given to :func:`use_formulas`; the
  directory in the environment variable ``SUSLOV_FORMULAS``; ``generated/suslov_formulas.py`` of a
  source checkout; ``suslov.formulas.suslov_formulas`` of an installed wheel (the same file, shipped
  inside the ``suslov`` namespace).
* :func:`load_formulas` -- a certified module for a larger range without touching the checkout:
  ``load_formulas(pmax=101)`` returns a module from the per-user store (:func:`store_dir`), building
  it once with ``python -m suslov.build --pmax 101 --install`` (the derivations shipped in the package,
  or the checkout's: :mod:`suslov.build`; it certifies the module, through the certificate cache, with
  progress on stderr) when the store has none that covers the range; ``load_formulas(path=DIR)`` loads
  a tree written with ``--out DIR``.
* :data:`gf` -- a stand-in that forwards attribute access to the active module at call time, so the
  simulator modules follow :func:`use_formulas` without re-importing.

A module loaded here answers ``load_certificates()`` from the bytes of ``certificates.json`` that
:func:`suslov.manifest.verify` read and checked against the tree's manifest -- the one read of that file
(:func:`_bind_certificates`); the emitted function would read the file again at each call, after the
verified load, and return an edit made in between unchecked (issue 44).  Before a build for
:func:`load_formulas`, the certificate cache it installs from must be private like the store
(:func:`suslov.manifest.refuse_shared_cache`).

Building needs the ``[build]`` extra (SymPy, symengine, Jinja2); without it :func:`load_formulas` says
which extra to install.  The build runs in a child process that ends with its caller: Ctrl-C stops both,
and a caller killed outright takes the build with it (``PR_SET_PDEATHSIG`` on Linux).
"""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from types import ModuleType

import suslov.manifest as manifest
from suslov.extras import require
from suslov.interrupts import die_with_parent

__all__ = ["active_formulas", "use_formulas", "load_formulas", "store_dir", "cache_dir", "gf", "FORMULAS_ENV",
           "DATA_ENV", "CACHE_ENV"]

FORMULAS_ENV = "SUSLOV_FORMULAS"   # a directory holding a generated suslov_formulas.py
DATA_ENV = "SUSLOV_DATA_DIR"       # the per-user store (default: $XDG_DATA_HOME/suslov-certified)
CACHE_ENV = "SUSLOV_CACHE_DIR"     # the build's certificate cache (default: $XDG_CACHE_HOME/suslov-certified)
NO_CACHE_ENV = "SUSLOV_NO_CACHE"   # set: builds bypass the cache (derivations/output/cli.py)
_active: ModuleType | None = None
_loaded: dict = {}


def store_dir() -> Path:
    """The per-user store of built modules: ``$SUSLOV_DATA_DIR``, else the platform's per-user data
    directory (platformdirs: ``$XDG_DATA_HOME/suslov-certified`` or ``~/.local/share/suslov-certified``
    on Linux)."""
    if os.environ.get(DATA_ENV):
        return Path(os.environ[DATA_ENV]).expanduser()
    import platformdirs

    return Path(platformdirs.user_data_dir("suslov-certified", appauthor=False))


def cache_dir() -> Path:
    """The build's certificate cache (``derivations.core.cache.cache_root`` calls this): ``$SUSLOV_CACHE_DIR``, else
    the platform's per-user cache directory (``$XDG_CACHE_HOME/suslov-certified`` or ``~/.cache/suslov-certified``
    on Linux)."""
    if os.environ.get(CACHE_ENV):
        return Path(os.environ[CACHE_ENV])
    import platformdirs

    return Path(platformdirs.user_cache_dir("suslov-certified", appauthor=False))


CERTIFICATES = "certificates.json"


def _pmax_in(data: bytes) -> int | None:
    try:
        value = json.loads(data.decode("utf-8"))["pmax"]
    except (ValueError, KeyError, TypeError):
        return None
    return value if isinstance(value, int) and not isinstance(value, bool) and value >= 1 else None


def _pmax_of(directory: Path) -> int | None:
    """The PMAX a store entry's ``certificates.json`` states, or None (unreadable; the entry is ignored).

    Read only if it is a regular file: a FIFO there is refused (``NotRegularFile``, naming it) rather than
    blocking :func:`load_formulas` forever.  This read only chooses an entry; :func:`_load_directory` then
    verifies the entry and uses the bytes it checked."""
    try:
        return _pmax_in(manifest.read_regular(directory / CERTIFICATES))
    except OSError:
        return None


def _load_directory(directory: Path) -> ModuleType:
    directory = Path(directory).expanduser().resolve()
    key = str(directory)
    if key in _loaded:
        return _loaded[key]
    if not all(os.path.lexists(directory / name) for name in (manifest.MODULE, CERTIFICATES)):
        raise FileNotFoundError(f"{directory}: not a generated tree (needs suslov_formulas.py and a readable "
                                "certificates.json; write one with build_formulas.py --out DIR)")
    # the manifest and who can write are checked, and every file read once (a FIFO refused, never opened
    # blocking), before anything runs; certificates.json is judged from those same bytes
    contents = manifest.verify(directory)
    if _pmax_in(contents[CERTIFICATES]) is None:
        raise ValueError(f"{directory / CERTIFICATES}: no positive integer 'pmax'; not a generated tree (write one "
                         "with build_formulas.py --out DIR)")
    # a distinct module name per directory: two ranges can be loaded side by side; exactly the checked bytes
    # are executed (suslov.manifest)
    module = manifest.load_module(directory, f"suslov_formulas_{abs(hash(key)):x}", contents=contents)
    _bind_certificates(module, directory)
    _loaded[key] = module
    return module


def _bind_certificates(module: ModuleType, directory: Path) -> ModuleType:
    """Replace ``module.load_certificates`` by one that parses the verified bytes of ``certificates.json``.

    The bytes are those :func:`suslov.manifest.verify` read and checked against the tree's manifest when the
    module was loaded (:func:`suslov.manifest.verified_files`): the file is read once, and
    ``load_certificates()`` parses exactly those bytes at every call, whatever happens to the file afterwards.
    A module imported some other way (found in ``sys.modules``) has its tree verified here, and those bytes are
    used.  The one exception is the build's own stale ``generated/`` (``SUSLOV_REBUILDING``,
    :mod:`suslov.manifest`): that tree is loaded unverified and keeps its emitted function.
    """
    if getattr(getattr(module, "load_certificates", None), "verified_bytes", None) is not None:
        return module   # bound already (a module taken from sys.modules)
    directory = Path(os.path.realpath(directory))
    files = manifest.verified_files(module)
    if files is None:
        if os.environ.get(manifest.REBUILD_ENV) == str(directory):
            return module
        files = manifest.verify(directory)
    data = files[CERTIFICATES]
    found = manifest.digest(data)
    emitted = module.load_certificates

    def load_certificates() -> dict:
        return json.loads(data.decode("utf-8"))

    load_certificates.__doc__ = (emitted.__doc__ or "").rstrip() + (
        f"\n\n    Parsed from the bytes of ``certificates.json`` checked against {manifest.MANIFEST} when the module "
        "was loaded (SHA-256 " + found + ").\n")
    load_certificates.__module__ = module.__name__
    load_certificates.__qualname__ = load_certificates.__name__ = "load_certificates"
    load_certificates.verified_bytes = data
    load_certificates.sha256 = found
    module.load_certificates = load_certificates
    return module


def _default() -> ModuleType:
    if os.environ.get(FORMULAS_ENV):
        return _load_directory(Path(os.environ[FORMULAS_ENV]))
    try:
        module = manifest.import_verified("generated.suslov_formulas")
    except ModuleNotFoundError as error:
        if error.name not in ("generated", "generated.suslov_formulas"):
            raise
        module = manifest.import_verified("suslov.formulas.suslov_formulas")
    return _bind_certificates(module, Path(module.__file__).parent)


def active_formulas() -> ModuleType:
    """The generated module in use (see the module docstring for the order of precedence)."""
    global _active
    if _active is None:
        _active = _default()
    return _active


def use_formulas(module_or_path=None) -> ModuleType:
    """Make ``module_or_path`` (a module from :func:`load_formulas` or a directory) the one ``suslov``
    uses; ``None`` goes back to the default.  Returns the active module."""
    global _active
    if module_or_path is None:
        _active = None
    elif isinstance(module_or_path, ModuleType):
        _active = module_or_path
    else:
        _active = _load_directory(Path(module_or_path))
    return active_formulas()


def _stored(pmax: int) -> Path | None:
    """The stored tree with the smallest PMAX >= pmax, if any."""
    root = store_dir()
    if not root.is_dir():
        return None
    found = [(_pmax_of(entry), entry) for entry in root.iterdir() if entry.is_dir() and entry.name.startswith("pmax-")]
    covering = sorted((p, entry) for p, entry in found if p is not None and p >= pmax)
    return covering[0][1] if covering else None


def load_formulas(pmax: int | None = None, path=None, *, build: bool = True, use: bool = False,
                  quiet: bool = False) -> ModuleType:
    """A certified generated module covering ``p <= pmax`` (or the tree at ``path``).

    From the per-user store when a stored module covers the range; otherwise, with ``build=True``,
    built once by ``python -m suslov.build --pmax N --install`` (the derivations shipped in the package or
    the checkout's; needs the ``[build]`` extra; progress and the time estimate on stderr unless ``quiet``;
    about 1 minute for pmax 51, 4 for 101 on two cores).  Ctrl-C stops the build too.
    ``use=True`` also makes it the module ``import suslov`` uses (:func:`use_formulas`).

    >>> sf = load_formulas(pmax=15)              # doctest: +SKIP
    >>> sf.gamma_basis(0.1, 15, 0.5).shape        # doctest: +SKIP
    (3, 3)
    """
    if (pmax is None) == (path is None):
        raise ValueError("load_formulas: give exactly one of pmax (a p range) or path (a --out directory)")
    if path is not None:
        module = _load_directory(Path(path))
    else:
        if isinstance(pmax, bool) or not isinstance(pmax, int) or pmax < 1:
            raise ValueError(f"pmax={pmax!r}: must be a positive integer")
        default = active_formulas()
        if default.PMAX >= pmax:
            module = default
        else:
            entry = _stored(pmax)
            if entry is None:
                if not build:
                    raise LookupError(f"no stored module covers pmax={pmax} in {store_dir()}")
                _build(pmax, quiet)
                entry = _stored(pmax)
            module = _load_directory(entry)
    return use_formulas(module) if use else module


def _build(pmax: int, quiet: bool) -> None:
    require("build", f"load_formulas(pmax={pmax}) beyond the shipped module (pmax {active_formulas().PMAX})")
    if not os.environ.get(NO_CACHE_ENV):
        # the build installs whole trees and unpickles per-p results from the cache: a cache others can write
        # would hand us their module with a consistent manifest, so it is held to the store's rule (issue 44)
        manifest.refuse_shared_cache(cache_dir(), f"${CACHE_ENV}" if os.environ.get(CACHE_ENV) else
                                     "the certificate cache")
    command = [sys.executable, "-m", "suslov.build", "--pmax", str(pmax), "--install"] + (["--quiet"] if quiet else [])
    # the child dies with this process (SIGTERM; its own workers die with it in turn)
    with subprocess.Popen(command, stdout=subprocess.DEVNULL if quiet else None,
                          preexec_fn=lambda: die_with_parent(signal.SIGTERM)) as child:
        try:
            returncode = child.wait()
        except BaseException:
            _stop(child)
            raise
    if returncode == 130:
        raise KeyboardInterrupt
    if returncode != 0:
        raise RuntimeError(f"python -m suslov.build --pmax {pmax} --install failed (exit {returncode}); see its "
                           "message above")


def _stop(child: subprocess.Popen) -> None:
    """End an interrupted build: a Ctrl-C at a terminal reached it too (the same process group), so it gets a
    moment to stop by itself; then SIGINT (it removes its staging and says so); then SIGKILL."""
    for action, grace in ((None, 1.0), (child.send_signal, 3.0)):
        if action is not None:
            action(signal.SIGINT)
        try:
            child.wait(grace)
            return
        except subprocess.TimeoutExpired:
            continue
    child.kill()
    child.wait()


class _Forward:
    """Attribute access forwarded to the active generated module (see :data:`gf`)."""

    def __getattr__(self, name: str):
        return getattr(active_formulas(), name)

    def __repr__(self) -> str:
        return f"<forward to {active_formulas().__name__} (pmax {active_formulas().PMAX})>"


gf = _Forward()
