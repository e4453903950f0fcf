"""The tests the quick loop (``pytest -m "not slow"``) leaves out, from a timed run of the whole suite (issue 43).

Reads the output of ``python -m pytest --durations=0`` (the README's command, every core) on standard input and prints, sorted, the
node id of every test whose setup, call and teardown took at least ``--threshold`` seconds (0.3) together; the suite's
``tests/conftest.py`` marks the ids listed in ``tests/slow_tests.txt`` as ``slow`` (CI still runs them: the
README's test command runs everything).  Regenerate after adding costly tests:

    CI=true python -m pytest --durations=0 -q | python bench/slow_tests.py > tests/slow_tests.txt

Tests that use a whole-build fixture (``default_build``, ``cli_build``, ``wheel``, ``venv``) are marked slow by
the conftest whatever this list says.
"""
from __future__ import annotations

import argparse
import collections
import re
import sys

LINE = re.compile(r"\s*([0-9.]+)s (?:call|setup|teardown)\s+(.+?)\s*$")


def slow_ids(lines, threshold: float) -> list[str]:
    seconds: collections.Counter = collections.Counter()
    for line in lines:
        match = LINE.match(line)
        if match:
            seconds[match.group(2)] += float(match.group(1))
    return sorted(node for node, total in seconds.items() if total >= threshold)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--threshold", type=float, default=0.3, help="seconds (default 0.3)")
    args = ap.parse_args(argv)
    ids = slow_ids(sys.stdin, args.threshold)
    if not ids:
        print("slow_tests.py: no durations on standard input (run pytest with --durations=0)", file=sys.stderr)
        return 1
    print("# tests marked slow (bench/slow_tests.py: at least %g s each in a timed run of the whole suite)" % args.threshold)
    print("\n".join(ids))
    return 0


if __name__ == "__main__":
    sys.exit(main())
