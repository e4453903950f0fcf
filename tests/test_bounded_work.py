"""Bounded validated work (issue 38): an estimate before starting, a time limit, progress, capped workers.

Near the equilibrium I13 = I23 = 0 the monodromy's working digits and the integration's step count
grow without bound; the audit saw both run past any limit without a word.  Here: the refusal comes
before any integration (measured: well under the limit), names the estimate and the working digits,
and gives the answer that does exist in closed form (the Galois group by Kimura's theorem, the angle by
the closed-form ball, which must contain the ordinary-body integration where both run).
"""

import re

import pytest

from suslov.executor import worker_limit
from suslov.kernel.cost import enclosure_seconds, monodromy_seconds
from suslov.validated import (
    EnclosureTooCostly,
    MonodromyTooCostly,
    galois_group,
    monodromy,
    scattering_angle_enclosure,
)

NEAR = ("5/4", 1, "1e-6", "-1e-6")     # |omega| ~ 6e5


def test_monodromy_near_the_equilibrium_is_refused_at_once_with_the_exact_group():
    reports = []
    with pytest.raises(MonodromyTooCostly) as caught:
        monodromy("5/4", 1, "0.01", "-0.01", dps=30, max_seconds=20, progress=lambda *a: reports.append(a))
    message = str(caught.value)
    assert "estimated" in message and "max_seconds=20" in message and "working digits" in message
    assert galois_group("5/4", 1, "0.01", "-0.01").group in message


def test_monodromy_reports_progress_and_stops_at_its_limit():
    reports = []
    m = monodromy("5/4", 1, "3/10", "-1/2", dps=20, progress=lambda *a: reports.append(a))
    assert m.verdict == "SO(3,C)"
    fractions = [r[0] for r in reports]
    assert fractions[0] == 0 and fractions[-1] == 1 and fractions == sorted(fractions)
    assert all(r[2] > 0 for r in reports)      # an estimate from the start
    # a limit below the estimate refuses before integrating; one between loops stops in the run
    with pytest.raises(MonodromyTooCostly, match="not integrated"):
        monodromy("5/4", 1, "3/10", "-1/2", dps=20, max_seconds=0.5)


@pytest.mark.parametrize("value", [0, -1, float("nan"), float("inf"), "10", True])
def test_max_seconds_is_validated(value):
    with pytest.raises(ValueError, match="max_seconds"):
        monodromy("5/4", 1, "3/10", "-1/2", dps=20, max_seconds=value)
    with pytest.raises(ValueError, match="max_seconds"):
        scattering_angle_enclosure("5/4", 1, "3/10", "-1/2", dps=10, method="integration", max_seconds=value)


def test_enclosure_near_the_equilibrium_is_refused_before_integrating_and_the_closed_form_answers():
    reports = []
    with pytest.raises(EnclosureTooCostly, match=r"not started.*closed_form"):
        scattering_angle_enclosure(*NEAR, dps=10, method="integration", progress=lambda *a: reports.append(a))
    assert reports and reports[0][2] > 120          # the estimate, reported before anything ran
    angle = scattering_angle_enclosure(*NEAR, dps=30).angle   # the closed form: milliseconds
    assert angle.rad() < 1e-29


def test_estimates_grow_towards_the_equilibrium():
    assert monodromy_seconds(400) > 10 * monodromy_seconds(30)
    assert enclosure_seconds(6e5, 10) > 1e4 * enclosure_seconds(1.7, 10)


def test_ordinary_enclosure_agrees_with_the_closed_form():
    # how long it takes against its estimate is measured in bench/, not asserted here (shared machines)
    body = ("5/4", 1, "3/10", "-1/2")
    integrated = scattering_angle_enclosure(*body, dps=10, method="integration").angle
    closed = scattering_angle_enclosure(*body, dps=30).angle
    assert integrated.overlaps(closed)


def test_workers_are_capped_by_cores_and_memory():
    n, message = worker_limit(1000)
    assert 1 <= n < 1000 and message and "--workers 1000: capped at" in message
    assert worker_limit(1) == (1, None)
    assert worker_limit(None)[1] is None


def test_simulator_cli_caps_workers_with_a_note():
    import subprocess
    import sys

    from derivations.output.pipeline import ROOT

    done = subprocess.run([sys.executable, "-m", "suslov", "simulate", "scenes/galois_map.toml", "--explain",
                           "--workers", "1000"], cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "--workers 1000: capped at" in done.stderr
    capped = worker_limit(1000)[0]   # the same cores as the subprocess (the suite may pin its processes to one)
    assert re.search(rf"\b{capped} workers?\b", done.stdout) and "1000 workers" not in done.stdout


def test_a_directory_given_as_scene_is_a_clear_error(tmp_path):
    """(noticed while testing --workers: `suslov simulate scenes/` ended in IsADirectoryError)"""
    from suslov.cli import main

    assert main(["simulate", str(tmp_path), "--explain"]) == 2
