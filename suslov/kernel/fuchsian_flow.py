"""Validated integration of the Poisson equations along complex paths: transfer matrices as acb balls.

Paper: eq:whole (``gamma' = gamma x omega``), eq:o12 (``omega(t) = u tanh t + v sech t`` for any body
with I12 = 0, a = e3), and the Conclusion's open problem (the monodromy of eq:genhipprep, whose
solutions are the components of gamma, in the general case I13 != 0).

**The system in x = e^t.**  ``tanh t = (x^2 - 1)/(x^2 + 1)``, ``sech t = 2x/(x^2 + 1)`` and
``dt = dx/x`` turn eq:whole into the Fuchsian system ``dY/dx = Y A(x)`` (Y a row of solutions, or a
3x3 fundamental matrix of rows) with

    A(x) = C(-u)/x + C(u - i v)/(x - i) + C(u + i v)/(x + i),     y C(w) = y x w,

by partial fractions of ``omega(x)/x`` (certified exactly by ``derivations/sections/fuchsian.py``).
Every finite singular point is a simple pole; at infinity ``A ~ C(u)/x``.  A path in the t-plane
that avoids the poles ``t = i pi/2 + k pi i`` is a path in the x-plane that avoids x = +-i (and 0).

**One step** from a centre c to ``c + h`` with ``|h| <= eta < rho = min(|c|, |c - i|, |c + i|)``: the
transfer matrix is ``T(h) = sum_k T_k h^k``, ``T_0 = I``, ``(k+1) T_(k+1) = sum_s Z_(s,k) R_s`` where
``Z_(s,k) = g_s T_k - g_s Z_(s,k-1)``, ``g_s = 1/(c - s)`` (the Taylor coefficients of
``R_s/(x - s)`` form a geometric sequence, so each order costs one product per singular point).
The terms after order N are bounded by a *majorant*: with the submultiplicative max-row-sum norm
(``||I|| = 1``) and ``M = sum_s ||R_s||``, every ``||A_j|| <= M / rho^(j+1)``, so by induction
``||T_k|| <= b_k = (M)_k / (k! rho^k)``, the coefficients of ``(1 - h/rho)^(-M)``; the ratios
``b_(k+1) eta / b_k = (M + k)/(k + 1) * eta/rho`` are at most ``q = max(1, (M + N + 1)/(N + 2)) eta/rho``
after N, hence ``||sum_(k > N) T_k h^k|| <= b_(N+1) eta^(N+1) / (1 - q)``, and that bound is added as
a radius to every entry of the step's matrix (each entry is at most the row sum).

**Error propagation off the real axis.**  There the transfer matrix lies in SO(3, C) and is not a
rotation, so the real-time argument (an error of norm delta stays of norm delta) does not apply.
Here nothing is argued: the steps' matrices are balls and are multiplied in ball arithmetic
(``acb_mat``), which encloses the product of any matrices inside the factors; the radii grow as
they must.  References: M. Mezzarobba, arXiv:1607.01967 (majorants for Fuchsian systems, in a much
finer form); F. Johansson, arXiv:1606.06977 (ball arithmetic).
"""
from __future__ import annotations

import math

from flint import acb, acb_mat, arb

__all__ = ["SINGULAR_POINTS", "cross_matrix", "residues", "transfer", "path_transfer", "circle", "segment",
           "guard_digits"]

SINGULAR_POINTS = (acb(0), acb(0, 1), acb(0, -1))
GUARD_CAP = 10**15   # guard_digits beyond this is reported as this: far beyond any working precision anyway


def cross_matrix(w) -> acb_mat:
    """C(w) with ``y C(w) = y x w`` for a row vector y (w: three acb)."""
    w1, w2, w3 = w
    zero = acb(0)
    return acb_mat([[zero, -w3, w2], [w3, zero, -w1], [-w2, w1, zero]])


def residues(u, v) -> list:
    """The residue matrices at x = 0, i, -i: C(-u), C(u - i v), C(u + i v) (u, v: pairs of balls)."""
    U = [acb(u[0]), acb(u[1]), acb(0)]
    V = [acb(v[0]), acb(v[1]), acb(0)]
    i = acb(0, 1)
    return [cross_matrix([-a for a in U]), cross_matrix([a - i * b for a, b in zip(U, V)]),
            cross_matrix([a + i * b for a, b in zip(U, V)])]


def _norm_upper(matrix: acb_mat) -> float:
    """An upper bound of the max-row-sum norm (a float rounded up generously)."""
    rows = [sum(float(abs(matrix[r, c]).upper()) for c in range(3)) for r in range(3)]
    return max(rows) * (1 + 1e-12) + 1e-300


def _distance_lower(c: acb) -> float:
    """A lower bound of the distance from c to the nearest singular point."""
    return min(float(abs(c - s).lower()) for s in SINGULAR_POINTS)


def transfer(R: list, c: acb, h: acb, log10_eps: float, max_order: int = 8000) -> acb_mat:
    """Ball enclosure of the transfer matrix from c to c + h (module docstring), every radius including
    a truncation bound below ``10^log10_eps`` (bounds kept as logarithms: no float underflow at
    hundreds of digits).  Needs ``|h| < rho(c)`` (raises ValueError otherwise)."""
    rho = _distance_lower(c)
    eta = float(abs(h).upper()) * (1 + 1e-12)
    if not eta < rho:
        raise ValueError(f"step {eta:.3g} not inside the disc of convergence {rho:.3g} at {c}")
    M = sum(_norm_upper(r) for r in R)
    log_eps = log10_eps * math.log(10)
    g = [1 / (c - s) for s in SINGULAR_POINTS]
    T = [acb_mat([[1, 0, 0], [0, 1, 0], [0, 0, 1]])]
    Z = [acb_mat(3, 3) for _ in SINGULAR_POINTS]
    log_ratio = math.log(eta / rho) if eta > 0 else -math.inf
    log_b = 0.0                      # log((M)_n / n!): b_n rho^n, n = 0
    n = 0
    while True:
        # Z_(s,n) = g_s T_n - g_s Z_(s,n-1);  (n+1) T_(n+1) = sum_s Z_(s,n) R_s
        # matrix times scalar: the same balls as scalar times matrix, at half the cost in python-flint
        Z = [(T[n] - Z[s]) * g[s] for s in range(3)]
        T.append((Z[0] * R[0] + Z[1] * R[1] + Z[2] * R[2]) / (n + 1))
        log_b += math.log((M + n) / (n + 1))
        n += 1
        # the terms after order n: b_(n+1) eta^(n+1) / (1 - q), q = max(1, (M+n+1)/(n+2)) eta/rho
        q = max(1.0, (M + n + 1) / (n + 2)) * eta / rho
        if q < 1:
            log_tail = log_b + math.log((M + n) / (n + 1)) + (n + 1) * log_ratio - math.log1p(-q)
            if log_tail < log_eps or n >= max_order:
                break
        elif n >= max_order:
            raise ArithmeticError(f"no convergent majorant at {c} (M = {M:.3g}, eta/rho = {eta / rho:.3g})")
    k = n
    total = T[k]
    for j in range(k - 1, -1, -1):
        total = total * h + T[j]
    # the float logarithm is rounded up generously before it becomes a radius
    radius = arb(0, arb(log_tail + 1e-9 * abs(log_tail) + 1e-9).exp())
    widen = acb(radius, radius)
    return acb_mat([[total[r, c] + widen for c in range(3)] for r in range(3)])


def segment(a: acb, b: acb) -> list:
    """Points from a to b (a straight segment), each step at most half the distance to the nearest
    singular point from its start."""
    points, c = [a], a
    while True:
        rho = _distance_lower(c)
        remaining = b - c
        length = float(abs(remaining).upper())
        if length <= rho / 2:
            points.append(b)
            return points
        c = c + remaining * (rho / 2 / length)
        points.append(c)


def circle(centre: acb, start: acb, turns: int = 1) -> list:
    """Points on the circle about ``centre`` through ``start``, counterclockwise ``turns`` times, back to
    ``start`` exactly; chords at most half the distance to the nearest singular point."""
    radius = float(abs(start - centre).mid())
    # every point of the circle is at least | radius - |s - centre| | from a singular point s
    rho = min(abs(radius - float(abs(s - centre).mid())) for s in SINGULAR_POINTS) * (1 - 1e-9)
    if rho <= 0:
        raise ValueError(f"the circle of radius {radius} about {centre} passes through a singular point")
    chord = rho / 2
    steps = max(8, math.ceil(2 * math.pi * turns * radius / chord * 1.1))
    offset = start - centre
    points = [start]
    for j in range(1, steps):
        points.append(centre + offset * acb(0, 2 * math.pi * turns * j / steps).exp())
    points.append(start)
    return points


def path_transfer(R: list, points: list, log10_eps: float) -> acb_mat:
    """The product of the step transfer matrices along ``points`` (each step from one point to the next)."""
    total = acb_mat([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    for a, b in zip(points, points[1:]):
        total = total * transfer(R, a, b - a, log10_eps)
    return total


def guard_digits(R: list) -> int:
    """Decimal digits lost, relative to an absolute radius of 10^-digits, by the loops of
    :mod:`suslov.kernel.monodromy` (an estimate; the caller checks the radius it gets and retries).

    Two losses, both growing with ``|omega|`` (large near the equilibrium I13 = I23 = 0):

    * the size of the matrices: a loop about a point with exponents 0, +-i sqrt(w.w) has eigenvalues
      ``exp(+-2 pi sqrt(w.w))``, entries up to ``10^L`` with ``L = 2 pi max |Re sqrt(w.w)| / ln 10``;
    * cancellation in each Taylor sum: the terms are bounded by the majorant ``(1 - eta/rho)^(-M)``,
      ``2^M`` at ``eta/rho = 1/2``, while the sum is much smaller: ``M log10 2`` digits per step,
      measured 0.36 M + 7 digits over a whole loop (M from 18 to 176); the 64 extra bits of
      :func:`working_precision` (19 digits) cover the constant.

    At most ``GUARD_CAP`` (a body within 1e-150 of the equilibrium needs some 1e150 digits: nothing runs).
    """
    M = sum(_norm_upper(r) for r in R)
    largest = 0.0
    for r in R:
        w1, w2, w3 = -r[1, 2], r[0, 2], -r[0, 1]
        root = (w1 * w1 + w2 * w2 + w3 * w3).sqrt()
        largest = max(largest, float(abs(root.real).upper()))
    guard = 0.4 * M + 2 * math.pi * largest / math.log(10)
    # |omega| ~ 1e300 (an entry I13 ~ 1e-300) or beyond float64 (largest = inf): capped, never an OverflowError
    return math.ceil(guard) if math.isfinite(guard) and guard < GUARD_CAP else GUARD_CAP


def working_precision(digits: int) -> int:
    """Bits for ``digits`` correct digits after a few hundred ball products."""
    return int(3.33 * digits) + 64
