"""The derive -> certify -> render pipeline, shipped inside the ``suslov`` namespace (the ``[build]`` extra).

The repository keeps its top level (``derivations/``, ``templates/``, ``build_formulas.py``): the build and
the tests run from the checkout root.  A wheel maps the same two directories into this package
(``suslov/build/derivations``, ``suslov/build/templates``: see ``[tool.setuptools.package-dir]`` in
``pyproject.toml``), so an installed copy carries a small checkout-shaped tree and the derivations keep
their own imports (``derivations.core...``), which resolve only inside a build process: the name
``derivations`` never appears in a user's ``sys.modules``.

:func:`main` (also ``python -m suslov.build``) runs ``build_formulas.py``'s command line from whichever tree
is present.  It needs SymPy, symengine and Jinja2 (``pip install 'suslov-certified[build]'``); without them
it says so instead of failing on an import.  In an installed copy there is no ``generated/`` to write, so
the output goes to ``--out DIR`` or the per-user store (``--install``; the default there).

>>> from suslov.build import build_root
>>> (build_root() / "derivations" / "registry.py").is_file()
True
"""
from __future__ import annotations

import sys
from pathlib import Path

from suslov.extras import require

__all__ = ["build_root", "is_checkout", "main"]

_HERE = Path(__file__).resolve().parent


def is_checkout() -> bool:
    """True when this package runs from a source checkout (editable install or the repository itself)."""
    return not (_HERE / "derivations").is_dir() and (_HERE.parents[1] / "derivations").is_dir()


def build_root() -> Path:
    """The directory holding ``derivations/`` and ``templates/``: the checkout root, or this package in a wheel."""
    if (_HERE / "derivations").is_dir():
        return _HERE
    root = _HERE.parents[1]
    if (root / "derivations").is_dir():
        return root
    raise RuntimeError(f"{_HERE}: the derivations are missing from this installation (neither "
                       f"{_HERE / 'derivations'} nor {root / 'derivations'} exists); reinstall suslov-certified")


def main(argv=None) -> int:
    """``build_formulas.py``'s command line, run from the tree :func:`build_root` finds."""
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        require("build", "building the formulas")
    except ModuleNotFoundError as error:
        print(f"python -m suslov.build: {error}", file=sys.stderr)
        return 2
    root = build_root()
    writes_default = not {"--out", "--install", "--only", "--check", "--verify", "--diff", "-h", "--help",
                          "--version"} & {a.split("=")[0] for a in args}
    if not is_checkout() and writes_default:
        args.append("--install")   # an installed copy has no generated/ of its own to overwrite
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    # run, not main: Ctrl-C, an untrusted cache and a full disk end in one line, as from build_formulas.py
    from derivations.output.cli import run as cli_run

    return cli_run(args)
