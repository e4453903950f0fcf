"""The proven float64 bound of gamma_basis (issue 34; derivations/proofs/basis_proof.py).

* Held-out hard points (large phases on both branches, d from 1e-3 to 1e3, long and tiny times): the float
  function is within the proven bound of gamma_basis_mp at 40 digits, itself checked against the exact
  numerators by the build.
* Seeded changes to one run-time operation (a lost double-double term, a reordered rational evaluation, a
  power recurrence changed) are rejected by the bit-for-bit check that ties the proof to the code.
* The Parseval bound on the coefficients holds for the run-time coefficients, and the proven bound is within the
  stated one up to p = 201.
"""

import mpmath
import numpy as np
import pytest

import suslov as sf
from conftest import mutated_function
from derivations.proofs import basis_proof
from suslov.kernel import phase, trig_series
from suslov.kernel.phase import PHASE_LIMIT
from suslov.runtime import basis as runtime_basis

FORMULAS = sf.active_formulas()


@pytest.fixture(scope="module")
def bounds():
    return {p: basis_proof.prove(p) for p in (1, 7, 15)}


@pytest.mark.parametrize("p", [1, 7, 15])
@pytest.mark.parametrize("d", [1e-3, 0.0213, 1.0, 41.5, 1e3])
def test_proven_bound_holds_at_held_out_hard_points(bounds, p, d):
    near_edge = PHASE_LIMIT * d / p
    ts = [5e-324, -2.0**-970, 1e-9, -0.777, 3.25, -45.0, 800.0, -2e4, 0.999 * near_edge, -0.9999999 * near_edge,
          1.0000001 * near_edge, 123.0 * near_edge, -1e6 * near_edge]
    values = FORMULAS.gamma_basis(np.array(ts), p, d)
    for row, t in zip(values, ts):
        twin = FORMULAS.gamma_basis_mp(t, p, d, dps=40)
        bound = float(bounds[p]["far" if abs(p * t / d) >= PHASE_LIMIT else "near"].upper())
        with mpmath.workdps(40):
            gap = max(abs(mpmath.mpf(float(row[i][j])) - twin[i, j]) for i in range(3) for j in range(3))
        assert gap <= bound, (t, float(gap), bound)


@pytest.mark.parametrize("module, name, old, new", [
    (phase, "reduce_scalar", "    low += q2 * b1\n", ""),                                     # a lost double-double term
    (phase, "reduce_scalar", "    h -= k * _C2\n    k *= _C3\n    low -= k\n    h += low\n",
     "    k *= _C3\n    low -= k\n    h += low\n    h -= (k / _C3) * _C2\n"),                     # a reordered sum
    (phase, "_cos_sin_reduced", "    np.subtract(1.0, u2, out=u2)\n    u2 *= inverse\n",
     "    u2 *= inverse\n    np.subtract(inverse, u2, out=u2)\n"),                                # reordered rational
    (trig_series, "evaluate", "np.multiply(powers[k - 1, :m], z, out=powers[k, :m])",
     "np.multiply(powers[k - 1, :m] if k % 2 else powers[k // 2, :m], z if k % 2 else powers[k // 2, :m], "
     "out=powers[k, :m])"),                                                                      # squaring recurrence
])
def test_a_seeded_change_to_one_operation_is_rejected(monkeypatch, module, name, old, new):
    assert basis_proof.same_operations(FORMULAS, 7)[0]
    monkeypatch.setattr(module, name, mutated_function(module, name, old, new))
    assert not basis_proof.same_operations(FORMULAS, 7)[0]


def test_a_weaker_tan_or_a_far_phase_at_float_precision_grows_the_bound_or_fails():
    tight, _ = basis_proof.cos_sin_error(basis_proof.arb(0))
    loose, _ = basis_proof.cos_sin_error(basis_proof.arb(0), libm_rel=16 * basis_proof.U)
    assert loose > tight
    assert basis_proof.far_phase_ok(3)


def test_far_phase_rounded_before_the_sine_is_caught(monkeypatch):
    careful = mutated_function(runtime_basis, "careful_phase", "flint.arb(angle).sin_cos()",
                       "flint.arb(float(angle)).sin_cos()")
    monkeypatch.setattr(runtime_basis, "careful_phase", careful)
    assert not basis_proof.far_phase_ok(3)


def test_parity_check_refuses_a_numerator_of_mixed_parity():
    class Poly:
        def __init__(self, exponents):
            self._monoms = [(e, 0, 0) for e in exponents]

        def monoms(self):
            return self._monoms

    assert basis_proof.parity_holds(([Poly([0, 2]), Poly([1, 3]), Poly([1])], [Poly([1, 5]), Poly([3]), Poly([0])]))
    assert not basis_proof.parity_holds(([Poly([0, 2]), Poly([1, 2]), Poly([1])], [Poly([1]), Poly([3]), Poly([0])]))


@pytest.mark.parametrize("p", [1, 3, 9, 15])
def test_run_time_coefficients_obey_the_parseval_bound(p):
    """The l1 norm of every series' float coefficients is at most sqrt(4p + 2) (+ rounding) over a d grid (an
    independent numerical check of the parity and |f| <= 1 argument the proof uses)."""
    for d in np.geomspace(1e-3, 1e3, 61):
        c = runtime_basis.series_float(FORMULAS._basis_core, p, float(d))
        l1 = np.abs(c).sum(axis=(3, 4))          # per row, component, re/im: sum over cos/sin and k
        assert l1.max() <= np.sqrt(4 * p + 2) * (1 + 1e-12), (d, l1.max())


@pytest.mark.parametrize("p", [1, 51, 101, 151, 201])
def test_proven_bound_within_the_stated_one_up_to_p_201(p):
    proof = basis_proof.prove(p)
    assert proof["near"].upper() <= basis_proof.stated(p)
    assert proof["far"].upper() <= basis_proof.stated(p)
    assert proof["far"] < proof["near"]
