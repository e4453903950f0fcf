"""Scalar in, scalar out: the float64 public functions return what a NumPy ufunc would (issue 47).

The run-time float paths compute on arrays (``np.broadcast_arrays``, masks, ``finite.repair``), so a call
whose arguments are all scalars ends with a 0-d array: ``scattering_angle(2.5, 0.7)`` was
``array(3.13...)``, where ``np.sin(2.5)`` gives ``np.float64(...)``.  Rather than each function
unwrapping its own result, the run-time functions are wrapped once with :func:`like_ufunc`: a 0-d float
result becomes a NumPy scalar (``np.float64``), anything with a shape is returned as it is, and a tuple
(``omega``'s two components) is unwrapped component by component.  As with ufuncs, 0-d array arguments
give a scalar too (same shape, ``()``), and a result is a scalar only when every broadcast argument was.
NumPy only.
"""
from __future__ import annotations

import functools

import numpy as np

__all__ = ["like_ufunc", "scalar_if_0d"]


def scalar_if_0d(result):
    """``result`` with every 0-d ndarray (alone or in a tuple) replaced by its NumPy scalar.

    >>> type(scalar_if_0d(np.array(2.0))).__name__, scalar_if_0d(np.array([2.0])).shape
    ('float64', (1,))
    """
    if isinstance(result, tuple):
        return tuple(scalar_if_0d(r) for r in result)
    if isinstance(result, np.ndarray) and result.ndim == 0:
        return result[()]   # np.float64: what np.sin returns for a scalar (and for a 0-d array)
    return result


def like_ufunc(function):
    """Decorator: ``function``'s 0-d array results returned as NumPy scalars (:func:`scalar_if_0d`)."""
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        return scalar_if_0d(function(*args, **kwargs))
    return wrapper
