"""``suslov catalog``: list, show and export the certified formulas (:mod:`suslov.formula_catalog`).

``suslov catalog list`` prints every id with its title and the paper's numbers; ``suslov catalog show ID
[--p N]`` prints the formula (SymPy's Unicode pretty form), its hypotheses, the paper's numbers and every
certificate (key, kind, outcome, claim); ``suslov catalog export --format mathematica|maple|json|latex
DIR`` writes the files of :mod:`suslov.catalog_files`.  ``list`` needs only the core install; ``show``
and ``export`` need SymPy (the ``[catalog]`` extra) and say so when it is missing.
"""
from __future__ import annotations

import sys
import textwrap


def add_parser(sub) -> None:
    cat = sub.add_parser("catalog", help="the certified formulas as objects: list, show, export")
    actions = cat.add_subparsers(dest="action", required=True)
    actions.add_parser("list", help="every formula id, its title and the paper's numbers")
    show = actions.add_parser("show", help="one formula: the formula, hypotheses, certificates (needs [catalog])")
    show.add_argument("id", help="a formula id (suslov catalog list)")
    show.add_argument("--p", type=int, default=None, help="the parameter of a family (first_integrals, basis)")
    export = actions.add_parser("export", help="write the catalog for another system (needs [catalog])")
    export.add_argument("--format", required=True, choices=("mathematica", "maple", "json", "latex"))
    export.add_argument("directory", help="output directory (created; files of the same name are replaced)")


def _plain(tex: str) -> str:
    return tex.replace("$", "")


def _show(catalog, args) -> int:
    import sympy

    from suslov.formula_catalog import Family

    item = catalog[args.id]
    if isinstance(item, Family):
        if args.p is None:
            print(f"suslov: error: catalog show {args.id}: a family; give --p (certified: {item.values})",
                  file=sys.stderr)
            return 2
        item = item(p=args.p)
    elif args.p is not None:
        item = item(p=args.p)
    print(f"{item.id}: {_plain(item.title)}")
    print(f"paper: {', '.join(item.numbers) or item.labels}")
    print("hypotheses: " + ("; ".join(_plain(h) for h in item.hypotheses) or "(none stated)"))
    print()
    print(sympy.pretty(item.expr, use_unicode=True) if item.expr is not None else "(prose; see the document)")
    print()
    print(f"certificates ({len(item.certificate_keys)}):")
    for record in item.certificates:
        line = f"{record['key']}  {record['kind']}, {record['outcome']}: {record['claim']}"
        print(textwrap.fill(line, 100, subsequent_indent="    "))
    return 0


def command(args) -> int:
    from suslov import __version__, catalog

    if args.action == "list":
        width = max(map(len, catalog))
        for key, item in catalog.items():
            numbers = ", ".join(getattr(item, "numbers", [])) or getattr(item, "labels", "family")
            print(f"{key:<{width}}  {_plain(item.title)}  [{numbers}]")
        return 0
    from suslov.extras import require

    try:
        require("catalog", f"suslov catalog {args.action}")
    except ModuleNotFoundError as error:
        print(f"suslov: error: {error}", file=sys.stderr)
        return 2
    try:
        if args.action == "show":
            return _show(catalog, args)
        from suslov.catalog_files import export

        for path in export(catalog, args.format, args.directory, __version__):
            print(path)
        return 0
    except (KeyError, ValueError, OSError) as error:
        print(f"suslov: error: catalog {args.action}: {error.args[0] if error.args else error}", file=sys.stderr)
        return 2
