"""Proofs of the float64 error bounds the generated module states (issue 34), one per emitted function.

Each proof runs the *emitted* function of the module under test (``module._omega``,
``module._scattering_angle``) with :class:`derivations.proofs.float_bounds.ErrorContext` over a
cover of its documented domain by boxes, together with the run-time code around it that computes
its inputs (``suslov.runtime.angle``: ``x = pi |p|/(2d)``, ``phase.half_pi_parts``), and takes the
worst box.  The bound is stated in units of u = 2^-53 and rounded up; the certificate passes when
the proven bound is at most the one the docstring states (``STATED``), so a change that makes the
emitted code less accurate fails the build (or, with a larger stated bound, shows in the docstring).

* ``omega`` (``omegas``): every t (|t| <= 1024 by boxes; beyond, every float operation gives what it gives at
  1024: exp(-|t|) = 0, expm1(-|t|) = -1), d in [1e-3, 1e3], every p short of overflow (the relative
  bound is invariant under p -> 2^k p and p -> -p): ``|w_i~ - w_i| <= B u |w_i| + 1e-300 (|p|/d) c``
  (the absolute part: sech t underflows for |t| > 708).
* ``scattering_angle`` (Theorem 5.4, evaluation form): every p, d > 0 with ``x = pi |p|/(2d) <= 1024``
  (the (x, r) boxes, r = |p - 2 round(p/2)| in [0, 1], cover every pair): ``|Dpsi~ - Dpsi| <= B u``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flint import arb, ctx

from derivations.core.certificates import Certificate, CertificateLog, Outcome, stopwatch

from derivations.proofs.float_bounds import (
    FE,
    _mag,
    METHOD,
    U,
    BoundFailure,
    ErrorContext,
    cos,
    sin,
)

PREC = 128                        # working precision of the analysis (u = 2^-53 must not be lost against 1)
# the bounds the docstrings state (derivations/output/public_api.py): relative per component for omega,
# absolute for the angle
STATED = {"omega": 5e-15, "scattering_angle": 1.5e-14, "omega_general": 6e-15}
OMEGA_FLOOR = arb("1e-300")       # omega's absolute part (where sech t underflows), units of (|p|/d) c


@dataclass(frozen=True)
class Proof:
    name: str
    bound_u: float               # proven bound in units of u (rounded up to an integer)
    boxes: int
    domain: str
    statement: str

    @property
    def bound(self) -> float:
        return self.bound_u * 2.0**-53


def box(lo: float, hi: float) -> arb:
    """[lo, hi] as a ball (non-negative when lo >= 0; a ball's rounding could reach below 0)."""
    ball = arb(lo).union(arb(hi))
    return ball.nonnegative_part() if lo >= 0 and not ball >= 0 else ball


def _in_u(x: arb) -> float:
    return float((x / U).upper())


def t_boxes(step: float = 1 / 16) -> list:
    """[0, 1024]: steps of ``step`` to 4, then binades (the relative bounds do not need narrow boxes)."""
    n = round(4 / step)
    return [box(i * step, (i + 1) * step) for i in range(n)] + [box(2.0**k, 2.0 ** (k + 1)) for k in range(2, 10)]


def d_boxes(n: int = 24) -> list:
    return [box(10 ** (-3 + 6 * j / n), 10 ** (-3 + 6 * (j + 1) / n)) for j in range(n)]


def prove_omega(module) -> Proof:
    with ctx.workprec(PREC):
        worst, floor, boxes = arb(0), arb(0), 0
        p = FE(box(1.0, 2.0))
        for t in t_boxes(step=0.5):
            for d in d_boxes():
                w1, w2 = module._omega(ErrorContext(), FE(t), p, FE(d))
                scale = p.v / d * (d * d + 1).sqrt()
                for w in (w1, w2):
                    # |w~ - w| <= r |w| + a: r relative, a in units of (|p|/d) c (underflow of sech t)
                    worst = max(worst, w.r, key=lambda a: a.upper())
                    floor = max(floor, w.a / arb(scale.lower()), key=lambda a: a.upper())
                boxes += 1
    bound_u = math.ceil(_in_u(worst))
    if not floor < OMEGA_FLOOR:
        raise BoundFailure(f"omega: absolute part {floor} of the bound exceeds {OMEGA_FLOOR} (|p|/d) c")
    return Proof("omega", bound_u, boxes, "all $t$, $d$ from $10^(-3)$ to $10^3$, $p != 0$ (no overflow)",
                 f"the computed $omega_i$ is within ${bound_u} u abs(omega_i) + 1e-300 (abs(p)/d) sqrt(d^2 + 1)$ of "
                 "the exact one")


def half_pi_parts(r: FE, upper_branch: bool | None = None) -> tuple:
    """``phase.half_pi_parts`` on r = |p - 2 round(p/2)| (exact in float64): s = sin(0.5 pi r),
    c = sin(0.5 pi (1 - r)) for r >= 0.5 else cos(0.5 pi r), with np.pi = fl(pi).  ``upper_branch`` is the branch of
    a box of :func:`r_cover` (a ball's radius is rounded up, so a box [1/2, 1] reaches just below 1/2: those points
    are covered by the box below, with the other branch)."""
    half_pi = FE(arb.pi() / 2, arb.pi() / 2 * U, U)          # 0.5 * np.pi: fl(pi)/2, relative error <= u
    s = sin(half_pi * r)
    # 1 - r is exact for r in [1/2, 1] (Sterbenz's lemma) and >= 0
    complement = FE((1 - r.v).nonnegative_part(), 0, 0, 0, sign=1) if r.e == 0 else 1.0 - r
    if upper_branch is None:
        upper_branch = True if r.v >= 0.5 else (False if r.v < 0.5 else None)
    if upper_branch:
        return s, sin(half_pi * complement)
    if upper_branch is False:
        return s, cos(half_pi * r)
    return s, join(sin(half_pi * complement), cos(half_pi * r))    # a box touching 1/2: either branch


def join(a: FE, b: FE) -> FE:
    """Either of two computations (a box that meets both branches of a float test)."""
    top = lambda x, y: arb(max(x.upper(), y.upper()))  # noqa: E731
    return FE(a.v.union(b.v), top(a.e, b.e), top(a.r, b.r), top(a.a, b.a), a.sign if a.sign == b.sign else 0)


def x_boxes() -> list:
    return [box(i / 8, (i + 1) / 8) for i in range(64)] + [box(2.0**k, 2.0 ** (k + 1)) for k in range(3, 10)]


def r_cover(n: int = 32) -> list:
    """(box, branch of half_pi_parts) covering r in [0, 1]; n even, so no box straddles 1/2."""
    return [(box(j / n, (j + 1) / n), j >= n // 2) for j in range(n)]


def prove_scattering_angle(module) -> Proof:
    with ctx.workprec(PREC):
        worst, boxes = arb(0), 0
        # x = fl(fl(fl(pi) |p|) / (2d)): three roundings, 2d exact (p and d beyond 2^1020 are divided by 4 first,
        # exactly: where p/4 falls below the normal range, x underflows to 0 with or without it)
        rho_x = (1 + U) ** 3 - 1
        # s and c depend on the r box only: computed once, not once per x box (the analysis never changes an
        # FE it is given, and each box gets its own ErrorContext, so every box sees the same operations)
        parts = [half_pi_parts(FE(r), upper) for r, upper in r_cover()]
        for x in x_boxes():
            fx = FE(x, _mag(x) * rho_x, rho_x, 0)
            for s, c in parts:
                angle = module._scattering_angle(ErrorContext(), fx, s, c)
                worst = max(worst, angle.e, key=lambda a: a.upper())
                boxes += 1
    bound_u = math.ceil(_in_u(worst))
    return Proof("scattering_angle", bound_u, boxes, "all $p$ and $d > 0$ with $pi abs(p)/(2 d) <= 1024$",
                 f"the computed $Deltapsi$ is within ${bound_u} u$ (absolute) of the exact one")


PROOFS = {"omega": prove_omega, "scattering_angle": prove_scattering_angle}   # omega_general added below
CLAIMS = {"omega": "`omega`: `float64` within $5e-15 abs(omega_i) + 1e-300 (abs(p)/d) sqrt(d^2 + 1)$ of the exact "
                   "$omega$",
          "scattering_angle": "`scattering_angle`: `float64` within absolute $1.5e-14$ of the exact $Deltapsi$",
          "omega_general": "`omega_general`: `float64` within $6e-15 B + 1e-300$ of the exact $omega$, "
                           "$B = (I11 I22 abs(I23) + I22 abs(I13) r + I11 I22 abs(I13) + I11 abs(I23) r)/D$"}


def method(proof: Proof) -> str:
    return METHOD.format(n=proof.boxes) + (f" (domain: {proof.domain}; `libm` calls within 4 ulp, square roots "
                                           "correctly rounded, every operation rounded: its exact result $x$ computed as "
                                           "$x (1 + e)$ with $abs(e) <= 2^(-53)$)")


MODEL_P = np.array([1.0, 3.0, 2.0, 0.5, 2.5, 1 + 1e-13, 3 - 1e-13, 2 + 1e-13, 7.3, -2.7, 1e-300, 1e6 + 0.5])
MODEL_D = np.array([1e-3, 0.31, 1.0, 7.0, 1e3])
MODEL_T = np.array([-1e4, -745.2, -30.0, -1.0, -1e-8, 0.0, 0.3, 5.0, 711.0, 1e4])


def modelled(module, name: str):
    """(public function's values, the analysed composition's values) at fixed points: the proof analyses
    the emitted core with its inputs computed as below (suslov.runtime.angle, phase.half_pi_parts,
    suslov.runtime.angular), so the public function must give the same bits."""
    from suslov.kernel.contexts import FLOAT

    if name == "omega":
        t, p, d = MODEL_T[:, None, None], MODEL_P[None, :, None], MODEL_D[None, None, :]
        public = np.stack(module.omega(t, p, d))
        core = np.stack([np.broadcast_to(w, public.shape[1:]) for w in module._omega(FLOAT, t, p, d)])
        return public, core
    if name == "omega_general":
        rng = np.random.default_rng(3435)
        entries = [rng.uniform(0.01, 3, 40), rng.uniform(0.01, 3, 40), rng.uniform(-2, 2, 40), rng.uniform(-2, 2, 40)]
        t = MODEL_T[:, None]
        public = np.stack(module.omega_general(t, *entries, -1))
        size = np.maximum(np.maximum(entries[0], entries[1]), np.maximum(np.abs(entries[2]), np.abs(entries[3])))
        I11, I22, I13, I23 = (e / size for e in entries)
        core = module._omega_general(FLOAT, t, I11, I22, I13, I23, -np.sqrt(I11 * I22))
        return public, np.stack([np.broadcast_to(w, public.shape[1:]) for w in core])
    p, d = MODEL_P[:, None], MODEL_D[None, :]
    quarter = np.where(np.maximum(np.abs(p), d) > 2.0**1020, 0.25, 1.0)
    x = np.pi * np.abs(p * quarter) / (2.0 * (d * quarter))
    r = np.abs(p - 2.0 * np.round(p / 2.0))
    s = np.sin(0.5 * np.pi * r)
    c = np.where(r >= 0.5, np.sin(0.5 * np.pi * (1.0 - r)), np.cos(0.5 * np.pi * r))
    with np.errstate(under="ignore", over="ignore"):
        return module.scattering_angle(p, d), module._scattering_angle(FLOAT, x, s, c)


def certificate(log: CertificateLog, module, name: str) -> Certificate:
    """Prove the bound of ``name`` for the emitted code of ``module`` and record it (pass when the proven
    bound is within the stated one; a box the analysis cannot bound is a failure naming the box)."""
    with stopwatch() as elapsed:
        try:
            proof = PROOFS[name](module)
            ok = proof.bound <= STATED[name]
            detail = (f"{proof.statement}, ${proof.bound_u} u = {proof.bound:.3g}$, at most ${STATED[name]:g}$" if ok
                      else f"proven only: {proof.statement}, ${proof.bound:.3g}$, above ${STATED[name]:g}$")
            public, core = modelled(module, name)
            same = public.shape == core.shape and np.array_equal(public, core)
            detail += (f"; the public function gives the analysed composition's bits at {core.size} points" if same
                       else "; the public function differs from the analysed composition (the run-time wrapper "
                            "computes its inputs otherwise)")
            ok = ok and same
            method_text, boxes = method(proof), proof.boxes
        except BoundFailure as failure:
            ok, detail, boxes = False, f"no bound: {failure}", 0
            method_text = METHOD.format(n="?")
    return log.record(Certificate(CLAIMS[name], "round trip", method_text, Outcome.PASS if ok else Outcome.FAIL,
                                  elapsed[0], boxes, detail))


def general_boxes() -> list:
    """Scaled entries (the largest magnitude is 1): I11, I22 in [1e-3, 1], one of |I13|, |I23| in [1e-3, 1], the
    other in [-1, 1].  The bound is in relative and magnitude forms, which do not depend on a box's width
    (narrower boxes give the same 53 u): the boxes only keep the divisor D away from 0, by its exact lower
    bound I11 I23^2 + I13^2 I22 >= 1e-9."""
    positive, anything = box(1e-3, 1.0), box(-1.0, 1.0)
    off = (box(1e-3, 1.0), -box(1e-3, 1.0))
    return ([(positive, positive, a, anything) for a in off] + [(positive, positive, anything, b) for b in off])


def prove_omega_general(module) -> Proof:
    """omega_general: the run-time wrapper divides the entries by the largest magnitude (each scaled entry within
    u of the exact ratio), r = sqrt(I11 I22) of the scaled entries, then the emitted core; the bound is in the
    magnitude form |w~ - w| <= W u B + A with B = sum |k_j| (the docstring's B: |T|, |S| <= 1)."""
    with ctx.workprec(PREC):
        worst, floor, boxes = arb(0), arb(0), 0
        for entries in general_boxes():
            I11, I22, I13, I23 = (FE(b, _mag(b) * U, U, 0) for b in entries)
            r = ErrorContext().sqrt(I11 * I22)
            for t in t_boxes(step=0.5):
                w1, w2 = module._omega_general(ErrorContext(), FE(t), I11, I22, I13, I23, r)
                for w in (w1, w2):
                    worst = max(worst, w.w, key=lambda a: a.upper())
                    floor = max(floor, w.aw, key=lambda a: a.upper())
                boxes += 1
    bound_u = math.ceil(_in_u(worst))
    if not floor < OMEGA_FLOOR:
        raise BoundFailure(f"omega_general: absolute part {floor} of the bound exceeds {OMEGA_FLOOR}")
    return Proof("omega_general", bound_u, boxes,
                 "all $t$, entries scaled by the largest magnitude: $I11 >= 10^(-3)$, $I22 >= 10^(-3)$, "
                 "$Max(abs(I13), abs(I23)) >= 10^(-3)$",
                 f"the computed $omega_i$ is within ${bound_u} u B + 1e-300$ of the exact one")


PROOFS["omega_general"] = prove_omega_general
