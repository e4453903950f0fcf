"""Every generated table pastes into a paper with ``suslov-preamble.tex`` alone.

The default build is rendered into a temporary directory; each table is compiled by itself in a plain
``\\documentclass[10pt,a4paper]{article}`` with the margins the preamble's comment and ``docs/layout.md``
state (``\\usepackage[a4paper,margin=2cm]{geometry}``: a 170 mm text block) and nothing but
``\\input{suslov-preamble}``: no error, no overfull box wider than 1 pt, no missing character
(:func:`derivations.output.pdf.layout_problems`).  About 15 s for the nine tables: slow.
"""
import os
import re
import shutil

import pytest

from derivations.output import pdf
from derivations.output.pipeline import render_into

TABLES = ("errata_table", "per_p_table", "integrals_table", "basis_tables", "monodromy_tables", "galois_tables",
          "galois_group_table", "certificates_table", "formulas_body")
WRAPPER = ("\\documentclass[10pt,a4paper]{article}\n\\usepackage[a4paper,margin=2cm]{geometry}\n"
           "\\input{suslov-preamble}\n\\begin{document}\n\\input{%s}\n\\end{document}\n")


@pytest.fixture(scope="module")
def tree(default_build, tmp_path_factory):
    if shutil.which("pdflatex") is None:
        if os.environ.get("CI"):
            pytest.fail("pdflatex not found under CI: .ci/run must install texlive-latex-base")
        pytest.skip("pdflatex not installed (apt-get install texlive-latex-base)")
    directory = tmp_path_factory.mktemp("tree")
    render_into(default_build, directory)
    return directory


def test_the_preamble_states_the_margins_it_is_tested_with(tree):
    preamble = (tree / "suslov-preamble.tex").read_text(encoding="utf-8")
    assert r"%   \usepackage[a4paper,margin=2cm]{geometry}" in preamble
    assert r"%   \documentclass[10pt,a4paper]{article}" in preamble
    assert r"\documentclass" not in "".join(line for line in preamble.splitlines() if not line.startswith("%"))
    assert all(re.search(r"\\newcommand\{\\%s\}" % macro, preamble) for macro in ("certkey", "certanchor", "tabmath"))


@pytest.mark.slow
@pytest.mark.parametrize("table", TABLES)
def test_table_compiles_with_the_preamble_alone(tree, table, tmp_path):
    document = tmp_path / f"standalone-{table}.tex"
    document.write_text(WRAPPER % table, encoding="utf-8")
    compiled = pdf.compile_document(tree, document, tmp_path)
    log = compiled.with_suffix(".log").read_text(encoding="latin-1")
    assert not re.search(r"^! ", log, re.M)
    assert pdf.layout_problems(log) == []
    assert pdf.page_count(log) >= 1
