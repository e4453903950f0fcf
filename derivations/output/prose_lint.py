"""The documents read as prose and typeset mathematics, checked on the compiled PDF by font (issue 46).

A pattern lint can be satisfied by avoiding its patterns; this one asks what every glyph *is*.  The PDF
is read with poppler's ``pdftohtml -xml``, which keeps each run of text with its font.  Runs in the math
fonts (Latin Modern Math Italic, Symbols, Extension, the blackboard ``MSBM``) are typeset mathematics;
runs in the typewriter font are program names and certificate keys (``\\texttt``, ``\\certkey``).  Every
run in a *text* font (Latin Modern Roman, upright, italic or slanted) must be prose: each word must be
an English word of a fixed list (:data:`WORDS`, ``prose_words.txt`` beside this module), a proper name
(:data:`NAMES`) or an operator name that TeX sets upright inside mathematics (:data:`OPERATORS`:
``tanh``, ``det``, ``Re``, ...).  Anything else in a text font -- ``I11``, ``omega``, ``gamma1``,
``oo``, ``s3`` -- is mathematics written as ASCII, since typeset it would have come out in a math font
(``I`` italic with a subscript ``11``).  On top of that the patterns no prose has: ``->``, ``+-``,
``**``, a caret or an underscore, a literal dollar sign, a 0-based index list ``[0, 2, 4]``, a prime
typed as a quote after a letter (``g''``).

Numbers and punctuation in a text font are fine (TeX sets digits of mathematics upright too); a word
broken by hyphenation at a line end is joined before it is looked up.
"""
from __future__ import annotations

import html
import re
import subprocess
from functools import lru_cache
from pathlib import Path

WORDS_FILE = Path(__file__).with_name("prose_words.txt")
# names that are not English words: people, places, journals, libraries
NAMES = frozenset("""
Arb Bernoulli Borel Cauchy Darboux Dekker DLMF Ekvacioj Euler Fedorov Frobenius Fuchsian Funkcialaj Galois
Gauss Higham Indagationes Jacobian Kimura Kolchin Kovacic Kovalevskaya Kummer LAPACK Lagrange Laurent Levelt
Lie Liouvillian Lyapunov Maciejewski Mathematicae NIST Painlevé Parseval Pauli Pochhammer Poisson Przybylska
Riccati Riemann Schlesinger Schwarz Sterbenz Suslov SymPy Taylor Yu Zariski Cayley Hamilton Jordan Kolmogorov
Fuchs Wronskian Lyapunov Schur Hermite Lamé Lame Heun Abel Picard Vessiot Zhu Chebyshev Horner Kahan
arXiv mpmath NumPy SciPy FLINT Python CPython Sage Maple Mathematica Jupyter Sphinx Dask heyoka PyPI
""".split())
# what TeX sets upright inside mathematics (\tanh, \det, \operatorname{Re}, \mathrm{SO}, ...)
OPERATORS = frozenset("""
sin cos tan cot sec csc sinh cosh tanh coth sech csch arcsin arccos arctan arg exp log ln det diag tr deg
lim max min sup inf dim ker rank sgn sign Re Im Res Ad Gal Id SO SL PSL GL SU Sp mod gcd lcm erf
""".split())
_PATTERNS = (
    (re.compile(r"->|<-|=>"), "an arrow typed as ASCII"),
    (re.compile(r"\+-|-\+"), "plus-minus typed as ASCII"),
    (re.compile(r"\*\*|\^|_"), "a power or subscript typed as ASCII"),
    (re.compile(r"\$"), "a literal dollar sign"),
    (re.compile(r"\[\s*\d+(?:\s*,\s*\d+)+\s*\]"), "an index list"),
    (re.compile(r"[A-Za-z]''?(?=[\s,.;:)]|$)"), "a prime typed as a quote"),
)
_WORD = re.compile(r"[A-Za-zÀ-ÿ]+(?:[0-9]+[A-Za-z0-9]*)?(?:[’'][a-z]+)?")
# abbreviations and enumerators of prose: e.g., i.e., (i), (ii), resp.
_PROSE_MARKS = re.compile(r"\b(?:e\.\s?g|i\.\s?e|cf|resp|etc)\.|\((?:i|ii|iii|iv)\)|\b[A-Z]\.(?=\s|,|$)"
                          r"|\b(?:re|non|semi|co)-(?=[a-z])")
_TEXT_FONT = re.compile(r"LMRoman|CMR|CMTI|CMSL|CMBX|LMSans")
_MONO_FONT = re.compile(r"Mono|CMTT")


@lru_cache(maxsize=1)
def words() -> frozenset:
    """The fixed list of English words (lower case), one per line in ``prose_words.txt``."""
    return frozenset(line.strip() for line in WORDS_FILE.read_text(encoding="utf-8").splitlines()
                     if line.strip() and not line.startswith("#"))


def runs(pdf: Path) -> list[tuple[int, str, str, int]]:
    """``(page, font family, text, top)`` of every text run of ``pdf``, in reading order (``top``: the
    run's vertical position on its page)."""
    xml = subprocess.run(["pdftohtml", "-xml", "-i", "-stdout", str(pdf)], capture_output=True, text=True,
                         check=True).stdout
    fonts = {m.group(1): m.group(2).split("+")[-1]
             for m in re.finditer(r'<fontspec id="(\d+)"[^>]*family="([^"]+)"', xml)}
    out, page = [], 0
    for m in re.finditer(r'<page number="(\d+)"|<text top="(\d+)"[^>]*font="(\d+)"[^>]*>(.*?)</text>', xml):
        if m.group(1):
            page = int(m.group(1))
            continue
        out.append((page, fonts[m.group(3)], html.unescape(re.sub(r"<[^>]+>", "", m.group(4))), int(m.group(2))))
    return out


def _acceptable(word: str) -> bool:
    word = re.sub(r"[’']s$", "", word)
    if word.lower() in words() and not any(ch.isdigit() for ch in word):
        return len(word) > 1 or word in ("a", "A")
    return word in NAMES or word in OPERATORS


def _joined(text_runs: list[list]) -> list[list]:
    """A word hyphenated at a line end is moved whole onto the next line's run (``equa-`` + ``tion``)."""
    for here, there in zip(text_runs, text_runs[1:]):
        if here[2] == there[2]:   # the same line: "per-" before a formula is a compound, not a break
            continue
        end = re.search(r"([A-Za-z]+)-\s*$", here[1])
        start = re.match(r"\s*([a-z]+)", there[1])
        if end and start:
            here[1] = here[1][:end.start()]
            there[1] = end.group(1) + start.group(1) + there[1][start.end():]
    return text_runs


def findings(pdf: Path) -> list[str]:
    """One line per text run that is not prose: ``page N: 'text' (why)``."""
    text_runs = _joined([[page, text, top] for page, font, text, top in runs(pdf)
                         if _TEXT_FONT.search(font) and not _MONO_FONT.search(font)])
    out = []
    for page, text, _ in text_runs:
        text = _PROSE_MARKS.sub(" ", text)
        reasons = [why for pattern, why in _PATTERNS if pattern.search(text)]
        bad = [w for w in _WORD.findall(text) if not _acceptable(w)]
        if bad:
            reasons.append("not prose: " + ", ".join(dict.fromkeys(bad)))
        if reasons:
            out.append(f"page {page}: {text.strip()!r} ({'; '.join(reasons)})")
    return out
