"""What a reader of the compiled documents sees (issue 35): no program syntax, no broken words.

The check reads the PDFs, not the LaTeX source: both documents are compiled from the committed
``generated/`` (``tests/test_build.py`` keeps it equal to what the sources build) and their text is
extracted with ``pdftotext -layout``; a line with ``**``, a product ``x*y``, ``<=``, ``>=``, ``!=``,
``sqrt(``, a caret, angle brackets typed as less/greater signs, "i · e." or "tensor t̂" is a line
the source left as program text (:data:`derivations.output.pdf.PROGRAM_SYNTAX`).

The claims themselves (:mod:`derivations.core.statement`) are checked by round trips: every
mathematical part of every certificate's claim, method and detail survives ``srepr`` and its plain
text (what ``certificates.json`` keeps) reads back as the same expression, so no term is lost between
the structure, the JSON and the documents.
"""
import shutil
import subprocess

import pytest
import sympy as sp
from conftest import require_tools
from sympy.functions.special.hyper import TupleArg

from derivations.core import statement
from derivations.core.statement import Ring, Statement, TextPrinter, math, say
from derivations.output import pdf


@pytest.fixture(scope="module")
def pdfs(generated_pdfs):
    """Both documents compiled from the committed tree (once per run: conftest.generated_pdfs): name -> PDF path."""
    require_tools(*("pdftotext", "pdftohtml"))
    return {d.name: d for d in generated_pdfs}


@pytest.fixture(scope="module")
def texts(pdfs):
    return {name: pdf.pdf_text(document) for name, document in pdfs.items()}


@pytest.mark.parametrize("name", ["suslov_formulas.pdf", "certificates.pdf"])
def test_no_program_syntax_in_the_compiled_text(texts, name):
    hits = pdf.program_syntax(texts[name])
    assert hits == [], f"{name}: {len(hits)} lines of program syntax, e.g.\n" + "\n".join(hits[:25])


def test_the_lint_finds_what_it_looks_for():
    bad = ["non-zero terms, leading -I11*I13*I22", "(J2-J3)^2 = 1/81", "p**2 = 81", "r = +sqrt(I11 I22)",
           "k <= 3", "p >= 1", "I13 I23 != 0", "- < a, I^-1 a >= -I11 I22", "i · e. the printed system",
           "tensor t̂"]
    assert [bool(pdf.program_syntax(line)) for line in bad] == [True] * len(bad)
    good = ["the verdicts agree for 0 < p < 15 (odd p)", "ω(t) solves eq:sysfin, both branches of c",
            "I11 = 5/4, |ω| = 1, 2 · 10−15", "that is, the printed system runs in the time τ"]
    assert [line for line in good if pdf.program_syntax(line)] == []


def _parts(default_build):
    for certificate in default_build.log.certificates:
        for value in (certificate.claim, certificate.method, certificate.detail):
            assert isinstance(value, Statement)
            yield certificate, value


NAMESPACE = {**vars(sp), "TupleArg": TupleArg, **{k: v for k, v in vars(statement).items() if isinstance(v, type)}}


def _canonical(expr):
    """The expression rebuilt with evaluation on: two spellings of one formula give one object."""
    namespace = NAMESPACE
    # the plain text names symbols, not their assumptions (I11 > 0): compare by name
    expr = expr.xreplace({s: sp.Symbol(s.name) for s in expr.free_symbols if isinstance(s, sp.Symbol)})
    return eval(sp.srepr(expr), namespace)


def _same(a, b) -> bool:
    """One formula: equal after evaluation and expansion (two spellings of a product of sums differ before)."""
    a, b = _canonical(a), _canonical(b)
    if a == b or sp.expand(a) == sp.expand(b):
        return True
    if isinstance(a, sp.Expr) and isinstance(b, sp.Expr):
        return sp.simplify(a - b) == 0
    return type(a) is type(b) and len(a.args) == len(b.args) and all(_same(x, y) for x, y in zip(a.args, b.args))


def test_every_formula_survives_srepr_and_its_plain_text(default_build):
    namespace = NAMESPACE
    checked = 0
    for certificate, value in _parts(default_build):
        for expr in value.expressions():
            written = sp.srepr(expr)     # (srepr itself must run with evaluation on: it sorts factors)
            with sp.evaluate(False):     # every node and term as written
                rebuilt = eval(written, namespace)
            if isinstance(expr, sp.Basic) and not isinstance(expr, sp.MatrixBase):
                assert _same(rebuilt, expr), (certificate.key, expr, rebuilt)
                reread = math(TextPrinter().doprint(expr))
                assert _same(reread, expr), (certificate.key, expr, reread)
            checked += 1
    assert checked > 500      # every claim of the default build, not a sample


def test_the_round_trip_sees_a_lost_term():
    full = math("I33 = (1 + I11 I23^2 + I22 I13^2)/(I11 I22)")
    assert _same(math(TextPrinter().doprint(full)), full)
    assert not _same(math("I33 = (1 + I11 I23^2)/(I11 I22)"), full)
    assert not _same(math("I33 = (1 + I11 I23^2 + I22 I13^2)/I11"), full)


def test_claims_are_words_and_formulas_not_dollar_text(default_build):
    """Prose parts keep no formula delimiters; the JSON text is the parts' text, nothing dropped."""
    for certificate, value in _parts(default_build):
        assert not any("$" in part for part in value.parts if isinstance(part, str)), certificate.key
        assert value.text() == "".join(statement.text_of(part) for part in value.parts)
    record = default_build.log.certificates[0].deterministic_record()
    assert isinstance(record["claim"], str) and "$" not in record["claim"]


def test_statement_form():
    claim = say("det I = 1 fixes $I33 = (1 + I11 I23^2 + I22 I13^2)/(I11 I22)$")
    assert claim.parts[0] == "det I = 1 fixes "
    I11, I22, I13, I23, I33 = sp.symbols("I11 I22 I13 I23 I33")
    assert isinstance(claim.parts[1], sp.Eq) and claim.parts[1].lhs == I33
    assert sp.expand(_canonical(claim.parts[1].rhs) - (1 + I11 * I23**2 + I22 * I13**2) / (I11 * I22)) == 0
    assert r"I_{33} = \frac{1 + I_{11} I_{23}^{2} + I_{22} I_{13}^{2}}{I_{11} I_{22}}" in claim.tex()
    assert claim.text() == "det I = 1 fixes I33 = (1 + I11*I23**2 + I22*I13**2)/((I11*I22))"
    ring = say("exact zero test in $Q(I11, I22)[r]/(r^2 - I11 I22)$").parts[1]
    assert isinstance(ring, Ring)
    assert ring.tex() == r"\mathbb{Q}(I_{11}, I_{22})[r]/(r^{2} - I_{11} I_{22})"
    # a claim from a branch that still writes plain strings is prose: typeset as text, nothing guessed
    plain = say("p^2 = 81")
    assert plain.parts == ("p^2 = 81",) and plain.tex() == r"p\textasciicircum{}2 = 81"
    assert pdf.program_syntax("p^2 = 81")          # ... so the PDF test names it
    assert say("$w1$, $g1$, $lam$, $Deltapsi$, $gammaI$").tex() == \
        r"$\omega_{1}$, $\gamma_{1}$, $\lambda$, $\Delta\psi$, $\gamma^{(1)}$"


def test_bad_statements_are_named():
    with pytest.raises(ValueError, match="odd number of"):
        say("the formula $p = 3 is not closed")
    with pytest.raises(ValueError, match=r"'p = = 3' is not SymPy syntax"):
        say("$p = = 3$")
    with pytest.raises(ValueError, match="unbalanced"):
        say("$Q(a, b[c]$")


# -- the prose lint by font (issue 46): what every glyph of a text font is ------------------------

@pytest.mark.parametrize("name", ["suslov_formulas.pdf", "certificates.pdf"])
def test_prose_is_words_and_typeset_mathematics(pdfs, name):
    from derivations.output.prose_lint import findings

    found = findings(pdfs[name])
    assert found == [], f"{name}: {len(found)} runs of text-font prose that are not prose, e.g.\n" + "\n".join(found[:30])


def test_the_prose_lint_cannot_be_satisfied_by_avoiding_patterns(tmp_path):
    """Maths written as ASCII identifiers, with none of the classic patterns, is still found; the same
    maths typeset, and program names in typewriter type, are not."""
    from derivations.output.prose_lint import findings

    if shutil.which("pdflatex") is None or shutil.which("pdftohtml") is None:
        pytest.skip("pdflatex or pdftohtml not installed")
    lines = {
        "ascii": r"the solution omega1 of the system tends to the limit rho times I11 as alpha grows",
        "typeset": r"the solution $\omega_1$ of the system tends to the limit $\rho I_{11}$ as $\alpha$ grows",
        "code": r"the emitted \texttt{first\_integral} of the module, in \texttt{float64}",
        "float": r"an error bound of 7e-38 on this interval",
    }
    found = {}
    for key, line in lines.items():
        source = tmp_path / f"{key}.tex"
        source.write_text("\\documentclass{article}\\usepackage[T1]{fontenc}\\usepackage{lmodern,amsmath}"
                          f"\\begin{{document}}\n{line}\n\\end{{document}}\n", encoding="utf-8")
        subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", source.name], cwd=tmp_path,
                       capture_output=True, check=True)
        found[key] = findings(tmp_path / f"{key}.pdf")
    assert found["typeset"] == [] and found["code"] == []
    assert len(found["ascii"]) == 1 and all(w in found["ascii"][0] for w in ("omega1", "rho", "I11", "alpha"))
    assert len(found["float"]) == 1 and "not prose: e" in found["float"][0]
