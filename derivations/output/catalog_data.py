"""The formula catalog's data: ``generated/catalog.json``, written by the build from the derived formulas.

Every formula the formulas document prints (each :class:`~derivations.core.result.DerivedFormula` of
every derivation, in document order) becomes one entry: its key as a stable id, the section, the
paper's labels and printed numbers (:mod:`derivations.core.paper_numbers`), the title, the hypotheses,
the certificate keys, the display the document prints, and the formula itself as ``srepr`` text --
SymPy's own exact serialisation, which ``sympy.sympify`` reads back to an equal object (checked here
for every entry, so a formula that would not round-trip stops the build).  The run-time side
(:mod:`suslov.formula_catalog`) reads this file from the verified generated tree, needs SymPy only to
turn ``srepr`` back into expressions, and exports them (:mod:`suslov.catalog_export`).

Families: a derivation that certifies a formula per value of a parameter (the first integrals
P1, P2, P3 of Theorem 6.2 for each odd p) puts ``catalog_family_certificates`` ({value: [keys]}) in its
exports; the catalog lists the certified values and their certificates and names the construction
(``suslov.catalog_families``) that writes the formula at run time from the tree's certified recipe.  A
larger range comes from a tree built with a larger pmax (``load_formulas(pmax=...)``), certified by the
same build.

Schema (``SCHEMA`` below; documented in ``docs/catalog.md``)::

    {"schema": 1, "pmax": 15,
     "entries": [{"id", "section", "section_title", "labels", "numbers", "title", "hypotheses",
                  "certificates", "latex", "kind": "formula" | "prose", "srepr": str | null}, ...],
     "families": {"first_integrals": {"parameter": "p", "construction", "title", "section", "labels",
                                      "numbers", "hypotheses", "values": {"5": {"certificates"}, ...}}}}
"""
from __future__ import annotations

import json

import sympy as sp

from derivations.core.paper_numbers import printed_numbers
from suslov.formula_catalog import FILENAME, SCHEMA  # noqa: F401 - one definition: what the reader expects


class CatalogError(ValueError):
    """A formula the catalog cannot carry exactly (it would not round-trip through ``srepr``)."""


# srepr is Python source of SymPy constructors: evaluated in SymPy's namespace it is what sympify(srepr) builds,
# without sympify's tokenizer passes (0.57 s instead of 0.96 s for every formula of the default build)
_SYMPY = {name: getattr(sp, name) for name in dir(sp) if not name.startswith("_")}


def serialised(expr, where: str) -> str:
    """``srepr(expr)``, checked to read back to an equal object (SymPy's constructors, evaluated)."""
    text = sp.srepr(expr)
    try:
        back = eval(text, {"__builtins__": {}}, _SYMPY)   # noqa: S307 - our own srepr of our own formula
    except Exception as error:   # noqa: BLE001 - any failure to read back is the same fault
        raise CatalogError(f"{where}: its SymPy form does not read back from srepr ({error})") from error
    if back != expr:
        raise CatalogError(f"{where}: its SymPy form reads back from srepr as a different object")
    return text


def read_back(chunk) -> list[str]:
    """The same check as :func:`serialised` for texts made elsewhere (run in a worker process): ``chunk`` is a list
    of (where, srepr text); each text, evaluated, must print back to itself (``srepr`` is SymPy's structural
    print, so equal texts are equal trees: the object the formula was).  Returns the failures, named."""
    failures = []
    for where, text in chunk:
        try:
            back = eval(text, {"__builtins__": {}}, _SYMPY)   # noqa: S307 - our own srepr of our own formula
        except Exception as error:   # noqa: BLE001 - any failure to read back is the same fault
            failures.append(f"{where}: its SymPy form does not read back from srepr ({error})")
            continue
        if sp.srepr(back) != text:
            failures.append(f"{where}: its SymPy form reads back from srepr as a different object")
    return failures


def read_back_chunks(document: dict, count: int = 4) -> list[list[tuple[str, str]]]:
    """The formulas of ``document`` as ``count`` chunks of (where, srepr text) for :func:`read_back`, balanced by
    the texts' lengths (the cost of evaluating them), in a fixed order."""
    chunks = [[] for _ in range(count)]
    sizes = [0] * count
    items = [(f"formula {e['id']!r} of {e['section']}", e["srepr"]) for e in document["entries"] if e["srepr"]]
    for where, text in sorted(items, key=lambda item: -len(item[1])):
        k = sizes.index(min(sizes))
        chunks[k].append((where, text))
        sizes[k] += len(text)
    return [chunk for chunk in chunks if chunk]


def _entry(result, title: str, formula, check: bool = True) -> dict:
    where = f"formula {formula.key!r} of {result.name}"
    return {
        "id": formula.key,
        "section": result.name,
        "section_title": title,
        "labels": formula.label,
        "numbers": printed_numbers(formula.label),
        "title": formula.title,
        "hypotheses": list(formula.hypotheses),
        "certificates": list(formula.certificates),
        "latex": formula.latex,
        "kind": "prose" if formula.expr is None else "formula",
        "srepr": None if formula.expr is None else serialised(formula.expr, where) if check else sp.srepr(formula.expr),
    }


# per-value families: (family id, derivation, title, the formula whose label and hypotheses they share);
# the family id names its run-time construction (suslov.catalog_families.CONSTRUCTIONS)
FAMILIES = (
    ("first_integrals", "first_integrals", "First integrals $P_1,P_2,P_3$ for odd $p$", "recipe"),
)


def _family(family: str, result, title: str, anchor) -> dict:
    keys = result.exports["catalog_family_certificates"]
    return {
        "parameter": "p",
        "construction": family,
        "title": title,
        "section": result.name,
        "labels": anchor.label if anchor else "",
        "numbers": printed_numbers(anchor.label) if anchor else [],
        "hypotheses": [h for h in anchor.hypotheses if "positive odd" not in h] if anchor else [],
        "values": {str(v): {"certificates": list(keys[v])} for v in sorted(keys)},
    }


def catalog_document(build, titles: dict, check: bool = True) -> dict:
    """The catalog of ``build`` (entries in document order; ids must be unique); ``check=False``: the srepr texts
    unchecked, for :func:`read_back` to check elsewhere before the file is used."""
    entries, seen = [], {}
    for name in build.names:
        result = build.results[name]
        for formula in result.formulas:
            if formula.key in seen:
                raise CatalogError(f"formula key {formula.key!r} of {name} is also a key of {seen[formula.key]}: "
                                   "catalog ids must be unique")
            seen[formula.key] = name
            entries.append(_entry(result, titles[name], formula, check))
    families = {}
    for family, name, title, anchor_key in FAMILIES:
        result = build.results.get(name)
        if result is None or "catalog_family_certificates" not in result.exports:
            continue
        anchor = next((f for f in result.formulas if f.key == anchor_key), None)
        families[family] = _family(family, result, title, anchor)
    return {"schema": SCHEMA, "pmax": build.options.pmax, "entries": entries, "families": families}


def catalog_text(build, titles: dict, check: bool = True) -> str:
    return text_of(catalog_document(build, titles, check))


def text_of(document: dict) -> str:
    """The file's text (``generated/catalog.json``)."""
    return json.dumps(document, indent=1, sort_keys=True, ensure_ascii=True) + "\n"
