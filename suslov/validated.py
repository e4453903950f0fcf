"""Rigorous enclosures, monodromy and the Galois group of any body (section 5.1, Theorem 5.4, eq:o12, Conclusion).

The angle between the limit rotation axes of the ss solution (``gamma(-oo) = -n``,
``cos Delta psi = -<gamma(+oo), n>``, the angle from its cosine and its sine), as a python-flint ball, for any inertia tensor
with I12 = 0 and a = e3 -- I13 != 0 included.  Two routes: the certified closed form of every body
(``method="closed_form"``, the default: Gauss's equation in s = sinh t, ``derivations/sections/general_angle.py``)
and, as the independent check, validated integration (``method="integration"``).  The coefficients
u, v of ``omega(s) = u tanh s + v sech s`` come from the generated module's *emitted* closed form
``_omega_general`` (certified, model:011), evaluated with probe values of (tanh, sech): exact,
because the emitted function is linear in them.  The enclosure itself is
:func:`suslov.kernel.enclosure.ss_angle_enclosure` (method and bounds in its module docstring).
For I13 = 0 the ball contains the closed form ``scattering_angle(p, d)`` (Theorem 5.4, corrected),
checked by the build (``scattering`` certificates, method "ball enclosure").
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

from flint import acb, arb, ctx

from suslov.kernel.enclosure import (
    DIGITS_RANGE,
    MAX_SECONDS,
    AngleEnclosure,
    EnclosureTooCostly,
    ss_angle_enclosure,
    to_arb,
)
from suslov.kernel.cost import enclosure_seconds, monodromy_seconds, seconds_limit
from suslov.kernel.gauss_angle import gauss_parameters
from suslov.kernel.kimura import GaloisGroup, exact_body, exact_invariants
from suslov.kernel.kimura import galois_group as _galois_group
from suslov.kernel.local_behaviour import LocalBehaviour
from suslov.kernel.local_behaviour import local_behaviour as _local_behaviour
from suslov.kernel.reprs import hypergeometric_html, hypergeometric_latex
from suslov.kernel.validate import MAX_ENTRY_BITS  # noqa: F401 (the one size limit of exact input, named here too)
from suslov.kernel.validate import PREC_RANGE, ball_prec, mp_dps, precision, renamed_keywords, shown
from suslov.loader import gf

__all__ = ["AngleEnclosure", "EnclosureTooCostly", "GaloisGroup", "HypergeometricForm", "MonodromyTooCostly",
           "LocalBehaviour", "galois_group", "local_behaviour",
           "hypergeometric_form", "monodromy", "omega_coefficients", "scattering_angle_enclosure"]


class _Probe:
    """A number context whose (tanh, sech) are fixed values: extracts the coefficients of the
    emitted omega, which is linear in (tanh t, sech t)."""

    def __init__(self, tanh, sech):
        self._pair = (arb(tanh), arb(sech))

    def tanh_sech(self, t):
        return self._pair

    sqrt = staticmethod(lambda x: arb(x).sqrt())


def omega_coefficients(I11, I22, I13, I23, branch: int = 1) -> tuple:
    """(u, v), each a pair of balls, with omega(s) = u tanh s + v sech s (rate 1, paper frame).

    Taken from the generated module's emitted ``_omega_general`` (certified, model:011).
    """
    I11, I22, I13, I23 = (to_arb(n, x) for n, x in (("I11", I11), ("I22", I22), ("I13", I13), ("I23", I23)))
    for name, x in (("I11", I11), ("I22", I22)):
        if not x > 0:
            raise ValueError(f"{name}={x}: must be positive")
    if I13.is_zero() and I23.is_zero():
        raise ValueError("I13=0 and I23=0: the constraint axis is a principal axis, every motion is an equilibrium")
    if branch not in (1, -1):
        raise ValueError(f"branch={branch!r}: must be +1 or -1")
    r = branch * (I11 * I22).sqrt()
    u = gf._omega_general(_Probe(1, 0), None, I11, I22, I13, I23, r)
    v = gf._omega_general(_Probe(0, 1), None, I11, I22, I13, I23, r)
    return tuple(u), tuple(v)


@dataclass(frozen=True)
class HypergeometricForm:
    """Gauss's equation z(1-z)F'' + (C - (A+B+1)z)F' - AB F = 0 of a body (see :func:`hypergeometric_form`)."""

    A: acb
    B: acb
    C: acb
    points: dict                  # "s=i", "s=-i", "s=oo" -> 0, 1, "oo" (z = (1 + i s)/2)
    exponent_differences: dict    # of the spinor lift: "s=i" -> kappa, "s=-i" -> mu, "s=oo" -> i U
    gauss_exponent_differences: tuple   # (1 - C, C - A - B, A - B) up to sign: (kappa, mu, 1 + i U)
    exact: dict | None            # exact input: U^2, Re w_-^2 (Fractions), Im w_-^2 = q sqrt(R) as (q, R)

    def _repr_latex_(self) -> str:   # notebooks: the equation, A, B, C and the exact invariants (suslov.kernel.reprs)
        return hypergeometric_latex(self)

    def _repr_html_(self) -> str:
        return hypergeometric_html(self)


def hypergeometric_form(I11, I22, I13, I23, dps: int | None = None, prec: int | None = None) -> HypergeometricForm:
    """Gauss's hypergeometric equation of the Poisson equations of a body (the general case in closed form).

    With s = sinh t, the spinor lift of eq:whole, psi1 = z^(kappa/2) (1-z)^(mu/2) F(z), z = (1 + i s)/2
    (certified: ``gauss``), gives Gauss's equation with ``A = (2 + kappa + mu + iU)/2``,
    ``B = (kappa + mu - iU)/2``, ``C = 1 + kappa``; ``kappa = (i/2) w_-``, ``mu = (i/2) w_+``,
    ``w_-+^2 = (u -+ i v).(u -+ i v)``, ``U^2 = u.u`` for omega = u tanh t + v sech t.  ``A``, ``B``, ``C``
    are complex balls at ``prec`` bits or ``dps`` digits (default ``mpmath.mp.prec``); for exact input (ints, Fractions,
    decimal strings, floats as their binary value) ``exact`` holds the squares exactly.

    The balls are formed from those exact squares (:func:`suslov.kernel.gauss_angle.gauss_parameters`): the
    differences that cancel (``I11 - I22`` of a nearly symmetric body, ``U - X``, ``1 - Y/2``) are taken in
    exact integers, so every real and imaginary part that is not exactly 0 carries ``prec`` bits relative to
    itself for entries of any size (``hypergeometric_form(10**100, 10**100 - 1, 10**99, 3)``).  The working
    precision is doubled while a part falls short of that (up to 8 times ``prec + 20``), then a
    ``ValueError`` says so -- never a NaN.  Entries whose numerator or denominator exceeds
    ``MAX_ENTRY_BITS`` (:mod:`suslov.kernel.validate`: 20000 bits, about 6000 digits; the exact invariants cost
    about the square of the size) are refused with a ``ValueError`` naming the entry, strings before they are
    converted (``"1e10000000"``).

    >>> form = hypergeometric_form(2, 1, 0, "-1/3")       # I13 = 0, p = 3: kappa = -3/2
    >>> form.points["s=i"], form.C.real.mid() == -0.5, form.exact["Re w_-^2"]
    (0, True, Fraction(-9, 1))
    """
    exact_values = exact_body(I11, I22, I13, I23)   # at most MAX_ENTRY_BITS each, checked before conversion
    exact = exact_invariants(*exact_values)
    target = ball_prec(dps, prec)
    working = target + 20
    while True:
        with ctx.workprec(working):
            A, B, C, kappa, mu, iU = gauss_parameters(exact["U^2"], exact["Re w_-^2"], *exact["Im w_-^2"])
        short = [f"{name}.{part}" for name, z in (("A", A), ("B", B), ("C", C))
                 for part, x in (("real", z.real), ("imag", z.imag))
                 if not x.is_finite() or not (x.is_zero() or x.rel_accuracy_bits() >= target)]
        if not short:
            break
        if working >= 8 * (target + 20):
            body = ", ".join(shown(x) for x in (I11, I22, I13, I23))
            raise ValueError(f"hypergeometric_form({body}): "
                             f"{', '.join(short)} not within {target} bits at {working} working bits; this body "
                             f"needs more than {working} bits of working precision")
        working *= 2
    return HypergeometricForm(A, B, C, {"s=i": 0, "s=-i": 1, "s=oo": "oo"},
                              {"s=i": kappa, "s=-i": mu, "s=oo": iU}, (kappa, mu, 1 + iU), exact)


def galois_group(I11, I22, I13, I23) -> GaloisGroup:
    """The differential Galois group of the Poisson equations of a body, decided exactly (Kimura's theorem).

    ``group``: "reducible" (the torus SO(2,C) of rotations about ``u/|u|``; Liouvillian) exactly when
    ``u.v = 0`` and ``w_-^2 = -P^2`` with P odd (I13 = 0 with odd p, or I23 = 0 with odd p by eq:lina), else
    "SO(3,C)"; ``method`` says "exact".  Entries are read exactly (decimal strings and floats as the
    numbers they are), at most ``MAX_ENTRY_BITS`` bits each (:mod:`suslov.kernel.validate`).  The equilibrium
    I13 = I23 = 0 and I11 <= 0 or I22 <= 0 raise ``ValueError``.
    The theorem and its proof: :mod:`suslov.kernel.kimura`.

    >>> g = galois_group("5/4", 1, "3/10", "-1/2")
    >>> g.group, g.liouvillian, "exact" in g.method
    ('SO(3,C)', False, True)
    """
    return _galois_group(I11, I22, I13, I23)


def local_behaviour(I11, I22, I13, I23) -> LocalBehaviour:
    """Meromorphic, logarithmic or branching at the poles of omega, decided exactly for any body (a theorem for every p).

    ``kind`` is "meromorphic" (the Kovalevskaya exponent Lambda an odd integer: every solution of the Poisson
    equations is meromorphic at every pole t0 = +-i pi/2 + i pi k), "logarithmic" (Lambda even, 0 included) or
    "branching" (Lambda not an integer); ``Lambda``, ``lambda_squared`` (exact), ``exponents`` at t0 and
    ``reason``.  For I13 = 0, Lambda = p: Theorem 3.2 and its converse, and the logarithms of Conjecture 1, for
    every p.  Entries are read exactly as in :func:`galois_group` (same limits, same ValueError).  The theorem
    and its proof: :mod:`suslov.kernel.local_behaviour`.

    >>> local_behaviour(2, 1, 0, "-1/101").kind, local_behaviour(2, 1, 0, "-1/100").Lambda   # p = 101, p = 100
    ('meromorphic', 100)
    >>> local_behaviour(2, 1, 0, "-1/100").kind
    'logarithmic'
    """
    return _local_behaviour(I11, I22, I13, I23)


def scattering_angle_enclosure(I11, I22, I13, I23, branch: int = 1, dps: int | None = None,
                               prec: int | None = None, max_seconds: float | None = MAX_SECONDS,
                               progress=None, method: str = "closed_form", **deprecated) -> AngleEnclosure:
    """Rigorous enclosure of the scattering angle of any body (I12 = 0 frame, a = e3, I11, I22 > 0).

    Entries are ints, Fractions, decimal strings (exact) or floats (their binary value).  For
    I13 = 0 the result contains the closed form of Theorem 5.4 (``scattering_angle``).
    ``dps``: the decimal digits asked of the ball, an integer in [1, 300] (default ``mpmath.mp.dps``; the old
    name ``digits=`` still works, with a ``DeprecationWarning``); ``prec`` (working bits, default
    3.33 dps + 40) in [16, 100000].
    ``method="closed_form"`` (default): the certified closed form of every body
    (``general_scattering_angle_ball``) in ball arithmetic, milliseconds even at 300 digits;
    ``method="integration"``: validated integration of the ss solution (the independent route the
    build checks the closed form against).  The integration's cost grows with digits and with ``|omega|`` (like p^2 as I23 -> 0 when I13 = 0): beyond
    ``max_seconds`` (default 120 s; None for no limit) it stops with
    :class:`suslov.kernel.enclosure.EnclosureTooCostly` saying how far it got and the estimated total;
    ``progress(fraction, seconds, estimated_total_or_None)`` is called at most once a second.

    >>> e = scattering_angle_enclosure("5/4", 1, "0.3", "-0.5", dps=12)
    >>> e.width < 1e-11, e.angle.contains(e.angle.mid())
    (True, True)
    """
    dps = renamed_keywords("scattering_angle_enclosure", deprecated, digits="dps").get("dps", dps)
    digits = precision("dps", mp_dps(None) if dps is None else dps, DIGITS_RANGE)
    if prec is not None:
        prec = precision("prec", prec, PREC_RANGE, "bits")
    if method not in ("closed_form", "integration"):
        raise ValueError(f"method={method!r}: must be 'closed_form' or 'integration'")
    if method == "closed_form":
        return _closed_form_enclosure(I11, I22, I13, I23, branch, digits, prec)
    limit = seconds_limit(max_seconds)
    with ctx.workprec(int(prec if prec is not None else 3.33 * digits + 40)):
        u, v = omega_coefficients(I11, I22, I13, I23, branch)
    size = max(float(abs(x).upper()) for x in u + v)
    estimate = enclosure_seconds(size, digits)
    if progress is not None:
        progress(0.0, 0.0, estimate)
    if limit is not None and estimate > limit:
        raise EnclosureTooCostly(
            f"enclosure not started: about {estimate:.3g} s estimated (|omega| coefficients up to {size:.3g}, "
            f"digits={digits}; kernel/cost.py) exceeds max_seconds={limit:g}: the body is near the equilibrium "
            "I13 = I23 = 0 or digits is high; method='closed_form' (the default) encloses the same angle in "
            "milliseconds; max_seconds=None integrates anyway")
    return ss_angle_enclosure(u, v, digits=digits, prec=prec, max_seconds=limit, progress=progress)


def _closed_form_enclosure(I11, I22, I13, I23, branch, digits, prec) -> AngleEnclosure:
    if branch not in (1, -1):
        raise ValueError(f"branch={branch!r}: must be +1 or -1")
    bits = prec if prec is not None else int(3.33 * digits + 40)
    angle = gf.general_scattering_angle_ball(I11, I22, I13, I23, prec=bits)
    with ctx.workprec(bits):
        cos_angle = angle.cos()
    return AngleEnclosure(angle, cos_angle, (), 0, 0, bits, {"closed_form": float(angle.rad())}, (), ())


class MonodromyTooCostly(RuntimeError):
    """The monodromy would take (or took) longer than ``max_seconds``; the message gives the estimate, the
    working digits it needs and the Galois group decided exactly."""


def monodromy(I11, I22, I13, I23, dps: int | None = None, branch: int = 1, max_dps: int | None = None,
              max_seconds: float | None = MAX_SECONDS, progress=None, **deprecated):
    """Certified monodromy and differential Galois group of the Poisson equations of any body.

    The paper's open problem (Conclusion): for omega(t) = u tanh t + v sech t (eq:o12, this body's
    coefficients from :func:`omega_coefficients`), the Poisson equations eq:whole in x = e^t are a
    Fuchsian system with singular points 0, +i, -i, oo.  Returns a
    :class:`suslov.kernel.monodromy.Monodromy`: ``matrices`` (``"x=0"``, ``"x=i"``, ``"x=-i"``,
    ``"x=oo"`` -> python-flint ``acb_mat`` with radii about 10^-digits, at the base x = 1/2),
    ``exponents`` (per singular point), ``verdict`` (``"SO(3,C)"``, ``"reducible"``, ``"unknown"``;
    ``"imprimitive"`` and ``"finite"`` are never concluded from balls), ``liouvillian`` (True, False or
    None) and ``certificates`` (claim, pass/fail/unknown, detail).  The theorems each step uses are in
    :mod:`suslov.kernel.monodromy`.  ``dps`` in [10, 200] (default ``max(mpmath.mp.dps, 10)``; the old names
    ``digits=`` and ``max_digits=`` still work, with a ``DeprecationWarning``): the radius 10^-dps asked of
    every entry.  Near
    I13 = I23 = 0 ``|omega|`` is large, the entries grow like ``exp(2 pi |u|)`` and the Taylor sums
    cancel; the loops then run with ``result.guard`` extra digits (estimated from the body, increased
    once if the radius still comes out wider than asked), and not at all beyond
    ``suslov.kernel.monodromy.MAX_WORKING_DIGITS`` (verdict "unknown", saying how many digits it would
    take).  When a test is still undecided the computation is repeated at twice the digits up to
    ``max_dps`` (default ``min(4 dps, 200)``); ``result.digits`` says which precision decided.
    "reducible" (odd p) needs the exact no-logarithm certificate of that p: I13 = 0, or I23 = 0 by
    eq:lina, and p at most the loaded formulas' ``PMAX`` (beyond it: "unknown").

    Time: before integrating, the cost of a pass is estimated from ``dps + guard``
    (:mod:`suslov.kernel.cost`); above ``max_seconds`` (default 120 s; None: no limit) nothing is
    integrated and :class:`MonodromyTooCostly` says the estimate, the working digits and the group
    decided exactly (:func:`galois_group`, the closed form: microseconds).  While running, the limit is
    checked between loops; ``progress(fraction, seconds, estimated_total)`` is called before each loop.

    >>> m = monodromy("5/4", 1, "3/10", "-1/2", dps=20)
    >>> m.verdict, m.liouvillian
    ('SO(3,C)', False)
    """
    from suslov.kernel.fuchsian_flow import guard_digits, residues
    from suslov.kernel.monodromy import MAX_WORKING_DIGITS, compute_monodromy, decide_group

    old = renamed_keywords("monodromy", deprecated, digits="dps", max_digits="max_dps")
    dps, max_dps = old.get("dps", dps), old.get("max_dps", max_dps)
    digits = precision("dps", max(mp_dps(None), 10) if dps is None else dps, (10, 200))
    ceiling = min(4 * digits, 200) if max_dps is None else precision("max_dps", max_dps, (digits, 200))

    def coefficients(working_digits: int):
        # beyond MAX_WORKING_DIGITS nothing is integrated (compute_monodromy says so): no precision of 1e300 digits
        with ctx.workprec(int(3.33 * min(working_digits, MAX_WORKING_DIGITS + 1)) + 64):
            return omega_coefficients(I11, I22, I13, I23, branch)

    limit = seconds_limit(max_seconds)
    u, v = coefficients(digits)
    guard = guard_digits(residues(u, v))
    exact, detail = _exact_trivial_at_poles(I11, I22, I13, I23)
    clock = _MonodromyClock((I11, I22, I13, I23), limit, progress)
    while True:
        clock.before_pass(digits, guard)
        # u, v at the working precision: their radii bound the monodromy's
        u, v = coefficients(digits + guard)
        mono = compute_monodromy(u, v, digits, guard, on_loop=clock.loop)
        if mono.matrices and mono.radius > 10.0 ** (1 - digits):   # the guard was too small: once more, measured
            guard += math.ceil(math.log10(mono.radius)) + digits + 5
            clock.before_pass(digits, guard)
            u, v = coefficients(digits + guard)
            mono = compute_monodromy(u, v, digits, guard, on_loop=clock.loop)
        result = decide_group(mono, exact_trivial_at_poles=exact, exact_detail=detail)
        if result.verdict != "unknown" or digits >= ceiling or not mono.matrices:
            return _with_exact_decision(result, I11, I22, I13, I23)
        digits = min(2 * digits, ceiling)


class _MonodromyClock:
    """The time limit and the progress reports of :func:`monodromy` (estimates: :mod:`suslov.kernel.cost`)."""

    def __init__(self, body, limit, progress):
        self.body, self.limit, self.progress = body, limit, progress
        self.start = time.perf_counter()
        self.pass_start, self.estimate, self.working = self.start, 0.0, 0

    def _refuse(self, why: str):
        try:
            group = f"the group itself, decided exactly: {_galois_group(*self.body).group} (galois_group)"
        except ValueError as error:
            group = f"no exact decision ({error})"
        raise MonodromyTooCostly(f"monodromy({', '.join(shown(x) for x in self.body)}): {why}; it needs {self.working} "
                                 f"working digits (|omega| is large near the equilibrium I13 = I23 = 0); "
                                 f"max_seconds=None integrates anyway; {group}")

    def before_pass(self, digits: int, guard: int) -> None:
        from suslov.kernel.monodromy import MAX_WORKING_DIGITS

        now = time.perf_counter()
        self.working, self.pass_start = digits + guard, now
        if self.working > MAX_WORKING_DIGITS:
            return   # compute_monodromy integrates nothing and says why ("unknown")
        self.estimate = (now - self.start) + monodromy_seconds(self.working)
        if self.limit is not None and self.estimate > self.limit:
            self._refuse(f"not integrated: about {self.estimate:.3g} s estimated > max_seconds={self.limit:g}")

    def loop(self, done: int, total: int) -> None:
        now = time.perf_counter()
        elapsed = now - self.start
        if self.progress is not None:
            self.progress(done / total, elapsed, max(self.estimate, elapsed))
        if self.limit is not None and elapsed > self.limit and done < total:
            self._refuse(f"stopped after {elapsed:.0f} s (max_seconds={self.limit:g}) at loop {done + 1} of {total}")


def _with_exact_decision(result, I11, I22, I13, I23):
    """The exact decision (Kimura, :func:`galois_group`) beside the balls: it fills in an "unknown" verdict,
    and a ball verdict that contradicted it would be recorded as a failed certificate (never silently kept)."""
    try:
        exact = _galois_group(I11, I22, I13, I23)
    except ValueError:
        return result
    if result.verdict in ("SO(3,C)", "reducible") and result.verdict != exact.group:
        result.certificates.append(("the ball verdict agrees with the exact decision (Kimura)", "fail",
                                    f"balls: {result.verdict}, exact: {exact.group}"))
        return result
    result.certificates.append(("the differential Galois group, decided exactly (Kimura's theorem on the body's Gauss "
                                "equation)", "pass", exact.reason))
    result.verdict, result.liouvillian = exact.group, exact.liouvillian
    return result


def _exact_trivial_at_poles(I11, I22, I13, I23) -> tuple:
    """(True, reason) when the theorem of :mod:`suslov.kernel.local_behaviour` (certified by the build:
    pole_theorem) says every solution is meromorphic at the poles -- the Kovalevskaya exponent Lambda an odd
    integer, for every p, not only the p a build's per-p recursion reached -- so the loops about x = +-i are the
    identity; (False, "") otherwise, and for input that is not an exact body."""
    try:
        behaviour = _local_behaviour(I11, I22, I13, I23)
    except ValueError:
        return False, ""
    if not behaviour.meromorphic:
        return False, ""
    return True, (f"Lambda = {behaviour.Lambda} odd: every solution meromorphic at the poles, M(x = +-i) = I "
                  "(theorem for every p, certified: pole_theorem)")
