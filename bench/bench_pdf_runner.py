"""The build's pdflatex runner beside latexmk, in one run (issue 36: libraries before hand-written code).

Compiles both generated documents (formulas, certificates) into a temporary directory with
``derivations.output.pdf.compile_pdfs`` (two pdflatex passes each) and with ``latexmk -pdf`` (which
decides the passes itself), ``--repeat`` times each, and writes the medians to
``bench/results/pdf_runner.md``.  Needs pdflatex and latexmk (Debian: texlive-latex-base, latexmk).

    python bench/bench_pdf_runner.py --repeat 5
"""
from __future__ import annotations

import argparse
import platform
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from derivations.output.pdf import DOCUMENTS, compile_pdfs  # noqa: E402

GENERATED = ROOT / "generated"


def ours() -> float:
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        compile_pdfs(GENERATED, Path(tmp))
        return time.perf_counter() - start


def latexmk() -> float:
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        for document in DOCUMENTS:
            subprocess.run(["latexmk", "-pdf", "-interaction=nonstopmode", "-halt-on-error", f"-outdir={tmp}",
                            document], cwd=GENERATED, capture_output=True, check=True)
        return time.perf_counter() - start


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    if not shutil.which("latexmk"):
        print("bench_pdf_runner.py: latexmk not found (apt-get install latexmk)", file=sys.stderr)
        return 2
    times = {"two pdflatex passes (derivations/output/pdf.py)": [], "latexmk -pdf": []}
    for _ in range(args.repeat):   # interleaved: the shared machine's load falls on both alike
        times["two pdflatex passes (derivations/output/pdf.py)"].append(ours())
        times["latexmk -pdf"].append(latexmk())
    base = statistics.median(times["two pdflatex passes (derivations/output/pdf.py)"])
    lines = ["# Compiling the two generated documents: the build's runner beside latexmk", "",
             f"`python bench/bench_pdf_runner.py --repeat {args.repeat}` on {platform.machine()} "
             f"({platform.processor() or 'cpu'}), Python {platform.python_version()}, a shared 2-core machine; "
             "runs interleaved, medians.", "", "| runner | median s | ratio |", "|---|---:|---:|"]
    for name, values in times.items():
        median = statistics.median(values)
        lines.append(f"| {name} | {median:.2f} | {median / base:.2f} |")
    text = "\n".join(lines) + "\n"
    (ROOT / "bench" / "results" / "pdf_runner.md").write_text(text, encoding="utf-8")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
