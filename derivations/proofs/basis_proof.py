"""Proof of ``gamma_basis``'s float64 error bound (issue 34; Theorem 6.1 corrected, ``eq:gam3``, ``asymp``).

``suslov.runtime.basis.gamma_basis`` computes, for one odd p and one float d in [1e-3, 1e3]:

1. *Series* (9 of them: gamma^(1)_j, Re V_j, Im V_j) ``f = sum_k alpha_k Re z^k + beta_k Im z^k`` with
   ``z = T + i S``, ``(T, S) = FLOAT.tanh_sech(t)``, the powers by repeated complex multiplication and the sums
   by one matrix product (``suslov.kernel.trig_series``).
2. *Phase*: cos and sin of ``(p/d) t`` by the double-double reduction of ``suslov.kernel.phase`` (near branch,
   ``fl(|fl(p t)/d|) < PHASE_LIMIT``), else by python-flint balls rounded to float64 (far branch).
3. *Rows*: gamma^(1) = the first three series; gamma^(2) = cphi Re V - sphi Im V; gamma^(3) = -sigma (sphi Re V +
   cphi Im V).

The proof, with every constant enclosed in python-flint balls (higher-order terms kept):

* **Coefficients.**  The float coefficients are ball midpoints of radius <= 1e-17 (``series_float``, checked at
  run time) rounded to float64 (within one ulp).  Their size: every series f is an entry of the orthonormal rows
  (|gamma^(1)_j| <= 1) or of V (|V_j|^2 = (gamma^(2)_j)^2 + (gamma^(3)_j)^2 <= 1), so |f| <= 1 on (0, pi); each
  numerator is even or odd in x = e^t (checked exactly below on the certified numerators), and x -> -x is
  th -> -th, so |f| <= 1 on the whole circle; Parseval gives sum alpha_k^2 + beta_k^2 <= 2 and
  ``sum |alpha_k| + |beta_k| <= sqrt(4p + 2)``.
* **Powers.**  tanh and sech carry the absolute errors of the walk of ``FLOAT.tanh_sech``
  (:func:`derivations.proofs.float_bounds.ErrorContext.tanh_sech`, all t by boxes); a complex product is within
  ``sqrt(2) gamma_2 |x| |y|`` of the exact one, with or without FMA (Higham 2002, Lemma 3.5), so
  ``E_k <= (1 + E_(k-1)) E_1 + E_(k-1) + sqrt(2) gamma_2 (1 + E_(k-1)) (1 + E_1)``.
* **Sums.**  A dot product of n terms in any order, with or without FMA, is within ``gamma_n sum |x_i y_i|``
  (Higham 2002, (3.5)): a reordered sum does not change the bound.
* **Near phase.**  The operation sequence of ``phase.split_quotient`` and ``phase.reduce_scalar``: q d and q t
  are exact double-doubles (Dekker 1971, Veltkamp splitting; exact when e_q + e_t >= -970, i.e. |t| >= 2^-960
  here; below, every intermediate is under 2^-900); p - fl(q d) is exact (Sterbenz); k C1 and k C2 are exact
  (C1, C2 have at most 30 significant bits, |k| <= 2^23: checked); h - k C1 is exact (both are multiples of
  ulp(h) and the difference is below 4).  The remaining roundings and the representation error of 2 pi
  (C1 + C2 + C3) give the angle error.  cos and sin come from u = tan(angle/2) (libm, 4 ulp: the angle moves by
  at most rho/(1 - rho)) and the rational functions walked on FE values over boxes of u.
* **Far phase.**  Balls of radius < 2^-70 rounded to float64: one ulp plus 2^-70.
* **Rows.**  |Re V_j| + |Im V_j| <= sqrt(2) and Cauchy-Schwarz: ``|row - exact| <= sqrt(2) e_phi +
  sqrt(2) (1 + sqrt(2) e_phi) e_V + gamma_2 (1 + e_phi) (sqrt(2) + 2 e_V)``.

The proof is of the operation sequences written here (:func:`reference_reduction`, :func:`reference_cos_sin`); the
certificate also checks, bit for bit at seeded and hard points, that the run-time code computes exactly these
sequences (a lost double-double term or a changed power recurrence fails it).  Assumption shared with the other
float proofs: libm and NumPy's tan, exp, expm1 within 4 ulp.

Cost (``bench/bench_gamma_basis_checks.py``): the parity of the numerators is read from their deflation in C
(:func:`parity_holds`, the same test: 0.14 s at p = 201 became about 0.01 s).  At p = 201 (one core) the rest is
mostly :func:`assembly_gap`: 8 ball series (4 for float64, 4 at 40 digits), each a recipe construction in balls
(about 0.1 s) and a Fourier product (55 ms), then 32 calls of ``gamma_basis_mp``: about 1.8 s of the round trip's
3.1 s ``check_gamma_basis``; the proof itself takes 0.05 s.
"""
from __future__ import annotations

import functools
import math
from fractions import Fraction

import numpy as np
from flint import arb, ctx

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.proofs.float_bounds import (
    ETA,
    FE,
    LIBM_REL,
    METHOD,
    BoundFailure,
    ErrorContext,
    U,
    _mag,
    gamma,
    largest,
)
from derivations.proofs.float_proofs import PREC, box, t_boxes

D_RANGE = (1e-3, 1e3)
SERIES_RADIUS = arb(1e-17)            # series_float: ball radius <= mpf(1e-17), the float 1e-17 (checked at run time)
FAR_RADIUS = arb(2) ** -70            # suslov.runtime.basis.FAR_RADIUS
TINY_T = arb(2) ** -960               # below it Dekker's product may underflow (e_q >= -10 on the domain)
STATED_PER_P = 1e-14                  # gamma_basis's docstring: absolute 1e-14 (p + 1)^1.5


def stated(p: int) -> float:
    return STATED_PER_P * (p + 1) ** 1.5


def significant_bits(x: float) -> int:
    mantissa, _ = Fraction(x).as_integer_ratio()
    mantissa = abs(mantissa)
    return (mantissa // (mantissa & -mantissa)).bit_length()


# ---------------------------------------------------------------- the analysed operation sequences


def reference_reduction(p: int, d: float, t: float) -> float:
    """The phase reduction as analysed, in Python floats (no FMA): split_quotient, then reduce_scalar."""
    from suslov.kernel.phase import _C1, _C2, _C3, _SPLIT

    def split(a):
        ta = _SPLIT * a
        hi = ta - (ta - a)
        return hi, a - hi

    q = p / d
    q1, q2 = split(q)
    d1, d2 = split(d)
    h = q * d
    low = ((q1 * d1 - h) + q1 * d2 + q2 * d1) + q2 * d2
    rd = ((p - h) - low) / d
    h = q * t
    t1, t2 = split(t)
    low = ((t1 * q1 - h) + q1 * t2 + q2 * t1) + t2 * q2
    low = low + rd * t
    k = float(np.rint(h * (1.0 / _C1)))
    return ((h - k * _C1) - k * _C2) + (low - k * _C3)


def reference_cos_sin(angle: float) -> tuple:
    """_cos_sin_reduced as analysed: u = tan(angle/2) (NumPy's tan), then the rational functions."""
    u = float(np.tan(np.float64(angle * 0.5)))
    u2 = u * u
    inverse = 1.0 / (u2 + 1.0)
    return (1.0 - u2) * inverse, (2.0 * u) * inverse


# ---------------------------------------------------------------- the bounds


@functools.cache
def tanh_sech_error() -> tuple:
    """Absolute error bounds of FLOAT.tanh_sech over every t (boxes of |t| to 1024; beyond, every float operation
    gives what it gives at 1024 and the exact values move by less than 4 e^-1024), and the number of boxes."""
    boxes = t_boxes(step=1 / 16)
    worst_t, worst_s = arb(0), arb(0)
    with ctx.workprec(PREC):     # cached: the same for every p
        for t in boxes:
            T, S = ErrorContext().tanh_sech(FE(t))
            worst_t, worst_s = largest(worst_t, T.e), largest(worst_s, S.e)
        tail = 4 * arb(-1024).exp()
        return worst_t + tail, worst_s + tail, len(boxes)


def power_errors(p: int, e1: arb) -> list:
    """E_k >= |z~^k - z^k| for k = 0..p (z^0 = 1 and z^1 = 1 * z are exact products)."""
    errors = [arb(0), e1]
    for _ in range(2, p + 1):
        previous = errors[-1]
        errors.append((1 + previous) * e1 + previous + arb(2).sqrt() * gamma(2) * (1 + previous) * (1 + e1))
    return errors


def series_error(p: int, powers: list) -> arb:
    """|f~ - f| for one of the nine series: coefficient errors, power errors, the dot product's rounding."""
    n = 2 * (p + 1)
    l1 = arb(4 * p + 2).sqrt()                              # Parseval (module docstring)
    e_max = largest(*powers)
    coefficients = n * SERIES_RADIUS + 2 * U * (l1 + n * SERIES_RADIUS)      # sum |c~_k - c_k|
    return coefficients * (1 + e_max) + l1 * e_max + gamma(n) * (l1 + coefficients) * (1 + e_max)


def reduction_error(p_max: int) -> arb:
    """|reduced - (phi - 2 pi k)| for every odd p <= p_max, d in D_RANGE, and t in the near branch."""
    from suslov.kernel.phase import _C1, _C2, _C3, PHASE_LIMIT

    for name, constant in (("C1", _C1), ("C2", _C2)):
        if significant_bits(constant) > 30:
            raise BoundFailure(f"{name} = {constant!r} has {significant_bits(constant)} significant bits (> 30): "
                               "k C is not exact")
    c1, c2, c3 = arb(_C1), arb(_C2), arb(_C3)
    phi = arb(PHASE_LIMIT) / (1 - U) ** 2                   # fl(fl(p t)/d) < L  =>  |p t/d| < L/(1 - u)^2
    h = phi * (1 + U) ** 2                                  # |h| = |fl(q t)|, q within u of p/d
    inverse = arb(1.0 / _C1)
    k_max = (h * inverse * (1 + U) + arb(1) / 2).upper()    # |k| <= |fl(h fl(1/C1))| + 1/2
    k = arb(math.floor(float(k_max)))
    if not k <= 2**23:
        raise BoundFailure(f"|k| may reach {k} > 2^23: k C1, k C2 are not exact")
    if not h < 2**26:
        raise BoundFailure("|h| may reach 2^26: h - k C1 is not exact")
    # |h/C1 - k| <= 1/2 + |h/C1| |1 - C1 fl(1/C1) (1 + delta)|
    h2 = c1 * (arb(1) / 2 + h / c1 * (abs(1 - c1 * inverse) + U * (1 + U)))
    if not h2 < 4:
        raise BoundFailure("|h - k C1| may reach 4")
    h3 = h2 + k * c2
    r_over_d = U * phi                                      # |r/d t| <= u |phi|
    rd_t = r_over_d * ((1 + U) ** 2 * (1 + U) - 1) + U * r_over_d * (1 + U) ** 2 + ETA   # fl(rd t) - (r/d) t
    low0 = U * h                                           # Dekker's low part: at most half an ulp of h
    low1 = (low0 + r_over_d * (1 + U) ** 3 + ETA) * (1 + U)
    kc3 = k * c3
    low2 = (low1 + kc3 * (1 + U)) * (1 + U)
    total = (U * h3 + rd_t + U * low1 + U * kc3 + U * low2 + U * (h3 + low2) * (1 + U)
             + k * abs(2 * arb.pi() - c1 - c2 - c3))
    # |t| < 2^-960: k = 0 and every intermediate is at most 16 |q t| + 16 ETA; the phase itself is below |q t| (1 + u)
    q_max = arb(p_max) / arb(D_RANGE[0]) * (1 + U)
    tiny = 32 * q_max * TINY_T + 32 * ETA
    return largest(total, tiny)


def u_boxes() -> list:
    """|u| = |tan(angle/2)| in [0, 2^55] (|angle/2| <= pi/2 + 0.03, a float: |tan| < 2^54): steps of 1/64 to 1, then
    eighths of binades; the rational functions are even (cos) and odd (sin) in u with the same roundings."""
    boxes = [box(i / 64, (i + 1) / 64) for i in range(64)]
    for k in range(55):
        boxes += [box(2.0**k * (1 + j / 8), 2.0**k * (1 + (j + 1) / 8)) for j in range(8)]
    return boxes


@functools.cache
def rational_error() -> tuple:
    """(rounding of the rational functions cos = (1 - u^2)/(1 + u^2), sin = 2u/(1 + u^2) by FE over the u boxes,
    boxes); the same for every p, so cached."""
    worst = arb(0)
    boxes = u_boxes()
    with ctx.workprec(PREC):
        for u in boxes:
            x = FE(u, 0, 0, 0)
            u2 = x * x
            inverse = 1.0 / (u2 + 1.0)
            c, s = (1.0 - u2) * inverse, (2.0 * x) * inverse
            worst = largest(worst, c.e, s.e)
    return worst, len(boxes)


def cos_sin_error(angle_error: arb, libm_rel: arb = LIBM_REL) -> tuple:
    """(bound on |c~ - cos phi| and |s~ - sin phi|, boxes): the angle error, tan's rounding rho moving the angle by
    at most rho/(1 - rho) (plus 2 ETA where tan(a/2) is subnormal), the rational functions' rounding."""
    worst, boxes = rational_error()
    return angle_error + libm_rel / (1 - libm_rel) + 2 * ETA + worst, boxes


def rows_error(phase: arb, series: arb) -> arb:
    """|c~ R~ - s~ I~ - (c R - s I)| <= |c~ - c| |R| + |s~ - s| |I| + |c~ (R~ - R) - s~ (I~ - I)| + rounding, with
    |R| + |I| <= sqrt(2) and (Cauchy-Schwarz) |c~ a - s~ b| <= sqrt(c~^2 + s~^2) sqrt(a^2 + b^2)."""
    two = arb(2).sqrt()
    return two * phase + two * (1 + two * phase) * series + gamma(2) * (1 + phase) * (two + 2 * series)


def prove(p: int) -> dict:
    """Bounds (arb) for the near and far branches of gamma_basis at this p, with the boxes walked."""
    with ctx.workprec(PREC):
        e_t, e_s, t_count = tanh_sech_error()
        powers = power_errors(p, (e_t * e_t + e_s * e_s).sqrt())
        series = series_error(p, powers)
        near_phase, u_count = cos_sin_error(reduction_error(p))
        far_phase = 2 * U + FAR_RADIUS
        near = largest(series, rows_error(near_phase, series))
        far = largest(series, rows_error(far_phase, series))
        return {"near": near, "far": far, "boxes": t_count + u_count, "series": series}


# ---------------------------------------------------------------- the checks tying the proof to the run-time code


def parity_holds(numerators) -> bool:
    """Every certified numerator (real and complex solution, three components each) is even or odd in x.

    For a python-flint polynomial, from its deflation (C): the exponents of x are all of one parity exactly when
    the gcd of their differences from the least (the stride N[0] of ``deflation_index``, 0 for a single exponent)
    is even.  The same test as collecting every monomial's parity in Python (kept for other polynomials), which
    took 0.14 s at p = 201 (six numerators, 300,000 monomials)."""
    real, cplx = numerators
    for poly in list(real) + list(cplx):
        if hasattr(poly, "deflation_index"):
            if not poly.is_zero() and poly.deflation_index()[0][0] % 2:
                return False
            continue
        parities = {monomial[0] % 2 for monomial in poly.monoms()}
        if len(parities) > 1:
            return False
    return True


HARD_T = (0.0, 5e-324, -1e-310, 2.0**-961, 1e-300, -1e-8, 0.3, -2.2, 30.0, -700.0, 1e4, -3.3e5, 7.77e6)


def _points(p: int) -> list:
    rng = np.random.default_rng(3400 + p)
    from suslov.kernel.phase import PHASE_LIMIT

    points = []
    for d in (1e-3, 0.5, 1.0, 3.7, 1e3, float(10 ** rng.uniform(-3, 3))):
        ts = list(HARD_T) + list(rng.uniform(-1, 1, 40) * PHASE_LIMIT * d / p) + list(rng.normal(0, 20, 40))
        ts += [PHASE_LIMIT * d / p * (1 - 1e-15), -PHASE_LIMIT * d / p * (1 - 1e-15)]
        points += [(d, float(t)) for t in ts]
    return points


def same_operations(module, p: int) -> tuple:
    """(ok, points): the run-time phase and series code computes the analysed sequences bit for bit."""
    from suslov.kernel import phase, trig_series
    from suslov.kernel.contexts import FLOAT

    points = _points(p)
    ok = True
    for d in sorted({d for d, _ in points}):
        ts = np.array([t for dd, t in points if dd == d])
        near = np.abs(p * ts / d) < phase.PHASE_LIMIT
        q, rd = phase.split_quotient(np.asarray(float(p)), np.asarray(d))
        reduced = phase.reduce_scalar(float(q), float(rd), ts[near])
        expected = np.array([reference_reduction(p, d, t) for t in ts[near]])
        ok &= np.array_equal(reduced, expected)
        cos_, sin_ = phase.phase_cos_sin(p, d, ts[near])
        pairs = np.array([reference_cos_sin(a) for a in expected]).reshape(-1, 2)
        ok &= np.array_equal(cos_, pairs[:, 0]) and np.array_equal(sin_, pairs[:, 1])
        # powers by repeated multiplication: the identity coefficient matrix returns [Re z^k; Im z^k] exactly
        T, S = FLOAT.tanh_sech(ts)
        table = trig_series.evaluate(T, S, np.eye(2 * (p + 1)))
        z = T + 1j * S
        powers = table[:p + 1] + 1j * table[p + 1:]
        ok &= np.array_equal(powers[0], np.ones(ts.size)) and np.array_equal(powers[1], z)
        ok &= all(np.array_equal(powers[k], powers[k - 1] * z) for k in range(2, p + 1))
    return bool(ok), len(points)


def far_phase_ok(p: int) -> bool:
    """careful_phase's values are within one ulp plus 2^-70 of the exact cos, sin (balls at 300 bits + size)."""
    from flint import fmpq

    from suslov.runtime.basis import careful_phase

    t = np.array([1e5, -3.3e6, 2.9e7, -1e9, 3e10, 1e300])
    c, s = careful_phase(p, 1e-3, t)
    with ctx.workprec(1400):
        for tv, cv, sv in zip(t, c, s):
            angle = arb(fmpq(p) * fmpq(*Fraction(float(tv)).as_integer_ratio()) / fmpq(*Fraction(1e-3).as_integer_ratio()))
            for value, exact in ((cv, angle.cos()), (sv, angle.sin())):
                if not abs(arb(value) - exact) <= 2 * U * _mag(exact) + FAR_RADIUS:
                    return False
    return True


def assembly_gap(module, p: int, bounds: dict) -> tuple:
    """(worst |float - twin| / proven bound, points): the rows as assembled (series columns, phase, sigma) against
    gamma_basis_mp at 40 digits, near and far.  Not part of the proof (which is of the rounding, given the
    formula): a check that the run-time code assembles the formula whose rounding was bounded."""
    import mpmath

    from suslov.kernel.phase import PHASE_LIMIT

    worst, points = 0.0, 0
    for d in (0.5, 1e-3, 1e3, 2.75):
        ts = [0.0, -1e-8, 2.2, -30.0, 0.61, 1e4, 3e-3 * PHASE_LIMIT * d / p, -1.7 * PHASE_LIMIT * d / p]
        values = module.gamma_basis(np.array(ts), p, d)
        for row, t in zip(values, ts):
            twin = module.gamma_basis_mp(t, p, d, dps=40)
            bound = bounds["far" if abs(p * t / d) >= PHASE_LIMIT else "near"]
            with mpmath.workdps(40):
                gap = max(abs(mpmath.mpf(float(row[i][j])) - twin[i, j]) for i in range(3) for j in range(3))
            worst = max(worst, float(gap / mpmath.mpf(float(bound.upper()))))
            points += 1
    return worst, points


def certificates(log: CertificateLog, module, p: int, numerators) -> list:
    """Two certificates for this p: the near branch (double-double phase) and the far one (ball phase)."""
    certs = []
    bound = stated(p)
    with stopwatch() as elapsed:
        try:
            proof = prove(p)
            parity = numerators is not None and parity_holds(numerators)
            same, points = same_operations(module, p)
            far_ok = far_phase_ok(p)
            assembly, assembled_points = assembly_gap(module, p, proof)
            failure = None
        except BoundFailure as error:
            failure, proof = str(error), None
    domain = "$d$ from $10^(-3)$ to $10^3$, every $t$"
    for branch, where in (("near", "abs(p t/d) < 5.3e7"), ("far", "abs(p t/d) >= 5.3e7")):
        claim = (f"$p = {p}$: `gamma_basis` ({'double-double' if branch == 'near' else 'ball'} phase, ${where}$) `float64` "
                 f"within absolute $1e-14 (p + 1)^1.5$ of the exact rows")
        if failure is not None:
            ok, detail, boxes = False, f"no bound: {failure}", 0
        else:
            value = proof[branch]
            ok = (bool(value.upper() <= bound) and parity and same and (branch == "near" or far_ok)
                  and assembly <= 1)
            in_u = math.ceil(float((value / U).upper()))
            detail = (f"proven ${in_u} u = {float(value.upper()):.3g}$ (at most ${bound:.3g}$); numerators even or odd "
                      f"in $x$ (exact): {'yes' if parity else 'no'}; run-time operations as analysed, bit for bit at "
                      f"{points} points: {'yes' if same else 'no'}")
            if branch == "far":
                detail += f"; ball phase within one ulp plus $2^(-70)$ at 6 points: {'yes' if far_ok else 'no'}"
            detail += (f"; rows as assembled within the proven bound of `gamma_basis_mp` at {assembled_points} points: "
                       f"{'yes' if assembly <= 1 else 'no'}")
            boxes = proof["boxes"]
        method = METHOD.format(n=boxes) + (f" (domain: {domain}; Dekker's product, Sterbenz's lemma, Higham's bounds "
                                           "for complex products and dot products in any order; `libm` calls within 4 "
                                           "ulp; coefficients by Parseval from the orthonormal rows)")
        certs.append(log.record(Certificate(claim, "round trip", method, Outcome.PASS if ok else Outcome.FAIL,
                                            elapsed[0] / 2, boxes, detail)))
    return certs
