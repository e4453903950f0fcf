"""The formula catalog: every certified formula of the documents as an object a researcher computes with.

``from suslov import catalog`` gives the catalog of the generated tree in use
(:func:`suslov.active_formulas`): a read-only mapping from a stable id (the formula's key in the
build, e.g. ``"omegas"``, ``"general_angle"``, ``"A0"``) to an :class:`Entry`, and from a family
id (``"first_integrals"``, ``"basis"``) to a :class:`Family`, which takes its parameter::

    >>> from suslov import catalog
    >>> catalog["omegas"].hypotheses[0]                 # doctest: +SKIP
    '$I_{13}=0$'
    >>> catalog["first_integrals"](p=5).expr            # doctest: +SKIP
    (Eq(P1, ...), Eq(P2, ...), Eq(P3, ...))

Each entry carries the paper's labels and printed numbers, the title, the hypotheses, the keys of the
certificates the build recorded for it (``entry.certificates`` returns their records from the same
verified ``certificates.json``), the display the document prints (``entry.latex``) and the formula
itself: ``entry.expr`` (SymPy, imported only when asked, so ``import suslov`` stays free of it),
``entry.text``, ``entry.mathematica``, ``entry.maple`` and ``entry.json`` (:mod:`suslov.catalog_export`).
Entries display themselves in Jupyter (``_repr_latex_``, ``_repr_html_``).

The data is ``catalog.json`` of the generated tree (written by the build from the derivations,
``derivations/output/catalog_data.py``), read from the bytes :mod:`suslov.manifest` verified when the
module was loaded, never re-read from disk.  A family value beyond the tree's pmax comes from a tree
built with a larger pmax: ``catalog["first_integrals"](p=101)`` calls ``load_formulas(pmax=101)``
(the per-user store, built and certified once), unless ``build=False`` is given.
"""
from __future__ import annotations

import html
import json
from collections.abc import Mapping
from types import ModuleType

from suslov.manifest import verified_files, verify

__all__ = ["Catalog", "Entry", "Family", "catalog_of", "certificate_kind"]

FILENAME = "catalog.json"
SCHEMA = 1
ALIASES = {"residue_A0": "A0"}


def certificate_kind(record: dict) -> str:
    """``exact``, ``enclosure`` or ``evidence``: what a certificate's method makes of its claim."""
    method = record.get("method", "").lower()
    if "evidence" in method:
        return "evidence"
    if "ball" in method or "enclosure" in method or "rounding-error" in method:
        return "enclosure"
    return "exact"


def _sympy():
    from suslov.catalog_export import sympy_module

    return sympy_module()


class Entry:
    """One certified formula (see the module docstring); ``parameters`` names a family value (``{"p": 5}``)."""

    def __init__(self, record: dict, certificates: dict, parameters: dict | None = None, construct=None):
        self._record = record
        self._construct = construct   # a family value: writes the formula from the certified recipe
        self._expr = None
        self._certificates = certificates
        self.parameters = dict(parameters or {})
        self.id = record["id"]
        self.title = record["title"]
        self.section = record["section"]
        self.labels = record["labels"]
        self.numbers = list(record["numbers"])
        self.hypotheses = list(record["hypotheses"])
        self.certificate_keys = list(record["certificates"])
        self.kind = record["kind"]

    @property
    def latex(self) -> str:
        """The display the document prints (a family value: SymPy's LaTeX of its formula)."""
        if not self._record["latex"] and self._construct is not None:
            self._record = {**self._record, "latex": _sympy().latex(self.expr)}
        return self._record["latex"]

    @property
    def srepr(self) -> str | None:
        """SymPy's exact serialisation of the formula (None for prose)."""
        if self._record["srepr"] is None and self._construct is not None:
            self._record = {**self._record, "srepr": _sympy().srepr(self.expr)}
        return self._record["srepr"]

    @property
    def expr(self):
        """The formula as a SymPy object (an equation, a tuple of equations, a matrix); None for prose."""
        if self._expr is None and self._construct is not None:
            self._expr = self._construct()
        elif self._expr is None and self._record["srepr"] is not None:
            self._expr = _sympy().sympify(self._record["srepr"])
        return self._expr

    def __call__(self, **values):
        """The formula with symbols replaced by name (``catalog["A0"](p=7)``): a new entry.

        Numbers are read exactly, as the run-time routines read them (:func:`suslov.kernel.validate.rational`):
        a float is its binary value, ``"0.7"`` is 7/10; a SymPy expression is substituted as it is."""
        expr = self.expr
        if expr is None:
            raise ValueError(f"catalog entry {self.id!r} is prose: it has no symbols to substitute")
        sp = _sympy()
        by_name = {s.name: s for s in expr.free_symbols}
        unknown = sorted(set(values) - set(by_name))
        if unknown:
            raise ValueError(f"catalog entry {self.id!r}: no symbol named {', '.join(unknown)} "
                             f"(its symbols: {', '.join(sorted(by_name))})")
        value = expr.subs({by_name[k]: _exact(sp, k, v) for k, v in values.items()})
        return Entry({**self._record, "srepr": sp.srepr(value), "latex": sp.latex(value)}, self._certificates,
                     {**self.parameters, **values})

    @property
    def certificates(self) -> list[dict]:
        """The records of this formula's certificates (claim, method, outcome, ...) with their ``kind``."""
        return [{**self._certificates[key], "kind": certificate_kind(self._certificates[key])}
                for key in self.certificate_keys if key in self._certificates]

    @property
    def text(self) -> str:
        """The formula in SymPy's plain-text form."""
        return "" if self.expr is None else _sympy().sstr(self.expr)

    @property
    def mathematica(self) -> str:
        from suslov.catalog_export import mathematica

        return mathematica(self.expr)

    @property
    def maple(self) -> str:
        from suslov.catalog_export import maple

        return maple(self.expr)

    @property
    def json(self) -> str:
        """The entry as JSON: the catalog record (``srepr`` is the formula) plus the family parameters."""
        return json.dumps({**self._record, "srepr": self.srepr, "parameters": self.parameters}, sort_keys=True)

    def _name(self) -> str:
        given = ", ".join(f"{k}={v}" for k, v in self.parameters.items())
        return f"{self.id}({given})" if given else self.id

    def __repr__(self) -> str:
        numbers = f" [paper {', '.join(self.numbers)}]" if self.numbers else ""
        return f"<catalog entry {self._name()}{numbers}: {len(self.certificate_keys)} certificates>"

    def _repr_latex_(self) -> str:
        return "$\\displaystyle " + self.latex.replace("\\\\", ",\\quad ").replace("&", "") + "$"

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><td><code>{html.escape(c['key'])}</code></td><td>{html.escape(c['kind'])}</td>"
                       f"<td>{html.escape(c['outcome'])}</td><td>{html.escape(c['claim'])}</td></tr>"
                       for c in self.certificates)
        hypotheses = "; ".join(html.escape(h) for h in self.hypotheses)
        numbers = html.escape(", ".join(self.numbers) or self.labels)
        return (f"<div><b>{html.escape(self._name())}</b>: {html.escape(self.title)} "
                f"<small>(paper: {numbers})</small><br>{html.escape(self._repr_latex_())}<br>"
                f"<small>Hypotheses: {hypotheses}</small>"
                f"<table><tr><th>certificate</th><th>kind</th><th>outcome</th><th>claim</th></tr>{rows}</table></div>")


def _exact(sp, name: str, value):
    """A substituted value: a SymPy object as it is, a number exactly (ValueError naming ``name`` otherwise)."""
    if isinstance(value, sp.Basic):
        return value
    from suslov.kernel.validate import rational

    number = rational(name, value)
    return sp.Rational(number.numerator, number.denominator)


class Family:
    """A formula certified per value of a parameter (``catalog["first_integrals"](p=5)``)."""

    def __init__(self, family_id: str, record: dict, certificates: dict, module: ModuleType):
        self.id = family_id
        self._record = record
        self._certificates = certificates
        self._module = module
        self.parameter = record["parameter"]
        self.title = record["title"]
        self.values = sorted(int(v) for v in record["values"])

    def __call__(self, build: bool = True, **given) -> Entry:
        if set(given) != {self.parameter}:
            raise TypeError(f"catalog family {self.id!r} takes exactly one argument, {self.parameter}=...")
        value = given[self.parameter]
        if isinstance(value, bool) or not isinstance(value, int):
            raise ValueError(f"{self.parameter}={value!r}: the family {self.id!r} is certified for integers "
                             f"(values in this tree: {self.values[0]}..{self.values[-1]})")
        record = self._record["values"].get(str(value))
        if record is None and value > max(self.values) and value >= 1:
            from suslov.loader import load_formulas

            larger = catalog_of(load_formulas(pmax=value, build=build))
            return larger[self.id](**given)
        if record is None:
            raise ValueError(f"{self.parameter}={value}: not a value of the family {self.id!r} "
                             f"(certified values: {', '.join(map(str, self.values))})")
        from suslov.catalog_families import CONSTRUCTIONS

        construct = CONSTRUCTIONS[self._record["construction"]]
        entry = {"id": self.id, "title": self.title, "section": self._record["section"],
                 "labels": self._record["labels"], "numbers": self._record["numbers"],
                 "hypotheses": [*self._record["hypotheses"], f"${self.parameter}={value}$"],
                 "certificates": record["certificates"], "latex": "", "kind": "formula", "srepr": None}
        return Entry(entry, self._certificates, {self.parameter: value},
                     construct=lambda: construct(self._module, value))

    def __repr__(self) -> str:
        return f"<catalog family {self.id}({self.parameter}=...): {self.parameter} in {self.values}>"


class Catalog(Mapping):
    """Id -> :class:`Entry` or :class:`Family`, in document order (see the module docstring)."""

    def __init__(self, data: dict, certificates: dict, module: ModuleType):
        if data.get("schema") != SCHEMA:
            raise ValueError(f"catalog.json schema {data.get('schema')!r}: this suslov reads schema {SCHEMA}")
        self.pmax = data["pmax"]
        records = {c["key"]: c for c in certificates["certificates"]}
        self._items = {e["id"]: Entry(e, records) for e in data["entries"]}
        self._items.update({k: Family(k, f, records, module) for k, f in data["families"].items()})

    def __getitem__(self, key: str):
        key = ALIASES.get(key, key)
        try:
            return self._items[key]
        except KeyError:
            raise KeyError(f"no catalog entry {key!r}; ids: {', '.join(self._items)}") from None

    def __iter__(self):
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def entries(self) -> list[Entry]:
        return [v for v in self._items.values() if isinstance(v, Entry)]

    def families(self) -> list[Family]:
        return [v for v in self._items.values() if isinstance(v, Family)]

    def __repr__(self) -> str:
        return f"<catalog of {len(self.entries())} formulas and {len(self.families())} families (pmax {self.pmax})>"

    def _repr_html_(self) -> str:
        rows = "".join(f"<tr><td><code>{html.escape(e.id)}</code></td><td>{html.escape(e.title)}</td>"
                       f"<td>{html.escape(', '.join(e.numbers) or e.labels)}</td></tr>" for e in self.entries())
        return f"<table><tr><th>id</th><th>title</th><th>paper</th></tr>{rows}</table>"


_catalogs: dict = {}


def catalog_of(module: ModuleType) -> Catalog:
    """The catalog of the generated tree ``module`` was loaded from (its verified ``catalog.json``)."""
    if module in _catalogs:
        return _catalogs[module]
    from pathlib import Path

    files = verified_files(module)
    if files is None:
        files = verify(Path(module.__file__).parent)
    if FILENAME not in files:
        raise FileNotFoundError(f"{Path(module.__file__).parent}: no {FILENAME} (a tree built before the catalog "
                                "existed: rebuild it with build_formulas.py)")
    made = Catalog(json.loads(files[FILENAME].decode("utf-8")), module.load_certificates(), module)
    _catalogs[module] = made
    return made
