"""PDF of the generated LaTeX, written outside the tracked tree (``build_formulas.py --pdf``).

The documents ``\\input`` their tables from the generated directory, so pdflatex runs there
with ``-output-directory`` pointing elsewhere (default ``build/pdf/``, git-ignored): two
passes (longtable settles on the second), nothing written into ``generated/``.  TeX
by-products that a user leaves in ``generated/`` by compiling in place (``*.aux``,
``*.log``, ``*.pdf``, ...) are not build outputs: ``--check`` ignores them and a rebuild
keeps them (:data:`TEX_BYPRODUCTS`, used by ``derivations.pipeline``).
"""
from __future__ import annotations

import fnmatch
import shutil
import subprocess
from pathlib import Path

TEX_BYPRODUCTS = ("*.aux", "*.log", "*.pdf", "*.out", "*.toc", "*.fls", "*.fdb_latexmk", "*.synctex.gz", "*.dvi")
DOCUMENTS = ("suslov_formulas.tex",)


class PdfError(RuntimeError):
    """pdflatex is missing or failed; the message says which and where the log is."""


def is_byproduct(name: str) -> bool:
    return any(fnmatch.fnmatch(name, pattern) for pattern in TEX_BYPRODUCTS)


def compile_pdfs(source: Path, outdir: Path, passes: int = 2) -> list[Path]:
    """Compile the documents of ``source`` into ``outdir``; returns the PDFs written."""
    if shutil.which("pdflatex") is None:
        raise PdfError("pdflatex not found (Debian: apt-get install texlive-latex-base)")
    source, outdir = Path(source).resolve(), Path(outdir).resolve()
    outdir.mkdir(parents=True, exist_ok=True)
    written = []
    for document in DOCUMENTS:
        if not (source / document).is_file():
            raise PdfError(f"{source / document}: no such document (build first)")
        for _ in range(passes):
            proc = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error",
                                   f"-output-directory={outdir}", document], cwd=source, capture_output=True,
                                  text=True, timeout=600)
            if proc.returncode != 0:
                raise PdfError(f"pdflatex failed on {document}; see {outdir / Path(document).with_suffix('.log')}")
        written.append(outdir / Path(document).with_suffix(".pdf").name)
    return written
