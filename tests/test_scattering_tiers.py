"""The numeric checks of Theorem 5.4: the default build's points and the full set, without a build (issue 43).

The scattering angle is derived exactly (``derivations/sections/scattering.py``, steps 1-4); the ss solution
enclosed in balls (``scattering_balls.grid``) and the fast-rotation column in mpmath
(``scattering_evidence.fast_rotation_certificate``, evidence) corroborate it.  A default build runs one p
of each kind (non-integer 0.5, odd 1, even 2): 9 enclosed points to 1e-18 and 3 fast-rotation points at 24
digits to 1e-18 (``GRIDS["default"]``, ``COLUMNS["default"]``); ``build_formulas.py --ball-checks full`` all
18 enclosed points and the column's six at 36 digits to 1e-30.  This file checks the default set is part of
the full one and runs the full set here, as the build's worker processes run it.
"""
import pytest

from derivations.core.certificates import Outcome
from derivations.core.options import BuildOptions
from derivations.sections import scattering, scattering_balls, scattering_evidence


def test_default_points_are_one_p_of_each_kind_and_part_of_the_full_set():
    default, full = scattering_balls.GRIDS["default"], scattering_balls.GRIDS["full"]
    assert set(default.points()) < set(full.points()) and len(full.points()) == 18 and len(default.points()) == 9
    assert default.d == full.d and default.tolerance == full.tolerance == "1e-18"
    assert set(default.p) == {"0.5", "1", "2"}                     # non-integer, odd, even
    column, full_column = scattering_evidence.COLUMNS["default"], scattering_evidence.COLUMNS["full"]
    assert set(column.p) < set(full_column.p) and column.d == full_column.d == ("0.05",)
    assert (full_column.dps, full_column.digits) == (36, 30) and column.digits < column.dps
    for tier in ("default", "full"):
        ((_, items, work),) = scattering.PREFETCH(BuildOptions(ball_checks=tier))
        assert work is scattering_evidence.numeric_certificates and {t for _, t in items} == {tier}


@pytest.mark.slow
@pytest.mark.parametrize("tier", ["default", "full"])
def test_numeric_checks_pass_and_say_which_set_ran(tier):
    """The build's two worker items for ``tier``, on two worker processes: every certificate passes and its
    claim names the points and the set of ball checks."""
    from suslov.executor import run_chunks   # the build's and the sweeps' worker pool

    items = [("enclosed grid", tier), ("fast rotation", tier)]
    (grid, lemma), (fast,) = run_chunks(scattering_evidence.numeric_certificates, items, ["grid", "fast"], workers=2)[0]
    for certificate in (grid, lemma, fast):
        assert certificate.outcome is Outcome.PASS, (certificate.claim, certificate.detail)
        assert f"the {tier} ball checks" in str(certificate.claim)
    points = len(scattering_balls.GRIDS[tier].points())
    assert f"({points} points:" in str(grid.claim) and f"({points} points:" in str(lemma.claim)
    column = scattering_evidence.COLUMNS[tier]
    assert f"to 1e-{column.digits};" in str(fast.claim) and f"{len(column.p)} points" in str(fast.claim)
