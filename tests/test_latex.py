"""The generated LaTeX documents compile with pdflatex to publication standard (issue 14).

Both documents (``suslov_formulas.tex`` and its companion ``certificates.tex``) are compiled
from the committed ``generated/`` into a temporary directory (with the volatile cost table
``certificate_costs.tex`` where a build left it, a document of its own); the logs
must show no overfull box wider than 1 pt, no missing character and no font substitution, and the
formulas document of the default build stays within 26 pages.  Skipped only outside CI when pdflatex
is missing; under CI (CI=true) a missing pdflatex is a failure.
"""

import pytest

from derivations.output import pdf

MAX_PAGES = 30   # 20 until the Proposition 4.1 triangle errata row (issue 34), 21 until the table of contents,
                 # the hypotheses lines, display-style table cells and the bibliography (24 then); 28 with the
                 # notation index and the figures (issue 46)


@pytest.fixture(scope="module")
def compiled(generated_pdfs):
    """The committed tree's documents, compiled once per run (conftest.generated_pdfs)."""
    return generated_pdfs


def test_both_documents_compile(compiled):
    assert [p.name for p in compiled[:2]] == ["suslov_formulas.pdf", "certificates.pdf"]
    assert [p.name for p in compiled[2:]] in ([], ["certificate_costs.pdf"])
    for document in compiled:
        log = document.with_suffix(".log").read_text(encoding="latin-1")
        assert "Undefined control sequence" not in log
        assert document.stat().st_size > 10_000


@pytest.mark.parametrize("index", [0, 1], ids=["formulas", "certificates"])
def test_no_layout_problems(compiled, index):
    pages, problems = pdf.document_report(compiled[index])
    assert problems == [], f"{compiled[index].name}: {problems[:10]}"


def test_formulas_document_is_short(compiled):
    pages, _ = pdf.document_report(compiled[0])
    assert 5 <= pages <= MAX_PAGES


def test_layout_problems_are_detected():
    """The log parser is not vacuous: a real overfull line and a font substitution are reported."""
    log = ("Overfull \\hbox (855.4628pt too wide) detected at line 115\n"
           "Overfull \\hbox (0.5pt too wide) in paragraph at lines 3--4\n"
           "LaTeX Font Warning: Font shape `OML/cmtt/m/n' undefined\n"
           "Output written on x.pdf (53 pages, 1 bytes).")
    assert pdf.layout_problems(log) == ["overfull hbox 855.5 pt at line 115",
                                        "LaTeX Font Warning: Font shape `OML/cmtt/m/n' undefined"]
    assert pdf.page_count(log) == 53
