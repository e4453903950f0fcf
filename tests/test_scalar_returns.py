"""Scalar in, scalar out (issue 47): the float64 public functions return what a NumPy ufunc would.

``scattering_angle(2.5, 0.7)`` was ``array(3.13...)``; like ``np.sin(2.5)`` it is now ``np.float64``.  Checked
for every broadcasting float function of the public API: all-scalar arguments give NumPy scalars (``ndim``
0, not an ndarray), 0-d array arguments give the same (as ufuncs do: shape ``()`` kept), arrays an array of
the broadcast shape, and the value is the same number whichever form the arguments take.
"""
import doctest

import numpy as np
import pytest

import suslov as sf
from suslov.kernel import scalars

# name -> (function, scalar arguments); every argument listed here is a broadcast one
CALLS = {
    "omega": (sf.omega, (0.3, 3.0, 0.5)),
    "omega_general": (sf.omega_general, (0.2, 2.0, 1.0, 0.3, 0.5)),
    "first_integral": (lambda *a: sf.first_integral(3, *a), (0.5, 1.2, -0.4, 0.6, 0.8, 0.0)),
    "scattering_angle": (sf.scattering_angle, (2.5, 0.7)),
    "general_scattering_angle": (sf.general_scattering_angle, (1.25, 1.0, 0.3, -0.5)),
}


def components(result):
    return result if isinstance(result, tuple) else (result,)


def assert_scalar(value):
    assert type(value) is np.float64, type(value)
    assert np.ndim(value) == 0 and not isinstance(value, np.ndarray)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_scalar_arguments_give_numpy_scalars(name):
    function, args = CALLS[name]
    for value in components(function(*args)):
        assert_scalar(value)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_zero_d_arrays_give_scalars_of_the_same_value(name):
    """0-d array arguments: shape () kept, returned as a NumPy scalar, as np.sin(np.array(1.0)) is."""
    function, args = CALLS[name]
    given = components(function(*args))
    for value, same in zip(components(function(*(np.array(a) for a in args))), given):
        assert_scalar(value)
        assert np.shape(value) == () and value == same


@pytest.mark.parametrize("name", sorted(CALLS))
@pytest.mark.parametrize("shape", [(1,), (3,), (2, 3)])
def test_arrays_keep_the_broadcast_shape(name, shape):
    """One argument an array (the others scalars): an ndarray of that shape, each entry the scalar call's."""
    function, args = CALLS[name]
    expected = components(function(*args))
    for position in range(len(args)):
        spread = list(args)
        spread[position] = np.full(shape, args[position])
        for value, scalar in zip(components(function(*spread)), expected):
            assert isinstance(value, np.ndarray) and value.shape == shape and value.dtype == np.float64
            assert np.all(value == scalar)


def test_mixed_shapes_broadcast():
    w1, w2 = sf.omega(np.linspace(-1, 1, 5)[:, None], 3.0, np.array([0.5, 2.0]))
    assert w1.shape == w2.shape == (5, 2)
    assert sf.scattering_angle(np.array([[2.5], [1.5]]), np.array([0.7, 1.0, 3.0])).shape == (2, 3)


def test_the_issue_example():
    angle = sf.scattering_angle(2.5, 0.7)
    assert_scalar(angle)
    assert 3.13 < angle < 3.14   # np.float64(3.1312...), was array(3.1312...)


def test_gamma_basis_keeps_its_matrix():
    """gamma_basis is never a scalar: one 3x3 rotation per broadcast point (scalar t: shape (3, 3))."""
    assert sf.gamma_basis(0.3, 3, 0.5).shape == (3, 3)
    assert sf.gamma_basis(np.array(0.3), 3, 0.5).shape == (3, 3)
    assert sf.gamma_basis([0.3, 0.4], 3, 0.5).shape == (2, 3, 3)


def test_helper_leaves_non_arrays_and_shaped_arrays_alone():
    kept = np.zeros((2, 2))
    assert scalars.scalar_if_0d(kept) is kept
    assert scalars.scalar_if_0d("text") == "text"
    assert scalars.scalar_if_0d((np.array(1.0), np.array([1.0])))[1].shape == (1,)
    assert doctest.testmod(scalars).failed == 0
