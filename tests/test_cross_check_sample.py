"""The per-p logarithm recursions as sampled cross-checks above a documented p.

``pole_theorem`` proves for every p and every body what ``residue.logarithm_verdict`` (Frobenius recursion at
t0 = i pi/2) and ``galois.decide_logarithms`` (obstructions at s1..s4) decide one p at a time, at a cost growing
like p^3 per p.  So the build runs them for every p <= ``cross_check_pmax`` (101 by default,
``--cross-check-pmax N``) and above it for a sample only (``derivations.core.options.cross_check_p_values``):
p = 0 or 1 mod 50 and the largest even and the largest odd p of the stage's range.  Here:

* the rule itself, for pmax 15, 101, 102, 201, 250 and with the threshold moved;
* the large-p test of each per-p certificate, run directly without a build: at p = 200 and 201 (the top of a
  pmax 201 build's sample) both recursions give the verdicts the theorem predicts (its run-time decision
  ``suslov.validated.local_behaviour``: odd p meromorphic, even p logarithmic; s3, s4 never);
* a small build with the threshold lowered (``--pmax 13 --cross-check-pmax 5``): the tables, the notes, the
  galois formula's title and hypotheses and ``pole_theorem``'s comparisons name exactly the p that ran.
"""
from __future__ import annotations

import json
import re
from fractions import Fraction

import pytest

import build_formulas
from derivations.core.cache import build_key
from derivations.core.options import (
    CROSS_CHECK_PMAX,
    BuildOptions,
    checked_words,
    cross_check_p_values,
    dense_prefix,
)
from derivations.output.cli import parser
from derivations.sections import galois
from suslov.validated import local_behaviour

EVERY_101 = list(range(1, 102))


@pytest.mark.parametrize("top, expected", [
    (15, list(range(1, 16))),
    (51, list(range(1, 52))),
    (101, EVERY_101),
    (102, EVERY_101 + [102]),
    (201, EVERY_101 + [150, 151, 200, 201]),
    (250, EVERY_101 + [150, 151, 200, 201, 249, 250]),
    (252, EVERY_101 + [150, 151, 200, 201, 250, 251, 252]),
])
def test_every_p_up_to_101_then_the_sample(top, expected):
    assert CROSS_CHECK_PMAX == 101
    assert cross_check_p_values(top) == expected
    assert BuildOptions(pmax=top).cross_check_p_values() == expected
    # both parities at the top of the range
    assert {top % 2, (top - 1) % 2} <= {q % 2 for q in expected if q >= top - 1}


def test_the_threshold_moves_and_every_p_runs_at_or_above_pmax():
    assert cross_check_p_values(201, 201) == list(range(1, 202))
    assert cross_check_p_values(201, 401) == list(range(1, 202))
    assert BuildOptions(pmax=250, cross_check_pmax=250).cross_check_p_values() == list(range(1, 251))
    assert cross_check_p_values(201, 150) == list(range(1, 151)) + [151, 200, 201]
    assert cross_check_p_values(13, 5) == [1, 2, 3, 4, 5, 12, 13]
    # galois: its own range, p <= max(40, pmax), sampled by the same rule
    assert BuildOptions(pmax=13, cross_check_pmax=5).cross_check_p_values(40) == [1, 2, 3, 4, 5, 39, 40]
    assert BuildOptions(pmax=15).cross_check_p_values(40) == list(range(1, 41))


def test_words_and_prefix():
    assert dense_prefix(EVERY_101 + [150, 151]) == 101
    assert dense_prefix([2, 3]) == 0
    assert checked_words(list(range(1, 16))) == "every $p <= 15$"
    assert checked_words(EVERY_101 + [150, 151, 200, 201]) == "every $p <= 101$ and the sample $p$ = 150, 151, 200, 201"


@pytest.mark.parametrize("value", [0, -1, 402, True, 1.5, "101"])
def test_bad_threshold_is_refused(value):
    with pytest.raises(ValueError, match="cross_check_pmax"):
        BuildOptions(cross_check_pmax=value)


def test_the_flag_reaches_the_options_and_the_cache_key():
    assert parser().parse_args([]).cross_check_pmax == 101
    assert parser().parse_args(["--pmax", "201", "--cross-check-pmax", "201"]).cross_check_pmax == 201
    with pytest.raises(SystemExit):
        parser().parse_args(["--cross-check-pmax", "0"])
    assert build_key(BuildOptions(pmax=201), None) != build_key(BuildOptions(pmax=201, cross_check_pmax=201), None)


# -- the large-p test of each per-p certificate (the top of a pmax 201 build's sample), no build ----------------

def _theorem(p: int):
    """The theorem's decision for the body (I11, I22, I13, I23) = (2, 1, 0, -1/p) of I13 = 0 with this p."""
    exact = local_behaviour(2, 1, 0, Fraction(-1, p))
    assert exact.Lambda == p
    return exact


@pytest.mark.parametrize("p", [200, 201])
def test_section_52_obstructions_at_the_top_of_the_sample(p):
    verdict, _ = galois.decide_logarithms(p)
    predicted = "log" if _theorem(p).logarithmic else "no log"
    assert predicted == ("log" if p % 2 == 0 else "no log")
    assert [verdict[k] for k in ("s1", "s2", "s3", "s4")] == [predicted, predicted, "no log", "no log"]


# -- a small build with the threshold lowered --------------------------------------------------------------------

@pytest.fixture(scope="module")
def sampled_tree(tmp_path_factory):
    out = tmp_path_factory.mktemp("cross_check") / "out"
    assert build_formulas.main(["--pmax", "13", "--cross-check-pmax", "5", "--only", "pole_theorem", "--out", str(out),
                                "--jobs", "1", "--quiet"]) == 0
    return out


def _table_ps(tex: str) -> list[int]:
    return [int(m.group(1)) for m in re.finditer(r"^(\d+) & .*\\certkey\{(?:residue|galois):", tex, re.MULTILINE)]


def test_tables_list_the_p_that_ran(sampled_tree):
    monodromy = (sampled_tree / "monodromy_tables.tex").read_text(encoding="utf-8")
    logarithms, bodies = monodromy.split(r"\subsection*{Physical bodies")
    assert _table_ps(logarithms) == [1, 2, 3, 4, 5, 12, 13]
    assert r"for every integer $1\le p\le5$ and $p\in\{12,13\}$" in logarithms
    assert "Above $p=5$ only the listed $p$ ran" in logarithms
    # the physical bodies stay on every p <= pmax
    assert [int(m.group(1)) for m in re.finditer(r"^(\d+) & .*\\certkey\{residue:", bodies, re.MULTILINE)] == list(range(1, 14))
    tables = (sampled_tree / "galois_tables.tex").read_text(encoding="utf-8").split("Proposition~5.8")[0]
    assert _table_ps(tables) == [1, 2, 3, 4, 5, 39, 40]
    assert r"for $p\le5$ and $p\in\{39,40\}$." in tables
    document = (sampled_tree / "suslov_formulas.tex").read_text(encoding="utf-8")
    assert r"\section{Local monodromy for $p\le13$ (logarithms sampled above $p=5$)}" in document
    body = (sampled_tree / "formulas_body.tex").read_text(encoding="utf-8")
    assert r"Logarithms at $s_1,\dots,s_4$ for $p\le5$ and $p\in\{39,40\}$" in body
    assert r"$1\le p\le5$ or $p\in\{39,40\}$ (the theorem on the poles covers every $p$)" in body


def test_notes_and_comparisons_name_the_p_that_ran(sampled_tree):
    document = json.loads((sampled_tree / "certificates.json").read_text(encoding="utf-8"))
    residue_note, = document["notes"]["residue"]
    assert ("checked by the recursion for every p <= 5 and the sample p = 12, 13: refuted for p = 2, 4, 12 "
            "(a non-zero resonance obstruction); confirmed for the other ones") in residue_note
    assert "Above p = 5 the recursion is a sampled cross-check: pole_theorem proves the verdict for every p." in residue_note
    galois_note, = document["notes"]["galois"]
    assert galois_note.startswith("Conjecture (section 5.2) decided for every p <= 5 and the sample p = 39, 40:")
    assert galois_note.endswith("this per-p table is its check, sampled above p = 5.")
    claims = {c["key"]: c for c in document["certificates"]}
    residue_agree = next(c for c in claims.values() if c["claim"].startswith("the theorem agrees with the exact Frobenius"))
    assert "for every p <= 5 and the sample p = 12, 13 (" in residue_agree["claim"]
    assert residue_agree["outcome"] == "pass"
    assert residue_agree["detail"] == "7 values of p agree: every p <= 5 and the sample p = 12, 13"
    galois_agree = next(c for c in claims.values() if c["claim"].startswith("the theorem agrees with the exact obstructions"))
    assert "for every p <= 5 and the sample p = 39, 40 (" in galois_agree["claim"]
    assert galois_agree["outcome"] == "pass"
    assert galois_agree["detail"] == "7 values of p agree: every p <= 5 and the sample p = 39, 40"
    # one logarithm certificate per p that ran, none for the p skipped
    logarithms = [c["claim"] for c in document["certificates"] if "local solutions of eq:ps" in c["claim"]]
    assert [int(re.match(r"p = (\d+):", c).group(1)) for c in logarithms] == [1, 2, 3, 4, 5, 12, 13]
