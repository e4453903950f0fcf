"""Proof of ``general_scattering_angle``'s float64 error bound, mixed forward-backward (issue 34; section ``gauss``).

``suslov.runtime.general_angle.general_scattering_angle`` scales the entries by the largest modulus (``size``),
then ``I13, I23`` by ``lam`` (so one of them is +-1), evaluates the emitted ``_gauss_invariants`` (U^2, a, b, c2),
the lengths of ``suslov.kernel.gauss_angle.float_lengths`` (U, gap = U - X, |Y|), ``h = pi U/(2 lam)``,
``g = pi gap/(2 lam)``, ``Y/lam``, ``phase.half_pi_parts(Y)`` and the emitted ``_general_angle(h, g, s, c)``.

The angle depends on Y modulo 2 (``s = |sin(pi Y/2)|``), so a relative error of Y moves it by about
(pi/2) |Y| times that error: the problem itself is ill-conditioned for large |Y|, and what can be proven of any
float64 evaluation is a *mixed* bound (Higham 2002, section 1.5): the computed angle is within ``E u`` of the exact
angle ``Delta psi(h', g', Y')`` at arguments within relative ``rho`` of the exact ``(h, g, Y)`` of a body whose
entries are within relative ``2u (1 + u)`` of the given ones.  Two stages, each with its own proof:

* **Stage 1** (entries -> h, g, Y), on the scaled floats taken as exact (the scalings' roundings are the
  backward error in the entries).  The emitted invariants are products, quotients and sums of positives, except
  ``C = I13^2 I22 - I11 I23^2`` in ``a = F C`` (``F = I11 I22 (I11 - I22)/D^2``, ``D = I11 I23^2 + I13^2 I22``):
  |C~ - C| <= gamma_3 D.  With ``M = |w^2| = |F| D`` (the identity C^2 + 4 I11 I22 I13^2 I23^2 = D^2), the pair
  ``(a, |b|)/M = (c, sqrt(1 - c^2))`` is on the unit circle, so ``float_lengths`` is walked once on normalised FE
  values over boxes of c in [-1, 1] (its operations are scale-invariant), the error of a^ being
  ``theta_F |c| + gamma_3 (1 + theta_F)``.  ``2U^2 - a = U^2 + V^2 >= max(U^2, |a|, M)`` bounds the one
  difference in the gap.  The operation counts are those of :func:`invariants_model`, checked bit for bit against
  the emitted ``_gauss_invariants``.
* **Stage 2** (h, g, s, c -> angle): the emitted ``_general_angle`` walked on FE values over boxes of
  ``(h, gamma = g/h)``, h from 2^-42 to 2^46 and gamma from 2^-24 to 1 + 2^-45 (stage 1's domain gives
  gamma >= D/8 >= 2^-23), with the inputs exact and ``s, c`` from the walk of ``half_pi_parts``.  The arguments
  ``2g - 2h``, ``2g - 4h``, ``-2g`` of the exponentials are intersected with their exact ranges over the box
  (``2 h (gamma - 1)`` ...): the independent balls of g and h would lose g <= h.

Domain: entries scaled by the largest modulus with I11, I22 >= 2^-20, and h = pi U/2 <= 7e13 (below 2^46 with the
relative error of h: closer to the equilibrium, 2(g - h) computed from g and h with their relative errors is no longer
small, and the walk next to g = h would need boxes of 2h(g/h - 1) narrower than float64 can tell).  Assumption shared with the other proofs: libm within 4 ulp.
"""
from __future__ import annotations

import functools
import math

import numpy as np
from flint import arb, ctx

from derivations.core.certificates import Certificate, CertificateLog, Outcome, stopwatch
from derivations.proofs.float_bounds import FE, METHOD, U, BoundFailure, ErrorContext, _fingerprint, gamma, hypot, largest
from derivations.proofs.float_bounds import sqrt as fe_sqrt
from derivations.proofs.float_proofs import PREC, box, half_pi_parts

ENTRY_FLOOR = 2.0**-20           # scaled I11, I22 >= 2^-20
H_RANGE = (2.0**-42, 2.0**46)    # h >= (pi/2) U, U >= I11 I22/D >= 2^-41; above 2^46 see the module docstring
GAMMA_RANGE = (2.0**-24, 1 + 2.0**-45)   # g~/h~ <= (1 + rho_g)/(1 - rho_h) <= 1 + 2^-45
TINY = arb(2) ** -800            # underflow of the non-maximal I13, I23 (absolute, relative to the scale M >= 2^-113)
UNDERFLOW = arb(2) ** -1000      # the same, relative to D >= 2^-20 and to I13^2 + I23^2 >= 1
STATED_U = 400                   # the docstring's E: within 400 u (about 4.5e-14)
STATED_RHO_U = 200               # the docstring's rho: within 200 u relative


# ---------------------------------------------------------------- stage 1


def invariants_model(I11, I22, I13, I23):
    """The emitted ``_gauss_invariants`` as analysed (NumPy or Python floats): the operation order of the counts
    in :func:`stage1`."""
    r = np.sqrt(I11) * np.sqrt(I22)
    D = I11 * (I23 * I23) + (I13 * I13) * I22
    C = -I11 * (I23 * I23) + (I13 * I13) * I22
    U2 = (I11 * I11) * (I22 * I22) * ((I13 * I13) + (I23 * I23)) / (D * D)
    a = I11 * I22 * (I11 - I22) * C / (D * D)
    b = -2 * I11 * I13 * I22 * I23 * r * (I11 - I22) / (D * D)
    c2 = (I11 * I11 * I11) * (I22 * I22 * I22) / (D * D)
    return U2, a, b, c2


def _lengths(a: FE, b: FE, branch: str):
    """``float_lengths`` after the invariants, on FE values: (modulus, X, Y) for the branch a >= 0 ('+') or a < 0."""
    b = abs(b)
    modulus = hypot(a, b)
    big = fe_sqrt(_fold(0.5 * (modulus + abs(a))))
    small = (0.5 * b) / big
    return (modulus, big, small) if branch == "+" else (modulus, small, big)


def _fold(fe: FE) -> FE:
    """The mixed bound r |x| + a as a relative one, r + a/min|x|, where the box keeps x away from 0."""
    low = fe.low
    return FE(fe.v, fe.e, fe.r + fe.a / low, 0, fe.sign) if low > 0 and fe.a > 0 else fe


def c_boxes(edge: arb) -> list:
    """c in [-1, 1]: [-1, -edge], [-edge, edge], [edge, 1] split in 16 each side (the middle box meets both branches)."""
    e = float(edge.upper())
    side = [(e + (1 - e) * j / 16, e + (1 - e) * (j + 1) / 16) for j in range(16)]
    return [("+", lo, hi) for lo, hi in side] + [("-", -hi, -lo) for lo, hi in side] + [("?", -e, e)]


def stage1() -> dict:
    """Relative error bounds of U, gap, Y and the modulus (stage 1), from the operation counts and the normalised walk."""
    eps_d = gamma(3) + UNDERFLOW                                       # D: two products and a sum of positives
    denominator = (1 - eps_d) ** 2 * (1 - U)                          # D~ D~ within that of D^2 (lower side)
    theta_f = (1 + U) ** 5 / denominator - 1                           # a = F C~: 5 roundings over D~^2
    theta_b = (1 + U) ** 10 / denominator - 1                          # b: 7 roundings and r's 3
    theta_u2 = (1 + U) ** 7 * (1 + UNDERFLOW) / denominator - 1       # I23^2 may underflow against I13^2 = 1
    theta_c2 = (1 + U) ** 6 / denominator - 1
    eps_c = gamma(3)                                                   # |C~ - C| <= gamma_3 D
    worst = {"X": arb(0), "Y": arb(0), "M": arb(0), "absolute": arb(0)}
    boxes = c_boxes(2 * (theta_f + eps_c * (1 + theta_f)) + 2 * TINY)
    for branch, lo, hi in boxes:
        c = box(lo, hi)
        beta = (1 - c * c).nonnegative_part().sqrt()
        a_hat = FE(c, 0, theta_f, eps_c * (1 + theta_f) + TINY)
        b_hat = FE(beta, 0, theta_b, TINY, sign=1)
        for path in (("+", "-") if branch == "?" else (branch,)):
            modulus, X, Y = _lengths(a_hat, b_hat, path)
            worst["M"] = largest(worst["M"], modulus.e)          # the exact modulus is 1: absolute = relative
            for name, fe in (("X", X), ("Y", Y)):
                if branch == "?":
                    # the computed branch may differ from the exact sign's; X, Y both within [sqrt((1-e)/2), sqrt((1+e)/2)]
                    e = arb(max(abs(lo), abs(hi)))
                    spread = ((1 + e) / 2).sqrt() - ((1 - e) / 2).sqrt()
                    worst[name] = largest(worst[name], (fe.e + spread) / ((1 - e) / 2).sqrt())
                else:
                    worst[name] = largest(worst[name], fe.r)
                    worst["absolute"] = largest(worst["absolute"], fe.a)    # underflow of b (units of sqrt(M) <= 1)
    theta_x, theta_y, theta_m = worst["X"], worst["Y"], worst["M"]
    theta_u = (2 - (1 - theta_u2).sqrt()) * (1 + U) - 1
    theta_d1 = (1 + 2 * theta_u2 + theta_f + eps_c * (1 + theta_f) + TINY) * (1 + U) - 1       # 2U^2 - a
    theta_d2 = (1 + largest(theta_d1, theta_m)) * (1 + U) - 1                                        # + modulus
    # U + X: X's absolute part (units of sqrt(M) <= 2^10) against U + X >= U >= 2^-41
    theta_d3 = (1 + largest(theta_u, theta_x) + worst["absolute"] * arb(2) ** 51) * (1 + U) - 1
    theta_gap = (1 + theta_c2) * (1 + U) / ((1 - theta_d2) * (1 - theta_d3) * (1 - U)) - 1
    rho_h = (1 + theta_u) * (1 + U) ** 3 - 1
    rho_g = (1 + theta_gap) * (1 + U) ** 3 - 1
    rho_y = (1 + theta_y) * (1 + U) - 1
    # stage 2's cover must hold every computed (h, g/h): exact g/h in [D/8, 1] with D >= 2^-20, h >= (pi/2) 2^-41
    if not ((1 + rho_g) / (1 - rho_h) <= GAMMA_RANGE[1] and arb(2) ** -23 * (1 - rho_g) / (1 + rho_h) >= GAMMA_RANGE[0]
            and arb.pi() / 2 * arb(2) ** -41 * (1 - rho_h) >= H_RANGE[0]):
        raise BoundFailure("stage 1's relative bounds leave the (h, g/h) domain that stage 2 covers")
    # Y's absolute part is in units of sqrt(M)/lam: M <= 2^20 (D >= 2^-20) and 1/lam <= 2^88 (h <= 2^46, U >= 2^-41)
    return {"h": rho_h, "g": rho_g, "Y": rho_y, "Y absolute": worst["absolute"] * arb(2) ** 98, "boxes": len(boxes)}


# ---------------------------------------------------------------- stage 2


class RelatedContext(ErrorContext):
    """ErrorContext whose exponentials see the exact ranges of 2g - 2h, 2g - 4h and -2g over an (h, gamma) box."""

    def __init__(self, h: FE, g: FE, ranges: dict):
        super().__init__()
        self._ranges = {_fingerprint(expression(h, g)): exact for expression, exact in ranges}

    def _related(self, x):
        exact = self._ranges.get(_fingerprint(x))
        if exact is None:
            return x
        return FE(x.v.intersection(exact), x.e, x.r, x.a)

    def expm1(self, x):
        return super().expm1(self._related(x))

    def exp(self, x):
        return super().exp(self._related(x))


def hull(*values) -> arb:
    """A ball containing the convex hull of exact end values (arb's product of two wide balls would widen it)."""
    ball = values[0]
    for value in values[1:]:
        ball = ball.union(value)
    return ball


def angle_on_box(module, h_lo: float, h_hi: float, g_lo: float, g_hi: float) -> arb:
    """The worst absolute error bound of the emitted angle over h in [h_lo, h_hi], g/h in [g_lo, g_hi] (both r
    branches).  Exact ranges from the ends (every function below is monotone in h and in gamma on the box)."""
    H0, H1, G0, G1 = (arb(v) for v in (h_lo, h_hi, g_lo, g_hi))
    h = FE(hull(H0, H1), 0, 0, 0, sign=1)
    g = FE(hull(H0 * G0, H1 * G1), 0, 0, 0, sign=1)
    ends = [(x, y) for x in (H0, H1) for y in (G0, G1)]
    ranges = [(lambda h, g: 2 * g - 2 * h, hull(*(2 * x * (y - 1) for x, y in ends))),
              (lambda h, g: 2 * g - 4 * h, hull(*(2 * x * (y - 2) for x, y in ends))),
              (lambda h, g: -2 * g, hull(*(-2 * x * y for x, y in ends))),
              (lambda h, g: -2 * h, hull(-2 * H0, -2 * H1))]
    worst = arb(0)
    for s, c in _half_pi_branches():
        angle = module._general_angle(RelatedContext(h, g, ranges), h, g, s, c)
        worst = largest(worst, angle.e)
    return worst


@functools.cache
def _half_pi_branches() -> tuple:
    """(s, c) of ``half_pi_parts`` on r in [0, 1/2] and in [1/2, 1] (the same for every box, so walked once)."""
    with ctx.workprec(PREC):
        return tuple(half_pi_parts(FE(r), upper) for r, upper in ((box(0, 0.5), False), (box(0.5, 1), True)))


def stage2(module, target_u: float = STATED_U) -> tuple:
    """(worst bound, boxes walked): a cover of the (h, gamma) domain, boxes bisected until each proves target_u."""
    target = target_u * U
    walked = [0]

    def cover(h_lo, h_hi, g_lo, g_hi, depth):
        walked[0] += 1
        try:
            bound = angle_on_box(module, h_lo, h_hi, g_lo, g_hi)
            if bound <= target:
                return bound
        except BoundFailure:
            bound = None
        if g_hi >= 1 and 1 - g_lo > 2.0**-50 and depth < 64:
            # next to g = h the box of 2h(gamma - 1) must be narrow against its size: halve 1 - gamma
            middle = 1 - (1 - g_lo) / 2
            return max(cover(h_lo, h_hi, g_lo, middle, depth + 1), cover(h_lo, h_hi, middle, g_hi, depth + 1),
                       key=lambda v: v.upper())
        if depth >= 14:
            raise BoundFailure(f"general angle: no bound below {target_u} u on h in [{h_lo:.3g}, {h_hi:.3g}], "
                               f"g/h in [{g_lo:.3g}, {g_hi:.3g}]" + ("" if bound is None else f" ({bound})"))
        h_mid = math.sqrt(h_lo * h_hi) if h_hi > 2 * h_lo else (h_lo + h_hi) / 2
        g_mid = math.sqrt(g_lo * g_hi) if g_hi > 2 * g_lo else (g_lo + g_hi) / 2
        return max((cover(a, b, c, d, depth + 1) for a, b in ((h_lo, h_mid), (h_mid, h_hi))
                    for c, d in ((g_lo, g_mid), (g_mid, g_hi))), key=lambda v: v.upper())

    worst = arb(0)
    # h boxes of ratio at most 2^16: a ball's radius has 30 bits, so a box [lo, hi] reaches about 2^-30 hi beyond its
    # ends, which must stay small against lo (exp(-2h) of a box reaching past 0 would be useless)
    h_edges = [H_RANGE[0] * 2.0 ** (4 * k) for k in range(0, 23)]
    g_edges = [GAMMA_RANGE[0] * 2.0 ** (4 * k) for k in range(0, 6)] + [GAMMA_RANGE[1]]
    for h_lo, h_hi in zip(h_edges, h_edges[1:]):
        for g_lo, g_hi in zip(g_edges, g_edges[1:]):
            worst = largest(worst, cover(h_lo, h_hi, g_lo, g_hi, 0))
    return worst, walked[0]


# ---------------------------------------------------------------- the checks tying the proof to the run-time code


def lengths_model(U2, a, b, c2):
    """``gauss_angle.float_lengths`` as analysed, for Python floats: (U, gap, |Y|)."""
    b = abs(b)
    modulus = float(np.hypot(a, b))
    big = math.sqrt(0.5 * (modulus + abs(a)))
    small = 0.5 * b / big if big > 0 else 0.0
    X, Y = (big, small) if a >= 0 else (small, big)
    U = math.sqrt(U2)
    return U, 2.0 * c2 / ((2.0 * U2 - a + modulus) * (U + X)), Y


def composition_model(module, I11, I22, I13, I23) -> float:
    """The run-time composition as analysed, one body (Python floats): scalings, invariants, lengths, h, g, Y.

    Beyond the proof's domain it follows the run time's contract, as it must for the bit check: h and g capped
    at ``_HUGE``, float64's NaN and inf where Python would raise (``lam`` = 0 when the scaled I13, I23 underflow;
    ``Y/lam`` beyond float64 when ``lam`` is subnormal), and where the float composition has no finite value the
    formula again in mpmath (``finite.repair``), as the public function does (issue 43: the model raised
    OverflowError there, where the public function returns the angle)."""
    from suslov.kernel import finite, gauss_angle
    from suslov.kernel.contexts import FLOAT, MP
    from suslov.runtime.general_angle import _HUGE, NAMES

    body = (I11, I22, I13, I23)
    size = max(I11, I22, abs(I13), abs(I23))
    I11, I22, I13, I23 = I11 / size, I22 / size, I13 / size, I23 / size
    lam = np.float64(max(abs(I13), abs(I23)))     # NumPy's division: 0/0 is NaN, x/0 inf, as at run time
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        U2, a, b, c2 = (float(v) for v in invariants_model(I11, I22, I13 / lam, I23 / lam))
        U, gap, Y = lengths_model(U2, a, b, c2)
        h, g, Y = (float(v) for v in (min(0.5 * math.pi * U / lam, _HUGE), min(0.5 * math.pi * gap / lam, _HUGE),
                                      Y / lam))
    if math.isfinite(Y):
        r = abs(Y - 2.0 * round(Y / 2.0))
        s = math.sin(0.5 * math.pi * r)
        c = math.sin(0.5 * math.pi * (1.0 - r)) if r >= 0.5 else math.cos(0.5 * math.pi * r)
    else:
        s = c = math.nan          # half_pi_parts of a non-finite Y
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        angle = float(module._general_angle(FLOAT, np.float64(h), np.float64(g), np.float64(s), np.float64(c)))
    if math.isfinite(angle):
        return angle
    (angle,) = finite.repair("general_scattering_angle", (np.array(angle),), NAMES, tuple(np.array(x) for x in body),
                             lambda *entries: (module._general_angle(
                                 MP, *gauss_angle.mp_arguments(*module._gauss_invariants(MP, *entries))),))
    return float(angle)


def seeded_bodies(count: int = 400) -> list:
    """Bodies in the domain (and its edges): random entries, I11 = I22, I13 or I23 zero or tiny, near the equilibrium."""
    rng = np.random.default_rng(3434)
    bodies = [(2.0, 1.0, 0.0, -1.0), (2.0, 1.0, 0.0, -1 / 3), (1.0, 1.0, 0.5, 0.5), (1.25, 1.0, 0.3, -0.5),
              (1.0, 2.0, 1e-200, 0.2), (3.0, 3.0 * (1 - 2**-50), 0.7, 0.01), (2.0, 1.0, 1e-9, -2e-9)]
    for _ in range(count):
        I11, I22 = (float(v) for v in 10 ** rng.uniform(-5, 0, 2))
        I13, I23 = (float(v) for v in rng.uniform(-1, 1, 2) * 10 ** rng.uniform(-6, 0))
        bodies.append((I11, I22, I13, I23))
    return bodies


def same_operations(module) -> tuple:
    """(ok, points): the emitted invariants, float_lengths and the run-time composition compute the analysed
    sequences bit for bit (the emitted angle itself is what stage 2 walks)."""
    from suslov.kernel import gauss_angle
    from suslov.kernel.contexts import FLOAT

    bodies = seeded_bodies()
    columns = [np.array(column) for column in zip(*bodies)]
    size = np.maximum(np.maximum(columns[0], columns[1]), np.maximum(np.abs(columns[2]), np.abs(columns[3])))
    scaled = [column / size for column in columns]
    lam = np.maximum(np.abs(scaled[2]), np.abs(scaled[3]))
    entries = (scaled[0], scaled[1], scaled[2] / lam, scaled[3] / lam)
    emitted = module._gauss_invariants(FLOAT, *entries)
    ok = all(np.array_equal(x, y) for x, y in zip(emitted, invariants_model(*entries)))
    lengths = gauss_angle.float_lengths(*emitted)
    modelled = np.array([lengths_model(*(float(v[i]) for v in emitted)) for i in range(len(bodies))]).T
    ok = ok and all(np.array_equal(x, y) for x, y in zip(lengths, modelled))
    public = module.general_scattering_angle(*columns)
    ok = ok and np.array_equal(public, np.array([composition_model(module, *body) for body in bodies]))
    return bool(ok), len(bodies)


def prove(module) -> dict:
    with ctx.workprec(PREC):
        first = stage1()
        worst, walked = stage2(module)
    return {**first, "angle": worst, "boxes": first["boxes"] + walked}


CLAIM = ("`general_scattering_angle`: `float64` within $400 u$ of the exact angle at arguments within relative $200 u$ "
         "of the exact $h = pi U/2$, $g = pi (U - X)/2$, $Y$ of a body whose entries are within relative $2 u (1 + u)$ "
         "of the given ones (mixed forward-backward bound)")


def certificate(log: CertificateLog, module) -> Certificate:
    """Prove the mixed bound for the emitted code of ``module`` and record it."""
    with stopwatch() as elapsed:
        try:
            proof = prove(module)
            angle_u = math.ceil(float((proof["angle"] / U).upper()))
            rho_u = {k: math.ceil(float((proof[k] / U).upper())) for k in ("h", "g", "Y")}
            same, points = same_operations(module)
            ok = angle_u <= STATED_U and max(rho_u.values()) <= STATED_RHO_U and same
            y_absolute = float(proof["Y absolute"].upper())
            ok = ok and y_absolute < 1e-190
            detail = (f"proven: angle within ${angle_u} u$ of the exact one at the computed $h$, $g$, $Y$; these within "
                      f"relative ${rho_u['h']} u$, ${rho_u['g']} u$, ${rho_u['Y']} u$ (and $Y$ absolute "
                      f"${y_absolute:.0e}$, underflow) of the exact ones; run-time operations as analysed, bit for bit "
                      f"at {points} bodies: {'yes' if same else 'no'}")
            boxes = proof["boxes"]
        except BoundFailure as failure:
            ok, detail, boxes = False, f"no bound: {failure}", 0
    method = METHOD.format(n=boxes) + (" (domain: entries scaled by the largest modulus with $I11 >= 2^(-20)$, "
                                       "$I22 >= 2^(-20)$, and $pi U/2 <= 7e13$; stage 1 by operation counts and a walk "
                                       "of the normalised lengths over boxes of $a/abs(w^2)$, stage 2 the emitted angle "
                                       "over boxes of $(h, g/h)$; `libm` calls within 4 ulp)")
    return log.record(Certificate(CLAIM, "round trip", method, Outcome.PASS if ok else Outcome.FAIL, elapsed[0], boxes,
                                  detail))


def certificates(log: CertificateLog, module) -> list:
    """The certificate, for a module that has the closed-form general angle (a tree from before it has not)."""
    return [certificate(log, module)] if hasattr(module, "general_scattering_angle") else []
