"""Argument validation for the public functions of the generated module.

Every error is a ``ValueError`` whose message names the field, the offending value
(and, for arrays, its index) and the reason, so a user can fix the call without reading
the source.  Real parameters that a formula allows to vary broadcast like NumPy ufunc
arguments; parameters that select a formula (the odd integer p of a basis) do not.
"""
from __future__ import annotations

import math
import numbers
from fractions import Fraction

import mpmath
import numpy as np

__all__ = ["real_scalar", "real_array", "odd_p", "mp_real", "rational", "precision", "mp_dps", "ball_prec",
           "renamed_keywords", "DPS_RANGE", "PREC_RANGE"]

# documented limits of the precision arguments (digits for the mpmath twins, bits for the balls)
DPS_RANGE = (1, 10_000)
PREC_RANGE = (16, 100_000)


def _where(array: np.ndarray, bad: np.ndarray) -> tuple:
    return tuple(int(i) for i in np.argwhere(bad)[0]) if array.ndim else ()


def real_array(name: str, value, *, positive: bool = False, nonzero: bool = False) -> np.ndarray:
    """float64 array of finite reals (any shape); ``positive``/``nonzero`` add a sign condition.

    >>> real_array("d", [0.5, 2.0], positive=True)
    array([0.5, 2. ])
    """
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise ValueError(f"{name}={value!r}: must be a real number or an array of real numbers")
    raw = value if isinstance(value, np.ndarray) else None
    if raw is None:
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name}={value!r}: must be a real number or an array of real numbers") from None
    if np.iscomplexobj(raw):   # NumPy would drop the imaginary part with only a ComplexWarning
        raise ValueError(f"{name}: complex values are not accepted (dtype {raw.dtype}); pass the real part "
                         "explicitly if that is what is meant")
    try:
        array = np.asarray(raw, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}: must be a real number or an array of real numbers") from None
    if array.size > 64 and np.isfinite(np.add.reduce(array, axis=None)) and not (positive or nonzero):
        return array  # one fast pass: a finite sum has no NaN or inf among its terms
    for bad, why in ((~np.isfinite(array), "must be finite"),
                     ((array <= 0) if positive else None, "must be > 0"),
                     ((array == 0) if nonzero else None, "must be non-zero")):
        if bad is not None and bad.any():
            index = _where(array, bad)
            shown = array[index].item() if index else array.item() if array.ndim == 0 else array
            raise ValueError(f"{name}{list(index) if index else ''}={shown!r}: {why}")
    return array


def real_scalar(name: str, value, *, positive: bool = False, nonzero: bool = False) -> float:
    """One finite real as a Python float (rejects bool, strings, arrays)."""
    if isinstance(value, bool) or not isinstance(value, (numbers.Real, mpmath.mpf)):
        raise ValueError(f"{name}={value!r}: must be a real number")
    return float(real_array(name, float(value), positive=positive, nonzero=nonzero))


def precision(name: str, value, limits: tuple[int, int] = DPS_RANGE, unit: str = "digits") -> int:
    """A precision argument (``dps``, ``prec``, ``digits``) as an int within ``limits``, else ValueError.

    A zero, negative, fractional, NaN or string precision used to give confident wrong answers
    (``dps=0`` rounded the angle to 3.0); it is refused naming the argument and the range.

    >>> precision("dps", 30)
    30
    >>> precision("dps", 0)
    Traceback (most recent call last):
    ...
    ValueError: dps=0: must be an integer number of digits in [1, 10000]
    """
    low, high = limits
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, np.integer)) \
            or not low <= int(value) <= high:
        raise ValueError(f"{name}={value!r}: must be an integer number of {unit} in [{low}, {high}]")
    return int(value)


def mp_dps(dps) -> int:
    """The decimal digits of an mpmath route: ``dps`` if given, else ``mpmath.mp.dps`` (mpmath's habit).

    >>> with mpmath.workdps(40):
    ...     mp_dps(None), mp_dps(25)
    (40, 25)
    """
    return mpmath.mp.dps if dps is None else precision("dps", dps)


def ball_prec(dps=None, prec=None) -> int:
    """The bits of a ball route: ``prec`` (bits, python-flint's unit) or ``dps`` (decimal digits) if given,
    else ``mpmath.mp.prec`` (so ``mp.dps = 40`` moves the balls as it moves the mp twins).

    >>> with mpmath.workdps(15):
    ...     ball_prec(), ball_prec(dps=30), ball_prec(prec=200)
    (53, 100, 200)
    """
    if dps is not None and prec is not None:
        raise ValueError(f"dps={dps!r}, prec={prec!r}: give one precision, decimal digits (dps) or bits (prec)")
    if prec is not None:
        return precision("prec", prec, PREC_RANGE, "bits")
    if dps is not None:
        return max(PREC_RANGE[0], math.ceil(precision("dps", dps) * math.log2(10)))
    return mpmath.mp.prec


def renamed_keywords(function: str, given: dict, **renames: str) -> dict:
    """Old keyword names still accepted for one release: ``given`` (a ``**kwargs``) mapped through
    ``renames`` (old -> new) with a ``DeprecationWarning`` each; any other name is a ``TypeError``."""
    import warnings

    out = {}
    for old, value in given.items():
        if old not in renames:
            raise TypeError(f"{function}() got an unexpected keyword argument {old!r}")
        warnings.warn(f"{function}({old}=...) is deprecated; use {renames[old]}= (mpmath's convention: "
                      f"{renames[old]}=None follows mpmath.mp.dps)", DeprecationWarning, stacklevel=3)
        out[renames[old]] = value
    return out


def mp_real(name: str, value, *, positive: bool = False, nonzero: bool = False):
    """``mpmath.mpf`` at the current precision from an int, float, Fraction, mpf or decimal string.

    >>> mp_real("d", "0.5")
    mpf('0.5')
    """
    if isinstance(value, bool):
        raise ValueError(f"{name}={value!r}: must be a real number")
    try:
        if isinstance(value, Fraction):
            number = mpmath.mpf(value.numerator) / value.denominator
        else:
            number = mpmath.mpf(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}: must be a real number (int, float, Fraction, mpf or a decimal "
                         "string such as '0.5')") from None
    if not mpmath.isfinite(number):
        raise ValueError(f"{name}={value!r}: must be finite")
    if positive and not number > 0:
        raise ValueError(f"{name}={value!r}: must be > 0")
    if nonzero and number == 0:
        raise ValueError(f"{name}={value!r}: must be non-zero")
    return number


def rational(name: str, value, *, positive: bool = False) -> Fraction:
    """An exact ``Fraction`` from an int, a Fraction, a float or mpf (its exact binary value), or 'a/b' / '0.5'."""
    if isinstance(value, bool):
        raise ValueError(f"{name}={value!r}: must be a rational number (int, Fraction, float or 'a/b')")
    try:
        if isinstance(value, mpmath.mpf):
            if not mpmath.isfinite(value):
                raise ValueError
            mantissa, exponent = value.man_exp
            number = Fraction(int(mantissa)) * Fraction(2) ** int(exponent)
        else:
            number = Fraction(value)
    except (TypeError, ValueError, OverflowError, ZeroDivisionError):
        raise ValueError(f"{name}={value!r}: must be a rational number (int, Fraction, float or 'a/b')") from None
    if positive and number <= 0:
        raise ValueError(f"{name}={value!r}: must be > 0")
    return number


def odd_p(value, allowed, what: str) -> int:
    """An odd positive integer in ``allowed`` (integral floats such as 3.0 are accepted).

    ``what`` says which object needs odd p (it ends the message for even p).
    """
    if isinstance(value, bool):
        raise ValueError(f"p={value!r}: must be an odd positive integer")
    if isinstance(value, (numbers.Integral, np.integer)):
        p = int(value)
    elif isinstance(value, (numbers.Real, mpmath.mpf)) and math.isfinite(float(value)) and float(value).is_integer():
        p = int(float(value))
    else:
        raise ValueError(f"p={value!r}: must be an odd positive integer ({what})")
    if p < 1 or p % 2 == 0:
        raise ValueError(f"p={p}: must be an odd positive integer ({what})")
    if p not in allowed:
        raise ValueError(f"p={p}: outside the certified range of this module (odd p <= {max(allowed)}); "
                         f"for a larger range: sf = suslov.load_formulas(pmax={p}) (built once into the per-user "
                         "store, the checkout untouched), or python build_formulas.py --pmax N --install")
    return p
