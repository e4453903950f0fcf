"""gamma(t) of every body from Gauss's 2F1 in float64, vectorised: the twin of :mod:`suslov.kernel.gauss_gamma_mp`.

The closed form is that module's (public routine: :func:`suslov.kernel.gauss_gamma.gamma_gauss`):
``S(gamma) = Phi X0 Phi^-1`` with the unitary fundamental matrix ``Phi`` built from the basis at infinity
``g_e(w) = 2F1(.; w)``, ``w = 1/z``, ``z = (1 + i sinh t)/2``.  Here its functions are evaluated by their convergent
series, per body once (``mpmath`` at ``PRE_DPS + GUARD_DIGITS`` digits), then at every sample in float64:

* **far** (``|w| <= r``, i.e. ``|t| >= acosh(2/r)``): the hypergeometric series of ``g_A``, ``g_B`` and their
  derivatives in w (coefficients from the 2F1 ratio, summed by Horner over all samples at once), with ``log z =
  log(cosh t/2) + i gd(t)`` and ``w = 2 sech t (sech t - i tanh t)`` (no overflow at any t), the column norms and
  the join matrix from mpmath.  ``r <= R_FAR``, smaller when the series' terms would exceed ``GROWTH`` (large U).
* **middle** (``|t| < acosh(2/r)``): Phi is the closed form; near a centre ``c`` (in s) it is its own Taylor
  series, ``Phi(s) = sum Phi_n (s - c)^n``, with ``Phi_0 = Phi(c)`` evaluated by the closed form in mpmath
  (``mpmath.hyp2f1``, or the series at z = 1/2 near s = 0) and ``Phi_(n+1)`` from the equation Phi satisfies,
  ``(1 + s^2) Phi' = (i/2) [[U s + v1, v2], [v2, -(U s + v1)]] Phi``:
  ``(1+c^2)(n+1) Phi_(n+1) = (i/2)(K0 Phi_n + K1 Phi_(n-1)) - 2c n Phi_n - (n-1) Phi_(n-1)``.  Every centre starts
  from the closed form, none from another centre: nothing is propagated, so no error accumulates.  The centres
  are placed by bisection in t until each covers ``|s - c| <= h`` with ``h <= RHO sqrt(1 + c^2)`` (half the
  distance to the poles s = +-i), ``sum |Phi_n| h^n <= GROWTH`` and a tail below ``TAIL``.

Accuracy (measured; ``bench/results/gauss_gamma.md``, ``tests/test_gauss_gamma.py``): about 1e-15 absolute for the
bodies of the paper's figures and the tests; the float64 rounding grows with ``GROWTH`` (at most a factor 30).
:func:`solve` checks every run: ``| |gamma| - |gamma0| |`` on all samples, the float values against the mpmath
closed form at a few samples, and the residual ``|gamma' - gamma x omega|`` of the closed form there (central
difference at ``PRE_DPS + GUARD_DIGITS`` digits).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import mpmath
import numpy as np

from suslov.kernel.gauss_gamma_mp import GUARD_DIGITS, Cancellation, GaussGamma

__all__ = ["PRE_DPS", "FloatForm", "GaussSolution", "solve"]

PRE_DPS = 20        # digits of the per-body precomputation (working: PRE_DPS + GUARD_DIGITS)
RHO = 0.5           # a centre covers |s - c| <= RHO sqrt(1 + c^2) at most (the series converges to 1)
R_FAR = 0.5         # the far series is used for |w| <= R_FAR at most
GROWTH = 30.0       # sum |coefficient| h^n allowed in a float64 series
TAIL = 1e-18        # relative size of the last terms kept
MAX_TERMS = 400
MAX_DEPTH = 40      # bisection depth of the centres


def _c(x) -> complex:
    return complex(x)


def _matrix(M) -> np.ndarray:
    return np.array([[_c(M[0, 0]), _c(M[0, 1])], [_c(M[1, 0]), _c(M[1, 1])]])


def _horner(coeffs: np.ndarray, x: np.ndarray) -> np.ndarray:
    """sum coeffs[n] x^n for arrays x; coeffs of shape (N,) + extra, result x.shape + extra."""
    out = np.zeros(x.shape + coeffs.shape[1:], dtype=complex)
    xx = x.reshape(x.shape + (1,) * (coeffs.ndim - 1))
    for c in coeffs[::-1]:
        out = out * xx + c
    return out


@dataclass
class _Centre:
    t_lo: float
    t_hi: float
    c: float                    # the centre in s
    coeffs: np.ndarray          # (N, 2, 2)


@dataclass
class FloatForm:
    """The per-body data of the float64 evaluation (module docstring)."""

    form: GaussGamma
    r_far: float
    t_far: float
    far: dict                   # e -> (g coefficients, g' coefficients)
    log_norms: dict             # (side, e) -> log of the column norm
    plus: np.ndarray            # Phi = G_+ @ plus on the far right
    centres: list = field(default_factory=list)
    constants: dict = field(default_factory=dict)

    @classmethod
    def build(cls, u, v, t_min: float, t_max: float) -> FloatForm:
        work = PRE_DPS + GUARD_DIGITS
        for _ in range(4):   # more working digits when the series at z = 1/2 reports cancellation beyond the guard
            try:
                return cls._build(u, v, t_min, t_max, work)
            except Cancellation as error:
                work = PRE_DPS + GUARD_DIGITS + math.ceil(error.digits) + 5
        raise ArithmeticError(f"the closed form needs more than {work} working digits for this body")

    @classmethod
    def _build(cls, u, v, t_min: float, t_max: float, work: int) -> FloatForm:
        with mpmath.workdps(work):
            form = GaussGamma(u, v, work, PRE_DPS)
            far, r = _far_series(form)
            t_far = math.acosh(2.0 / r)
            plus = _matrix(form.joins()[1])
            log_norms = form.log_norms
            i = 1j
            A, B, kappa, mu = (_c(x) for x in (form.A, form.B, form.kappa, form.mu))
            U, v1, v2 = float(form.U), float(form.v1), float(form.v2)
            constants = {"A": A, "B": B, "kappa": kappa, "mu": mu, "U": U, "v1": v1, "v2": v2,
                         "c0": {e: 2 * kappa - i * U - v1 - 4 * x for e, x in (("A", A), ("B", B))}}
            self = cls(form, r, t_far, far, {k: float(x) for k, x in log_norms.items()}, plus, [], constants)
            lo, hi = max(t_min, -t_far), min(t_max, t_far)
            a = math.asinh(RHO)          # a centre at s = 0 (Phi(0) is the join matrix, free) covers |s| <= RHO
            if lo < a and hi > -a:
                self.centres = ((self._cover(lo, -a, 0) if lo < -a else []) + self._centre_at_zero(a)
                                + (self._cover(a, hi, 0) if hi > a else []))
            elif lo <= hi:
                self.centres = self._cover(lo, hi, 0)
        return self

    def _centre_at_zero(self, a: float) -> list:
        coeffs = _taylor(self.form, 0.0, RHO)
        return [_Centre(-a, a, 0.0, coeffs)] if coeffs is not None else self._cover(-a, a, 1)

    def _cover(self, a: float, b: float, depth: int) -> list:
        sa, sb = math.sinh(a), math.sinh(b)
        c, h = (sa + sb) / 2, (sb - sa) / 2
        if h <= RHO * math.sqrt(1 + c * c):
            coeffs = _taylor(self.form, c, h)
            if coeffs is not None:
                return [_Centre(a, b, c, coeffs)]
        if depth >= MAX_DEPTH:
            raise ArithmeticError(f"no convergent Taylor series of the closed form about s = {c:.6g} within "
                                  f"{MAX_DEPTH} bisections (|omega| too large for float64 here)")
        m = (a + b) / 2
        return self._cover(a, m, depth + 1) + self._cover(m, b, depth + 1)

    # ------------------------------------------------------------------ evaluation
    def _far(self, t: np.ndarray, side: int) -> np.ndarray:
        k = self.constants
        a = np.abs(t)
        log_z = (a + np.log1p(np.exp(-2 * a)) - 2 * math.log(2.0)) + 1j * (2 * np.arctan(np.tanh(t / 2)))
        sech, tanh = 1 / np.cosh(np.minimum(a, 700.0)) * (a < 700), np.tanh(t)
        w = 2 * sech * (sech - 1j * tanh)
        cols = {}
        for e in ("B", "A"):
            g_c, gp_c = self.far[e]
            g, gp = _horner(g_c, w), _horner(gp_c, w)
            L = k["kappa"] / 2 * log_z + k["mu"] / 2 * np.conj(log_z) - k[e] * log_z - self.log_norms[(side, e)]
            E = np.exp(L)
            psi1 = E * g
            psi2 = E * (-4 * (w - 1) * gp + k["c0"][e] * g) / k["v2"]
            if e == "A":
                psi2 = psi2 + 4 * (k["A"] - k["B"]) * np.exp(L + log_z) * g / k["v2"]
            cols[e] = (psi1, psi2)
        G = np.empty(t.shape + (2, 2), dtype=complex)
        G[..., 0, 0], G[..., 1, 0] = cols["B"]
        G[..., 0, 1], G[..., 1, 1] = cols["A"]
        return G if side < 0 else G @ self.plus

    def phi(self, t) -> np.ndarray:
        """Phi at rate-1 times t (float64 array), shape t.shape + (2, 2)."""
        t = np.asarray(t, dtype=float)
        out = np.full(t.shape + (2, 2), np.nan, dtype=complex)
        left, right = t <= -self.t_far, t >= self.t_far
        if left.any():
            out[left] = self._far(t[left], -1)
        if right.any():
            out[right] = self._far(t[right], 1)
        for centre in self.centres:
            inside = (t >= centre.t_lo) & (t <= centre.t_hi) & ~left & ~right
            if inside.any():
                out[inside] = _horner(centre.coeffs, np.sinh(t[inside]) - centre.c)
        if not np.all(np.isfinite(out)):
            missing = t[~np.all(np.isfinite(out), axis=(-2, -1))]
            raise ArithmeticError(f"Phi not covered or not finite at t = {missing[:3]} (rate-1 time)")
        return out

    def rotate(self, g: np.ndarray) -> np.ndarray:
        """Vectors (..., 3) of the rotated frame (u = (U, 0, 0)) in the paper frame."""
        e1, e2 = (np.array([float(x) for x in e]) for e in (self.form.e1, self.form.e2))
        return np.stack([g[..., 0] * e1[0] + g[..., 1] * e2[0], g[..., 0] * e1[1] + g[..., 1] * e2[1], g[..., 2]],
                        axis=-1)


def _far_series(form: GaussGamma) -> tuple:
    """({e: (g coefficients, g' coefficients)}, r): the 2F1 series in w of g_A, g_B, cut where their terms fall
    below TAIL at |w| = r, r <= R_FAR shrunk until the terms' sum stays below GROWTH."""
    A, B, C = form.A, form.B, form.C
    params = {"A": (A, A - C + 1, A - B + 1), "B": (B, B - C + 1, B - A + 1)}
    r = R_FAR
    for _ in range(60):
        out, ok = {}, True
        for e, (a, b, c) in params.items():
            coeffs, term, n, small = [mpmath.mpc(1)], mpmath.mpc(1), 0, 0
            while small < 2 and n < MAX_TERMS:
                term = term * (a + n) * (b + n) / ((c + n) * (n + 1))
                n += 1
                coeffs.append(term)
                small = small + 1 if abs(term) * r ** n < TAIL else 0
            g = np.array([_c(x) for x in coeffs])
            gp = np.array([n * g[n] for n in range(1, len(g))] + [0j])
            powers = r ** np.arange(len(g))
            # cancellation in the sums, relative to their leading terms 1 and g'(0) = ab/c
            spread = max(np.sum(np.abs(g) * powers), np.sum(np.abs(gp) * powers) / max(abs(gp[0]), 1.0))
            if small < 2 or spread > GROWTH:
                ok = False
                break
            out[e] = (g, gp)
        if ok:
            return out, r
        r *= 0.7
    raise ArithmeticError(f"no usable series at infinity for |w| >= {r:.3g} (|omega| too large for float64)")


def _taylor(form: GaussGamma, c: float, h: float):
    """The Taylor coefficients (N, 2, 2) of Phi about s = c, usable for |s - c| <= h, or None (module docstring).

    ``Phi(c)`` is the closed form in mpmath; the recurrence runs in complex128 (its terms are bounded by GROWTH)."""
    P0 = _matrix(form.phi(mpmath.asinh(mpmath.mpf(c))))
    U, v1, v2 = float(form.U), float(form.v1), float(form.v2)
    K0 = 0.5j * np.array([[U * c + v1, v2], [v2, -(U * c + v1)]])
    K1 = 0.5j * np.array([[U, 0.0], [0.0, -U]])
    q0 = 1 + c * c
    coeffs, prev, cur, small, total, power = [P0], np.zeros((2, 2), dtype=complex), P0, 0, 0.0, 1.0
    for n in range(MAX_TERMS):
        nxt = (K0 @ cur + K1 @ prev - 2 * c * n * cur - (n - 1) * prev) / (q0 * (n + 1))
        coeffs.append(nxt)
        power *= h
        size = float(np.max(np.abs(nxt))) * power
        total += size
        if total > GROWTH or not math.isfinite(total):
            return None
        small = small + 1 if size < TAIL else 0
        if small >= 2:
            return np.array(coeffs)
        prev, cur = cur, nxt
    return None


@dataclass
class GaussSolution:
    """Samples ``values`` (n, k, 3), paper frame, and what the run checked (:func:`solve`)."""

    t: np.ndarray
    values: np.ndarray
    norm_drift: float
    checks: dict
    pieces: dict

    def summary(self) -> dict:
        return {"norm_drift": self.norm_drift, **self.checks, **self.pieces}


def _omega(form, t):
    """omega at rate-1 time t (mpmath), rotated frame: (U tanh t + v1 sech t, v2 sech t, 0)."""
    th, sh = mpmath.tanh(t), mpmath.sech(t)
    return form.U * th + form.v1 * sh, form.v2 * sh, 0


def _check_points(t: np.ndarray, t_far: float, count: int) -> list:
    """Up to ``count`` sample indices: one in each piece present (far left, middle at 80 %: past the join at s = 0.6
    for a window symmetric about 0, far right), then the last."""
    picks = []
    for mask, at in ((t <= -t_far, 0.5), (np.abs(t) < t_far, 0.8), (t >= t_far, 0.5)):
        idx = np.flatnonzero(mask)
        if idx.size:
            picks.append(int(idx[int(at * (idx.size - 1))]))
    picks.append(len(t) - 1)
    return list(dict.fromkeys(picks))[:count]


def solve(u, v, t, initial="ss", t0=None, checks: int = 3) -> GaussSolution:
    """gamma at rate-1 times ``t`` (1-d float array) for ``omega = u tanh t + v sech t`` (paper frame).

    ``initial``: "ss" (``gamma(-oo) = -u/|u|``), a vector gamma0 (3,) or several (k, 3), holding at ``t0``
    (default ``t[0]``).  Returns :class:`GaussSolution` with ``values`` (n, k, 3); ``checks`` holds the largest
    difference to the mpmath closed form at ``checks`` samples (``mp_check``), the ODE residual of the closed form
    there (``ode_residual``), the initial error (``|gamma(t0) - gamma0|``, or for ss ``|gamma(-40) + u/|u||``).
    Raises ``ArithmeticError`` when the body is beyond what float64 series can evaluate (very large |omega|).
    """
    t = np.asarray(t, dtype=float)
    if t.ndim != 1 or t.size == 0 or not np.all(np.isfinite(t)):
        raise ValueError(f"t: need a 1-d array of finite times, got shape {t.shape}")
    ss = isinstance(initial, str)
    t0 = float(t[0] if t0 is None else t0)
    ff = FloatForm.build(u, v, float(min(t.min(), t0)), float(max(t.max(), t0)))
    form = ff.form
    with mpmath.workdps(form.dps):
        if ss:
            starts = [form.start(None)]
            initial = np.array([[-1.0, 0.0, 0.0]])   # its norm
        else:
            initial = np.atleast_2d(np.asarray(initial, dtype=float))
            starts = [form.start(g, mpmath.mpf(t0)) for g in initial]
    values = _gammas(ff, ff.phi(t), starts)
    drift = float(np.max(np.abs(np.linalg.norm(values, axis=-1) - np.linalg.norm(initial, axis=-1)[None, :])))
    out = _verify(ff, t, values, starts, count=checks)
    if ss:
        out["initial_check"] = "|gamma(-40) + u/|u|| by the mpmath closed form (ss: gamma -> -u/|u| as t -> -oo)"
    else:
        out["initial_error"] = float(np.max(np.abs(_gammas(ff, ff.phi(np.array([t0])), starts)[0] - initial)))
        out["initial_check"] = "|gamma(t0) - gamma0| (float64 evaluation at t0)"
    pieces = {"far_series_radius": ff.r_far, "far_series_from_abs_lam_t": ff.t_far, "taylor_centres": len(ff.centres)}
    return GaussSolution(t, values, drift, out, pieces)


def _gammas(ff: FloatForm, P: np.ndarray, starts) -> np.ndarray:
    """gamma (n, k, 3), paper frame, from Phi (n, 2, 2) and the k matrices X0."""
    det = P[..., 0, 0] * P[..., 1, 1] - P[..., 0, 1] * P[..., 1, 0]
    inv = np.stack([np.stack([P[..., 1, 1], -P[..., 0, 1]], -1), np.stack([-P[..., 1, 0], P[..., 0, 0]], -1)], -2)
    inv = inv / det[..., None, None]
    values = []
    for X0 in starts:
        S = P @ _matrix(X0) @ inv
        g = np.stack([(2j * S[..., 0, 0]).real, (1j * (S[..., 0, 1] + S[..., 1, 0])).real,
                      (S[..., 1, 0] - S[..., 0, 1]).real], axis=-1)
        values.append(ff.rotate(g))
    return np.stack(values, axis=1)


def _verify(ff: FloatForm, t, values, starts, count) -> dict:
    """The float values against the mpmath closed form at ``count`` samples, and the closed form's ODE residual
    ``max |gamma' - gamma x omega|`` there (central difference at the working precision, step 10^-(digits/3));
    for ss also ``initial_error = |gamma(-40) + u/|u||``."""
    form = ff.form
    idx = _check_points(t, ff.t_far, count)
    worst, residual = 0.0, 0.0
    with mpmath.workdps(form.dps):
        h = mpmath.mpf(10) ** (-(form.dps // 3)) / (1 + form.U + abs(form.v1) + abs(form.v2))
        for j in idx:
            tj = mpmath.mpf(float(t[j]))
            for k, X0 in enumerate(starts):
                g = form.gamma(tj, X0)
                worst = max(worst, max(abs(float(a) - float(b)) for a, b in zip(g, values[j, k])))
                if k == 0:
                    plus, minus = form.gamma(tj + h, X0), form.gamma(tj - h, X0)
                    w_rot = _omega(form, tj)
                    w = form.to_paper((w_rot[0], w_rot[1], 0))
                    cross = (g[1] * w[2] - g[2] * w[1], g[2] * w[0] - g[0] * w[2], g[0] * w[1] - g[1] * w[0])
                    slopes = ((a - b) / (2 * h) for a, b in zip(plus, minus))
                    residual = max(residual, max(float(abs(d - c)) for d, c in zip(slopes, cross)))
        out = {"mp_check": {"samples_lam_t": [float(t[j]) for j in idx], "max_abs_difference": worst,
                            "digits": PRE_DPS},
               "ode_residual": residual}
        if starts and len(starts) == 1 and starts[0][0, 1] == 0 and starts[0][1, 0] == 0:   # the ss start
            g = form.gamma(mpmath.mpf(-40), starts[0])
            out["initial_error"] = float(max(abs(g[0] + form.e1[0]), abs(g[1] + form.e1[1]), abs(g[2])))
    return out
