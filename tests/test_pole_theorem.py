"""Meromorphy and logarithms for every p and every body (issue 45): the theorem against independent routes.

The theorem (``derivations/sections/pole_theorem.py``) decides, from the Kovalevskaya exponent Lambda alone,
whether the Poisson solutions are meromorphic (Lambda odd), logarithmic (Lambda even) or branching at the poles of
omega; ``suslov.validated.local_behaviour`` is its run-time decision.  Expected values come from routes that share
none of its steps:

* the exact Frobenius recursion of the Poisson system at t0 = i pi/2 (``residue.logarithm_verdict``, one p at a
  time, in Q(d)) at p well beyond the default pmax, odd and even;
* the exact obstructions of the section-5.2 equation at s1..s4 (``galois.decide_logarithms``);
* the validated complex-path monodromy (``suslov.validated.monodromy``, balls): the loop about x = i excludes the
  identity where a logarithm or a branch is predicted (a ball cannot prove equality, so meromorphic bodies are
  checked with the recursion instead);
* hand arithmetic for Lambda^2 (I13 = 0: p^2 = I22 (I11 - I22)/I23^2; the mirror I23 = 0; I11 = I22: Lambda = 0).
"""
from __future__ import annotations

from fractions import Fraction

import pytest

from derivations.sections import galois, residue
from suslov.validated import local_behaviour, monodromy


@pytest.mark.parametrize("p", [27, 28, 60, 61])
def test_frobenius_recursion_agrees_beyond_the_default_pmax(p):
    """I13 = 0 with p^2 = I22 (I11 - I22)/I23^2: (I11, I22, I23) = (2, 1, -1/p) has p exactly."""
    verdict = residue.logarithm_verdict(p)[0]
    exact = local_behaviour(2, 1, 0, Fraction(-1, p))
    assert exact.Lambda == p
    assert (verdict == "no logarithms") == exact.meromorphic
    assert exact.kind == ("meromorphic" if p % 2 else "logarithmic")


@pytest.mark.parametrize("p", [41, 44])
def test_section_52_obstructions_agree_at_s1_to_s4(p):
    verdict, _ = galois.decide_logarithms(p)
    predicted = "log" if local_behaviour(2, 1, 0, Fraction(-1, p)).logarithmic else "no log"
    assert (verdict["s1"], verdict["s2"], verdict["s3"], verdict["s4"]) == (predicted, predicted, "no log", "no log")


@pytest.mark.parametrize("body, kind", [
    (("1", "1", "0", "-1"), "logarithmic"),          # I11 = I22: Lambda = 0
    (("2", "1", "0", "-1/2"), "logarithmic"),        # p = 2
    (("2", "1", "0", "-2/5"), "branching"),          # p = 5/2
    (("5/4", "1", "3/10", "-1/2"), "branching"),     # u.v != 0
])
def test_ball_monodromy_excludes_the_identity_where_the_theorem_says_not_meromorphic(body, kind):
    assert local_behaviour(*body).kind == kind
    loop = monodromy(*body, dps=20).matrices["x=i"]
    assert any(not (loop[r, c] - (1 if r == c else 0)).contains(0) for r in range(3) for c in range(3))


def test_lambda_squared_by_hand_in_each_case():
    # I13 = 0: p^2 = 3 (5 - 3)/(1/2)^2 = 24: not a square -> branching, Lambda^2 = 24 exactly
    b = local_behaviour(5, 3, 0, "0.5")
    assert (b.kind, b.lambda_squared[0], b.lambda_squared[1][0]) == ("branching", 24, 0)
    # the mirror I23 = 0 (eq:lina: I11 <-> I22, I13 <-> I23): p^2 = I11 (I22 - I11)/I13^2 = 1 (10 - 1)/1 = 9
    assert (local_behaviour(1, 10, -1, 0).kind, local_behaviour(1, 10, -1, 0).Lambda) == ("meromorphic", 3)
    assert (local_behaviour(1, 5, "-0.5", 0).kind, local_behaviour(1, 5, "-0.5", 0).Lambda) == ("logarithmic", 4)
    # I11 = I22 with both I13, I23 non-zero: u.v = 0 and Lambda^2 = I11^2 (0) = 0
    assert local_behaviour(2, 2, "0.3", "-0.7").kind == "logarithmic"


def test_decimals_and_floats_are_the_numbers_they_are():
    assert local_behaviour("2", "1", "0", "-0.2").kind == "meromorphic"                    # p = 5 exactly
    assert local_behaviour("2", "1", "0", "-0.20000000000000001").kind == "branching"      # p^2 = 1/0.2...^2
    assert local_behaviour(2, 1, 0, -0.5).kind == "logarithmic"                            # -0.5 is binary: p = 2
    assert local_behaviour(2, 1, 0, -0.2).kind == "branching"                              # the float 0.2 is not 1/5
    assert local_behaviour(2, 1, 0, Fraction(-1, 10**6 + 1)).Lambda == 10**6 + 1            # any p: no pmax
    assert local_behaviour(2, 1, 0, Fraction(-1, 10**6 + 1)).meromorphic


@pytest.mark.parametrize("body, field", [((2, 1, 0, 0), "I13=0 and I23=0"), ((0, 1, 0, 1), "I11"),
                                         ((2, -1, 0, 1), "I22"), ((2, 1, "1/0", 1), "I13")])
def test_bad_bodies_are_refused_naming_the_field(body, field):
    with pytest.raises(ValueError, match=field.replace("=", "=")):
        local_behaviour(*body)


def test_monodromy_uses_the_theorem_beyond_any_pmax():
    """The ball verdict for an odd p far beyond the loaded formulas' PMAX: before the theorem, the identity about
    x = i could not be certified there (balls cannot prove equality) and the per-p recursion stopped at PMAX."""
    mono = monodromy(2, 1, 0, "-1/17", dps=15)
    assert mono.verdict == "reducible"
    assert any("theorem for every p" in str(c) for c in mono.certificates)


def _scene_verdict(body):
    import suslov

    result = suslov.simulate({"body": body, "motion": {"time": [-1, 1], "samples": 3},
                              "effects": {"compute": ["local_behaviour"]}})
    return result.results["local_behaviour"]


@pytest.mark.parametrize("p, kind", [(1, "meromorphic"), (3, "meromorphic"), (5, "meromorphic"), (2, "logarithmic"),
                                     (4, "logarithmic"), ("2.5", "branching")])
def test_the_simulator_effect_decides_the_scene_body_as_written(p, kind):
    """p and d as a scene gives them (d = 1.0 is the binary 1, p = '2.5' the decimal): Lambda = p for I13 = 0."""
    verdict = _scene_verdict({"p": p, "d": 1.0})
    assert verdict["kind"] == kind
    assert verdict["Lambda"] == (p if isinstance(p, int) else None)


def test_a_tensor_turned_about_the_constraint_axis_keeps_its_verdict():
    """The p = 3 body (2, 1, 0, -1/3) turned about e3 by the rational rotation (3/5, 4/5): I12 != 0 in the scene's
    frame, the same body; and a general body with irrational paper-frame entries (u.v != 0) branches."""
    c, s = Fraction(3, 5), Fraction(4, 5)
    A = [[2, 0], [0, 1]]
    R = [[c, -s], [s, c]]
    turned = [[sum(R[i][k] * A[k][l] * R[j][l] for k in range(2) for l in range(2)) for j in range(2)] for i in range(2)]
    b = [sum(R[i][k] * bk for k, bk in enumerate((0, Fraction(-1, 3)))) for i in range(2)]
    inertia = [[str(turned[0][0]), str(turned[0][1]), str(b[0])], [str(turned[1][0]), str(turned[1][1]), str(b[1])],
               [str(b[0]), str(b[1]), "3"]]
    verdict = _scene_verdict({"inertia": inertia})
    assert (verdict["kind"], verdict["Lambda"]) == ("meromorphic", 3)
    general = _scene_verdict({"inertia": [["2", "0.5", "0.3"], ["0.5", "1", "-0.2"], ["0.3", "-0.2", "3"]]})
    assert general["kind"] == "branching"


def test_a_sweep_maps_the_local_behaviour_over_p_and_d(tmp_path):
    """A (p, d) sweep: the column is 0 (meromorphic) at odd p, 1 (logarithmic) at even p, 2 (branching) between,
    whatever d (Lambda = p for I13 = 0); the map draws the three classes."""
    from suslov.simulator import sweep
    from suslov.simulator.scene import load_scene

    scene = tmp_path / "scene.toml"
    scene.write_text('name = "poles"\n[sweep]\np = [1, 2, 2.5, 3, 4]\nd = [0.5, 2]\n'
                     '[effects]\ncompute = ["local_behaviour"]\nfigures = ["map"]\n')
    table, _, _, _ = sweep.run_sweep(load_scene(scene), tmp_path / "out", workers=1)
    expected = {1: 0.0, 2: 1.0, 2.5: 2.0, 3: 0.0, 4: 1.0}
    assert [expected[p] for p in table["p"]] == list(table["local_behaviour"])
    assert all(m.split(" ")[0] in ("meromorphic", "logarithmic", "branching") for m in table["local_behaviour_method"])
    assert (tmp_path / "out" / "map.png").is_file()
