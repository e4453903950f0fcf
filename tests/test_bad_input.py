"""Bad input fails loudly at the boundary (issue 27, findings 4-8, 12-14).

Each case used to return a confident wrong answer or a Python-internal message: a precision of 0 or
-5 (the angle rounded to 3.0 or 4.0 > pi), complex arrays silently cut to their real part, a tiny or
huge tensor giving NaN or a wrong message, a truncated certificates file accepted by ``--verify``,
an enclosure without a time bound, a sweep of any size started without a word.  Expected values
come from the definitions: the angle of Theorem 5.4 is in [0, pi]; the answers are scale-invariant,
so a scaled tensor must give the unscaled tensor's answers.
"""
import json
import shutil
import subprocess
import sys

import numpy as np
import pytest

from derivations.output.pipeline import GENERATED, ROOT
from generated import suslov_formulas as sf
from suslov.kernel.enclosure import EnclosureTooCostly
from suslov.validated import scattering_angle_enclosure

BODY = np.array([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]])


@pytest.mark.parametrize("call", [
    lambda v: sf.scattering_angle_mp(2.5, 0.7, dps=v),
    lambda v: sf.gamma_basis_mp(0.3, 1, 0.5, dps=v),
    lambda v: sf.omega_mp(0.3, 1, 0.5, dps=v),
    lambda v: sf.first_integral_mp(1, 0.5, 1, 2, 0.6, 0.8, 0, dps=v),
    lambda v: sf.omega_general_mp(0.3, 2, 1, 0.3, -0.5, dps=v),
], ids=["scattering_angle_mp", "gamma_basis_mp", "omega_mp", "first_integral_mp", "omega_general_mp"])
@pytest.mark.parametrize("value", [-5, 0, 2.5, float("nan"), "30", True, 10**6])
def test_invalid_dps_is_refused_naming_the_argument(call, value):
    with pytest.raises(ValueError, match=r"dps=.*integer number of digits in \[1, 10000\]"):
        call(value)


def test_valid_dps_gives_the_angle_in_range():
    angle = sf.scattering_angle_mp(2.5, 0.7, dps=5)
    assert 0 <= angle <= np.pi and abs(angle - 3.1312) < 1e-3


@pytest.mark.parametrize("value", [2.5, 8, "128", 10**6])
def test_invalid_prec_is_refused(value):
    with pytest.raises(ValueError, match="prec="):
        sf.scattering_angle_ball(2, 1, prec=value)


@pytest.mark.parametrize("call", [
    lambda: sf.scattering_angle(np.array([2.5 + 1j]), 0.7),
    lambda: sf.omega(np.array([0.5 + 0j]), 3, 0.5),
    lambda: sf.gamma_basis(np.array([0.1 + 0j]), 1, 0.5),
    lambda: sf.omega_general(0.3, 2, 1, np.array([0.3 + 1e-9j]), -0.5),
    lambda: sf.special_case_parameters(BODY + 0j),
])
def test_complex_input_is_refused(call):
    with pytest.raises(ValueError, match="complex"):
        call()


@pytest.mark.parametrize("scale", [1e-300, 1e-150, 1e103, 1e300])
def test_tensor_answers_are_scale_invariant(scale):
    p, d, _ = sf.special_case_parameters(scale * BODY)
    assert (p, d) == pytest.approx(sf.special_case_parameters(BODY)[:2], rel=1e-12)
    assert np.allclose(sf.kovalevskaya_exponents(scale * BODY), sf.kovalevskaya_exponents(BODY), rtol=1e-12)
    assert sf.meromorphy(scale * BODY) == sf.meromorphy(BODY)


def test_eigenvector_message_only_for_an_eigenvector():
    with pytest.raises(ValueError, match="eigenvector"):
        sf.kovalevskaya_exponents(1e103 * np.diag([2.0, 1.0, 1.5]))
    sf.kovalevskaya_exponents(1e103 * BODY)   # no message for a body whose a is not an eigenvector


@pytest.mark.parametrize("damage", ["truncate", "not json", "no certificates"])
def test_verify_refuses_unreadable_certificates_whatever_the_flags(tmp_path, damage):
    copy = tmp_path / "generated"
    shutil.copytree(GENERATED, copy, ignore=shutil.ignore_patterns("__pycache__"))
    path = copy / "certificates.json"
    text = path.read_text()
    path.write_text({"truncate": text[:len(text) // 2], "not json": "certificates",
                     "no certificates": json.dumps({"pmax": 15})}[damage])
    done = subprocess.run([sys.executable, "build_formulas.py", "--verify", str(copy), "--pmax", "15", "--quiet"],
                          cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert done.returncode == 1 and "certificates.json cannot be read" in done.stderr


@pytest.mark.parametrize("value", [float("nan"), "30", 0, 1000, 2.5])
def test_enclosure_digits_are_validated(value):
    with pytest.raises(ValueError, match=r"dps=.*\[1, 300\]"):
        scattering_angle_enclosure(2, 1, "0.3", "-0.5", dps=value, method="integration")


def test_costly_enclosure_stops_at_max_seconds_and_reports_progress():
    reports = []
    with pytest.raises(EnclosureTooCostly, match="max_seconds=2"):
        scattering_angle_enclosure(2, 1, 0, "-1e-4", dps=10, max_seconds=2,
                                   progress=lambda *a: reports.append(a), method="integration")
    assert reports   # progress was reported before the limit stopped it


def test_per_d_caches_are_bounded():
    from suslov.runtime import basis, integrals

    for i in range(2 * integrals.CACHE_SIZE + 5):
        sf.gamma_basis(0.1, 1, 0.5 + i * 1e-6)
    sizes = [f.cache_info().currsize for f in (basis.series_float, basis._series_matrix)]
    assert 0 < max(sizes) <= integrals.CACHE_SIZE, sizes


def test_large_sweep_needs_confirmation(tmp_path, capsys):
    from suslov.cli import main

    scene = tmp_path / "big.toml"
    scene.write_text('name = "big"\n[sweep]\np = { linear = [0.5, 9.5], count = 1000 }\n'
                     'd = { linear = [0.1, 3], count = 300 }\n[effects]\ncompute = ["scattering_angle"]\n')
    assert main(["simulate", str(scene), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "300000 points" in err and "--yes" in err and not (tmp_path / "out").exists()
