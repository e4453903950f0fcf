"""PDF of the generated LaTeX, written outside the tracked tree (``build_formulas.py --pdf``).

The documents ``\\input`` their tables from the generated directory, so pdflatex runs there
with ``-output-directory`` pointing elsewhere (default ``build/pdf/``, git-ignored): two
passes (longtable settles on the second), nothing written into ``generated/``.  TeX
by-products that a user leaves in ``generated/`` by compiling in place (``*.aux``,
``*.log``, ``*.pdf``, ...) are not build outputs: ``--check`` ignores them and a rebuild
keeps them (:data:`TEX_BYPRODUCTS`, used by ``derivations.output.pipeline``).

The passes are run here rather than by latexmk (issue 36 asked): the bibliography is a
``thebibliography`` (no BibTeX), so the only reruns are LaTeX's own (table of contents, citations,
longtable widths, hyperref's outline): two passes, then more while the log asks for a rerun (at most
:data:`MAX_PASSES`); the runner's real work is reading the log (overfull boxes, missing characters) and
keeping every by-product out of ``generated/``.  latexmk runs a confirming pass: 10.4 s beside 7.9 s for
both documents before they had a table of contents, medians of 5 interleaved runs
(``python bench/bench_pdf_runner.py``, ``bench/results/pdf_runner.md``).

The documents are ``suslov_formulas.tex`` and ``certificates.tex`` (:data:`DOCUMENTS`, always) and the
cost table ``certificate_costs.tex`` (:data:`OPTIONAL_DOCUMENTS`: volatile, compiled where the build left
it).  They link into each other by file name (``certificates.pdf#cert.KEY``, ``suslov_formulas.pdf#formula.KEY``),
so they are compiled into one directory; :func:`link_annotations` and :func:`named_destinations` read
those links and their targets back from the PDFs.
"""
from __future__ import annotations

import fnmatch
import re
import shutil
import subprocess
import zlib
from pathlib import Path

TEX_BYPRODUCTS = ("*.aux", "*.log", "*.pdf", "*.out", "*.toc", "*.fls", "*.fdb_latexmk", "*.synctex.gz", "*.dvi")
DOCUMENTS = ("suslov_formulas.tex", "certificates.tex")
OPTIONAL_DOCUMENTS = ("certificate_costs.tex",)   # volatile: compiled when present
MAX_PASSES = 4
RERUN = re.compile(r"Rerun to get|Rerun LaTeX|\(rerunfilecheck\).*Rerun|Label\(s\) may have changed")


OVERFULL = re.compile(r"Overfull \\hbox \(([\d.]+)pt too wide\) (?:in paragraph at lines (\d+)--\d+|in alignment at "
                      r"lines (\d+)--\d+|detected at line (\d+))")
FONT_PROBLEMS = re.compile(r"Missing character: There is no .*|LaTeX Font Warning: .*")
TOLERANCE_PT = 1.0


def layout_problems(log_text: str, tolerance_pt: float = TOLERANCE_PT) -> list[str]:
    """Typesetting faults in a pdflatex log: overfull boxes wider than ``tolerance_pt``, missing
    characters and font substitutions, one line each (with the source line TeX reports)."""
    problems = [f"overfull hbox {float(m.group(1)):.1f} pt at line {next(g for g in m.groups()[1:] if g)}"
                for m in OVERFULL.finditer(log_text) if float(m.group(1)) > tolerance_pt]
    return problems + [m.group(0).strip() for m in FONT_PROBLEMS.finditer(log_text)]


def page_count(log_text: str) -> int:
    """Pages of the PDF, as pdflatex reports them at the end of its log ("Output written on ... (N pages")."""
    # TeX wraps log lines at 79 characters, also inside a long output path
    found = re.findall(r"Output written on .*?\((\d+) pages?", log_text.replace("\n", ""))
    return int(found[-1]) if found else 0


# What a reader must not meet in a compiled document (issue 35): program syntax outside mathematics,
# and the broken words a text-to-TeX guesser made.  Matched on ``pdftotext -layout`` output, where
# typeset mathematics has no ``**``, ``^`` or ``<=`` left: a hit is text the source did not typeset.
PROGRAM_SYNTAX = {
    "power **": re.compile(r"\*\*"),
    "product x*y": re.compile(r"[\w)\]]\s?\*\s?[\w(]"),
    "<=": re.compile(r"<="), ">=": re.compile(r">="), "!=": re.compile(r"!="),
    "sqrt(": re.compile(r"\bsqrt\("),
    "caret ^": re.compile(r"\^"),
    "angle brackets typed as < >": re.compile(r"<\s*[^<>=\s][^<>]*,[^<>]*>"),
    "broken 'i.e.'": re.compile(r"\bi\s*[·⋅]\s*e\s*\."),
    "broken word 'tensor'": re.compile(r"tensor\s*t\u0302|tensor\s*\u0074\u0302|tensor t̂"),
}


def program_syntax(text: str) -> list[str]:
    """The lines of extracted PDF text with program syntax or a broken word, each prefixed by what it has."""
    hits = []
    for line in text.splitlines():
        found = [name for name, pattern in PROGRAM_SYNTAX.items() if pattern.search(line)]
        if found:
            hits.append(f"{', '.join(found)}: {line.strip()}")
    return hits


def pdf_text(pdf: Path) -> str:
    """``pdftotext -layout`` of a PDF (poppler-utils)."""
    if shutil.which("pdftotext") is None:
        raise PdfError("pdftotext not found (Debian: apt-get install poppler-utils)")
    proc = subprocess.run(["pdftotext", "-layout", str(pdf), "-"], capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        raise PdfError(f"pdftotext failed on {pdf}: {proc.stderr.strip()}")
    return proc.stdout


class PdfError(RuntimeError):
    """pdflatex is missing or failed; the message says which and where the log is."""


def is_byproduct(name: str) -> bool:
    return any(fnmatch.fnmatch(name, pattern) for pattern in TEX_BYPRODUCTS)


def compile_document(cwd: Path, document: str | Path, outdir: Path, passes: int = 2) -> Path:
    """Run pdflatex on ``document`` in ``cwd`` (where its ``\\input`` files are) into ``outdir``: ``passes``
    runs, more while the log asks for a rerun, up to :data:`MAX_PASSES`.  Returns the PDF; raises
    :class:`PdfError` naming the log when pdflatex fails."""
    if shutil.which("pdflatex") is None:
        raise PdfError("pdflatex not found (Debian: apt-get install texlive-latex-base)")
    log = Path(outdir) / Path(document).with_suffix(".log").name
    for run in range(MAX_PASSES):
        proc = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error",
                               f"-output-directory={outdir}", str(document)], cwd=cwd, capture_output=True,
                              text=True, timeout=600)
        if proc.returncode != 0:
            raise PdfError(f"pdflatex failed on {Path(document).name}; see {log}")
        if run + 1 >= passes and not RERUN.search(log.read_text(encoding="latin-1")):
            break
    return Path(outdir) / Path(document).with_suffix(".pdf").name


def compile_pdfs(source: Path, outdir: Path, passes: int = 2) -> list[Path]:
    """Compile the documents of ``source`` into ``outdir`` (:func:`compile_document`); returns the PDFs
    written, :data:`DOCUMENTS` first, then the cost table where the build left one that is a document (a
    cost table written before it became one, an ``\\input`` fragment, is not compiled)."""
    if shutil.which("pdflatex") is None:
        raise PdfError("pdflatex not found (Debian: apt-get install texlive-latex-base)")
    source, outdir = Path(source).resolve(), Path(outdir).resolve()
    outdir.mkdir(parents=True, exist_ok=True)
    for document in DOCUMENTS:
        if not (source / document).is_file():
            raise PdfError(f"{source / document}: no such document (build first)")
    optional = tuple(d for d in OPTIONAL_DOCUMENTS if (source / d).is_file()
                     and "\\documentclass" in (source / d).read_text(encoding="utf-8"))
    return [compile_document(source, document, outdir, passes) for document in DOCUMENTS + optional]


_STREAM = re.compile(rb"stream\r?\n(.*?)\r?\nendstream", re.S)
_LINK = re.compile(rb"/Subtype\s*/Link\b(.*?)>>\s*>>", re.S)
_ACTION = re.compile(rb"/S\s*/(GoToR|GoTo|URI)\b")
_STRING = {key: re.compile(rb"/" + key + rb"\s*\(((?:[^()\\]|\\.)*)\)") for key in (b"F", b"D", b"URI")}


def pdf_objects(data: bytes) -> bytes:
    """The PDF's bytes with every Flate stream decompressed after it (pdfTeX packs annotations into object
    streams): enough to find annotation dictionaries with a regular expression, no PDF library needed."""
    parts = [data]
    for match in _STREAM.finditer(data):
        try:
            parts.append(zlib.decompress(match.group(1)))
        except zlib.error:
            continue      # an image, a font: not Flate or not whole
    return b"\n".join(parts)


def link_annotations(pdf: Path) -> list[dict]:
    """The link annotations of a pdfTeX PDF: ``{"action": "GoTo" | "GoToR" | "URI", "file": ..., "dest": ...,
    "uri": ...}`` (absent parts are None), in the order they are stored."""
    links = []
    for match in _LINK.finditer(pdf_objects(Path(pdf).read_bytes())):
        body = match.group(1)
        action = _ACTION.search(body)
        found = {key.decode().lower(): (m.group(1).decode("latin-1").replace("\\\\", "\\") if m else None)
                 for key, pattern in _STRING.items() for m in [pattern.search(body)]}
        links.append({"action": action.group(1).decode() if action else None, "file": found["f"],
                      "dest": found["d"], "uri": found["uri"]})
    return links


def named_destinations(pdf: Path) -> set[str]:
    """The named destinations of a PDF (``pdfinfo -dests``, poppler-utils): the targets links may name."""
    if shutil.which("pdfinfo") is None:
        raise PdfError("pdfinfo not found (Debian: apt-get install poppler-utils)")
    proc = subprocess.run(["pdfinfo", "-dests", str(pdf)], capture_output=True, text=True, timeout=120)
    if proc.returncode != 0:
        raise PdfError(f"pdfinfo failed on {pdf}: {proc.stderr.strip()}")
    return set(re.findall(r'"(.*)"\s*$', proc.stdout, re.M))


def document_report(pdf: Path) -> tuple[int, list[str]]:
    """(pages, layout problems) of a PDF compiled by :func:`compile_pdfs`, read from its log."""
    log_text = Path(pdf).with_suffix(".log").read_text(encoding="latin-1")
    return page_count(log_text), layout_problems(log_text)
