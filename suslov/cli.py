"""Command line: ``suslov simulate SCENE.toml --out DIR [--explain]`` (also ``python -m suslov``).

Exit codes: 0 success, 2 bad input (scene file, output directory), 1 a
computation failed.  Errors are one line naming the file, the field and the
reason; nothing is written to ``--out`` unless the whole scene succeeded.
"""
from __future__ import annotations

import argparse
import sys

from .engine import execute, write_outputs
from .planner import make_plan
from .scene import SceneError, load_scene


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="suslov", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sim = sub.add_parser("simulate", help="run a scene file")
    sim.add_argument("scene", help="scene file (TOML), see scenes/README.md")
    sim.add_argument("--out", help="output directory (required unless --explain)")
    sim.add_argument("--explain", action="store_true", help="print the plan and exit without computing")
    sim.add_argument("--quiet", action="store_true", help="no progress lines")
    args = parser.parse_args(argv)
    progress = None if args.quiet else (lambda msg: print(msg, file=sys.stderr, flush=True))
    try:
        scene = load_scene(args.scene)
        try:
            plan = make_plan(scene)
        except ValueError as exc:
            raise SceneError(scene.path, "body", str(exc)) from None
    except SceneError as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    if args.explain:
        print(plan.explain())
        return 0
    if not args.out:
        print("suslov: error: --out DIR is required (or --explain)", file=sys.stderr)
        return 2
    try:
        run = execute(plan, progress)
        files = write_outputs(run, args.out, progress)
    except FileExistsError as exc:
        print(f"suslov: error: {exc}", file=sys.stderr)
        return 2
    except (RuntimeError, ArithmeticError, ValueError) as exc:
        print(f"suslov: error: scene {scene.path}: computation failed: {exc}", file=sys.stderr)
        return 1
    if progress:
        progress(f"wrote {len(files)} files to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
