"""Numeric inertia tensors: the paper's frame, the special case I13 = 0, Kovalevskaya exponents, meromorphy.

Sections 2, 3.1 and Theorem 3.2 (corrected).  ``canonical_frame`` (``suslov.kernel.frames``) validates
the tensor, scales it to entries of order 1 (every answer is scale-invariant) and rotates about
a = e3 to I12 = 0, I11 >= I22, det I = 1.  The formulas are the generated module's emitted
``_special_parameters``, ``_lambda_squared``, ``_p_squared_i13_zero`` and ``_p_squared_i23_zero``, passed in.
"""
from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from suslov.kernel.contexts import FLOAT
from suslov.kernel.frames import canonical_frame, rotation_about_e3
from suslov.kernel.validate import real_scalar

__all__ = ["SpecialCase", "Meromorphy", "special_case_parameters", "kovalevskaya_exponents", "meromorphy"]


class SpecialCase(NamedTuple):
    """(p, d, frame) of a body with I13 = 0; see the generated ``special_case_parameters``."""

    p: float
    d: float
    frame: np.ndarray


class Meromorphy(NamedTuple):
    """(case, p_squared, p, odd); see the generated ``meromorphy``."""

    case: str
    p_squared: float | complex
    p: float | None
    odd: bool


def special_case_parameters(special_parameters, I, tol) -> SpecialCase:
    tol = real_scalar("tol", tol, positive=True)
    R, (I11, I22, I13, I23) = canonical_frame(I)
    size = max(abs(I11), abs(I22), abs(I13), abs(I23))
    if abs(I13) > tol * size:
        raise ValueError(f"I13 = {I13:.6g} in the paper's frame (I12 = 0, I11 >= I22): not the case I13 = 0")
    if I11 - I22 <= tol * size:
        raise ValueError("I11 = I22 in the paper's frame: d = 0, the special case needs I11 > I22")
    if I23 > 0:  # turning by pi about e3 flips I13 and I23
        R, I23 = R @ rotation_about_e3(math.pi), -I23
    p, d = special_parameters(FLOAT, I11, I22, I23)
    return SpecialCase(float(p), float(d), R)


def kovalevskaya_exponents(lambda_squared, I) -> np.ndarray:
    re, im = lambda_squared(FLOAT, *canonical_frame(I)[1])
    lam = np.sqrt(complex(re, im))
    return np.array([-1, 1, 2, 1 + lam, 1 - lam], dtype=complex)


def meromorphy(lambda_squared, p_squared_i13_zero, p_squared_i23_zero, I, tol) -> Meromorphy:
    tol = real_scalar("tol", tol, positive=True)
    I11, I22, I13, I23 = canonical_frame(I)[1]
    size = max(abs(I11), abs(I22), abs(I13), abs(I23))
    if abs(I13) <= tol * size:
        case, p2 = "I13=0", float(p_squared_i13_zero(FLOAT, I11, I22, I23))
    elif abs(I23) <= tol * size:
        case, p2 = "I23=0", float(p_squared_i23_zero(FLOAT, I11, I22, I13))
    else:
        case, p2 = "neither", complex(*lambda_squared(FLOAT, I11, I22, I13, I23))
    p = math.sqrt(p2) if isinstance(p2, float) and p2 >= 0 else None
    odd = p is not None and abs(p - round(p)) <= tol * max(1.0, p) and round(p) % 2 == 1
    return Meromorphy(case, p2, p, odd)
