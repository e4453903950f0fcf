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

A module loaded here answers ``load_certificates()`` from the bytes of ``certificates.json`` read once
when it was loaded and checked then against the tree's manifest (:func:`_bind_certificates`); the
emitted function would read the file again at each call, after the verified load, and return an edit
made in between unchecked (issue 44).

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

__all__ = ["active_formulas", "use_formulas", "load_formulas", "store_dir", "gf", "FORMULAS_ENV", "DATA_ENV"]

FORMULAS_ENV = "SUSLOV_FORMULAS"   # a directory holding a generated suslov_formulas.py
DATA_ENV = "SUSLOV_DATA_DIR"       # the per-user store (default: $XDG_DATA_HOME/suslov-certified)
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


def _pmax_of(directory: Path) -> int | None:
    try:
        return int(json.loads((directory / "certificates.json").read_text(encoding="utf-8"))["pmax"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _load_directory(directory: Path) -> ModuleType:
    directory = Path(directory).expanduser().resolve()
    key = str(directory)
    if key in _loaded:
        return _loaded[key]
    path = directory / "suslov_formulas.py"
    if not path.is_file() or _pmax_of(directory) is None:
        raise FileNotFoundError(f"{directory}: not a generated tree (needs suslov_formulas.py and a readable "
                                "certificates.json; write one with build_formulas.py --out DIR)")
    # a distinct module name per directory: two ranges can be loaded side by side; the manifest is
    # checked and exactly the checked bytes are executed (suslov.manifest)
    module = manifest.load_module(directory, f"suslov_formulas_{abs(hash(key)):x}")
    _bind_certificates(module, directory)
    _loaded[key] = module
    return module


CERTIFICATES = "certificates.json"


def _bind_certificates(module: ModuleType, directory: Path) -> ModuleType:
    """Replace ``module.load_certificates`` by one that parses the bytes of ``certificates.json`` checked here.

    The file is read once; its SHA-256 must be the one the tree's manifest records (a file changed since
    the module's verified load is refused, :class:`suslov.manifest.ManifestError`); ``load_certificates()``
    then parses exactly those bytes at every call, whatever happens to the file afterwards.  The one
    exception is the build's own stale ``generated/`` (``SUSLOV_REBUILDING``, :mod:`suslov.manifest`): that tree
    is loaded unverified and keeps its emitted function.
    """
    if getattr(getattr(module, "load_certificates", None), "verified_bytes", None) is not None:
        return module   # bound already (a module taken from sys.modules)
    directory = Path(os.path.realpath(directory))
    if os.environ.get(manifest.REBUILD_ENV) == str(directory):
        return module
    expected = manifest.read(directory)[CERTIFICATES]
    path = directory / CERTIFICATES
    try:
        with open(path, "rb") as handle:   # the one read: these bytes are checked and parsed
            data = handle.read()
    except OSError as error:
        raise manifest.ManifestError(f"{path}: cannot be read ({error.strerror or error}); refusing the tree") from None
    found = manifest.digest(data)
    if found != expected:
        raise manifest.ManifestError(f"{path}: SHA-256 {found} where {manifest.MANIFEST} records {expected}: the "
                                     "file was changed after the build (or during this load); refusing the tree")
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
