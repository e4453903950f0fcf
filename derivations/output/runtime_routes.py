"""Every public run-time route of the generated module against the certified closed forms (issue 44).

Part 4 of the round trip (:mod:`derivations.output.roundtrip`).  The other parts certify the emitted
formulas (exactly), the shared recipes (exactly) and the float64 rounding of the emitted code (proofs);
the run-time code *around* them (``suslov/runtime/*.py``, ``suslov/kernel/*.py``: validation, scaling, the
``_mp`` twins' precision handling, the ball routes, the finite-value repair of ``suslov.kernel.finite``, the
far phase of ``gamma_basis``, the ball-checked branches of ``general_scattering_angle``) was compared only
with models that call the same run-time code, so a fault there could pass ``--verify`` (issue 44: 5 of 9
seeded faults did).  Here every public route is called at a few fixed points chosen to reach each of its
branches (listed below, each with the branch it reaches) and compared with the certified closed form
evaluated by a route that shares none of the run-time code (:mod:`derivations.output.ball_reference`:
the build's certified SymPy expressions walked in python-flint balls from the exact inputs; the first
integral from the certified numerators exactly in Q; the basis from the certified numerators at
``x = e^t`` in balls).

Claims, one certificate per route (the repair branch its own): a float64 route is within the error bound
its docstring states (``general_scattering_angle``: its run-time contract ``1e-13 (1 + |Y|)``, relative below
an angle of 1); an ``_mp`` twin within ``10^(1 - dps)`` (relative for the angles and omega, absolute for the
basis rows, of modulus at most 1, and relative to the sum of the moduli of the terms for the first integral);
a ball route returns a ball that *contains* the reference ball (so the exact value) and carries at least the
``prec`` relative bits asked.  Each comparison is decided in ball arithmetic, so a pass is a **certificate for
the listed points**, not a bound over the domain (the proofs in ``derivations/proofs`` bound the float64
rounding); a comparison that cannot be decided makes the outcome ``unknown``, a route that raises fails,
and the detail names the route, the call and the two values.  Cost: about 60 calls, 64 to 400 bits, some
50 ms.  The points are fixed, so the texts are deterministic; the worst ratio of error to bound (it depends
on libm for the float routes) is a volatile measurement.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
from flint import arb, ctx

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)
from derivations.output.ball_reference import (
    MAX_BITS,
    Reference,
    ball,
    basis_rows,
    enclose,
    exact,
    integral_at,
    integral_value,
)

LABEL = "round trip"
METHOD = ("ball enclosure (`python-flint` `arb`) of the certified closed form at each listed point, from the exact "
          "inputs, by a route sharing no run-time code; a certificate for these points")


# ---------------------------------------------------------------- comparisons, decided in ball arithmetic


class Tally:
    """The comparisons of one route: failures named with their point, undecided ones, the worst ratio."""

    def __init__(self, route: str):
        self.route, self.points, self.failed, self.undecided, self.worst = route, 0, [], [], 0.0

    def call(self, where: str, function, *args, **kwargs):
        """The route's value, or None (recorded as a failure) when it raises."""
        try:
            return function(*args, **kwargs)
        except Exception as error:  # noqa: BLE001  any exception of the route under test is the finding
            self.points += 1
            self.failed.append(f"{where}: raised {type(error).__name__}: {str(error)[:160]}")
            return None

    def within(self, where: str, value, reference, bound) -> None:
        """|value - reference| <= bound (bound a ball or a number)."""
        self.points += 1
        if reference is None:
            self.undecided.append(f"{where}: no reference within {MAX_BITS} bits")
            return
        with ctx.workprec(max(ctx.prec, 256)):
            try:
                got = ball(value)
            except (TypeError, ValueError):      # not a real number: a faulty route's return, named below
                got = arb("nan")
            if not got.is_finite():
                self.failed.append(f"{where}: got {value!r}, not a finite real number")
                return
            error, bound = abs(got - reference), ball(bound) if not isinstance(bound, arb) else bound
            if error <= bound:
                self.worst = max(self.worst, float((error.upper() / bound.lower()).mid()) if bound > 0 else 0.0)
            elif error > bound:
                self.failed.append(f"{where}: got {_show(value)}, certified {reference.str(20, radius=False)}; "
                                   f"beyond the bound {bound.upper().str(3, radius=False)}")
            else:
                self.undecided.append(f"{where}: |error| and the bound overlap")

    def contains(self, where: str, value, reference, bits: int) -> None:
        """``value`` (a ball) contains ``reference`` and has at least ``bits`` relative bits."""
        self.points += 1
        if reference is None:
            self.undecided.append(f"{where}: no reference within {MAX_BITS} bits")
            return
        if not isinstance(value, arb):
            self.failed.append(f"{where}: returned {type(value).__name__}, not a ball")
        elif not value.overlaps(reference):
            self.failed.append(f"{where}: the ball {value.str(20)} excludes the certified value "
                               f"{reference.str(20, radius=False)}")
        elif not value.contains(reference):
            self.undecided.append(f"{where}: the ball and the reference overlap without containment")
        elif not value.rel_accuracy_bits() >= bits:
            self.failed.append(f"{where}: the ball carries {value.rel_accuracy_bits()} relative bits, fewer than "
                               f"the {bits} asked")
        else:
            self.worst = max(self.worst, 2.0 ** (bits - value.rel_accuracy_bits()))

    def record(self, log: CertificateLog, claim: str, method: str, seconds: float) -> Certificate:
        outcome = Outcome.FAIL if self.failed else Outcome.UNKNOWN if self.undecided else Outcome.PASS
        if self.failed or self.undecided:
            detail = f"`{self.route}`: " + "; ".join((self.failed + self.undecided)[:3])
        else:
            detail = f"{self.points} comparisons at the listed points, each within its bound"
        return log.record(Certificate(f"`{self.route}`: {claim}", LABEL, method, outcome, seconds, self.points, detail,
                                      measured=f"worst error / bound = {self.worst:.3g}"))


def _show(value) -> str:
    if isinstance(value, mpmath.mpf):
        return mpmath.nstr(value, 20)
    return repr(float(value)) if isinstance(value, (float, np.floating)) else str(value)


def relative(reference, digits: int):
    """The bound 10^(1 - digits) |reference| of an ``_mp`` twin (None passes through)."""
    return None if reference is None else abs(reference) * arb(10) ** (1 - digits)


def _call_text(function: str, args, **kwargs) -> str:
    shown = [_show(a) if isinstance(a, (float, np.floating)) else repr(a) if isinstance(a, str) else str(a) for a in args]
    return f"{function}({', '.join(shown + [f'{k}={v}' for k, v in kwargs.items()])})"


# ---------------------------------------------------------------- the points (each reaches the branch named)

# omega: ordinary, sech t underflowing (the absolute part of the bound), tiny t, large p, tiny p
OMEGA = ((0.3, 3.0, 0.5), (-745.2, 2.5, 0.31), (1e-8, -2.7, 7.0), (30.0, 1e6 + 0.5, 1e3), (-3.0, 1e-300, 1e-3))
OMEGA_MP = ((("0.25", 3, "0.5"), 30), ((-7.5, "-5/2", "1e-3"), 30), ((40, 1, 2), 45))
# omega_general (both branches of r): ordinary, I11 < I22, |I23| << |I13|, tiny t, a tensor of size 1e150
GENERAL_OMEGA = ((0.7, 2.0, 1.0, 0.3, -0.5), (-3.0, 1.0, 2.0, 0.3, 0.2), (25.0, 3.0, 0.2, 0.9, -0.01),
                 (1e-8, 1.25, 1.0, 0.3, -0.5), (2.0, 1e150, 5e149, 3e149, -4e149))
GENERAL_OMEGA_MP = ((("7/10", 2, 1, "3/10", "-1/2"), -1, 30), ((-3, 1, 2, "0.3", "0.2"), 1, 40))
# finite.repair: float64 evaluation non-finite, the value finite (c p overflows at d = 1e10; scaled entries
# spanning more than float64's range)
REPAIR_OMEGA = ((0.5, 1e300, 1e10),)
REPAIR_GENERAL = ((0.7, 1e300, 1e-300, 1.0, 1.0),)
# Theorem 5.4: even p, non-integer p, negative p with large d, p next to an odd integer, p and d beyond 2^1020
# (the scaled branch), tiny p; twins and balls also at an odd p (the angle pi) and exact decimals
ANGLE = ((2.0, 1.0), (2.5, 0.7), (-2.7, 1e3), (3 - 2.0**-40, 0.5), (7.3, 0.31), (1.5e308, 1e308), (1e-300, 1e-3))
ANGLE_MP = (((2, 1), 30), (("5/2", "7/10"), 30), (("-27/10", 1000), 30), ((3 - 2.0**-40, 0.5), 30), ((7.3, 0.31), 60))
ANGLE_BALL = ((("5/2", "7/10"), 128), ((2, 1), 64), ((1.5e308, 1e308), 200), ((3, "1/2"), 100))
# any body: the proven float64 domain (ordinary, I11 < I22, small I23, a tensor of size 1e150), then the
# ball-checked branch (I22 < 2^-20 times the largest entry) and the repaired one (float64 has no value)
BODY = ((1.25, 1.0, 0.3, -0.5), (1.0, 2.0, 0.3, 0.2), (3.0, 0.2, 0.9, -0.01), (1e150, 5e149, 3e149, -4e149),
        (1.0, 1e-7, 0.3, -0.5), (1.0, 1e-300, 1e-300, 1.0))
# twins and balls: exact decimals, a body whose |Y| ~ 1e20 needs 20 more digits (the precision must grow; its
# digits are not round: at (10^40, 1, 1, 1) mpmath's value at too low a precision happened to be right)
GROWTH = (10**40 + 12345, "0.7", "0.3", "-0.5")
BODY_MP = ((("5/4", 1, "3/10", "-1/2"), 30), (GROWTH, 20), ((1.0, 1e-7, 0.3, -0.5), 25))
BODY_BALL = ((("5/4", 1, "3/10", "-1/2"), 128), (GROWTH, 64), ((1.0, 2.0, "3/10", "1/5"), 300))


def integral_points(p: int) -> tuple:
    """(d, omega1, omega2, gamma1, gamma2, gamma3): |omega2| > |omega1|, |omega1| > |omega2| (Horner's rule in either
    ratio), s^p about 2^900 (the power-of-two scaling); two values of d in one call (the loop over d)."""
    big = 1.5 * 2.0 ** (900 // p)
    return ((0.5, 0.75, -1.25, 0.5, -0.625, 0.6), (1.75, 2.5, 0.5, -0.25, 0.875, -0.5),
            (0.5, big, -0.375 * big, 0.125, 0.25, -1.0))


# gamma_basis: the far phase (|p t/d| >= 5.3e7, python-flint balls) at d = 1e-3 and 0.5, and two near points
BASIS_T = {1e-3: (1.2e4, -3.3e6, 2.9e7), 0.5: (0.4, -2.0, 1e8)}
FAR_PHASE = 2.0**23 * 2 * math.pi    # gamma_basis's docstring: the phase in balls from here on (about 5.3e7)
BASIS_DPS = 40
STATED = {"omega": 5e-15, "omega_general": 6e-15, "scattering_angle": 1.5e-14, "general": 1e-13,
          "first_integral": 2e-15, "gamma_basis": 1e-14}


# ---------------------------------------------------------------- omega, omega_general and the repair


def _omega_bound(reference, p, d):
    """omega's docstring: 5e-15 |omega_i| + 1e-300 (|p|/d) sqrt(d^2 + 1) per component."""
    p, d = ball(p), ball(d)
    return [STATED["omega"] * abs(w) + arb("1e-300") * abs(p) / d * (d * d + 1).sqrt() for w in reference]


def _omega_general_bound(I11, I22, I13, I23):
    """omega_general's docstring: 6e-15 B + 1e-300, B = (I11 I22 |I23| + I22 |I13| r + I11 I22 |I13| + I11 |I23| r)/D."""
    a, b, e, f = (ball(x) for x in (I11, I22, I13, I23))
    r, D = (a * b).sqrt(), a * f * f + e * e * b
    B = (a * b * abs(f) + b * abs(e) * r + a * b * abs(e) + a * abs(f) * r) / D
    return STATED["omega_general"] * B + arb("1e-300")


def _float_pairs(tally, name, function, points, reference, bound, *extra):
    """A float64 route returning two arrays, called once on the columns of ``points``, each point compared."""
    values = tally.call(f"{name} at the listed points", function, *(np.array(c) for c in zip(*points)), *extra)
    if values is None:
        return
    for k, point in enumerate(points):
        refs = enclose(80, reference, *point, *extra)
        bounds = bound(refs, point) if refs is not None else (None, None)
        for i in range(2):
            tally.within(f"{_call_text(name, point + extra)} component {i + 1}", np.asarray(values[i]).flat[k],
                         None if refs is None else refs[i], bounds[i])


def check_omega(log, module, ref) -> list:
    certs = []
    tally = Tally("omega")
    with stopwatch() as elapsed:
        _float_pairs(tally, "omega", module.omega, OMEGA, ref.omega, lambda r, pt: _omega_bound(r, *pt[1:]))
    certs.append(tally.record(log, f"`float64` within its docstring's bound of the certified $omega$ at {len(OMEGA)} "
                              "points ($sech(t)$ underflowing, $p$ from $1e-300$ to $1e6$)", METHOD, elapsed[0]))
    tally = Tally("omega_mp")
    with stopwatch() as elapsed:
        for args, dps in OMEGA_MP:
            values = tally.call(_call_text("omega_mp", args, dps=dps), module.omega_mp, *args, dps=dps)
            refs = enclose(int(3.33 * dps) + 20, ref.omega, *args)
            for i in range(2):
                if values is not None:
                    tally.within(f"{_call_text('omega_mp', args, dps=dps)} component {i + 1}", values[i],
                                 refs and refs[i], refs and relative(refs[i], dps))
    certs.append(tally.record(log, f"within $10^(1 - dps)$ relative of the certified $omega$ at {len(OMEGA_MP)} points "
                              "(exact decimals, $dps = 30$ and $45$)", METHOD, elapsed[0]))
    tally = Tally("omega_general")
    with stopwatch() as elapsed:
        for branch in (1, -1):
            _float_pairs(tally, "omega_general", module.omega_general, GENERAL_OMEGA, ref.omega_general,
                         lambda r, pt: (_omega_general_bound(*pt[1:]),) * 2, branch)
    certs.append(tally.record(log, f"`float64` within its docstring's bound of the certified general solution at "
                              f"{len(GENERAL_OMEGA)} points, both branches of $r$", METHOD, elapsed[0]))
    tally = Tally("omega_general_mp")
    with stopwatch() as elapsed:
        for args, branch, dps in GENERAL_OMEGA_MP:
            text = _call_text("omega_general_mp", args, branch=branch, dps=dps)
            values = tally.call(text, module.omega_general_mp, *args, branch=branch, dps=dps)
            refs = enclose(int(3.33 * dps) + 20, ref.omega_general, *args, branch)
            for i in range(2):
                if values is not None:
                    tally.within(f"{text} component {i + 1}", values[i], refs and refs[i], refs and relative(refs[i], dps))
    certs.append(tally.record(log, f"within $10^(1 - dps)$ relative of the certified general solution at "
                              f"{len(GENERAL_OMEGA_MP)} points (both branches)", METHOD, elapsed[0]))
    return certs


def check_repair(log, module, ref) -> Certificate:
    """The finite-value repair (suslov.kernel.finite.repair) through the two routes that reach it."""
    tally = Tally("finite.repair (omega, omega_general)")
    with stopwatch() as elapsed:
        _float_pairs(tally, "omega", module.omega, REPAIR_OMEGA, ref.omega, lambda r, pt: _omega_bound(r, *pt[1:]))
        _float_pairs(tally, "omega_general", module.omega_general, REPAIR_GENERAL, ref.omega_general,
                     lambda r, pt: (_omega_general_bound(*pt[1:]),) * 2, 1)
    return tally.record(log, "at points whose `float64` evaluation is not finite while the value is ($c p$ beyond "
                        "`float64` at $d = 1e10$; entries spanning $1e-300$ to $1e300$), the repaired values are within "
                        "the docstrings' bounds of the certified $omega$", METHOD, elapsed[0])


# ---------------------------------------------------------------- the scattering angles


def check_angles(log, module, ref) -> list:
    """Theorem 5.4's angle: the float64 route, the mp twin, the ball route."""
    certs = [_angle_float(log, module, "scattering_angle", ANGLE, ref.scattering_angle,
                          lambda angle: STATED["scattering_angle"],
                          f"`float64` within absolute $1.5e-14$ of the angle of Theorem 5.4 at {len(ANGLE)} points "
                          "(even, non-integer, negative $p$, $p$ next to an odd integer, $p$ and $d$ beyond $2^1020$, "
                          "$p = 1e-300$)")]
    certs.append(_angle_mp(log, module, "scattering_angle_mp", ANGLE_MP, ref.scattering_angle,
                           f"within $10^(1 - dps)$ relative of the angle of Theorem 5.4 at {len(ANGLE_MP)} points "
                           "(exact decimals, $dps = 30$ and $60$)"))
    certs.append(_angle_ball(log, module, "scattering_angle_ball", ANGLE_BALL, ref.scattering_angle,
                             f"the ball contains the angle of Theorem 5.4 and carries the `prec` relative bits asked, at "
                             f"{len(ANGLE_BALL)} points (odd $p$: the angle $pi$)"))
    return certs


def _angle_float(log, module, name: str, points, reference, bound, claim: str) -> Certificate:
    """An angle's float64 route, vectorised over ``points``, against the reference enclosed at 80 bits;
    ``bound(found)`` is the allowed error given the enclosure (``found``: the reference's tuple)."""
    tally = Tally(name)
    with stopwatch() as elapsed:
        values = tally.call(f"{name} at the listed points", getattr(module, name), *(np.array(c) for c in zip(*points)))
        for k, point in enumerate(points if values is not None else ()):
            found = enclose(80, reference, *point)
            tally.within(_call_text(name, point), np.asarray(values).flat[k], found and found[0],
                         found and bound(found))
    return tally.record(log, claim, METHOD, elapsed[0])


def _angle_mp(log, module, name: str, points, reference, claim: str) -> Certificate:
    """An angle's mp twin at (args, dps) points against the reference enclosed at about dps digits."""
    tally = Tally(name)
    with stopwatch() as elapsed:
        for args, dps in points:
            text = _call_text(name, args, dps=dps)
            value = tally.call(text, getattr(module, name), *args, dps=dps)
            found = enclose(int(3.33 * dps) + 20, reference, *args)
            if value is not None:
                tally.within(text, value, found and found[0], found and relative(found[0], dps))
    return tally.record(log, claim, METHOD, elapsed[0])


def _angle_ball(log, module, name: str, points, reference, claim: str) -> Certificate:
    """An angle's ball route at (args, prec) points: contains the reference and carries prec relative bits."""
    tally = Tally(name)
    with stopwatch() as elapsed:
        for args, prec in points:
            text = _call_text(name, args, prec=prec)
            value = tally.call(text, getattr(module, name), *args, prec=prec)
            found = enclose(prec + 64, reference, *args)
            if value is not None:
                tally.contains(text, value, found and found[0], prec)
    return tally.record(log, claim, METHOD, elapsed[0])


def _general_bound(angle, Y):
    """The float64 route's contract (suslov/runtime/general_angle.py): within 1e-13 (1 + |Y|), relative below an
    angle of 1 (the docstring's forward bound, sampled; the mixed bound is proven)."""
    return STATED["general"] * (1 + Y) * (angle if angle < 1 else arb(1))


def check_general_angles(log, module, ref) -> list:
    """The angle of any body: the float64 route (three branches), the mp twin, the ball route."""
    certs = [_angle_float(log, module, "general_scattering_angle", BODY, ref.general_angle,
                          lambda found: _general_bound(*found),
                          f"`float64` within $1e-13 (1 + abs(Y))$ (relative below an angle of 1) of the certified "
                          f"angle at {len(BODY)} bodies: four in the proven domain, one in the ball-checked "
                          "branch ($I22$ below $2^(-20)$ of the largest entry), one repaired (`float64` has no value)")]
    certs.append(_angle_mp(log, module, "general_scattering_angle_mp", BODY_MP, ref.general_angle,
                           f"within $10^(1 - dps)$ relative of the certified angle at {len(BODY_MP)} bodies (exact "
                           "decimals; $abs(Y)$ about $1e20$: 20 digits more than asked)"))
    certs.append(_angle_ball(log, module, "general_scattering_angle_ball", BODY_BALL, ref.general_angle,
                             f"the ball contains the certified angle and carries the `prec` relative bits asked, at "
                             f"{len(BODY_BALL)} bodies ($abs(Y)$ about $1e20$: the precision must grow)"))
    return certs


def check_first_integral(log, module, build) -> list:
    """first_integral and first_integral_mp against the certified numerators evaluated exactly in Q."""
    objects = build.results["first_integrals"].exports["objects"]
    ps = [p for p in (3, max(objects)) if p in objects and p in module.INTEGRAL_PS]
    certs = []
    for route in ("first_integral", "first_integral_mp"):
        tally = Tally(route)
        with stopwatch() as elapsed:
            for p in sorted(set(ps)):
                points = integral_points(p)
                columns = [np.array(c) for c in zip(*points)]
                values = (tally.call(f"first_integral(p={p}) at the listed points", module.first_integral, p, *columns)
                          if route == "first_integral" else [None] * len(points))
                for k, (d, w1, w2, *gammas) in enumerate(points if values is not None else ()):
                    value, scale = integral_value(integral_at(objects[p], exact(d)), p, w1, w2, gammas)
                    with ctx.workprec(400):
                        certified = ball(value)
                        if route == "first_integral":
                            got, bound = np.asarray(values).flat[k], STATED["first_integral"] * (p + 1) * ball(scale)
                        else:
                            text = _call_text("first_integral_mp", (p, d, w1, w2, *gammas), dps=30)
                            got = tally.call(text, module.first_integral_mp, p, d, w1, w2, *gammas, dps=30)
                            bound = arb(10) ** -29 * (p + 1) * ball(scale)
                        if got is not None:
                            tally.within(_call_text(route, (p, d, w1, w2, *gammas)), got, certified,
                                         bound + arb("5e-324"))
        what = ("`float64` within its docstring's bound $2e-15 (p + 1) s^p G A$"
                if route == "first_integral" else "within $10^(1 - dps) (p + 1) s^p G A$")
        what += (", $G = abs(gamma_1) + abs(gamma_2) + abs(gamma_3)$, $A$ the sum of the moduli of the coefficients $a_ik$")
        certs.append(tally.record(log, f"{what} of $F3$ from the certified numerators, evaluated exactly in rational "
                                  f"arithmetic, at 3 points for {' and '.join(f'$p = {q}$' for q in sorted(set(ps)))}",
                                  "exact rational evaluation of "
                                  "the build's certified numerators (`fractions.Fraction`) at each listed point, the comparison "
                                  "in 400-bit balls; a certificate for these points", elapsed[0]))
    return certs


def check_basis(log, module, build) -> list:
    """gamma_basis (far and near phase) and gamma_basis_mp (far phase) against the certified numerators in arb."""
    cores = build.results["meromorphic"].exports["objects"]
    p = next((q for q in (5, *sorted(cores)) if q in cores and q in module.BASIS_PS), None)
    if p is None:
        return []
    certs = []
    for route in ("gamma_basis", "gamma_basis_mp"):
        tally = Tally(route)
        with stopwatch() as elapsed:
            for d, ts in BASIS_T.items():
                values = (tally.call(f"gamma_basis(t, {p}, {d!r}) at t = {ts}", module.gamma_basis, np.array(ts), p, d)
                          if route == "gamma_basis" else [None] * len(ts))
                for n, t in enumerate(ts if values is not None else ()):
                    if route == "gamma_basis":
                        got, bound = values[n], STATED["gamma_basis"] * (p + 1) ** 1.5
                    else:
                        got = tally.call(_call_text(route, (t, p, d), dps=BASIS_DPS), module.gamma_basis_mp, t, p, d,
                                         dps=BASIS_DPS)
                        bound = arb(10) ** (1 - BASIS_DPS)
                    digits = 64 if route == "gamma_basis" else int(3.33 * BASIS_DPS) + 20
                    rows = enclose(digits, basis_rows, cores[p], p, t, d, absolute=True)
                    for entry in range(9 if got is not None else 0):
                        i, j = divmod(entry, 3)
                        tally.within(f"{_call_text(route, (t, p, d))} row {i + 1} entry {j + 1}", got[i, j],
                                     rows and rows[entry], bound)
        far = sum(1 for d, ts in BASIS_T.items() for t in ts if abs(p * t / d) >= FAR_PHASE)
        what = ("`float64` within absolute $1e-14 (p + 1)^1.5$ (its docstring)" if route == "gamma_basis" else
                f"within absolute $10^(1 - dps)$ at $dps = {BASIS_DPS}$")
        certs.append(tally.record(log, f"{what} of the rows from the certified numerators at $p = {p}$, "
                                  f"{sum(len(ts) for ts in BASIS_T.values())} points, {far} with the far phase "
                                  "($abs(p t/d) >= 5.3e7$: `careful_phase`)", "ball enclosure (`python-flint` `arb`) "
                                  "of the certified numerators at $x = e^t$ and of the phase $e^(i p t/d)$ from the "
                                  "exact $t$; a certificate for these points", elapsed[0]))
    return certs


def certify(log: CertificateLog, module, build) -> list:
    """Every public run-time route at its listed points (one certificate per route, the repair branch its own)."""
    if not hasattr(module, "general_scattering_angle"):    # a tree from before the closed-form angle of every body
        return []
    ref = Reference(build)
    with mpmath.workdps(15):
        return [*check_omega(log, module, ref), check_repair(log, module, ref), *check_first_integral(log, module, build),
                *check_basis(log, module, build), *check_angles(log, module, ref),
                *check_general_angles(log, module, ref)]
