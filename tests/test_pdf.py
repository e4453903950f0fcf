"""PDFs outside the tracked tree; TeX by-products in generated/ are neither compared nor deleted."""
import os
import shutil

import pytest

from derivations.core.options import BuildOptions
from derivations.output import pdf
from derivations.output.pipeline import (
    GENERATED,
    ROOT,
    compare_trees,
    derive,
    write_atomically,
)

BYPRODUCTS = ("suslov_formulas.aux", "suslov_formulas.log", "suslov_formulas.pdf", "suslov_formulas.out")


def snapshot(root):
    return {p.name: p.read_bytes() for p in root.iterdir() if p.is_file()}


def test_check_ignores_tex_byproducts(tmp_path):
    copy = tmp_path / "generated"
    shutil.copytree(GENERATED, copy, ignore=shutil.ignore_patterns("__pycache__"))
    for name in BYPRODUCTS:
        (copy / name).write_text("compiled in place by a user")
    assert compare_trees(copy, GENERATED) == []
    (copy / "suslov_formulas.tex").write_text("changed")
    assert compare_trees(copy, GENERATED) == ["suslov_formulas.tex"]


def test_rebuild_keeps_the_users_pdf(tmp_path):
    out = tmp_path / "generated"
    build = derive(BuildOptions(pmax=3), ["special_case"])
    write_atomically(build, out)
    (out / "suslov_formulas.pdf").write_bytes(b"%PDF-1.5 the user's copy")
    write_atomically(build, out)
    assert (out / "suslov_formulas.pdf").read_bytes() == b"%PDF-1.5 the user's copy"


def test_pdf_is_written_outside_generated(tmp_path):
    if shutil.which("pdflatex") is None:
        if os.environ.get("CI"):
            pytest.fail("pdflatex not found under CI: .ci/run must install texlive-latex-base")
        pytest.skip("pdflatex not installed (apt-get install texlive-latex-base)")
    before = snapshot(GENERATED)
    written = pdf.compile_pdfs(GENERATED, tmp_path / "pdf")
    assert [p.name for p in written[:2]] == ["suslov_formulas.pdf", "certificates.pdf"]
    assert all(p.stat().st_size > 10_000 and p.parent == tmp_path / "pdf" for p in written)
    assert snapshot(GENERATED) == before
    # the page count docs/build.md states is the compiled document's
    import re
    stated = re.search(r"standalone LaTeX, (\d+) pages at the default pmax", (ROOT / "docs" / "build.md").read_text())
    assert stated and int(stated.group(1)) == pdf.document_report(written[0])[0]


def test_missing_pdflatex_is_a_clear_error(tmp_path, monkeypatch):
    monkeypatch.setattr(pdf.shutil, "which", lambda name: None)
    with pytest.raises(pdf.PdfError, match="apt-get install texlive-latex-base"):
        pdf.compile_pdfs(GENERATED, tmp_path)
