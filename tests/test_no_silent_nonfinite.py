"""No silent non-finite output: every public float function, finite input of any magnitude (issue 38).

Property (hypothesis): for arguments of magnitude 1e-300..1e300, each public float function of the
generated module returns finite values or raises ``ValueError`` naming one of its arguments.  Values
where float64's intermediate quantities leave its range are checked against references computed
here from the defining formulas in mpmath (not the code under test): ``omega`` = ((p/d) tanh t,
-(p/d) sqrt(d^2+1) sech t); ``omega_general`` from eq:o12; the general angle against its 1050-bit ball
(the ball route shares no float path); ``canonical_frame`` by det I = 1 and the invariants of I.
"""
import math

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import suslov as sf

SETTINGS = settings(max_examples=150, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])


def magnitude(positive=False):
    signs = st.just(1.0) if positive else st.sampled_from([1.0, -1.0])
    return st.builds(lambda m, e, s: s * m * 10.0 ** e, st.floats(1.0, 9.999), st.integers(-300, 299), signs)


def finite(value) -> bool:
    if isinstance(value, dict):
        return all(finite(v) for v in value.values())
    if isinstance(value, (tuple, list)):
        return all(finite(v) for v in value)
    if hasattr(value, "__dataclass_fields__"):
        return all(finite(getattr(value, f)) for f in value.__dataclass_fields__)
    if value is None or isinstance(value, (str, bool, int)):
        return True
    array = np.asarray(value)
    return bool(np.all(np.isfinite(array))) if array.dtype.kind in "fc" else True


def finite_or_named(function, names, *args):
    try:
        with np.errstate(under="ignore"):   # an underflow to 0 is harmless; NaN and inf in the output are not
            out = function(*args)
    except ValueError as error:
        assert any(name in str(error) for name in names), f"{function.__name__}{args}: {error}"
        return None
    assert finite(out), f"{function.__name__}{args} = {out!r}"
    return out


@SETTINGS
@given(magnitude(), magnitude(True), magnitude(True))
def test_omega(t, p, d):
    finite_or_named(sf.omega, ("t", "p", "d"), t, p, d)


@SETTINGS
@given(magnitude(), magnitude(True), magnitude(True), magnitude(), magnitude())
def test_omega_general(t, I11, I22, I13, I23):
    finite_or_named(sf.omega_general, ("t", "I11", "I22", "I13", "I23"), t, I11, I22, I13, I23)


@SETTINGS
@given(st.sampled_from(sf.INTEGRAL_PS), magnitude(True), magnitude(), magnitude(), magnitude(), magnitude(),
       magnitude())
def test_first_integral(p, d, w1, w2, g1, g2, g3):
    finite_or_named(sf.first_integral, ("p", "d", "omega1", "omega2", "gamma1", "gamma2", "gamma3"),
                    p, d, w1, w2, g1, g2, g3)


@SETTINGS
@given(magnitude(), st.sampled_from(sf.BASIS_PS), magnitude(True))
def test_gamma_basis(t, p, d):
    B = finite_or_named(sf.gamma_basis, ("t", "p", "d"), t, p, d)
    if B is not None:   # a rotation, whatever the phase
        assert np.allclose(B @ B.T, np.eye(3), atol=1e-12)


@SETTINGS
@given(magnitude(True), magnitude(True))
def test_scattering_angle(p, d):
    angle = finite_or_named(sf.scattering_angle, ("p", "d"), p, d)
    assert angle is None or 0 <= angle <= math.pi


@SETTINGS
@given(magnitude(True), magnitude(True), magnitude(), magnitude())
def test_general_scattering_angle(I11, I22, I13, I23):
    angle = finite_or_named(sf.general_scattering_angle, ("I11", "I22", "I13", "I23"), I11, I22, I13, I23)
    assert angle is None or 0 <= angle <= math.pi


def tensors():
    return st.builds(lambda a, b, c, x, y, z: np.array([[abs(a), x, y], [x, abs(b), z], [y, z, abs(c)]]),
                     *(magnitude() for _ in range(6)))


@SETTINGS
@given(tensors())
def test_tensor_functions(I):
    for function in (sf.canonical_frame, sf.kovalevskaya_exponents, sf.special_case_parameters, sf.meromorphy):
        finite_or_named(function, ("I",), I)


@SETTINGS
@given(st.sampled_from(sf.INTEGRAL_PS), magnitude(True))
def test_first_integral_coefficients(p, d):
    finite_or_named(sf.first_integral_coefficients, ("p", "d"), p, d)


# the entries that float64 cannot form directly, against the defining formulas in mpmath

@pytest.mark.parametrize("t, p, d", [(3.0, 1e200, 1e200), (-2.0, 1e250, 1e150), (0.5, 1e300, 1e100)])
def test_omega_whose_intermediate_product_overflows(t, p, d):
    """sqrt(d^2 + 1) p overflows, sqrt(d^2 + 1) p / d does not."""
    w1, w2 = sf.omega(t, p, d)
    with mpmath.workdps(40):
        t_, p_, d_ = (mpmath.mpf(x) for x in (t, p, d))
        e1 = p_ / d_ * mpmath.tanh(t_)
        e2 = -p_ / d_ * mpmath.sqrt(d_**2 + 1) * mpmath.sech(t_)
    for got, expected in ((w1, e1), (w2, e2)):
        if abs(expected) > 1.7e308:
            pytest.fail("the reference is beyond float64: the call should have raised")
        assert abs(float(got) - float(expected)) <= 1e-15 * abs(float(expected))


def test_omega_beyond_float64_is_refused_naming_the_arguments():
    with pytest.raises(ValueError, match=r"omega\(t=1\.0, p=1e\+99, d=1e-298\).*beyond float64.*omega_mp"):
        sf.omega(1.0, 1e99, 1e-298)


@pytest.mark.parametrize("body", [(6.1e-287, 2.2e-42, 3.0e-228, -8.2e250), (2.2e-42, 3.0e-228, -8.2e250, -5.9e-55),
                                  (1e300, 1e-300, 1.0, 2.0)])
def test_omega_general_of_entries_spanning_float64(body):
    t = 0.5
    try:
        w1, w2 = sf.omega_general(t, *body)
    except ValueError as error:
        assert "beyond float64" in str(error)
        with mpmath.workdps(40):
            I11, I22, I13, I23 = (mpmath.mpf(x) for x in body)
            D = I11 * I23**2 + I13**2 * I22
            assert abs(I11 * I22 * I23 / D) * mpmath.tanh(t) > 1e308 or abs(I11 * I23 * mpmath.sqrt(I11 * I22) / D) > 1e308
        return
    with mpmath.workdps(40):
        I11, I22, I13, I23 = (mpmath.mpf(x) for x in body)
        D, r, tt = I11 * I23**2 + I13**2 * I22, mpmath.sqrt(I11 * I22), mpmath.mpf(t)
        e1 = (-I11 * I22 * I23 * mpmath.tanh(tt) + I13 * I22 * r * mpmath.sech(tt)) / D
        e2 = (I11 * I13 * I22 * mpmath.tanh(tt) + I11 * I23 * r * mpmath.sech(tt)) / D
    assert abs(float(w1) - float(e1)) <= 1e-14 * abs(float(e1)) and abs(float(w2) - float(e2)) <= 1e-14 * abs(float(e2))


@pytest.mark.parametrize("body", [(3.8906664977080136e+166, 1.896756754274739e-109, 8.454705274134093e+259,
                                   2.424979347753828e-136), (1e-300, 1e300, 2.0, -3.0)])
def test_general_angle_of_entries_spanning_float64_against_the_ball(body):
    got = sf.general_scattering_angle(*body)
    ball = sf.general_scattering_angle_ball(*body, prec=400)
    assert np.isfinite(got) and abs(got - float(ball.mid())) <= 1e-13 + float(ball.rad())


def test_canonical_frame_of_a_tensor_whose_det_underflows():
    """I/max|I| has eigenvalues about 1, 1e-11 and 1e-305: its det (9e-317) underflows, its cube root does not."""
    I = np.array([[1e150, 0.0, 1e144], [0.0, 1e-155, 0.0], [1e144, 0.0, 1e139]])
    R, (I11, I22, I13, I23) = sf.canonical_frame(I)
    with mpmath.workdps(60):
        a, b, c3, e = (mpmath.mpf(x) for x in (I[0, 0], I[1, 1], I[2, 2], I[0, 2]))
        c = mpmath.cbrt(b * (a * c3 - e * e))                     # det I (I12 = I23 = 0), by hand
        invariant_trace = (a + b + c3) / c                         # trace of I / det^(1/3): rotation-invariant
    new = np.array([[I11, 0, I13], [0, I22, I23], [I13, I23, 0]])
    assert np.isfinite(new).all() and np.allclose(R.T @ R, np.eye(3))
    # the (3,3) entry is unchanged by a rotation about e3: I33 / det^(1/3)
    I33 = float(mpmath.mpf(I[2, 2]) / c)
    assert abs(I11 + I22 + I33 - float(invariant_trace)) <= 1e-12 * float(invariant_trace)
