"""The documents' apparatus: equation numbers beside the paper's, bibliography, contents, links, hypotheses.

Fast unit tests check the paper's printed numbers (:mod:`derivations.core.paper_numbers`) and the render
filters (:mod:`derivations.output.render`); the rest renders the default build into a temporary directory,
compiles the documents there (:func:`derivations.output.pdf.compile_pdfs`) and reads the PDFs back: link
annotations (:func:`~derivations.output.pdf.link_annotations`), named destinations (``pdfinfo -dests``),
the outline and the text (``pdftotext``).
"""
import re
from collections import Counter

import pytest
from conftest import require_tools

from derivations.core import paper_numbers
from derivations.core.paper_numbers import PRINTED, printed_numbers, unnumbered
from derivations.core.result import DerivationResult
from derivations.output import pdf
from derivations.output.pipeline import context, render_into
from derivations.output.render import (
    cite,
    literature,
    numbered_rows,
    paper_label,
    paper_refs,
    paper_refs_display,
    render,
)

BIBLIOGRAPHY = ("FMP09", "Kimura69", "DLMF", "Levelt61")


# --- the paper's printed numbers ------------------------------------------------------------------------------

def test_printed_numbers_of_the_paper():
    # equations are (section.n); a two-row gather numbers both rows; an align with \nonumber rows skips them
    assert [PRINTED[k] for k in ("3.25", "eq:ps", "gen12", "eq:whole", "eq:o12", "c's", "eq:enlev")] == \
        ["(1.2)", "(1.4)", "(2.1)", "(2.2)", "(2.7)", "(2.8)", "(2.9)"]
    assert [PRINTED[k] for k in ("eq:necc1", "eq:necc11", "eq:d", "eq:am2", "omegas", "ss")] == \
        ["(3.1)", "(3.2)", "(3.6)", "(3.17)", "(4.1)", "(4.4)"]
    assert [PRINTED[k] for k in ("eq:genhip", "eq:param", "gam_0", "eq:rlin", "gam1", "gam3", "eq:p23")] == \
        ["(5.7)", "(5.9)", "(5.25)", "(5.41)", "(6.1)", "(6.3)", "(6.10)"]
    # one counter for theorem, lemma, proposition, remark and problem, per section; conjectures on their own
    assert [PRINTED[k] for k in ("pro:necc", "angle", "pro:a", "Theorem 3.5", "Theorem 6.2", "Proposition 4.1")] == \
        ["Theorem 3.2", "Theorem 5.4", "Proposition 5.8", "Theorem 3.5", "Theorem 6.2", "Proposition 4.1"]
    assert (PRINTED["Theorem 3.1"], PRINTED["Theorem 5.2"], PRINTED["Conjecture 5.2"]) == \
        ("Theorem 3.2", "Theorem 5.4", "Conjecture 1")
    assert PRINTED["Conclusion"] == "Section 6.4" and PRINTED["section 3.1"] == "Section 3.1"


def test_label_fields_split_at_commas_and_skip_what_has_no_number():
    assert printed_numbers("eq:o12, c's") == ["(2.7)", "(2.8)"]
    assert printed_numbers("gam1, gam2, gam3, eq:gam3") == ["(6.1)", "(6.2)", "(6.3)", "(6.5)"]
    assert printed_numbers("Theorem 5.2 (p)") == ["Theorem 5.4"]
    assert printed_numbers("Theorem 5.2, angle") == ["Theorem 5.4"]          # no repeats
    assert printed_numbers("derived") == [] and unnumbered("derived") == ["derived"]
    assert printed_numbers("example p = 1, eq:d") == ["(3.6)"] and unnumbered("example p = 1, eq:d") == ["example p = 1"]
    assert printed_numbers("eq:kowal") == ["(3.7)"]        # the project's label for the Kovalevskaya exponents
    assert printed_numbers("alpha,beta") == ["(5.17)"]                         # a label with a comma of its own
    assert paper_numbers.__doc__ and "arXiv:0902.0079" in paper_numbers.__doc__


# --- the render filters ---------------------------------------------------------------------------------------

def test_paper_label_prints_numbers_not_labels():
    assert paper_label("eq:o12, c's", prefix=True) == "paper (2.7), (2.8)"
    assert paper_label("Theorem 5.2 (p)") == "Theorem 5.4 ($p$)"      # an old tree's label; the qualifier typeset
    assert paper_label("Theorem 5.4 (p)") == "Theorem 5.4 ($p$)"
    assert paper_label("derived", prefix=True) == "derived here"
    assert paper_label("example p = 1") == "example $p = 1$"


def test_numbered_rows_give_one_number_to_a_display():
    assert numbered_rows(r"a=1\\b=2\\c=3") == r"a=1\notag\\b=2\notag\\c=3"
    inner = r"M=\begin{pmatrix}1&0\\0&1\end{pmatrix},\ \substack{x\\y}"
    assert numbered_rows(inner) == inner                          # row breaks of inner structures stay
    assert numbered_rows(r"\text{a $x$}\\\{y\}") == r"\text{a $x$}\notag\\\{y\}"


def test_citations_and_labels_in_prose():
    assert literature("By Kimura's theorem ... DLMF 15.10.21-22 ... (Levelt)") == ["Kimura69", "DLMF", "Levelt61"]
    assert cite("Kummer (DLMF 15.10.21-22) and Kimura's theorem") == \
        r"Kummer (DLMF 15.10.21-22~\cite{DLMF}) and Kimura's theorem~\cite{Kimura69}"
    assert paper_refs(r"$\gamma_1$ solves eq:gamma_1 and eq:sysfin; $\omega$ of omegas") == \
        r"$\gamma_1$ solves (5.5) and (4.2); $\omega$ of (4.1)"
    assert paper_refs(r"eq:gamma\_1, eq:necc11, unknown eq:foo_bar") == r"(5.5), (3.2), unknown eq:foo\_bar"
    assert paper_refs(r"the angle of ss $a_b$") == r"the angle of ss $a_b$"     # English words stay
    assert paper_refs(r"$I_{23}=0$ (eq:lina), the corrected eq:necc1's root") == \
        r"$I_{23}=0$ (3.3), the corrected (3.1)'s root"                       # no doubled parentheses
    assert paper_refs(r"$x=\text{all solutions of eq:whole}$") == r"$x=\text{all solutions of (2.2)}$"
    assert paper_refs_display(r"\text{odd $p$ (eq:lina)}\to\text{a {b} eq:whole}\ x_{eq}") == \
        r"\text{odd $p$ (3.3)}\to\text{a {b} (2.2)}\ x_{eq}"


def test_hypotheses_are_printed_with_the_formula():
    result = DerivationResult("model")
    result.formula("k1", "eq:sysfin", "A formula", r"x=1\\y=2", hypotheses=["$d>0$", "$p$ odd, solves eq:whole"])
    result.formula("k2", "derived", "Another", "z=3")
    body = render("formulas_body.tex.j2", {"results": [result], "titles": {"model": "Model"}})
    assert r"\formulanote{Hypotheses: $d>0$; $p$ odd, solves (2.2).}" in body
    assert body.count("Hypotheses:") == 1                          # none printed where none are stated
    assert r"\begin{gather}" in body and r"\begin{gather*}" not in body
    assert r"x=1\notag\\y=2\label{formula:k1}" in body and r"z=3\label{formula:k2}" in body
    assert r"\hfill{\small paper (4.2)}" in body and r"\hfill{\small derived here}" in body
    assert "eq:sysfin" not in body


# --- the compiled documents -------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def documents(default_build, tmp_path_factory):
    """(tree, pdfs by name, context) of the default build, rendered and compiled in a temporary directory."""
    require_tools(*("pdflatex", "pdftotext", "pdfinfo"))
    tree = tmp_path_factory.mktemp("tree")
    render_into(default_build, tree)
    compiled = pdf.compile_pdfs(tree, tmp_path_factory.mktemp("pdf"))
    return tree, {p.stem: p for p in compiled}, context(default_build)


def _read(tree, name):
    return (tree / name).read_text(encoding="utf-8")


def test_bibliography_in_both_documents(documents):
    tree, pdfs, _ = documents
    preamble = _read(tree, "suslov-preamble.tex")
    assert [re.search(r"\\bibitem\{%s\}" % key, preamble) is not None for key in BIBLIOGRAPHY] == [True] * 4
    for name in ("suslov_formulas", "certificates"):
        source = _read(tree, name + ".tex")
        assert r"\input{suslov-preamble}" in source and r"\suslovbibliography" in source
        assert r"\cite{FMP09}" in source.split(r"\tableofcontents")[0]          # the introduction cites the paper
        text = pdf.pdf_text(pdfs[name])
        assert "References" in text and "Funkcialaj Ekvacioj" in text and "arXiv:0902.0079" in text
        log = pdfs[name].with_suffix(".log").read_text(encoding="latin-1")
        assert "Citation" not in log and "undefined" not in log
    body = _read(tree, "formulas_body.tex")
    assert r"\cite{Kimura69" in body or r"\cite{Kimura69}" in _read(tree, "suslov_formulas.tex")
    for key in BIBLIOGRAPHY:   # every entry is cited in the formulas document
        assert re.search(r"\\cite(\[[^]]*\])?\{[^}]*%s" % key, _read(tree, "suslov_formulas.tex") + body), key


def test_table_of_contents_and_outline(documents):
    tree, pdfs, ctx = documents
    assert r"\tableofcontents" in _read(tree, "suslov_formulas.tex")
    toc = (pdfs["suslov_formulas"].with_suffix(".toc")).read_text(encoding="latin-1")
    assert toc.count(r"\contentsline {section}") >= len(ctx["results"]) + 2      # sections, errata, references
    assert "Contents" in pdf.pdf_text(pdfs["suslov_formulas"])
    for name in ("suslov_formulas", "certificates"):
        assert b"/Outlines" in pdf.pdf_objects(pdfs[name].read_bytes())            # hyperref's bookmarks


def test_equations_numbered_beside_the_paper_numbers(documents):
    tree, pdfs, ctx = documents
    body = _read(tree, "formulas_body.tex")
    formulas = [f for r in ctx["results"] for f in r.formulas]
    assert body.count(r"\begin{gather}") == len(formulas) and r"\begin{gather*}" not in body
    aux = pdfs["suslov_formulas"].with_suffix(".aux").read_text(encoding="latin-1")
    numbers = {k: int(n) for k, n in re.findall(r"\\newlabel\{formula:([^}]*)\}\{\{(\d+)\}", aux)}
    assert numbers == ctx["formula_numbers"]        # the numbers the certificates document prints are LaTeX's
    for f in formulas:
        heading = re.search(r"\\paragraph\{%s\}\\hypertarget\{formula\.%s\}\{\}\\hfill\{\\small ([^}]*)\}"
                            % (re.escape(f.title), re.escape(f.key)), body)
        assert heading, f.key
        expected = printed_numbers(f.label)
        assert heading.group(1).startswith("paper " + ", ".join(expected)) if expected else \
            heading.group(1) == "derived here", (f.key, heading.group(1))
    assert not re.search(r"\\texttt\{eq:", body)          # no raw label printed
    for name in ("suslov_formulas", "certificates"):
        assert not re.findall(r"eq:\w+", pdf.pdf_text(pdfs[name])), name
    o12 = next(f for f in formulas if f.label == "eq:o12, c's")
    text = pdf.pdf_text(pdfs["suslov_formulas"])
    assert "paper (2.7), (2.8)" in text and f"({ctx['formula_numbers'][o12.key]})" in text


def test_hypotheses_printed_where_stated(documents):
    tree, _, ctx = documents
    body = _read(tree, "formulas_body.tex")
    stated = [f for r in ctx["results"] for f in r.formulas if f.hypotheses]
    assert body.count(r"\formulanote{Hypotheses:") == len(stated)
    for f in stated:
        assert paper_refs(f.hypotheses[0]) in body, f.key


def test_scattering_angle_is_defined_in_words(documents):
    tree, pdfs, _ = documents
    source = _read(tree, "suslov_formulas.tex")
    assert r"$\Delta\psi$ is the angle between that axis in space at $t\to-\infty$ and at" in source
    assert r"\cos\Delta\psi=-\langle\gamma(+\infty),n\rangle" in source
    assert r"\cos\Delta\psi=-\gamma_1(+\infty)" in source


def test_links_between_the_documents(documents):
    tree, pdfs, ctx = documents
    formulas_links = pdf.link_annotations(pdfs["suslov_formulas"])
    certificate_links = pdf.link_annotations(pdfs["certificates"])
    to_certificates = [l for l in formulas_links if l["action"] == "GoToR" and l["file"] == "certificates.pdf"]
    inputs = ["formulas_body.tex", "errata_table.tex", "per_p_table.tex", "monodromy_tables.tex", "galois_tables.tex",
              "galois_group_table.tex", "basis_tables.tex", "integrals_table.tex", "figures.tex"]
    keys = Counter(k.replace(r"\_", "_") for name in inputs if (tree / name).is_file()
                   for k in re.findall(r"\\certkey\{([^}]*)\}", _read(tree, name)))
    # one annotation per key printed (a key never breaks across lines), each to an existing row
    assert Counter(l["dest"] for l in to_certificates) == Counter({"cert." + k: n for k, n in keys.items()})
    targets = pdf.named_destinations(pdfs["certificates"])
    assert {l["dest"] for l in to_certificates} <= targets
    assert {"cert." + c["key"] for c in ctx["certificates"]} <= targets
    # back: every certificate cited by a formula links to that formula's display
    back = [l for l in certificate_links if l["action"] == "GoToR" and l["file"] == "suslov_formulas.pdf"]
    expected = Counter("formula." + fkey for citing in ctx["cited_by"].values() for fkey, _ in citing)
    assert Counter(l["dest"] for l in back) == expected and expected
    assert {l["dest"] for l in back} <= pdf.named_destinations(pdfs["suslov_formulas"])
    uris = {l["uri"] for l in formulas_links if l["action"] == "URI"}
    assert uris == {"https://arxiv.org/abs/0902.0079", "https://dlmf.nist.gov"}
    assert sum(l["action"] == "GoTo" for l in formulas_links) >= len(ctx["results"])   # contents, citations


def test_certificate_keys_in_the_formulas_have_rows(documents):
    """Source level: every key the formulas cite is a row target of the certificates table."""
    tree, _, _ = documents
    cited = set(re.findall(r"\\certkey\{([^}]*)\}", _read(tree, "formulas_body.tex")))
    anchors = set(re.findall(r"\\certanchor\{([^}]*)\}", _read(tree, "certificates_table.tex")))
    assert cited and cited <= anchors


def test_cost_table_is_a_document_of_its_own(documents):
    tree, pdfs, _ = documents
    assert "certificate_costs" not in _read(tree, "certificates.tex").split(r"\begin{document}")[1].replace(
        r"certificate\_costs.pdf", "")
    assert _read(tree, "certificate_costs.tex").startswith("% GENERATED") and r"\documentclass" in \
        _read(tree, "certificate_costs.tex")
    assert pdfs["certificate_costs"].is_file()
    assert pdf.document_report(pdfs["certificate_costs"])[1] == []


def test_a4_and_no_layout_problems(documents):
    _, pdfs, _ = documents
    for name, document in pdfs.items():
        info = pdf.subprocess.run(["pdfinfo", str(document)], capture_output=True, text=True).stdout
        assert re.search(r"Page size:\s+595\.\d+ x 841\.\d+ pts \(A4\)", info), (name, info)
        pages, problems = pdf.document_report(document)
        assert problems == [], (name, problems[:5])
        log = document.with_suffix(".log").read_text(encoding="latin-1")
        assert "Underfull" not in log, name
