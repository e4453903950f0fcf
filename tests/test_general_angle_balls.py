"""The full ball checks of the general angle's analytic step, without a build (issue 43).

The default build corroborates the connection step of the closed-form scattering angle of every body
(``derivations/sections/general_angle.py``, step 5) on the first few of the twenty seeded bodies
(``BALL_TIERS["default"]``), so that a cold build stays in seconds; ``build_formulas.py --ball-checks full``
runs all twenty at 100 digits.  This file runs every seeded body here (``BALL_TIERS["tests"]``: 60 digits where
the full set has 100 -- the connection itself is exact since issue 45, Kummer's formulas -- a pass still proves
distances below 1e-50), on two worker processes, against two independent validated routes:

* the complex-path monodromy in x = e^t (``suslov.kernel.monodromy``), whose traces the closed form predicts;
* the ss enclosure (``suslov.kernel.enclosure``: validated integration along the real t-axis).

A pass proves the stated distance; the tolerance is the build's, ``10^(10 - digits)``.
"""
import pytest

from derivations.sections import general_angle

FULL = general_angle.BALL_TIERS["tests"]      # every seeded body; 60 digits where --ball-checks full has 100
JOBS = general_angle.ball_jobs(FULL)


def test_default_tier_is_a_prefix_of_the_full_set():
    default = general_angle.ball_jobs(general_angle.BALL_TIERS["default"])
    bodies = general_angle.seeded_bodies()
    assert len(bodies) == general_angle.SEEDED == 20 and len(set(bodies)) == 20
    assert all(job[0] in bodies for job in default)
    assert len(JOBS) == FULL.trace_bodies + FULL.angle_bodies + FULL.deep_bodies == 42
    assert {(kind, digits) for _, kind, digits, _ in JOBS} == {("trace", 60), ("angle", 20), ("angle", 60)}
    full = general_angle.BALL_TIERS["full"]
    assert (full.trace_bodies, full.angle_bodies, full.deep_bodies) == (FULL.trace_bodies, FULL.angle_bodies,
                                                                      FULL.deep_bodies)


@pytest.mark.slow
def test_full_ball_checks():
    """All 42 checks, on two worker processes (the suite runs in one process; the checks are independent)."""
    from suslov.executor import run_chunks   # the build's and the sweeps' worker pool

    rows, _ = run_chunks(general_angle._run_check, JOBS, [str(i) for i in range(len(JOBS))], workers=2)
    failures = []
    for (body, kind, digits, _), row in zip(JOBS, rows):
        distance = row["relative_float"] if kind == "trace" else row["difference_float"]
        if row["body"] != body or not 0 <= distance <= 10.0 ** (10 - digits):
            failures.append((kind, digits, body, row))
    assert len(rows) == len(JOBS) and failures == []
