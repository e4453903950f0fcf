"""The ``suslov`` command: ``--version``, ``scenes`` and ``catalog`` in the core install, ``simulate`` with ``[sim]``.

This module imports nothing beyond the standard library and ``suslov.__version__`` until a subcommand
needs more, so ``suslov --version`` and ``suslov scenes`` work in a core install (NumPy, mpmath,
python-flint); ``suslov simulate`` (:mod:`suslov.simulator.cli`, a thin layer over
``suslov.simulate``) says which extra to install when SciPy, matplotlib or heyoka is missing.

Exit status: 0 success, 2 bad input (a scene file, an output directory, a missing extra), 1 a
computation failed, 130 interrupted.
"""
from __future__ import annotations

import argparse
import shutil
import sys
import tomllib
from pathlib import Path

from suslov.interrupts import listen_for_interrupts


def scenes_dir() -> Path:
    """The example scenes: ``suslov/scenes`` in a wheel, ``scenes/`` in a checkout."""
    here = Path(__file__).resolve().parent
    for candidate in (here / "scenes", here.parent / "scenes"):
        if (candidate / "README.md").is_file():
            return candidate
    raise FileNotFoundError(f"the example scenes are missing from this installation ({here / 'scenes'})")


def scene_files() -> dict[str, Path]:
    """Example scene name -> its TOML file."""
    return {path.stem: path for path in sorted(scenes_dir().glob("*.toml"))}


def _list_scenes(args) -> int:
    files = scene_files()
    if args.copy is not None:
        target = Path(args.copy)
        if target.exists() and not target.is_dir():
            print(f"suslov: error: scenes --copy {target}: exists and is not a directory", file=sys.stderr)
            return 2
        clashes = [name for name in files if (target / f"{name}.toml").exists()]
        if clashes:
            print(f"suslov: error: scenes --copy {target}: would overwrite {', '.join(clashes)}.toml; nothing copied",
                  file=sys.stderr)
            return 2
        copied, created = [], not target.exists()
        try:
            target.mkdir(parents=True, exist_ok=True)
            for path in files.values():
                copied.append(target / path.name)
                shutil.copyfile(path, copied[-1])
        except OSError as error:   # a full disk: no scene half-copied, none of this run's copies left
            from suslov.outdir import write_failure   # here: the console script imports this module before main()

            for done in copied:
                done.unlink(missing_ok=True)
            if created and target.is_dir() and not any(target.iterdir()):
                target.rmdir()
            failed = write_failure(error, copied[-1] if copied else target)
            print(f"suslov: error: scenes --copy {target}: {failed}; nothing copied", file=sys.stderr)
            return 2
        print(f"copied {len(files)} scenes to {target}")
        return 0
    width = max(map(len, files))
    for name, path in files.items():
        data = tomllib.loads(path.read_text(encoding="utf-8"))
        text = " ".join(data.get("description", "").split())
        print(f"{name:<{width}}  {text if len(text) <= 96 else text[:95] + '...'}")
    print(f"\n{len(files)} scenes in {scenes_dir()}; run one: suslov simulate {files[next(iter(files))]} --out DIR")
    return 0


def parser() -> argparse.ArgumentParser:
    from suslov import __version__

    ap = argparse.ArgumentParser(
        prog="suslov", description="Certified formulas of the Suslov problem: run declarative scenes (TOML).",
        epilog="Exit status: 0 success, 2 bad input, 1 a computation failed, 130 interrupted. "
               "Scene schema: suslov scenes, then the scenes' README.md.")
    ap.add_argument("--version", action="version", version=f"suslov-certified {__version__}")
    sub = ap.add_subparsers(dest="command", required=True)
    listing = sub.add_parser("scenes", help="list the example scenes shipped with the package")
    listing.add_argument("--copy", metavar="DIR", help="copy them into DIR (refuses to overwrite)")
    from suslov.catalog_cli import add_parser as add_catalog

    add_catalog(sub)
    sim = sub.add_parser("simulate", help="run a scene file ([sim] for integration and figures)")
    sim.add_argument("scene", help="scene file (TOML), or the name of an example scene (suslov scenes)")
    sim.add_argument("--out", help="output directory (required unless --explain)")
    sim.add_argument("--explain", action="store_true", help="print the plan and exit without computing")
    sim.add_argument("--quiet", action="store_true", help="no progress lines")
    sim.add_argument("--workers", type=int, help="sweeps: local worker processes (default: the cores this process may run on)")
    sim.add_argument("--yes", action="store_true",
                     help="sweeps: run even when above 200000 points or an hour of estimated work")
    sim.add_argument("--scheduler", help="sweeps: dask.distributed scheduler address (default: $SUSLOV_SCHEDULER)")
    return ap


def main(argv=None) -> int:
    """The ``suslov`` command (console script and ``python -m suslov``): exit status as in the module docstring.

    Ctrl-C is heard from here on, before the subcommands' heavy imports (NumPy, SciPy, heyoka, matplotlib:
    about a second): a background job (``suslov simulate ... &`` in a script) starts with SIGINT ignored, and
    a ``kill -INT`` sent during those imports was lost (issue 44)."""
    listen_for_interrupts()
    copying = False
    try:
        args = parser().parse_args(argv)
        copying = args.command == "scenes" and args.copy is not None
        return _command(args)
    except KeyboardInterrupt:   # simulate_command reports its own (what a sweep kept); this is before it
        print("suslov: interrupted" + ("" if copying else "; nothing was written"), file=sys.stderr)
        return 130


def _command(args) -> int:
    if args.command == "scenes":
        return _list_scenes(args)
    if args.command == "catalog":
        from suslov.catalog_cli import command

        return command(args)
    # suslov simulate: the [sim] extra is asked for per scene, by the steps its plan needs (an integrator, a
    # figure: suslov.simulator.api.check_extras); closed forms, balls and exact decisions run on the core install
    if not Path(args.scene).exists() and args.scene in scene_files():
        args.scene = str(scene_files()[args.scene])
    from suslov.simulator.cli import simulate_command

    return simulate_command(args)


if __name__ == "__main__":
    sys.exit(main())
