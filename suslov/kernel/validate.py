"""Argument validation for the public functions of the generated module.

Every error is a ``ValueError`` whose message names the field, the offending value
(and, for arrays, its index) and the reason, so a user can fix the call without reading
the source.  Real parameters that a formula allows to vary broadcast like NumPy ufunc
arguments; parameters that select a formula (the odd integer p of a basis) do not.

Numbers are read as the numbers they are: ints (and NumPy integers) exactly, floats (and NumPy floating
scalars) as their binary value, Fractions, decimal strings (``"0.7"`` is 7/10, ``"1e-5"``) and ``"a/b"``
strings exactly.  Exact input is bounded before any work (issue 44: ``"1e100000000"`` used to build a
100-million-digit integer before any time limit started): an exact number whose numerator or denominator,
in lowest terms, has more than :data:`MAX_ENTRY_BITS` bits (about 6000 decimal digits) is refused with a
``ValueError`` naming the field, the value (abbreviated) and the size.  A string is measured *before* it
is converted (its digits and its decimal exponent bound the size from below; the integers ``a`` and ``b``
of ``"a/b"`` are each held to the limit as written), a Python int by ``int.bit_length()``, an mpf by its
mantissa and exponent.  Floats are always within it (at most 1075 bits).
"""
from __future__ import annotations

import math
import numbers
import re
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np

__all__ = ["DPS_RANGE", "MAX_ENTRY_BITS", "PREC_RANGE", "ball_prec", "mp_dps", "mp_real", "odd_p", "precision",
           "rational", "real_array", "real_scalar", "renamed_keywords", "shown"]

# documented limits of the precision arguments (digits for the mpmath twins, bits for the balls)
DPS_RANGE = (1, 10_000)
PREC_RANGE = (16, 100_000)
# the largest numerator or denominator (lowest terms) of an exact input number, in bits (about 6000 digits):
# one limit for every exact route (galois_group, hypergeometric_form, the balls, the mp twins, scenes)
MAX_ENTRY_BITS = 20_000
_LOG2_10, _LOG2_5 = math.log2(10), math.log2(5)
_CHUNK = 4000   # digits per int() call: below Python's int_max_str_digits (4300)


def _where(array: np.ndarray, bad: np.ndarray) -> tuple:
    return tuple(int(i) for i in np.argwhere(bad)[0]) if array.ndim else ()


def shown(value, width: int = 60) -> str:
    """``value`` for an error message: its repr when short, else abbreviated.

    A 6000-digit int is not printed (Python refuses to convert ints beyond 4300 digits to text, and the
    message would be unreadable), nor a string of a million characters.

    >>> shown(10**5000)
    '<an int of 16610 bits, about 10^5000>'
    >>> shown("1e" + "0" * 100)
    "'1e0000000000000000000000'...'000000000000' (102 characters)"
    """
    if isinstance(value, str):
        return repr(value) if len(value) <= width else f"{value[:24]!r}...{value[-12:]!r} ({len(value)} characters)"
    if isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_)):
        n = int(value)
        if n.bit_length() <= 200:
            return repr(value)
        return f"<an int of {n.bit_length()} bits, about {'-' if n < 0 else ''}10^{_decades(abs(n))}>"
    if isinstance(value, Fraction):
        n, d = value.numerator, value.denominator
        if max(n.bit_length(), d.bit_length()) <= 200:
            return str(value)
        return (f"<a Fraction of about {'-' if n < 0 else ''}10^{_decades(abs(n)) - _decades(d)} (numerator "
                f"{n.bit_length()} bits, denominator {d.bit_length()} bits)>")
    try:
        text = repr(value)
    except (ValueError, TypeError, OverflowError):   # e.g. an object array holding a 5000-digit int
        return f"<a {type(value).__name__}>"
    return text if len(text) <= 3 * width else f"{text[:2 * width]}... ({len(text)} characters)"


def _decades(n: int) -> int:
    """round(log10(n)) of a positive int of any size, without converting it to text."""
    bits = n.bit_length()
    if bits <= 1000:
        return round(math.log10(n)) if n else 0
    return round(math.log10(n >> (bits - 64)) + (bits - 64) * math.log10(2))


def _too_big(name: str, value, bits: str, detail: str = "") -> ValueError:
    return ValueError(f"{name}={shown(value)}: its numerator or denominator has {bits} bits{detail}, beyond the "
                      f"{MAX_ENTRY_BITS} bits an exact number may have (MAX_ENTRY_BITS in suslov.kernel.validate, "
                      "about 6000 decimal digits)")


def _within(name: str, value, numerator: int, denominator: int) -> Fraction:
    """``Fraction(numerator, denominator)`` when both fit in :data:`MAX_ENTRY_BITS` (checked before the gcd)."""
    bits = max(numerator.bit_length(), denominator.bit_length())
    if bits > MAX_ENTRY_BITS:
        raise _too_big(name, value, str(bits))
    if denominator == 0:
        raise ValueError(f"{name}={shown(value)}: not a number (zero denominator)")
    if isinstance(value, Fraction):
        return value
    return Fraction(numerator, denominator)


def _int_of_digits(digits: str) -> int:
    """``int(digits)`` for a string of ASCII digits of any length (int() refuses more than 4300 digits)."""
    if len(digits) <= _CHUNK:
        return int(digits or "0")
    low = len(digits) // 2
    return _int_of_digits(digits[:-low]) * 10**low + _int_of_digits(digits[-low:])


_DIGITS = r"[0-9]+(?:_[0-9]+)*"
_NUMBER = re.compile(rf"""\A\s*(?P<sign>[-+]?)
    (?:(?P<num>{_DIGITS})\s*/\s*(?P<den>{_DIGITS})                  # a/b
     |(?=[0-9]|\.[0-9])(?P<int>(?:{_DIGITS})?)(?:\.(?P<frac>(?:{_DIGITS})?))?(?:[eE](?P<exp>[-+]?{_DIGITS}))?)
    \s*\Z""", re.VERBOSE | re.ASCII)


def _parse(name: str, text: str, given) -> Fraction:
    """The exact value of a decimal or ``a/b`` string, its size checked *before* any integer is built.

    A decimal is ``+-M 10^e`` with M its significant digits (no trailing zero: m of them).  In lowest terms its
    numerator is at least ``M/5^k`` and its denominator at least ``2^k`` (k = -e > 0: M is not a multiple of 10,
    so gcd(M, 10^k) is a power of 2 or a power of 5, at most 5^k), or the numerator is ``M 10^e`` (e >= 0).  When that lower
    bound exceeds :data:`MAX_ENTRY_BITS` the string is refused unconverted; otherwise the integers built are at
    most a few times the limit, and the exact size is checked after.
    """
    match = _NUMBER.match(text)
    if match is None:
        if text.strip().lower().lstrip("+-") in ("inf", "infinity", "nan"):
            raise ValueError(f"{name}={shown(given)}: must be finite")
        raise ValueError(f"{name}={shown(given)}: not a decimal or rational number (e.g. '0.7', '-1/3', '1e-5')")
    negative = match["sign"] == "-"
    if match["den"] is not None:   # a/b: the integers as written, each held to the limit like a Python int
        parts = []
        for digits in (match["num"].replace("_", ""), match["den"].replace("_", "")):
            significant = len(digits.lstrip("0"))
            if (significant - 1) * _LOG2_10 >= MAX_ENTRY_BITS + 1:
                raise _too_big(name, given, f"at least {int((significant - 1) * _LOG2_10) + 1}",
                               f" (an integer of {significant} digits as written; refused before converting it)")
            parts.append(_int_of_digits(digits))
        if parts[1] == 0:
            raise ValueError(f"{name}={shown(given)}: not a decimal or rational number (zero denominator)")
        return _within(name, given, -parts[0] if negative else parts[0], parts[1])
    fraction = (match["frac"] or "").replace("_", "")
    digits = ((match["int"] or "").replace("_", "") + fraction).lstrip("0")
    if not digits:
        return Fraction(0)
    significant = digits.rstrip("0")
    exponent = (match["exp"] or "0").replace("_", "")
    magnitude = exponent.lstrip("+-").lstrip("0")
    if len(magnitude) > 18:
        raise _too_big(name, given, f"more than 10^{len(magnitude) - 2}",
                       f" (a decimal exponent of {len(magnitude)} digits; refused before converting it)")
    e = (-1 if exponent.startswith("-") else 1) * int(magnitude or "0") - len(fraction) + len(digits) - len(significant)
    m = len(significant)
    low = (m - 1 + e) * _LOG2_10 if e >= 0 else max(-e, (m - 1) * _LOG2_10 + e * _LOG2_5)
    if low >= MAX_ENTRY_BITS + 1:
        raise _too_big(name, given, f"at least {int(low)}",
                       f" ({m} significant digit{'s' if m > 1 else ''} times 10^{e}; refused before converting it)")
    mantissa = _int_of_digits(significant)
    number = Fraction(mantissa * 10**e) if e >= 0 else Fraction(mantissa, 10**-e)
    return _within(name, given, -number.numerator if negative else number.numerator, number.denominator)


def _exact(name: str, value, accepted: str) -> Fraction:
    """The exact value of a number (module docstring), size-checked; ValueError naming ``name`` otherwise."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name}={value!r}: a number, not a bool ({accepted})")
    if isinstance(value, (int, np.integer)):
        return _within(name, value, int(value), 1)
    if isinstance(value, Fraction):
        return _within(name, value, value.numerator, value.denominator)
    if isinstance(value, str):
        return _parse(name, value, value)
    if isinstance(value, (float, np.floating)):
        if not np.isfinite(value):
            raise ValueError(f"{name}={value!r}: must be finite")
        numerator, denominator = value.as_integer_ratio()   # the binary value, exactly
        return Fraction(int(numerator), int(denominator))
    if isinstance(value, mpmath.mpf):
        if not mpmath.isfinite(value):
            raise ValueError(f"{name}={value!r}: must be finite")
        mantissa, exponent = (int(x) for x in value.man_exp)
        bits = mantissa.bit_length() + exponent if exponent >= 0 else max(mantissa.bit_length(), 1 - exponent)
        if mantissa and bits > MAX_ENTRY_BITS:
            raise _too_big(name, value, str(bits), " (an mpf with binary exponent " + str(exponent) + ")")
        return Fraction(mantissa * 2**exponent) if exponent >= 0 else Fraction(mantissa, 2**-exponent)
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise ValueError(f"{name}={value!r}: must be finite")
        return _parse(name, str(value), value)
    if isinstance(value, numbers.Rational):
        return _within(name, value, int(value.numerator), int(value.denominator))
    if type(value).__name__ == "arb" and hasattr(value, "is_finite") and not value.is_finite():
        raise ValueError(f"{name}={value}: must be finite")
    raise ValueError(f"{name}={shown(value)}: must be {accepted}")


def real_array(name: str, value, *, positive: bool = False, nonzero: bool = False) -> np.ndarray:
    """float64 array of finite reals (any shape); ``positive``/``nonzero`` add a sign condition.

    >>> real_array("d", [0.5, 2.0], positive=True)
    array([0.5, 2. ])
    """
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise ValueError(f"{name}={shown(value)}: must be a real number or an array of real numbers")
    raw = value if isinstance(value, np.ndarray) else None
    if raw is None:
        try:
            raw = np.asarray(value)
        except (TypeError, ValueError):
            raise ValueError(f"{name}={shown(value)}: must be a real number or an array of real numbers") from None
    if np.iscomplexobj(raw):   # NumPy would drop the imaginary part with only a ComplexWarning
        raise ValueError(f"{name}: complex values are not accepted (dtype {raw.dtype}); pass the real part "
                         "explicitly if that is what is meant")
    try:
        array = np.asarray(raw, dtype=float)
    except OverflowError:   # a Python int or Fraction beyond float64 (10**1000)
        raise _out_of_float_range(name, raw, "beyond float64's range (|x| <= 1.8e308)") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name}={shown(value)}: must be a real number or an array of real numbers") from None
    if raw.dtype == object and array.size and not np.all(array[np.asarray(raw != 0, dtype=bool)]):
        raise _out_of_float_range(name, raw, "not 0, but 0 in float64 (|x| < 5e-324)")
    if array.size > 64 and np.isfinite(np.add.reduce(array, axis=None)) and not (positive or nonzero):
        return array  # one fast pass: a finite sum has no NaN or inf among its terms
    for bad, why in ((~np.isfinite(array), "must be finite"),
                     ((array <= 0) if positive else None, "must be > 0"),
                     ((array == 0) if nonzero else None, "must be non-zero")):
        if bad is not None and bad.any():
            index = _where(array, bad)
            entry = array[index].item() if index else array.item() if array.ndim == 0 else array
            raise ValueError(f"{name}{list(index) if index else ''}={entry!r}: {why}")
    return array


def _out_of_float_range(name: str, raw: np.ndarray, why: str) -> ValueError:
    """The first entry of an object array (Python ints, Fractions, mpf) that float64 cannot hold, by name."""
    for index in np.ndindex(raw.shape):
        x = raw[index]
        try:
            if x == 0 or float(x) != 0:
                continue
        except OverflowError:
            pass
        where = list(index) if index else ""
        return ValueError(f"{name}{where}={shown(x)}: {why}; the mpmath (_mp) and ball (_ball) routes take it")
    return ValueError(f"{name}: {why}")


def real_scalar(name: str, value, *, positive: bool = False, nonzero: bool = False) -> float:
    """One finite real as a Python float (rejects bool, strings, arrays)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Real, mpmath.mpf)):
        raise ValueError(f"{name}={shown(value)}: must be a real number")
    try:
        number = float(value)
    except OverflowError:
        raise ValueError(f"{name}={shown(value)}: beyond float64's range (|x| <= 1.8e308)") from None
    return float(real_array(name, number, positive=positive, nonzero=nonzero))


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
        raise ValueError(f"{name}={shown(value)}: must be an integer number of {unit} in [{low}, {high}]")
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
    """``mpmath.mpf`` at the current precision from an int, float, Fraction, mpf, NumPy scalar or a decimal or
    ``a/b`` string: exact input is read exactly (size-checked, module docstring) and rounded once, to nearest.

    >>> mp_real("d", "0.5")
    mpf('0.5')
    """
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name}={value!r}: must be a real number")
    if isinstance(value, (float, mpmath.mpf)):
        number = mpmath.mpf(value)
    elif isinstance(value, (str, numbers.Rational, np.integer, np.floating, Decimal)):
        exact = _exact(name, value, "a real number (int, float, Fraction, mpf or a decimal or 'a/b' string such as "
                                    "'0.5')")
        number = mpmath.mpf(mpmath.libmp.from_rational(exact.numerator, exact.denominator, mpmath.mp.prec,
                                                       mpmath.libmp.round_nearest))
    else:
        try:
            number = mpmath.mpf(value)
        except (TypeError, ValueError, OverflowError, ZeroDivisionError):
            raise ValueError(f"{name}={shown(value)}: must be a real number (int, float, Fraction, mpf or a decimal "
                             "string such as '0.5')") from None
    if not mpmath.isfinite(number):
        raise ValueError(f"{name}={shown(value)}: must be finite")
    if positive and not number > 0:
        raise ValueError(f"{name}={shown(value)}: must be > 0")
    if nonzero and number == 0:
        raise ValueError(f"{name}={shown(value)}: must be non-zero")
    return number


def rational(name: str, value, *, positive: bool = False,
             accepted: str = "a rational number (int, Fraction, float, decimal string or 'a/b')") -> Fraction:
    """An exact ``Fraction`` from an int or NumPy integer, a Fraction, a float, NumPy floating scalar or mpf (its
    exact binary value), a Decimal, or a decimal / ``'a/b'`` string; at most :data:`MAX_ENTRY_BITS` bits in
    numerator and denominator, strings measured before conversion (module docstring).  ValueError naming
    ``name`` otherwise (``accepted`` says what would do).

    >>> rational("d", "7/10"), rational("d", 0.5), rational("d", "1e-3")
    (Fraction(7, 10), Fraction(1, 2), Fraction(1, 1000))
    """
    number = _exact(name, value, accepted)
    if positive and number <= 0:
        raise ValueError(f"{name}={shown(value)}: must be > 0")
    return number


def odd_p(value, allowed, what: str) -> int:
    """An odd positive integer in ``allowed`` (integral floats such as 3.0 are accepted).

    ``what`` says which object needs odd p (it ends the message for even p).
    """
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"p={value!r}: must be an odd positive integer")
    if isinstance(value, (numbers.Integral, np.integer)):
        p = int(value)
    elif isinstance(value, (numbers.Real, mpmath.mpf)) and math.isfinite(float(value)) and float(value).is_integer():
        p = int(float(value))
    else:
        raise ValueError(f"p={shown(value)}: must be an odd positive integer ({what})")
    if p < 1 or p % 2 == 0:
        raise ValueError(f"p={shown(p)}: must be an odd positive integer ({what})")
    if p not in allowed:
        raise ValueError(f"p={shown(p)}: outside the certified range of this module (odd p <= {max(allowed)}); "
                         f"for a larger range: sf = suslov.load_formulas(pmax={shown(p)}) (built once into the per-user "
                         "store, the checkout untouched), or python build_formulas.py --pmax N --install")
    return p
