"""A Suslov body and its angular velocity, from the certified closed forms (paper sections 2 and 4).

A body is an inertia tensor with the constraint axis ``a = e3`` (``omega3 = 0``),
or the parameters ``p, d`` of the case ``I13 = 0`` (``eq:necc1`` corrected,
``eq:cpr``).  Everything is computed in the *paper's frame* (rotation about e3
with ``I12 = 0``, ``I11 >= I22``; in the case ``I13 = 0`` also ``I23 < 0``, so that
``p > 0``) and reported in the scene's frame.

The angular velocity is always a closed form (``eq:o12`` / ``omegas``, derived
and certified by the build): in the paper's frame
``omega(t) = lam (u tanh(lam t) + v sech(lam t))`` with the rate ``lam`` fixed by
the energy; ``t = 0`` is the instant at which omega crosses the line through the
two equilibria's midpoint (``tanh = 0``).  Every other motion on the same energy
level is a time shift of this one (or its mirror, ``branch = -1`` of
``omega_general``).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from suslov.kernel.contexts import FLOAT
from suslov.loader import gf


@dataclass(frozen=True)
class Body:
    """A body in the paper's frame; ``frame`` maps paper coordinates to scene coordinates."""

    frame: np.ndarray            # columns: the paper's axes in the scene frame
    tensor: np.ndarray           # the inertia tensor in the scene frame (as given, physical units)
    entries: tuple               # (I11, I22, I13, I23) in the paper's frame, det I = 1
    special: bool                # I13 = 0: closed-form angle, p and d defined
    p: float | None
    d: float | None
    u: np.ndarray                # omega = lam (u tanh(lam t) + v sech(lam t)) in the paper's frame
    v: np.ndarray
    rate: float                  # lam
    exact: object = None         # the body as written (suslov.simulator.exact.ExactBody): the exact effects' body

    @property
    def odd_integer_p(self) -> int | None:
        """p when it is (within 1e-9) an odd integer with a certified basis, else None."""
        if not self.special:
            return None
        k = round(self.p)
        if abs(self.p - k) <= 1e-9 * max(1.0, self.p) and k % 2 == 1 and k in gf.BASIS_PS:
            return int(k)
        return None

    def omega(self, t) -> np.ndarray:
        """omega(t) in the paper's frame, shape t.shape + (2,)."""
        s = self.rate * np.asarray(t, dtype=float)
        if self.special:
            w1, w2 = gf.omega(s, self.p, self.d)
        else:
            w1, w2 = gf.omega_general(s, *self.entries)
        return self.rate * np.stack([w1, w2], axis=-1)

    def omega_at(self, t: float) -> np.ndarray:
        """omega at one float ``t`` (paper frame, shape (2,)): the values :meth:`omega` returns, bit for bit.

        Why: the integrators call omega once per right-hand side evaluation, and the public function's
        validation and broadcasting took about 45 of its 60 us per call (a guarded integration makes 10^5 calls).
        Here the emitted kernel is called directly, with the arguments the public function passes it: the
        body's parameters were validated when it was made (the general case scaled exactly as
        ``suslov.runtime.angular.omega_general`` scales them).  A non-finite value (none is known for a body that
        :func:`make_body` accepts: it refuses p/d beyond float64) would go through :meth:`omega`, whose repair
        computes it or raises its error.
        """
        s = self.rate * float(t)
        with np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore"):
            if self.special:
                w1, w2 = gf._omega(FLOAT, s, self.p, self.d)
            else:
                w1, w2 = gf._omega_general(FLOAT, s, *self._scaled_entries)
        if math.isfinite(w1) and math.isfinite(w2):
            return self.rate * np.array([w1, w2])
        return self.omega(np.asarray(t, dtype=float))

    @functools.cached_property
    def _scaled_entries(self) -> tuple:
        """(I11, I22, I13, I23, r): the entries divided by the largest of I11, I22, |I13|, |I23| and r = sqrt(I11 I22)
        of the scaled ones, as ``omega_general`` computes them for branch +1 (once per body: ``omega_at`` is a hot
        path)."""
        I11, I22, I13, I23 = (np.float64(v) for v in self.entries)
        size = np.maximum(np.maximum(I11, I22), np.maximum(np.abs(I13), np.abs(I23)))
        I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / size
        return I11, I22, I13, I23, np.sqrt(I11 * I22)

    def omega_scene(self, t) -> np.ndarray:
        """omega(t) in the scene frame, shape t.shape + (3,)."""
        return self._in_scene(self.omega(t))

    def _in_scene(self, w: np.ndarray) -> np.ndarray:
        """Paper-frame (w1, w2) values, shape (..., 2), as scene-frame vectors (w1, w2, 0) R^T, shape (..., 3)."""
        full = np.concatenate([w, np.zeros(w.shape[:-1] + (1,))], axis=-1)
        return full @ self.frame.T

    def to_paper(self, vectors) -> np.ndarray:
        return np.asarray(vectors, dtype=float) @ self.frame

    def to_scene(self, vectors) -> np.ndarray:
        return np.asarray(vectors, dtype=float) @ self.frame.T

    def energy(self, t=0.0) -> float:
        """Kinetic energy (1/2) <I omega, omega> with the tensor as given.

        At one instant through :meth:`omega_at` (the same bits as :meth:`omega`): :func:`make_body` calls this for
        every body with an energy, and a sweep builds a body for each point it plans (20000 of them), where the
        public function's validation took two thirds of the time."""
        if np.ndim(t) == 0:
            w = self._in_scene(self.omega_at(t))
        else:
            w = self.omega_scene(np.asarray(t, dtype=float))
        return float(0.5 * w @ self.tensor @ w)

    def limit_axis(self) -> np.ndarray:
        """Unit vector ``u/|u|`` (paper frame): omega -> -lam u at t -> -oo and +lam u at +oo."""
        return np.array([*self.u / np.hypot(*self.u), 0.0])   # hypot: no underflow of |u|^2 (|u| = 2e-300)

    def describe(self) -> str:
        if self.special:
            return (f"case I13 = 0: p = {self.p:.12g}, d = {self.d:.12g}"
                    + (" (odd integer p: closed-form Poisson basis)" if self.odd_integer_p else ""))
        I11, I22, I13, I23 = self.entries
        return f"general body: I11 = {I11:.6g}, I22 = {I22:.6g}, I13 = {I13:.6g}, I23 = {I23:.6g} (det I = 1)"


def tensor_from_pd(p: float, d: float) -> np.ndarray:
    """A representative tensor of the case I13 = 0 with I22 = 1 (I33 does not enter the motion)."""
    i23 = -d / p
    return np.array([[d * d + 1.0, 0.0, 0.0], [0.0, 1.0, i23], [0.0, i23, i23 * i23 + 1.0]])


def make_body(tensor=None, p=None, d=None, energy=None, tol=1e-9, exact=None) -> Body:
    """Build a :class:`Body` from a tensor or from (p, d); ``energy`` fixes the rate (default rate 1).

    ``exact``: the body as the user wrote it (:class:`suslov.simulator.exact.ExactBody`), for the exact
    effects; the floats here drive the numerics.  Raises ValueError naming the offending quantity.
    """
    if tensor is None:
        if p is None or d is None:
            raise ValueError("a body needs either 'inertia' or both 'p' and 'd'")
        if not (math.isfinite(p) and p > 0):
            raise ValueError(f"p={p!r}: must be finite and > 0")
        if not (math.isfinite(d) and d > 0):
            raise ValueError(f"d={d!r}: must be finite and > 0")
        return _pd_body(float(p), float(d), energy, exact)
    tensor = np.asarray(tensor, dtype=float)
    R, (I11, I22, I13, I23) = gf.canonical_frame(tensor)
    size = max(abs(I11), abs(I22), abs(I13), abs(I23))
    # I13 negligible makes the case I13 = 0 only when I23 is not negligible too (else p = -I22 d/I23 divides by 0)
    special = abs(I13) <= tol * size and I11 - I22 > tol * size and abs(I23) > tol * size
    if special:
        if I23 > 0:  # rotate the frame by pi about e3 so that p > 0
            R = R @ np.diag([-1.0, -1.0, 1.0])
            I13, I23 = -I13, -I23
        I13 = 0.0
        d_val = math.sqrt(I11 / I22 - 1.0)
        p_val = -I22 * d_val / I23
        a = p_val / d_val
        u, v = np.array([a, 0.0]), np.array([0.0, -a * math.sqrt(d_val * d_val + 1.0)])
    else:
        p_val = d_val = None
        D = I13 * I13 * I22 + I23 * I23 * I11
        if not D > 0:   # I13 and I23 underflow together: float64 cannot tell this body from the equilibrium
            raise ValueError(f"I13={I13!r}, I23={I23!r} (paper frame): I13^2 I22 + I23^2 I11 underflows to 0 in float64; "
                             "give the entries exactly (decimal strings) for the exact effects")
        r = math.sqrt(I11 * I22)
        u = np.array([-I11 * I22 * I23 / D, I11 * I22 * I13 / D])
        v = np.array([I22 * I13 * r / D, I11 * I23 * r / D])
    body = Body(R, tensor, (I11, I22, I13, I23), special, p_val, d_val, u, v, 1.0, exact)
    if energy is not None:
        if not (math.isfinite(energy) and energy > 0):
            raise ValueError(f"energy={energy!r}: must be finite and > 0")
        body = Body(R, tensor, body.entries, special, p_val, d_val, u, v, math.sqrt(energy / body.energy()), exact)
    return body


def _pd_body(p: float, d: float, energy, exact) -> Body:
    """The body of the case I13 = 0 from p and d directly, in the paper's frame (the frame of
    :func:`tensor_from_pd`: I12 = 0, I11 = 1 + d^2 >= I22 = 1, I13 = 0, I23 = -d/p < 0).

    Not through the float tensor and :func:`suslov.kernel.frames.canonical_frame` (issue 44): there
    ``I23 = -d/p`` fell below its relative tolerance for p >= 1e12 d (p = 1e300 or d = 1e-300 were called the
    equilibrium I13 = I23 = 0, whose scattering angle the closed form gives as pi), and ``1 + d^2`` or
    ``d^2/p^2`` overflowed (d = 1e300, p = 1e-300: "NaN or inf").  omega = lam (u tanh + v sech) with
    ``u = (p/d, 0)``, ``v = (0, -(p/d) sqrt(1 + d^2))`` (eq:o12 for I13 = 0) needs only p/d and |v| in float64;
    ValueError naming p and d when they are not.  The tensor is the representative ``tensor_from_pd`` (entries
    beyond float64 are inf there; the exact effects use the numbers as written, ``exact``).
    """
    a = p / d
    speed = p * math.hypot(1.0, 1.0 / d) if d >= 1.0 else a * math.hypot(d, 1.0)   # |v| = (p/d) sqrt(1 + d^2)
    for name, x in (("p/d", a), ("|v| = (p/d) sqrt(1 + d^2)", speed)):
        if not (math.isfinite(x) and x >= 2.2250738585072014e-308):
            raise ValueError(f"p={p!r}, d={d!r}: {name} of omega = lam (u tanh(lam t) + v sech(lam t)) is beyond "
                             "float64's range (1e-308 to 1e308): a scene's float64 numerics cannot represent this "
                             "body; suslov.validated (scattering_angle_enclosure, galois_group) and the module's _mp "
                             "and _ball routes take its exact entries (I11, I22, I13, I23) = (1 + d^2, 1, 0, -d/p)")
    with np.errstate(over="ignore", under="ignore"):
        tensor = tensor_from_pd(p, d)
    u, v = np.array([a, 0.0]), np.array([0.0, -speed])
    # det(tensor_from_pd) = 1 + d^2: the entries of det I = 1 (as canonical_frame scales them), through logarithms;
    # informative only for this case (the numerics use p, d, u, v): I11 = (1 + d^2)^(2/3) is inf beyond d ~ 1e231
    log_det = 2.0 * math.log(d) + math.log1p(d ** -2.0) if d > 1.0 else math.log1p(d * d)
    with np.errstate(over="ignore", under="ignore"):
        scale = float(np.exp(-log_det / 3.0))
        entries = (float(np.exp(2.0 * log_det / 3.0)), scale, 0.0, float(-(d / p) * np.float64(scale)))
    rate = 1.0
    if energy is not None:
        if not (math.isfinite(energy) and energy > 0):
            raise ValueError(f"energy={energy!r}: must be finite and > 0")
        # the energy of tensor_from_pd at rate 1 is |v|^2/2 (I22 = 1; at t = 0 omega = v), so lam = sqrt(2 E)/|v|
        rate = math.sqrt(2.0 * energy) / speed
        if not (math.isfinite(rate) and rate > 0):
            raise ValueError(f"energy={energy!r} with p={p!r}, d={d!r}: the rate sqrt(2 energy)/|v| = {rate!r} is beyond "
                             "float64's range")
    return Body(np.eye(3), tensor, entries, True, p, d, u, v, rate, exact)
