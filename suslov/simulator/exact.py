"""The scene's body, exactly: what the exact effects (``galois_group``, ``scattering_angle_enclosure``) are computed for.

A scene's body is the numbers the user wrote (issue 44).  ``p = 3`` and ``d = 1`` (TOML integers) are the
rationals 3 and 1; a decimal string ``"0.7"`` (or ``"7/10"``) is 7/10; a float (``d = 0.7`` as a TOML
float) is the binary number it holds, ``Fraction(0.7)``, and the results say so.  The float, det-normalised
entries of :class:`suslov.simulator.body.Body` (``body.entries``) drive the numerics only; deciding the
Galois group from them, or enclosing their angle, answers for a body a rounding error away (p = 3 became
SO(3,C), the ball of pi excluded pi).

The exact body is the tensor in the paper's frame (I12 = 0, I11 >= I22, a = e3; when I13 = 0 turned so
that I23 < 0, as :func:`suslov.simulator.body.make_body` does), *not* scaled to det I = 1 (a cube root;
every answer is scale-invariant):

* ``p, d``: the representative ``(I11, I22, I13, I23) = (1 + d^2, 1, 0, -d/p)`` of
  :func:`suslov.simulator.body.tensor_from_pd` (p^2 = I22 (I11 - I22)/I23^2, d^2 = (I11 - I22)/I22):
  rational whenever p and d are, i.e. always.
* a tensor with I12 = 0: its entries (swapped by the quarter turn when I11 < I22), rational.
* a tensor with I12 != 0: the rotation about e3 to I12 = 0 has nested square roots; the entries are
  rational when those roots are (then they are Fractions), else they are kept as the exact scene
  entries and evaluated in ball arithmetic at any precision (rigorous), and the Galois group is decided
  from the rotation invariants Kimura's criterion reads (``u.v = 0`` and ``w_-^2``), exactly in rationals.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from fractions import Fraction
from math import isqrt

from suslov.kernel.validate import rational
from suslov.kernel.validate import shown as validate_shown

__all__ = ["ExactBody", "ball_entries", "enclosure", "exact_number", "from_pd", "from_tensor", "galois_group",
           "local_behaviour",
           "of_scene_body"]


def exact_number(name: str, value) -> tuple[Fraction, str]:
    """(the exact value, how it was read) of a number as written.

    ints are integers, Fractions themselves, strings decimals or ``a/b`` (read exactly; each at most
    ``MAX_ENTRY_BITS`` in numerator and denominator, :mod:`suslov.kernel.validate`), floats their
    binary value: "float64 (exact)" when the shortest decimal that reads back as that float is its binary
    value (0.5, 3.0), else "float64" (0.7 is 3152519739159347/2^52, not 7/10).  ValueError for anything else.
    """
    if isinstance(value, bool):
        raise ValueError(f"{name}={value!r}: a number, not a bool")  # noqa: TRY004 (input errors are ValueError here)
    if isinstance(value, numbers.Integral):
        return rational(name, int(value)), "integer"
    if isinstance(value, Fraction):
        return rational(name, value), "rational"
    if isinstance(value, str):   # read exactly, its size checked before conversion (MAX_ENTRY_BITS)
        return rational(name, value), ("rational string" if "/" in value else "decimal string")
    if isinstance(value, numbers.Real):
        x = float(value)
        if not math.isfinite(x):
            raise ValueError(f"{name}={value!r}: must be finite")
        number = Fraction(x)
        return number, ("float64 (exact)" if Fraction(repr(x)) == number else "float64")
    raise ValueError(f"{name}={value!r}: must be a number (int, decimal string, Fraction or float)")


def shown(name: str, value) -> str:
    """``name = value (how it was read)``, saying the exact value where it is not what the float prints."""
    number, how = exact_number(name, value)
    if how == "float64":
        return (f"{name} = {float(value)!r} (float64: its binary value {_text(number)}, not the decimal "
                f"{float(value)!r}; write \"{float(value)!r}\" for the decimal)")
    if how == "float64 (exact)":
        return f"{name} = {float(value)!r} (float64, exactly {_text(number)})"
    if how == "integer":
        return f"{name} = {_text(number)} (integer)"
    return f"{name} = {value.strip() if isinstance(value, str) else value} ({how}, exactly {_text(number)})"


def _text(q: Fraction) -> str:
    if max(q.numerator.bit_length(), q.denominator.bit_length()) > 14_000:   # str() refuses ints over 4300 digits
        return validate_shown(q)
    return str(q.numerator) if q.denominator == 1 else f"{q.numerator}/{q.denominator}"


def rational_sqrt(q: Fraction) -> Fraction | None:
    """The non-negative rational square root of ``q``, or None when it is irrational."""
    if q < 0:
        return None
    n, d = isqrt(q.numerator), isqrt(q.denominator)
    return Fraction(n, d) if n * n == q.numerator and d * d == q.denominator else None


@dataclass(frozen=True)
class ExactBody:
    """A Suslov body as the exact numbers it was given as (module docstring).

    ``entries``: (I11, I22, I13, I23) in the paper's frame as Fractions, or None when they are irrational;
    ``tensor``: the scene's 2x2 block and (I13, I23) exactly, ``(I11, I12, I22, I13, I23)`` (the scene's frame),
    always; ``read_as``: how the user's numbers were read; ``source``: "p, d" or "inertia"; ``floats``: True
    when some number was a float that is not exactly the decimal it prints as (the body is then that float's
    binary value, not the decimal).
    """

    entries: tuple | None
    tensor: tuple
    source: str
    read_as: str
    floats: bool
    note: str = ""

    @property
    def rational(self) -> bool:
        return self.entries is not None

    def entries_text(self) -> list[str]:
        """The paper-frame entries as exact strings ("-1/3"), or 25-digit balls when irrational."""
        if self.rational:
            return [_text(x) for x in self.entries]
        return [x.str(25) for x in ball_entries(self, 120)]

    def for_whom(self) -> str:
        """Which body a result is for, in words."""
        if self.floats:
            head = "the body with these float64 entries (their binary values, not the decimals they print as)"
        else:
            head = "the body as written (exact)"
        return f"{head}: {self.read_as}"

    def whose(self) -> str:
        """Which body, in a few words (a method string; :meth:`for_whom` has the details)."""
        if self.floats:
            return "for the body with the scene's float64 entries (their binary values; see 'body')"
        return "for the body as written, exactly (see 'body')"

    def as_json(self) -> dict:
        out = {"for": self.for_whom(), "entries_paper_frame": self.entries_text(), "rational": self.rational,
               "scale": "as given (not det I = 1; every answer is scale-invariant)"}
        if self.note:
            out["note"] = self.note
        return out


def from_pd(p, d, how: str | None = None) -> ExactBody:
    """The exact body of the case I13 = 0 with these p, d (as written; see :func:`exact_number`)."""
    (pq, p_how), (dq, d_how) = exact_number("p", p), exact_number("d", d)
    if pq <= 0 or dq <= 0:
        raise ValueError(f"p={p!r}, d={d!r}: both must be > 0")
    entries = (1 + dq * dq, Fraction(1), Fraction(0), -dq / pq)
    read = how or f"{shown('p', p)}, {shown('d', d)}"
    floats = any(h == "float64" for h in (p_how, d_how))
    return ExactBody(entries, (entries[0], Fraction(0), entries[1], entries[2], entries[3]), "p, d", read, floats,
                     "I22 = 1, I11 = 1 + d^2, I23 = -d/p (p^2 = I22 (I11 - I22)/I23^2, d^2 = (I11 - I22)/I22)")


def _positive_definite(m) -> bool:
    a, b, c = m[0][0], m[0][1], m[0][2]
    e, f, i = m[1][1], m[1][2], m[2][2]
    return a > 0 and a * e - b * b > 0 and a * (e * i - f * f) - b * (b * i - f * c) + c * (b * f - e * c) > 0


def from_tensor(rows, how: str | None = None) -> ExactBody:
    """The exact body of a 3x3 inertia tensor (constraint axis a = e3) given as numbers (see :func:`exact_number`).

    ValueError when it is, exactly, not positive definite or has I13 = I23 = 0.
    """
    read = [[exact_number(f"inertia[{i}][{j}]", rows[i][j]) for j in range(3)] for i in range(3)]
    m = [[q for q, _ in row] for row in read]
    kinds = sorted({h for row in read for _, h in row})
    floats = "float64" in kinds
    note = ""
    if any(m[i][j] != m[j][i] for i in range(3) for j in range(i)):
        note = "the tensor is not exactly symmetric: its symmetric part (I + I^T)/2 is the body"
        m = [[(m[i][j] + m[j][i]) / 2 for j in range(3)] for i in range(3)]
    if not _positive_definite(m):
        raise ValueError("inertia: not positive definite in exact arithmetic (the numbers as written)")
    I11, I12, I22, I13, I23 = m[0][0], m[0][1], m[1][1], m[0][2], m[1][2]
    if I13 == 0 and I23 == 0:
        raise ValueError("inertia: I13 = I23 = 0 exactly: a = e3 is a principal axis, every motion is an equilibrium")
    inexact = [shown(f"I{i + 1}{j + 1}", rows[i][j]) for i in range(3) for j in range(i, 3) if read[i][j][1] == "float64"]
    text = how or ("inertia as written (" + ", ".join(kinds) + ")" + (": " + "; ".join(inexact) if inexact else ""))
    entries = _paper_entries(I11, I12, I22, I13, I23)
    if entries is None:
        irrational = ("I12 != 0: the paper's frame (I12 = 0) has irrational entries; they are enclosed in balls "
                      "computed from the exact entries as written")
        note = f"{note}; {irrational}" if note else irrational
    return ExactBody(entries, (I11, I12, I22, I13, I23), "inertia", text, floats, note)


def _paper_entries(I11, I12, I22, I13, I23) -> tuple | None:
    """(I11, I22, I13, I23) in the paper's frame, exactly, or None when some entry is irrational.

    The frame of :func:`suslov.kernel.frames.canonical_frame`: the rotation by theta = atan2(2 I12, I11 - I22)/2
    (I11 >= I22 after it); when I13 = 0 there, turned by pi so that I23 < 0 (``make_body``)."""
    if I12 == 0:
        out = (I11, I22, I13, I23) if I11 >= I22 else (I22, I11, I23, -I13)   # the quarter turn
    else:
        r = rational_sqrt((I11 - I22) ** 2 + 4 * I12 * I12)
        det = _det_b_ab(I11, I12, I22, I13, I23)
        bb = I13 * I13 + I23 * I23
        if det == 0:
            # b = (I13, I23) is an eigenvector of the 2x2 block: eigenvalues rational, one entry 0, the other |b|
            lam = (I13 * (I11 * I13 + I12 * I23) + I23 * (I12 * I13 + I22 * I23)) / bb
            mu = I11 + I22 - lam
            size = rational_sqrt(bb)
            if size is None:
                return None
            out = (mu, lam, Fraction(0), -size) if lam < mu else (lam, mu, _sign_of_i13(I11, I12, I22, I13, I23) * size,
                                                                  Fraction(0))
        else:
            if r is None:
                return None
            cos2 = (I11 - I22) / r
            c, s = rational_sqrt((1 + cos2) / 2), rational_sqrt((1 - cos2) / 2)
            if c is None or s is None:
                return None
            s = s if I12 > 0 else -s
            out = ((I11 + I22 + r) / 2, (I11 + I22 - r) / 2, c * I13 + s * I23, -s * I13 + c * I23)
    if out[2] == 0 and out[3] > 0:
        out = (out[0], out[1], Fraction(0), -out[3])
    return out


def _sign_of_i13(I11, I12, I22, I13, I23) -> int:
    from flint import ctx

    with ctx.workprec(200):
        value = _rotated_balls(I11, I12, I22, I13, I23)[2]
    return 1 if value > 0 else -1


def _det_b_ab(I11, I12, I22, I13, I23) -> Fraction:
    """det[b, A b], b = (I13, I23), A the 2x2 block: rotation-invariant, = -(I11 - I22) I13 I23 in the paper's frame."""
    return I12 * I13 * I13 + (I22 - I11) * I13 * I23 - I12 * I23 * I23


def _rotated_balls(I11, I12, I22, I13, I23) -> tuple:
    """The paper-frame entries as balls at the current precision (I12 != 0: cos, sin of theta > 0 and signed)."""
    from flint import arb

    def ball(q: Fraction):
        return arb(q.numerator) / q.denominator

    a, h, b, c13, c23 = (ball(x) for x in (I11, I12, I22, I13, I23))
    r = ((a - b) ** 2 + 4 * h * h).sqrt()
    cos2 = (a - b) / r
    c = ((1 + cos2) / 2).sqrt()
    s = ((1 - cos2) / 2).sqrt() * (1 if I12 > 0 else -1)
    return (a + b + r) / 2, (a + b - r) / 2, c * c13 + s * c23, -s * c13 + c * c23


def ball_entries(body: ExactBody, prec: int) -> tuple:
    """The paper-frame entries as python-flint balls at ``prec`` bits containing the exact values.

    Rational entries are Fractions (exact for every consumer); irrational ones balls, with I13 or I23
    exactly 0 when it is (u.v = 0 is decided in rationals, :func:`_det_b_ab`)."""
    if body.rational:
        return body.entries
    from flint import arb, ctx

    I11, I12, I22, I13, I23 = body.tensor
    with ctx.workprec(prec + 20):
        out = list(_rotated_balls(I11, I12, I22, I13, I23))
        if _det_b_ab(I11, I12, I22, I13, I23) == 0:   # b is an eigenvector: one of I13, I23 is exactly 0
            lam = (I13 * (I11 * I13 + I12 * I23) + I23 * (I12 * I13 + I22 * I23)) / (I13 * I13 + I23 * I23)
            mu = I11 + I22 - lam
            size = arb((I13 * I13 + I23 * I23).numerator) / (I13 * I13 + I23 * I23).denominator
            size = size.sqrt()
            big, small = max(lam, mu), min(lam, mu)
            out[0], out[1] = arb(big.numerator) / big.denominator, arb(small.numerator) / small.denominator
            if lam < mu:
                out[2], out[3] = arb(0), -size
            else:
                out[2], out[3] = (size if out[2] > 0 else -size), arb(0)
    return tuple(out)


def of_scene_body(body: dict) -> ExactBody:
    """The exact body of a parsed scene's ``body`` table (``scene.body``): its ``written`` numbers when the
    scene was parsed from a file or a dict, else the float values it holds (their binary values)."""
    written = body.get("written") or {k: body[k] for k in ("p", "d", "inertia") if k in body}
    if "inertia" in written:
        return from_tensor(written["inertia"])
    return from_pd(written["p"], written["d"])


# ------------------------------------------------------------------------------------------ the exact effects

def galois_group(body: ExactBody):
    """The differential Galois group of the exact body (Kimura's theorem), a ``GaloisGroup``.

    Rational entries: :func:`suslov.validated.galois_group` on them.  Irrational ones (I12 != 0): the same
    decision from the rotation invariants it reads, exactly in rationals: ``u.v = 0`` iff
    ``(I11 - I22) I13 I23 = 0`` in the paper's frame, i.e. ``det[b, A b] = 0`` for b = (I13, I23) and the
    2x2 block A in the scene's frame; then b is an eigenvector of A with eigenvalue lam (the other mu) and
    ``w_-^2 = |u|^2 - |v|^2 = lam (lam - mu)/|b|^2`` (both cases I13 = 0 and I23 = 0 of the paper's frame).
    """
    from suslov.kernel.kimura import METHOD, GaloisGroup
    from suslov.validated import galois_group as validated_galois_group

    if body.rational:
        return validated_galois_group(*body.entries)
    method = METHOD + "; the paper's frame has irrational entries here, so read from the rotation invariants of " \
                      "the scene's exact entries"
    det, w2 = _rotation_invariants(body)
    if det != 0:
        return GaloisGroup("SO(3,C)", False, method, "SL(2,C)",
                           f"u.v != 0: (I11 - I22) I13 I23 in the paper's frame is -det[b, A b] = {_text(-det)} != 0 "
                           "(b = (I13, I23), A the 2x2 block; rotation-invariant): not Liouvillian")
    root = isqrt((-w2).numerator) if -w2 > 0 and w2.denominator == 1 else None
    if root is not None and root * root == -w2 and root % 2 == 1:
        return GaloisGroup("reducible", True, method, "imprimitive (normaliser of a torus)",
                           f"u.v = 0 (b an eigenvector of A) and w_-^2 = lam (lam - mu)/|b|^2 = -{root}^2 (odd): kappa, "
                           "mu half-odd (Kimura's first family): the torus of rotations about n = u/|u|", root)
    return GaloisGroup("SO(3,C)", False, method, "SL(2,C)",
                       f"u.v = 0 (b an eigenvector of A) but w_-^2 = lam (lam - mu)/|b|^2 = {_text(w2)} is not minus the "
                       "square of an odd integer: not Liouvillian")


def _rotation_invariants(body: ExactBody) -> tuple:
    """(det[b, A b], w_-^2 when that determinant is 0 else None) from the scene's exact entries (rotation-invariant:
    :func:`galois_group`'s docstring)."""
    I11, I12, I22, I13, I23 = body.tensor
    det = _det_b_ab(I11, I12, I22, I13, I23)
    if det != 0:
        return det, None
    bb = I13 * I13 + I23 * I23
    lam = (I13 * (I11 * I13 + I12 * I23) + I23 * (I12 * I13 + I22 * I23)) / bb
    return det, lam * (lam - (I11 + I22 - lam)) / bb


def local_behaviour(body: ExactBody):
    """Meromorphic, logarithmic or branching at the poles of omega for the exact body (the certified theorem,
    :mod:`suslov.kernel.local_behaviour`), a ``LocalBehaviour``.  Rational entries: on them; irrational ones
    (I12 != 0): from the same rotation invariants as :func:`galois_group` (u.v = 0 iff det[b, A b] = 0, then
    ``Lambda^2 = -w_-^2 = -lam (lam - mu)/|b|^2``), exactly in rationals."""
    from suslov.kernel.local_behaviour import METHOD, classify
    from suslov.validated import local_behaviour as validated_local_behaviour

    if body.rational:
        return validated_local_behaviour(*body.entries)
    method = METHOD + "; the paper's frame has irrational entries here, so read from the rotation invariants"
    det, w2 = _rotation_invariants(body)
    if det != 0:
        return classify(None, None, f"u.v != 0 (det[b, A b] = {_text(det)} != 0)", method)
    return classify(-w2, (-w2, (0, 1)), "u.v = 0 (b an eigenvector of A)", method)


def enclosure(body: ExactBody, dps: int):
    """``suslov.validated.scattering_angle_enclosure`` (closed form, rigorous) of the exact body at ``dps`` digits;
    irrational entries are balls 40 bits tighter than asked, tightened further if the ball comes out wide."""
    from suslov.validated import scattering_angle_enclosure

    if body.rational:
        return scattering_angle_enclosure(*body.entries, dps=dps)
    prec = int(3.33 * dps) + 80
    for _ in range(4):
        result = scattering_angle_enclosure(*ball_entries(body, prec), dps=dps)
        if result.angle.is_finite() and float(result.angle.rad()) <= 10.0 ** -dps:
            return result
        prec *= 2
    return result
