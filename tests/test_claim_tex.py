"""Claims and notes typeset with their formulas as mathematics (issue 26, item 7).

Expected LaTeX is written by hand for claims of the build (an independent reading of each formula,
not the converter's output pasted back); the documents' claims and errata notes must keep no ASCII
operator in their text (every ``^``, ``->``, ``+-``, ``<=``, ``=``, ... inside ``$...$``); nothing is
dropped (the digits of every claim survive); and the committed tables use the conversion.
"""
import json
import re
from collections import Counter

import pytest

from derivations.output.claim_tex import claim_latex
from derivations.output.pipeline import GENERATED

CASES = [
    ("Re Lambda^2 = (I11 I22)^2 x printed eq:neccg12 left-hand side (det I = 1)",
     r"$\operatorname{Re} \Lambda^{2} = (I_{11} I_{22})^{2} \times$ printed \texttt{eq:neccg12} left-hand side "
     r"$(\det I = 1)$"),
    ("p = 13: gamma^(1) -> (-1,0,0) as t -> -oo",
     r"$p = 13$: $\gamma^{(1)} \to  (-1,\allowbreak 0,\allowbreak 0)$ as $t \to  -\infty$"),
    ("c^2 = d**2 + 1 -+ 0 with R^T e", r"$c^{2} = d^{2} + 1 \mp  0$ with $R^{T} e$"),
    ("p = 5: Fhat_k = -p (d-i)((2k+1)d+ip)/((p-2k)d-ip) F_k",
     r"$p = 5$: $\hat F_{k} = -p (d-i)((2k+1)d+ip)/((p-2k)d-ip) F_{k}$"),
    ("exponents 0, +-i sqrt(w.w) at a simple pole", r"exponents $0,\allowbreak  \pm i \sqrt{w\cdot w}$ at a simple pole"),
    ("P2 is a polynomial (w1 divides K^2 P1~ - d L~ M3 exactly)",
     r"$P_{2}$ is a polynomial $(w_{1}$ divides $K^{2} \tilde P_{1} - d \tilde L M_{3}$ exactly)"),
    ("gamma_basis within 1e-15 (p+1)^1.5 of gamma_basis_mp, and I13 != 0",
     r"\texttt{gamma\_basis} within $10^{-15} (p+1)^{1.5}$ of \texttt{gamma\_basis\_mp}, and $I_{13} \ne  0$"),
    ("in z = sech^2 t the equation is eq:3F2 with 3F2(a; b; z) for all d >= 0",
     r"in $z = \operatorname{sech}^{2} t$ the equation is \texttt{eq:3F2} with ${}_{3}F_{2}(a$; $b$; $z)$ for all "
     r"$d \ge  0$"),
    ("exact division by x and x^2-1; the loop about x = i", r"exact division by $x$ and $x^{2}-1$; the loop about "
     r"$x = i$"),
]


@pytest.mark.parametrize("claim, expected", CASES, ids=[c[0][:30] for c in CASES])
def test_hand_typeset_claims(claim, expected):
    assert claim_latex(claim) == expected


ASCII_OPERATORS = re.compile(r"\\textasciicircum|\\textless|\\textgreater|\\textbar|\\textasciitilde|->|\+-|-\+"
                             r"|<=|>=|!=|\*|=|\+|(?<![A-Za-z])-(?![A-Za-z])|/")


def text_outside_math(latex: str) -> str:
    latex = re.sub(r"\$[^$]*\$", " ", latex)
    return re.sub(r"\\texttt\{(?:[^{}]|\{\})*\}", " ", latex)


def documents_texts():
    document = json.loads((GENERATED / "certificates.json").read_text(encoding="utf-8"))
    return [c["claim"] for c in document["certificates"]] + [e["note"] for e in document["errata"]]


def test_no_ascii_operator_is_left_in_the_text_of_any_claim_or_note():
    left = [(text, m.group()) for text in documents_texts()
            for m in ASCII_OPERATORS.finditer(text_outside_math(claim_latex(text)))]
    assert left == []


def test_the_checker_sees_an_operator_left_as_text():
    assert ASCII_OPERATORS.search(text_outside_math(r"the value (I11 I22)\textasciicircum{}2 $x$"))
    assert ASCII_OPERATORS.search(text_outside_math(r"t -> oo"))


def test_nothing_is_dropped():
    """Every digit of every claim is in its LaTeX (e-notation numbers aside, which become 10^{...})."""
    for text in documents_texts():
        if re.search(r"\de[-+]?\d", text):
            continue
        assert Counter(re.findall(r"\d", text)) == Counter(re.findall(r"\d", claim_latex(text))), text


def test_the_committed_tables_use_the_conversion():
    document = json.loads((GENERATED / "certificates.json").read_text(encoding="utf-8"))
    table = (GENERATED / "certificates_table.tex").read_text(encoding="utf-8")
    errata = (GENERATED / "errata_table.tex").read_text(encoding="utf-8")
    assert all(claim_latex(c["claim"]) in table for c in document["certificates"])
    assert all(claim_latex(e["note"]) in errata for e in document["errata"])
