"""The formula catalog (issue 47): every formula of the document, exact exports, certificates attached.

Expected values come from routes the catalog does not use: the document's own LaTeX (the count of
formulas), SymPy's independent Mathematica parser and a Maple reader built on Python's tokenizer
(``suslov.catalog_export``: they share nothing with the printers), and the equations of motion (a first
integral of the family is checked to be conserved by differentiating it along the system here).
"""
from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest
import sympy as sp

from suslov import active_formulas, catalog
from suslov.catalog_export import maple, mathematica, parse_maple, parse_mathematica_back, same
from suslov.formula_catalog import Entry, Family

ROOT = Path(__file__).resolve().parents[1]
GENERATED = Path(active_formulas().__file__).parent   # the tree the catalog was read from


def _everything():
    """Every catalog formula with a SymPy form: the entries and two values of each family."""
    items = [e for e in catalog.entries() if e.kind == "formula"]
    for family in catalog.families():
        items += [family(p=v) for v in family.values[:2] + family.values[-1:]]
    return items


ITEMS = _everything()
IDS = [e.id + "".join(f"_p{v}" for v in e.parameters.values()) for e in ITEMS]


def test_every_formula_of_the_document_has_an_entry():
    body = (GENERATED / "formulas_body.tex").read_text(encoding="utf-8")
    labelled = re.findall(r"\\label\{formula:([^}]+)\}", body)
    assert labelled, "formulas_body.tex labels no formula (\\label{formula:KEY})"
    assert sorted(labelled) == sorted(e.id for e in catalog.entries())
    prose = [e.id for e in catalog.entries() if e.kind == "prose"]
    assert all("\\parbox" in e.latex for e in catalog.entries() if e.kind == "prose"), prose


def test_entries_carry_hypotheses_certificates_and_the_paper():
    certificates = {c["key"]: c for c in json.loads((GENERATED / "certificates.json").read_text())["certificates"]}
    for entry in catalog.entries():
        assert entry.hypotheses, f"{entry.id}: no hypotheses"
        assert entry.certificate_keys and all(k in certificates for k in entry.certificate_keys), entry.id
        assert [c["key"] for c in entry.certificates] == entry.certificate_keys
        assert {c["kind"] for c in entry.certificates} <= {"exact", "enclosure", "evidence"}
        assert entry.labels


@pytest.mark.parametrize("entry", ITEMS, ids=IDS)
def test_mathematica_export_parses_back_to_the_certified_formula(entry):
    expr = entry.expr
    assert same(expr, parse_mathematica_back(mathematica(expr), expr))


@pytest.mark.parametrize("entry", ITEMS, ids=IDS)
def test_maple_export_parses_back_to_the_certified_formula(entry):
    expr = entry.expr
    assert same(expr, parse_maple(maple(expr), expr))


@pytest.mark.parametrize("entry", ITEMS, ids=IDS)
def test_json_round_trips_exactly(entry):
    record = json.loads(entry.json)
    assert sp.sympify(record["srepr"]) == entry.expr
    assert sp.srepr(sp.sympify(record["srepr"])) == record["srepr"]


def test_a_wrong_export_is_caught():
    """The comparison can fail: a changed coefficient in the Mathematica text is not the formula."""
    entry = catalog["first_integrals"](p=3)
    text = mathematica(entry.expr)
    changed = text.replace("+ 9", "+ 8", 1)
    assert changed != text
    assert not same(entry.expr, parse_mathematica_back(changed, entry.expr))


def _conserved(P1, P2, P3, p_value):
    """d/dt (P1 g1 + P2 g2 + P3 g3) along the special case I13 = 0: the Euler equations from the catalog's
    ``sysfin`` entry (a separate derivation's formula) and the Poisson equations gamma' = gamma x omega
    written out here, omega = (omega1, omega2, 0)."""
    F = P1 * sp.Symbol("gamma1", real=True) + P2 * sp.Symbol("gamma2", real=True) + P3 * sp.Symbol("gamma3", real=True)
    by_name = {s.name: s for s in F.free_symbols}
    w1, w2, g1, g2, g3 = (by_name.get(n, sp.Symbol(n, real=True))
                          for n in ("omega1", "omega2", "gamma1", "gamma2", "gamma3"))
    rates = {}
    for eq in catalog["sysfin"](p=p_value).expr:
        functions = {f: by_name.get(f.func.__name__, sp.Symbol(f.func.__name__, real=True))
                     for f in eq.rhs.atoms(sp.core.function.AppliedUndef)}
        rhs = eq.rhs.xreplace(functions)
        rates[eq.lhs.expr.func.__name__] = rhs.xreplace({s: by_name.get(s.name, s) for s in rhs.free_symbols})
    dg = (-g3 * w2, g3 * w1, g1 * w2 - g2 * w1)
    dot = F.diff(w1) * rates["omega1"] + F.diff(w2) * rates["omega2"] + sum(F.diff(g) * v for g, v in zip((g1, g2, g3), dg))
    return sp.cancel(sp.together(dot))


@pytest.mark.parametrize("p_value", [1, 5])
def test_first_integral_family_is_conserved_along_the_equations(p_value):
    entry = catalog["first_integrals"](p=p_value)
    assert isinstance(catalog["first_integrals"], Family)
    parts = {str(eq.lhs): eq.rhs for eq in entry.expr}
    assert _conserved(parts["P1"], parts["P2"], parts["P3"], p_value) == 0
    wrong = parts["P3"] * -1
    assert _conserved(parts["P1"], parts["P2"], wrong, p_value) != 0


def test_residue_family_has_eigenvalues_zero_and_plus_minus_p():
    entry = catalog["residue_A0"](p=7)
    A0 = entry.expr[0].rhs
    assert isinstance(A0, sp.MatrixBase) and A0.shape == (3, 3)
    lam = sp.Symbol("lam")
    assert sp.factor(sp.simplify((A0 - lam * sp.eye(3)).det())) in (sp.factor(-lam * (lam - 7) * (lam + 7)),
                                                                    sp.factor(lam * (lam - 7) * (lam + 7)))


def test_family_refuses_values_it_cannot_certify(monkeypatch, tmp_path):
    monkeypatch.setenv("SUSLOV_DATA_DIR", str(tmp_path / "store"))
    family = catalog["first_integrals"]
    with pytest.raises(ValueError, match="p=4"):
        family(p=4)
    with pytest.raises(ValueError, match="integers"):
        family(p=2.5)
    with pytest.raises(LookupError, match="no stored module"):
        family(p=max(family.values) + 2, build=False)
    with pytest.raises(KeyError, match="no catalog entry"):
        catalog["no_such_formula"]


def test_substituted_numbers_are_read_exactly():
    """A decimal string is the rational it writes, a float its binary value, a huge integer itself (expected
    values by Python's Fraction, not by the catalog)."""
    from fractions import Fraction

    for given, exact in (("0.7", Fraction(7, 10)), (0.1, Fraction(0.1)), (1e300, Fraction(1e300)),
                         (10**40, Fraction(10**40))):
        rhs = catalog["omegas"](p=3, d=given).expr[0].rhs
        t = [s for s in rhs.free_symbols if s.name == "t"][0]
        assert sp.simplify(rhs - sp.Rational(3) / sp.Rational(exact.numerator, exact.denominator) * sp.tanh(t)) == 0
        assert not rhs.atoms(sp.Float)
    with pytest.raises(ValueError, match="d="):
        catalog["omegas"](d=float("nan"))


def test_entry_substitution_names_unknown_symbols():
    with pytest.raises(ValueError, match="no symbol named q"):
        catalog["omegas"](q=2)
    assert isinstance(catalog["omegas"](p=3), Entry)


def test_import_suslov_and_the_catalog_listing_stay_free_of_sympy():
    code = ("import sys, suslov; c = suslov.catalog; [e.latex for e in c.entries()]; "
            "assert 'sympy' not in sys.modules, sorted(m for m in sys.modules if m.startswith('sympy'))[:3]; "
            "print(len(c))")
    done = subprocess.run([sys.executable, "-X", "importtime", "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    imported = re.findall(r"\|\s+(\S+)$", done.stderr, re.M)
    assert not [m for m in imported if m.split(".")[0] == "sympy"]


def test_cli_show_and_export(tmp_path):
    run = [sys.executable, "-m", "suslov", "catalog"]
    shown = subprocess.run(run + ["show", "first_integrals", "--p", "3"], cwd=ROOT, capture_output=True, text=True)
    assert shown.returncode == 0, shown.stderr
    assert "certificates (" in shown.stdout and "hypotheses:" in shown.stdout and "exact, pass" in shown.stdout
    family = subprocess.run(run + ["show", "first_integrals"], cwd=ROOT, capture_output=True, text=True)
    assert family.returncode == 2 and "--p" in family.stderr
    missing = subprocess.run(run + ["show", "nope"], cwd=ROOT, capture_output=True, text=True)
    assert missing.returncode == 2 and "no catalog entry 'nope'" in missing.stderr
    done = subprocess.run(run + ["export", "--format", "mathematica", str(tmp_path / "wl")], cwd=ROOT,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert set(done.stdout.split()) == {str(p) for p in (tmp_path / "wl").glob("*.wl")}
    bad = subprocess.run(run + ["export", "--format", "maple", str(tmp_path / "wl" / "model.wl")], cwd=ROOT,
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "not a directory" in bad.stderr


def test_every_format_writes_one_file_per_section_and_family(tmp_path):
    from suslov.catalog_files import export

    for fmt, ext in (("mathematica", "wl"), ("maple", "mpl"), ("json", "json"), ("latex", "tex")):
        files = export(catalog, fmt, tmp_path / fmt, "test")
        assert all(f.suffix == "." + ext for f in files)
        assert {f.stem for f in files} == {e.section for e in catalog.entries()} | {"first_integrals"}
        assert not list((tmp_path / fmt).glob(".*partial"))


def test_mathematica_file_definitions_parse_back(tmp_path):
    from suslov.catalog_files import export

    export(catalog, "mathematica", tmp_path, "test")
    text = (tmp_path / "special_case.wl").read_text()
    definitions = dict(re.findall(r'^SuslovFormula\["([^"]+)"\] = (.*);$', text, re.M))
    assert set(definitions) == {e.id for e in catalog.entries() if e.section == "special_case" and e.expr is not None}
    for key, body in definitions.items():
        assert same(catalog[key].expr, parse_mathematica_back(body, catalog[key].expr)), key
    assert "Usage" not in text and "SuslovFormula::usage" in text


def test_maple_file_procedures_parse_back(tmp_path):
    from suslov.catalog_files import export

    export(catalog, "maple", tmp_path, "test")
    text = (tmp_path / "first_integrals.mpl").read_text()
    bodies = dict(re.findall(r"^SuslovFormula_first_integrals_p(\d+) := proc\(\) (.*) end proc:$", text, re.M))
    family = catalog["first_integrals"]
    assert sorted(map(int, bodies)) == family.values
    for value, body in bodies.items():
        entry = family(p=int(value))
        assert same(entry.expr, parse_maple(body, entry.expr))


def test_first_integral_family_at_p_101_is_conserved_exactly():
    """Beyond the default range (issue 43's rule): the family's construction at p = 101, its time derivative
    along the equations of motion (written out here) evaluated exactly at a rational point."""
    from suslov import active_formulas
    from suslov.catalog_families import first_integrals

    expr = first_integrals(active_formulas(), 101)
    parts = {str(eq.lhs): eq.rhs for eq in expr}
    symbols = {s.name: s for s in expr.free_symbols}
    d, w1, w2 = symbols["d"], symbols["omega1"], symbols["omega2"]
    g1, g2, g3 = sp.symbols("gamma1 gamma2 gamma3")
    # eq:sysfin with p = 101 (section 4): omega1' = (p/d) omega2^2/(d^2+1) ... as the sysfin entry states it
    rates = {}
    for eq in catalog["sysfin"](p=101).expr:
        functions = {f: {"omega1": w1, "omega2": w2}[f.func.__name__] for f in eq.rhs.atoms(sp.core.function.AppliedUndef)}
        rhs = eq.rhs.xreplace(functions)
        rates[eq.lhs.expr.func.__name__] = rhs.xreplace({s: symbols.get(s.name, s) for s in rhs.free_symbols})
    at_d = {d: sp.Rational(3, 7)}
    at_w = {w1: sp.Rational(2, 5), w2: sp.Rational(-5, 11)}
    g = {g1: sp.Rational(1, 3), g2: sp.Rational(2, 3), g3: sp.Rational(-2, 3)}
    # polynomials in (omega, gamma) over Q once d is a number: exact derivatives of about 150 terms each
    P = {name: sp.Poly(value.subs(at_d), w1, w2, domain="QQ") for name, value in parts.items()}
    rate = {name: value.subs(at_d).subs(at_w) for name, value in rates.items()}
    def dP(name, var):
        return P[name].diff(var).eval(at_w) if P[name].degree(var) > 0 else 0

    values = {name: P[name].eval(at_w) for name in P}
    Fw1 = sum(dP(n, w1) * gv for n, gv in zip(("P1", "P2", "P3"), g.values()))
    Fw2 = sum(dP(n, w2) * gv for n, gv in zip(("P1", "P2", "P3"), g.values()))
    W1, W2 = at_w[w1], at_w[w2]
    G1, G2, G3 = g.values()
    dg = (-G3 * W2, G3 * W1, G1 * W2 - G2 * W1)
    dot = Fw1 * rate["omega1"] + Fw2 * rate["omega2"] + sum(values[n] * v for n, v in zip(("P1", "P2", "P3"), dg))
    assert dot == 0
    F = sum(values[n] * gv for n, gv in zip(("P1", "P2", "P3"), g.values()))
    assert F != 0
