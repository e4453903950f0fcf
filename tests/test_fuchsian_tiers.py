"""The ball monodromy of the representative bodies: the default build's set and the full set, without a build (issue 43).

The Galois group and the local behaviour at the poles of every body are decided exactly
(``derivations/sections/general_galois.py``: Kimura; ``pole_theorem.py``); the ball monodromy of
``derivations/sections/fuchsian.py`` corroborates them.  A default build runs one body of each kind the
agreement certificates compare (odd, even and non-integer p with I13 = 0, a general body) at 20 digits
(``BODY_TIERS["default"]``); ``build_formulas.py --ball-checks full`` runs all seven at 30.  This file checks
the default set is what the certificates need and runs the full set here, on two worker processes, with
the comparisons the build makes: the verdict against the exact decision (Kimura), the loop about x = i
against the pole theorem, the even body's monodromy of infinite order and M(x = i) != I.
"""
import pytest

from derivations.output.pipeline import ROOT
from derivations.sections import fuchsian
from suslov.kernel.kimura import galois_group
from suslov.kernel.local_behaviour import local_behaviour


def _kind(case: str) -> str:
    return case.split()[0]


def test_default_set_keeps_one_body_of_each_kind_and_is_part_of_the_full_set():
    default, full = fuchsian.tier_bodies("default"), fuchsian.tier_bodies("full")
    assert full == list(fuchsian.BODIES) and len(full) == 7
    assert set(default) < set(full)
    assert {_kind(case) for case, *_ in default} == {"odd", "even", "non-integer", "general"}
    # the default build's certificates read an even row (the Conclusion's p = 2) and an odd one
    assert any(case.startswith("even $p = 2$") for case, *_ in default)
    assert fuchsian.BODY_TIERS["default"].digits < fuchsian.BODY_TIERS["full"].digits == 30
    jobs = fuchsian.ball_jobs("default")
    assert [body for body, _ in jobs] == [tuple(body) for _, *body in default]
    assert {digits for _, digits in jobs} == {fuchsian.BODY_TIERS["default"].digits}


def test_the_claims_name_the_set_that_ran():
    default, full = fuchsian.bodies_words("default"), fuchsian.bodies_words("full")
    assert default.startswith("the 4 representative bodies of the default ball checks") and "all 7 at 30" in default
    assert full.startswith("the 7 representative bodies of the full ball checks") and "$I23 = 0$" in full
    # the formulas document says so too (the table's sentence for the default set)
    template = (ROOT / "templates" / "galois_group_table.tex.j2").read_text(encoding="utf-8")
    assert (f"at {fuchsian.BODY_TIERS['default'].digits} digits" in template
            and f"on all seven at {fuchsian.BODY_TIERS['full'].digits} digits" in template)


@pytest.mark.slow
def test_full_set_of_bodies():
    """All seven bodies at 30 digits, as ``--ball-checks full`` runs them, with the build's comparisons."""
    from suslov.executor import run_chunks   # the build's and the sweeps' worker pool

    jobs = fuchsian.ball_jobs("full")
    rows, _ = run_chunks(fuchsian.monodromy_summary, jobs, [str(i) for i in range(len(jobs))], workers=2)
    assert len(rows) == len(jobs) == 7
    for (case, *body), row in zip(fuchsian.BODIES, rows):
        assert row["verdict"] in ("SO(3,C)", "reducible"), (case, row["verdict"])
        assert all(outcome != "fail" for _, outcome, _ in row["certificates"]), case
        # the build's agreement certificates: reducible exactly for odd p; the exact decision; the pole theorem
        assert (row["verdict"] == "reducible") == case.startswith("odd"), case
        assert row["verdict"] == galois_group(*body).group, case
        assert row["not_identity_at_i"] != local_behaviour(*body).meromorphic, case
        assert row["digits"] >= 30
    even = rows[[case for case, *_ in fuchsian.BODIES].index("even $p = 2$")]
    assert next(c for c in even["certificates"] if "infinite order" in fuchsian._test_name(c[0]))[1] == "pass"
    assert even["not_identity_at_i"]
