"""gamma(t) of every body from Gauss's 2F1 (issue 44): the closed form in mpmath (:mod:`suslov.kernel.gauss_gamma`).

The Poisson equations ``gamma' = gamma x omega``, ``omega = u tanh t + v sech t`` (paper eq:whole, eq:o12, rate 1,
paper frame, omega3 = 0), read ``dgamma/ds = gamma x (u s + v)/(1 + s^2)`` in ``s = sinh t``; their spinor lift
``Psi' = -S(Omega) Psi``, ``S(w) = -(i/2)(w1 sigma3 + w2 sigma1 + w3 sigma2)``, gives ``S(gamma) = Psi S(gamma0)
Psi^-1`` and is solved by 2F1 (certified: ``derivations/sections/gauss.py``).  What this module evaluates:

**Frame.**  Rotate about e3 so that ``u = (U, 0, 0)``: ``e1 = u/U``, ``e2 = e3 x e1``, ``v1 = v.e1``, ``v2 = v.e2``
(``v2 = (u x v)_3/U != 0`` for every body).  There ``-S(Omega) = [[a, b], [b, -a]]``, ``a = (i/2)(U s + v1)/(1 + s^2)``,
``b = (i/2) v2/(1 + s^2)``, and a column ``(psi1, psi2)`` solves the lift iff ``psi1 = P F`` with
``P = z^(kappa/2) (1-z)^(mu/2)``, ``z = (1 + i s)/2``, F a solution of Gauss's equation with
``A = (2 + kappa + mu + iU)/2``, ``B = (kappa + mu - iU)/2``, ``C = 1 + kappa``, and

    psi2 = (psi1' - a psi1)/b = P [4 z (1-z) F'(z) + (2 kappa - iU - v1 - 4 B z) F] / v2.        (*)

``kappa = (i/2) w_-``, ``mu = (i/2) conj(w_-)``, ``w_- = X + iY = sqrt((u - iv).(u - iv))`` with ``X >= 0`` (the
principal root; either root is certified), as :func:`suslov.validated.hypergeometric_form` takes them.  Every
power is principal: on the path ``Re z = 1/2`` neither ``log z`` nor ``log(1 - z)`` meets its cut, and
``|P| = 1`` there (``|z| = |1 - z|``, ``Re(kappa + mu) = 0``, ``Im kappa = Im mu``).

**The basis at infinity.**  ``F_e = z^-e g_e(w)``, ``w = 1/z``, e = A or B, ``g_A = 2F1(A, A-C+1; A-B+1; w)``,
``g_B = 2F1(B, B-C+1; B-A+1; w)`` (``mpmath.hyp2f1``, which continues analytically).  ``A - B = 1 + iU`` is never an
integer (U > 0 for every body), so this basis never degenerates, also where kappa is an integer (even p, I11 = I22:
the bases at z = 0 and z = 1 are logarithmic there).  Inserted in (*) without cancellation at large s:

    psi1 = E g,   psi2 = E [-4 (w - 1) g' + (2 kappa - iU - v1 - 4 e) g] / v2 + 4 (e - B) E z g / v2,
    E = exp((kappa/2) log z + (mu/2) log(1 - z) - e log z).

Solutions of the lift keep ``|psi1|^2 + |psi2|^2`` (``-S(Omega)`` is anti-Hermitian for real s), so each column is
divided by its norm; at ``s -> -oo`` the columns tend to ``(*, 0)`` (e = B) and ``(0, *)`` (e = A), hence
``G = [col_B, col_A]`` is unitary on each half-line and ``G (i/2) sigma3 G^-1 = S(gamma_ss)``, the ss solution
(``gamma -> -u/U`` at ``t -> -oo``), exactly and without a limit.

**The join at s = 0.**  At s = 0, ``w = 2`` lies on the cut of ``g_e``: the principal branches on ``s < 0`` (``G_-``)
and ``s > 0`` (``G_+``) are two different bases.  They are connected through ``H(s) = Psi(s, 0)``, the solution
with ``H(0) = I``, by the Taylor series of Gauss's equation at its ordinary point ``z = 1/2`` (radius 1/2: ``|s| < 1``):
``F = sum a_n zeta^n``, ``zeta = z - 1/2 = i s/2``,
``a_(n+2) = 4 [(n (n-1) + (A+B+1) n + AB) a_n - (C - (A+B+1)/2)(n+1) a_(n+1)] / ((n+1)(n+2))``,
started from ``(F, F') = (1/P0, -N0/P0)`` and ``(0, v2/P0)`` (``P0 = 2^-(kappa+mu)/2``,
``N0 = 2 kappa - iU - v1 - 2B``).  With ``s1 = min(JOIN, JOIN_U/U)`` (the sum loses about ``0.25 U |s|`` digits to
cancellation): ``K = H(s1) H(-s1)^-1 G_-(-s1)``, and the fundamental matrix (unitary, continuous on the real
line) is ``Phi = G_-(s)`` for ``s <= -s1``, ``H(s) H(-s1)^-1 G_-(-s1)`` for ``|s| < s1`` and ``G_+(s) G_+(s1)^-1 K``
for ``s >= s1``.  Then ``S(gamma(t)) = Phi X0 Phi^-1`` with ``X0 = (i/2) sigma3`` (ss) or
``Phi(t0)^-1 S(gamma0) Phi(t0)`` (gamma0 at t0), and gamma = the vector of that matrix, rotated back.

Precision: the working precision is ``dps + GUARD_DIGITS`` digits plus what the Taylor sum at z = 1/2 reports
lost to cancellation (:class:`Cancellation`: redone with that many more digits); the measured accuracy
is in ``docs/simulator.md`` and ``tests/test_gauss_gamma.py``.  The float64 vectorised twin is
:mod:`suslov.kernel.gauss_gamma_float`; the public routine :func:`suslov.kernel.gauss_gamma.gamma_gauss`.  No SymPy,
no ``generated`` import (the kernel layer).
"""
from __future__ import annotations

import math

import mpmath

__all__ = ["GUARD_DIGITS", "JOIN", "JOIN_U", "Cancellation", "GaussGamma", "body_uv", "solve_mp", "spinor", "vector"]

JOIN = 0.6              # |s| of the two joins between G_-, H and G_+ (H converges for |s| < 1), at most
JOIN_U = 20.0           # ... and at most JOIN_U/U: the Taylor sum at z = 1/2 loses about 0.25 U |s| digits
GUARD_DIGITS = 15       # working digits beyond those asked for
_MAX_TERMS = 20_000     # the Taylor sum at z = 1/2 (ratio |s| <= JOIN < 1; thousands of terms only for huge U)


class Cancellation(ArithmeticError):
    """The Taylor sum at z = 1/2 lost ``digits`` to cancellation, more than the working precision allows."""

    def __init__(self, digits: float):
        super().__init__(f"cancellation of {digits:.0f} digits in the Taylor series at z = 1/2")
        self.digits = digits


def spinor(g):
    """S(g) = -(i/2) (g1 sigma3 + g2 sigma1 + g3 sigma2) as an mpmath matrix."""
    i = mpmath.mpc(0, 1)
    return -i / 2 * mpmath.matrix([[g[0], g[1] - i * g[2]], [g[1] + i * g[2], -g[0]]])


def vector(S) -> tuple:
    """The g of ``S = S(g)`` (complex parts: real up to rounding for a real rotation)."""
    i = mpmath.mpc(0, 1)
    return 2 * i * S[0, 0], i * (S[0, 1] + S[1, 0]), S[1, 0] - S[0, 1]


def _inverse(M):
    det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    return mpmath.matrix([[M[1, 1], -M[0, 1]], [-M[1, 0], M[0, 0]]]) / det


def body_uv(I11, I22, I13, I23) -> tuple:
    """(u, v) of ``omega = u tanh t + v sech t`` (paper frame, the branch r = +sqrt(I11 I22) of ``omega_general``)
    at the current mpmath precision: ``D = I13^2 I22 + I23^2 I11``, ``u = (-I11 I22 I23, I11 I22 I13)/D``,
    ``v = (I22 I13 r, I11 I23 r)/D`` (eq:o12; as :func:`suslov.simulator.body.make_body`)."""
    from suslov.kernel.validate import mp_real

    I11, I22 = mp_real("I11", I11, positive=True), mp_real("I22", I22, positive=True)
    I13, I23 = mp_real("I13", I13), mp_real("I23", I23)
    if I13 == 0 and I23 == 0:
        raise ValueError("I13=0 and I23=0: the constraint axis is a principal axis, every motion is an equilibrium")
    D = I13 * I13 * I22 + I23 * I23 * I11
    r = mpmath.sqrt(I11 * I22)
    return (-I11 * I22 * I23 / D, I11 * I22 * I13 / D), (I22 * I13 * r / D, I11 * I23 * r / D)


class GaussGamma:
    """The closed form of the Poisson solutions of one body at ``dps`` working digits (module docstring).

    ``u``, ``v``: pairs of numbers (floats are taken as their binary values).  All methods work at the
    object's precision; ``phi(t)`` is the unitary fundamental matrix Phi at rate-1 time t, ``gamma(t, X0)`` the
    solution with ``S(gamma) = Phi X0 Phi^-1`` in the paper frame.
    """

    def __init__(self, u, v, dps: int, target: int | None = None):
        self.dps = int(dps)
        self.target = self.dps - GUARD_DIGITS if target is None else int(target)   # the digits the result must keep
        with mpmath.workdps(self.dps):
            u1, u2 = (mpmath.mpf(x) for x in u)
            w1, w2 = (mpmath.mpf(x) for x in v)
            U = mpmath.hypot(u1, u2)
            if not U > 0:
                raise ValueError(f"u={u!r}: |u| = 0 is not a body (U^2 = u.u > 0 for every body)")
            self.e1 = (u1 / U, u2 / U)
            self.e2 = (-self.e1[1], self.e1[0])
            self.U, self.v1, self.v2 = U, w1 * self.e1[0] + w2 * self.e1[1], w1 * self.e2[0] + w2 * self.e2[1]
            if self.v2 == 0:
                raise ValueError(f"u={u!r}, v={v!r}: (u x v)_3 = 0 is not a body ((u x v)_3 != 0 for every body)")
            i = mpmath.mpc(0, 1)
            root = mpmath.sqrt((U - i * self.v1) ** 2 - self.v2 ** 2)      # w_- = X + iY, X >= 0
            self.kappa, self.mu = i * root / 2, i * mpmath.conj(root) / 2
            self.A = (2 + self.kappa + self.mu + i * U) / 2
            self.B = (self.kappa + self.mu - i * U) / 2
            self.C = 1 + self.kappa
            self._join = None
            self.join = min(JOIN, JOIN_U / float(U))   # |s| of the joins

    # ------------------------------------------------------------------ the pieces
    def _log_z(self, t):
        """(z, log z, log(1 - z), w = 1/z) at rate-1 time t."""
        s = mpmath.sinh(t)
        z = mpmath.mpc(1, s) / 2
        return z, mpmath.log(z), mpmath.log(1 - z), 1 / z

    def column_inf(self, t, e: str, normalise: bool = True) -> tuple:
        """The column of G (``e`` = "A" or "B") at rate-1 time t != 0 (its half-line's principal branch): unit
        when ``normalise``, else ``(psi1, psi2, log |psi|)`` unnormalised (the norm is constant on a half-line)."""
        A, B, C, kappa, mu, U, v1, v2 = self.A, self.B, self.C, self.kappa, self.mu, self.U, self.v1, self.v2
        i = mpmath.mpc(0, 1)
        ee, b, c = (A, A - C + 1, A - B + 1) if e == "A" else (B, B - C + 1, B - A + 1)
        _, lz, l1z, w = self._log_z(t)
        g = mpmath.hyp2f1(ee, b, c, w)
        gp = ee * b / c * mpmath.hyp2f1(ee + 1, b + 1, c + 1, w)
        L = kappa / 2 * lz + mu / 2 * l1z - ee * lz
        E = mpmath.exp(L)
        psi1 = E * g
        psi2 = E * (-4 * (w - 1) * gp + (2 * kappa - i * U - v1 - 4 * ee) * g) / v2
        if e == "A":
            psi2 += 4 * (ee - B) * mpmath.exp(L + lz) * g / v2
        norm = mpmath.sqrt(abs(psi1) ** 2 + abs(psi2) ** 2)
        return (psi1 / norm, psi2 / norm) if normalise else (psi1, psi2, mpmath.log(norm))

    def G(self, t, norms: bool = False):
        """G = [col_B, col_A] at t (unitary; the principal branch of t's half-line); with ``norms`` also the logs
        of the two columns' norms before normalising, ``{"B": .., "A": ..}`` (constant on the half-line)."""
        (b1, b2, lb), (a1, a2, la) = self.column_inf(t, "B", False), self.column_inf(t, "A", False)
        nb, na = mpmath.exp(lb), mpmath.exp(la)
        G = mpmath.matrix([[b1 / nb, a1 / na], [b2 / nb, a2 / na]])
        return (G, {"B": lb, "A": la}) if norms else G

    def H(self, t):
        """H(s) = Psi(s, 0) for |s| < 1 by the Taylor series of Gauss's equation at z = 1/2 (module docstring);
        raises :class:`Cancellation` when the sum lost more digits than the working precision has beyond the target."""
        A, B, C, kappa, mu, U, v1, v2 = self.A, self.B, self.C, self.kappa, self.mu, self.U, self.v1, self.v2
        i = mpmath.mpc(0, 1)
        s = mpmath.sinh(t)
        if not abs(s) < 1:
            raise ValueError(f"t={t}: H converges for |sinh t| < 1 only")
        zeta = i * s / 2
        z = mpmath.mpf(1) / 2 + zeta
        c0, c1, AB = C - (A + B + 1) / 2, A + B + 1, A * B
        P0 = mpmath.exp(-(kappa + mu) / 2 * mpmath.log(2))
        N0 = 2 * kappa - i * U - v1 - 2 * B
        P = mpmath.exp(kappa / 2 * mpmath.log(z) + mu / 2 * mpmath.log(1 - z))
        N = 2 * kappa - i * U - v1 - 4 * B * z
        eps = mpmath.mpf(10) ** (-mpmath.mp.dps)
        # both columns at once: (F, F') from (1/P0, -N0/P0) and (0, v2/P0); magnitudes looked at every 4th term
        prev, cur = [1 / P0, mpmath.mpc(0)], [-N0 / P0, v2 / P0]
        F = [prev[k] + cur[k] * zeta for k in (0, 1)]
        Fp, power = list(cur), zeta
        big, small = max(abs(x) for x in prev + cur), 0
        for n in range(_MAX_TERMS if zeta != 0 else 0):
            weight, shift = n * (n - 1) + c1 * n + AB, c0 * (n + 1)
            scale, dpower = mpmath.mpf(4) / ((n + 1) * (n + 2)), (n + 2) * power     # power = zeta^(n+1)
            power *= zeta
            nxt = [scale * (weight * prev[k] - shift * cur[k]) for k in (0, 1)]
            terms = [x * power for x in nxt]
            dterms = [x * dpower for x in nxt]
            F = [F[k] + terms[k] for k in (0, 1)]
            Fp = [Fp[k] + dterms[k] for k in (0, 1)]
            prev, cur = cur, nxt
            if n % 4 == 3:
                size = max(abs(x) for x in terms + dterms)
                big = max(big, size)
                small = small + 1 if size <= eps * (1 + min(abs(F[0]) + abs(Fp[0]), abs(F[1]) + abs(Fp[1]))) else 0
                if small >= 2:
                    break
        else:
            if zeta != 0:
                raise ArithmeticError(f"the Taylor series at z = 1/2 did not converge in {_MAX_TERMS} terms")
        columns, lost = [], 0.0
        for k in (0, 1):
            lost = max(lost, math.log10(float(big) / max(float(abs(F[k]) + abs(Fp[k])), 1e-300) + 1))
            columns.append((P * F[k], P * (4 * z * (1 - z) * Fp[k] + N * F[k]) / v2))
        if lost > self.dps - self.target - 5:
            raise Cancellation(lost)
        return mpmath.matrix([[columns[0][0], columns[1][0]], [columns[0][1], columns[1][1]]])

    def joins(self) -> tuple:
        """(M_mid, M_plus): Phi = H(s) M_mid for |s| < s1, G_+(s) M_plus for s >= s1 (cached); also sets
        ``log_norms[(side, e)]``, the logs of the column norms of G on each half-line (side -1, +1)."""
        if self._join is None:
            t1 = mpmath.asinh(mpmath.mpf(self.join))
            (left, lnorms), (right, rnorms) = self.G(-t1, True), self.G(t1, True)
            mid = _inverse(self.H(-t1)) * left
            self._join = (mid, _inverse(right) * self.H(t1) * mid)
            self.log_norms = {(side, e): n[e] for side, n in ((-1, lnorms), (1, rnorms)) for e in ("A", "B")}
        return self._join

    def phi(self, t):
        """The unitary fundamental matrix Phi at rate-1 time t (Phi = G_- for s <= -s1)."""
        t = mpmath.mpf(t)
        s = mpmath.sinh(t)
        if s <= -self.join:
            return self.G(t)
        mid, plus = self.joins()
        return self.H(t) * mid if s < self.join else self.G(t) * plus

    def start(self, gamma0=None, t0=0):
        """X0 for the ss solution (``gamma0`` None) or for gamma0 (paper frame) at rate-1 time t0."""
        i = mpmath.mpc(0, 1)
        if gamma0 is None:
            return mpmath.matrix([[i / 2, 0], [0, -i / 2]])
        g = [mpmath.mpf(x) for x in gamma0]
        rotated = (g[0] * self.e1[0] + g[1] * self.e1[1], g[0] * self.e2[0] + g[1] * self.e2[1], g[2])
        P = self.phi(t0)
        return _inverse(P) * spinor(rotated) * P

    def to_paper(self, g) -> tuple:
        """A vector of the rotated frame (u = (U, 0, 0)) in the paper frame (real parts)."""
        g1, g2, g3 = (mpmath.re(x) for x in g)
        return g1 * self.e1[0] + g2 * self.e2[0], g1 * self.e1[1] + g2 * self.e2[1], g3

    def gamma(self, t, X0) -> tuple:
        """gamma(t), paper frame, with ``S(gamma) = Phi(t) X0 Phi(t)^-1``."""
        P = self.phi(t)
        return self.to_paper(vector(P * X0 * _inverse(P)))


def solve_mp(u, v, t, gamma0, t0, dps: int) -> list:
    """gamma at each time of ``t`` (rate 1, a sequence), working at ``dps + GUARD_DIGITS`` digits plus what the sum
    at z = 1/2 loses to cancellation; returns tuples of mpf rounded to ``dps``."""
    work = dps + GUARD_DIGITS
    for _ in range(4):
        try:
            with mpmath.workdps(work):
                form = GaussGamma(u, v, work, dps)
                X0 = form.start(gamma0, mpmath.mpf(t0))
                out = [form.gamma(mpmath.mpf(x), X0) for x in t]
            with mpmath.workdps(dps):
                return [tuple(+x for x in g) for g in out]
        except Cancellation as error:
            work = dps + GUARD_DIGITS + math.ceil(error.digits) + 5
    raise ArithmeticError(f"gamma_gauss: no result at {work} working digits")
