"""No silent non-finite output from finite input (issue 38): repair in mpmath, or refuse naming the arguments.

The float64 paths are scale-covariant where the formula allows it (``suslov.runtime.angular``,
``general_angle``); what is left are entries whose intermediate quantities leave float64's exponent
range although the answer may not (``p/d = 1e397`` times ``tanh t = 1e-300``; an inertia tensor whose
entries span 1e-300..1e300, whose scaled products underflow to 0/0).  :func:`repair` re-evaluates
exactly those entries with the same emitted formula in mpmath, whose exponent range is unbounded,
at 30 digits (the float result needs 17), and stores the rounded value; a value beyond float64's range
is refused with a ``ValueError`` that names the function, the arguments and their values, and the
``_mp`` twin that returns it.  Finite entries are untouched, so the common path costs one
``isfinite`` pass.  No SymPy.
"""
from __future__ import annotations

import sys

import mpmath
import numpy as np

__all__ = ["repair", "FLOAT_MAX", "REPAIR_DPS"]

FLOAT_MAX = sys.float_info.max
REPAIR_DPS = 30


def _show(names, values) -> str:
    return ", ".join(f"{n}={float(v)!r}" for n, v in zip(names, values))


def repair(function: str, outputs: tuple, names: tuple, arrays: tuple, evaluate) -> tuple:
    """``outputs`` (float arrays of one broadcast shape) with every non-finite entry re-evaluated.

    ``arrays`` are the (broadcastable) inputs named ``names``; ``evaluate(*mpf_values)`` returns the
    outputs at one point as mpmath numbers (it runs at :data:`REPAIR_DPS` digits).  Raises
    ``ValueError`` naming ``function``, the arguments and their values when a true value is beyond
    float64 (or the formula has no value there).
    """
    outputs = tuple(np.array(o, dtype=float) for o in outputs)
    bad = np.zeros(outputs[0].shape, dtype=bool)
    for o in outputs:
        bad |= ~np.isfinite(o)
    if not bad.any():
        return outputs
    inputs = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in arrays), outputs[0])[:-1]
    for index in map(tuple, np.argwhere(bad)):
        point = [a[index] for a in inputs]
        with mpmath.workdps(REPAIR_DPS):
            values = evaluate(*(mpmath.mpf(float(x)) for x in point))
            for k, (o, v) in enumerate(zip(outputs, values)):
                if not mpmath.isfinite(v) or abs(v) > FLOAT_MAX:
                    where = f" at index {list(index)}" if index else ""
                    raise ValueError(f"{function}({_show(names, point)}){where}: output {k + 1} is "
                                     f"{mpmath.nstr(v, 3)}, beyond float64's range (max {FLOAT_MAX:.3g}); "
                                     f"{function}_mp returns it")
                o[index] = float(v)
    return outputs
