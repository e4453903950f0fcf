"""The generated LaTeX document compiles with pdflatex (texlive-latex-base).

Skipped only outside CI when pdflatex is missing; under CI (CI=true) a missing
pdflatex is a failure, so the test cannot be silently skipped there.
"""
import os
import shutil
import subprocess

import pytest

from derivations.pipeline import GENERATED


def test_generated_latex_compiles(tmp_path):
    if shutil.which("pdflatex") is None:
        if os.environ.get("CI"):
            pytest.fail("pdflatex not found under CI: .ci/run must install texlive-latex-base")
        pytest.skip("pdflatex not installed (apt-get install texlive-latex-base)")
    for item in GENERATED.glob("*.tex"):
        shutil.copy(item, tmp_path / item.name)
    for _ in range(2):  # longtable needs two passes to settle
        proc = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "suslov_formulas.tex"],
                              cwd=tmp_path, capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stdout[-3000:]
    assert (tmp_path / "suslov_formulas.pdf").stat().st_size > 10_000
    log = (tmp_path / "suslov_formulas.log").read_text(errors="replace")
    assert "Undefined control sequence" not in log
