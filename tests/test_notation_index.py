"""The notation index of the formulas document (issue 46): one line per symbol, every printed symbol indexed.

:data:`derivations.core.notation.NOTATION` says what each symbol of the formulas means; the printer sets the
symbols' TeX (:data:`derivations.core.statement_printers.SYMBOL_NAMES`).  Fast tests check the table itself (no
symbol on two lines, the printer's names mapped to lines whose spellings match them, the paper's labels
printable); the rest renders the default build: every printer symbol that occurs in ``formulas_body.tex`` has
a line or a reason (:data:`~derivations.core.notation.OMITTED`), every line's spellings occur in the document and
every display it names exists, and the index compiles alone with ``suslov-preamble.tex`` (no error, no overfull
or underfull box) and inside the formulas document, listed in its table of contents.
"""
import os
import re
import shutil

import pytest

from derivations.core import notation
from derivations.core.notation import (
    NOTATION,
    OMITTED,
    Symbol,
    index_rows,
    meaning_tex,
    occurs,
)
from derivations.core.paper_numbers import printed_numbers
from derivations.core.statement_printers import SYMBOL_NAMES
from derivations.output import pdf
from derivations.output.pipeline import context, render_into

WRAPPER = ("\\documentclass[10pt,a4paper]{article}\n\\usepackage[a4paper,margin=2cm]{geometry}\n"
           "\\input{suslov-preamble}\n\\begin{document}\n\\input{%s}\n\\end{document}\n")


def _symbols(symbol: Symbol) -> set:
    """The symbols a line indexes: its TeX split at the top-level commas and semicolons, normalised."""
    parts = re.split(r",|;", re.sub(r"\\[ ,;]|\\dots", "", symbol.tex))
    return {notation._normal(part) for part in parts if part.strip()}


# --- the table ------------------------------------------------------------------------------------------------

def test_no_symbol_has_two_lines():
    seen = {}
    for symbol in NOTATION:
        for part in _symbols(symbol):
            assert part not in seen, f"{part} on two lines: {seen.get(part)!r} and {symbol.tex!r}"
            seen[part] = symbol.tex
    named = [name for symbol in NOTATION for name in symbol.printer]
    assert len(named) == len(set(named)), "a printer name on two lines"
    assert not set(named) & set(OMITTED), "a printer name both indexed and omitted"


def test_printer_names_are_on_lines_that_spell_them():
    for symbol in NOTATION:
        for name in symbol.printer:
            tex = SYMBOL_NAMES[name]
            assert any(re.search(s, tex) for s in symbol.spellings), (name, tex, symbol.tex)
    assert set(OMITTED) <= set(SYMBOL_NAMES)


def test_paper_labels_print_as_numbers():
    for symbol in NOTATION:
        if symbol.paper:
            assert printed_numbers(symbol.paper), (symbol.tex, symbol.paper)
        assert symbol.spellings, symbol.tex
        assert "\n" not in symbol.meaning and symbol.meaning.count("$") % 2 == 0, symbol.tex


def test_occurs_reads_braces_and_blanks_alike():
    assert occurs(r"t_{0}", r"rate $A=1$, $t_0=0$") and occurs(r"(u \times v)_{3}", r"$(u\times v)_3=0$")
    assert occurs(r"\lambda", r"\lambda_k") and not occurs(r"\lambda", r"\lambdabar") and not occurs(r"\lambda", "x")
    assert occurs(r"w_{-}", r"w_-^2") and not occurs(r"w_{+}", r"w_-^2")


def test_a_display_missing_from_a_partial_build_is_left_out():
    line = Symbol("x", r"the thing [[a]], [[b]]; also [[c]]", spellings=("x",))
    assert meaning_tex(line, {"a": 1, "b": 2, "c": 3}) == \
        r"the thing \hyperlink{formula.a}{(1)}, \hyperlink{formula.b}{(2)}; also \hyperlink{formula.c}{(3)}"
    assert meaning_tex(line, {"b": 2}) == r"the thing \hyperlink{formula.b}{(2)}"      # "also [[c]]": not used
    assert meaning_tex(Symbol("y", r"$a;b$ here; there [[c]]", spellings=("y",)), {}) == r"$a;b$ here"
    assert meaning_tex(line, {"a": 1, "c": 3}) == \
        r"the thing \hyperlink{formula.a}{(1)}; also \hyperlink{formula.c}{(3)}"
    assert meaning_tex(Symbol("x", r"one [[a]], [[b]], [[c]] two", spellings=("x",)), {"a": 1, "c": 3}) == \
        r"one \hyperlink{formula.a}{(1)}, \hyperlink{formula.c}{(3)} two"
    assert [row["symbol"] for row in index_rows([], {})] == [s.tex for s in NOTATION if s.where]


# --- the index of the default build ---------------------------------------------------------------------------

@pytest.fixture(scope="module")
def tree(default_build, tmp_path_factory):
    directory = tmp_path_factory.mktemp("tree")
    render_into(default_build, directory)
    return directory, context(default_build)


def test_every_printer_symbol_in_the_formulas_has_a_line(tree):
    directory, _ = tree
    body = (directory / "formulas_body.tex").read_text(encoding="utf-8")
    indexed = {name for symbol in NOTATION for name in symbol.printer}
    occurring = {name for name, tex in SYMBOL_NAMES.items() if occurs(tex, body)}
    assert {"w1", "g1", "lam", "Deltapsi", "gammaI", "t0", "A0"} <= occurring      # the check reads the document
    missing = sorted(occurring - indexed - set(OMITTED))
    assert missing == [], f"printer symbols in formulas_body.tex with no index line: {missing}"


def test_every_line_is_used_and_names_existing_displays(tree):
    directory, ctx = tree
    document = "\n".join(p.read_text(encoding="utf-8") for p in sorted(directory.glob("*.tex"))
                         if p.name not in ("notation.tex", "certificates.tex", "certificates_table.tex",
                                           "certificate_costs.tex", "suslov-preamble.tex"))
    formulas = [f for r in ctx["results"] for f in r.formulas]
    for symbol in NOTATION:
        assert any(re.search(s, document) for s in symbol.spellings), f"{symbol.tex}: used nowhere"
        assert set(notation.displays(symbol)) <= set(ctx["formula_numbers"]), symbol.tex
        first = notation.first_use(symbol, formulas)
        assert first is not None or symbol.where, f"{symbol.tex}: in no display and no place named"
    rows = ctx["notation"]
    assert [row["symbol"] for row in rows] == [s.tex for s in NOTATION]
    assert all("[[" not in row["meaning"] for row in rows)
    omega = next(row for row in rows if row["symbol"] == r"\omega")
    assert omega["paper"] == "(2.1)"
    assert omega["first"] == rf"\hyperlink{{formula.euler}}{{({ctx['formula_numbers']['euler']})}}"


def test_the_index_compiles_alone_and_in_the_document(tree, tmp_path):
    if shutil.which("pdflatex") is None or shutil.which("pdftotext") is None:
        if os.environ.get("CI"):
            pytest.fail("pdflatex or pdftotext not found under CI")
        pytest.skip("pdflatex not installed")
    directory, _ = tree
    source = (directory / "notation.tex").read_text(encoding="utf-8")
    assert len(re.findall(r"^\$.*\\\\$", source, re.MULTILINE)) == len(NOTATION)          # one row a symbol
    document = tmp_path / "standalone-notation.tex"
    document.write_text(WRAPPER % "notation", encoding="utf-8")
    compiled = pdf.compile_document(directory, document, tmp_path)
    log = compiled.with_suffix(".log").read_text(encoding="latin-1")
    assert not re.search(r"^! ", log, re.MULTILINE) and "Underfull" not in log and pdf.layout_problems(log) == []
    main = (directory / "suslov_formulas.tex").read_text(encoding="utf-8")
    assert main.index(r"\addcontentsline{toc}{section}{Notation}") < main.index(r"\input{formulas_body}")
    text = pdf.pdf_text(pdf.compile_document(directory, directory / "suslov_formulas.tex", tmp_path))
    assert "Notation" in text.split("Contents")[1].split("References")[0]          # in the table of contents
    assert "the inertia tensor, in a body frame" in text
