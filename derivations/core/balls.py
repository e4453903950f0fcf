"""Enclosure certificates: numeric claims decided with python-flint balls (issue 16; docs/design.md's rules).

A claim is an inequality about a computable real number, ``|quantity| <= tolerance`` (the
quantity usually a difference between two routes, e.g. a closed form and a validated
integration).  ``quantity(prec)`` returns an ``arb`` ball that contains the exact value
when evaluated at ``prec`` bits.  Three honest outcomes:

* **pass**: the ball's upper bound is at most the tolerance (the inequality is proved);
* **fail**: the ball's lower bound exceeds the tolerance (the inequality is refuted);
* **unknown**: the ball straddles the tolerance at the working precision, after a bounded
  number of precision doublings (``doublings``): too wide to decide, never a pass.

An equality of two transcendental numbers cannot be proved by enclosures; what a pass proves is
the stated bound on their distance.  The method string says so, and the detail records the
enclosure, the precision used and how many doublings it took.
"""
from __future__ import annotations

from collections.abc import Callable

from flint import arb, ctx

from derivations.core.certificates import (
    Certificate,
    CertificateLog,
    Outcome,
    stopwatch,
)

METHOD = "ball enclosure (`python-flint` `arb`)"


def decide(value: arb, tolerance: arb) -> Outcome:
    """pass / fail / unknown for ``|value| <= tolerance`` given a ball containing value."""
    magnitude = abs(value)
    if magnitude.upper() <= tolerance:
        return Outcome.PASS
    if magnitude.lower() > tolerance:
        return Outcome.FAIL
    return Outcome.UNKNOWN


def certify_enclosure(log: CertificateLog, claim: str, label: str, quantities: Callable[[int], list],
                      tolerance, *, prec: int = 128, doublings: int = 3, expect: Outcome = Outcome.PASS,
                      what: str = "") -> Certificate:
    """Certify ``|q| <= tolerance`` for every ball ``q`` in ``quantities(prec)``.

    On unknown, the precision is doubled (at most ``doublings`` times) and everything recomputed;
    the first decisive precision is recorded.  ``what`` names the route in the method string.
    """
    tolerance = arb(tolerance)
    outcome, work, bits, worst = Outcome.UNKNOWN, 0, prec, arb(0)
    with stopwatch() as elapsed:
        for attempt in range(doublings + 1):
            bits = prec * 2 ** attempt
            with ctx.workprec(bits):
                values = quantities(bits)
            work += len(values)
            outcomes = [decide(v, tolerance) for v in values]
            worst = max((abs(v).upper() for v in values), default=arb(0))
            if Outcome.FAIL in outcomes:
                outcome = Outcome.FAIL
                break
            if all(o is Outcome.PASS for o in outcomes):
                outcome = Outcome.PASS
                break
    detail = (f"{len(values)} enclosures at {bits} bits ({attempt} doublings): $abs(q) <= {worst.str(3, radius=False)}$ "
              f"vs tolerance ${tolerance.str(3, radius=False)}$")
    method = f"{METHOD}{': ' + what if what else ''}; a pass proves the stated bound"
    return log.record(Certificate(claim, label, method, outcome, elapsed[0], work, detail, expected=expect))
