"""Proven float64 rounding-error bounds of the emitted functions (issue 34; replaces sampled round-trip bounds).

The emitted functions (``derivations.core.emit``) take their elementary functions from a number
context ``ctx``; here they are run with :class:`ErrorContext` on :class:`FE` values, so the *emitted
text itself*, operation by operation in Python's evaluation order (the order NumPy evaluates it in),
is what is analysed.  An ``FE`` carries

* ``v``: a python-flint ``arb`` ball containing every exact value over the current box of inputs;
* ``e``: an ``arb`` upper bound of |computed float64 value - exact value| over the box;
* ``r``, ``a``: a mixed bound |computed - exact| <= r |exact| + a at every point of the box.  Products,
  quotients, squares, sums of one sign and sqrt keep r small without the dependency of a box (the ratio
  of two balls' ends), and next to 0 (sqrt of a sum of squares at 0) r |x| + a is what keeps the bound
  tight; a is the absolute remainder (underflow, cancellation).

Rules (the standard model, every bound rigorous, higher-order terms included, not only first order):

* ``fl(a op b) = (a op b)(1 + delta) + eta``, ``|delta| <= u = 2^-53``, ``|eta| <= 2^-1074`` (underflow;
  0 for + and -); a product by a power of two is exact;
* propagation: ``|a~ b~ - a b| <= |a| e_b + |b| e_a + e_a e_b``, ``|a~/b~ - a/b| <= (e_a + |a/b| e_b) /
  (|b| - e_b)`` (refused when the box of b, widened by e_b, meets 0), sums add;
* a library call f (exp, expm1, tanh, sin, cos, atan2, hypot) contributes ``sup|f'| e_arg`` (sup over the
  argument ball widened by its error, from Arb) plus its rounding, assumed at most ``ULP_LIBM`` = 4 ulp
  (relative ``8 u`` plus ``4 * 2^-1074``): NumPy documents its SIMD float64 kernels within 4 ULP and glibc
  lists at most 1-2 ulp for these functions on x86_64; sqrt is correctly rounded (IEEE 754);
* the project's own reductions are walked like the emitted text: ``FLOAT.tanh_sech`` and
  ``FLOAT.sech`` (exp, expm1, products, one reciprocal) and ``phase.half_pi_parts``.

A bound is proven over a domain by covering it with boxes (Arb balls) and taking the worst box.
Method string of the certificates: "proven rounding-error bound, ball arithmetic over N boxes".
"""
from __future__ import annotations

from flint import arb

U = arb(2) ** -53                 # unit roundoff of binary64
ETA = arb(2) ** -1074             # smallest subnormal: the absolute part of an underflowing product
ULP_LIBM = 4                      # assumed accuracy of libm / NumPy transcendental kernels, in ulp
LIBM_REL = 2 * ULP_LIBM * U       # k ulp <= k 2^-52 |y| = 2 k u |y| for normal y
LIBM_ABS = ULP_LIBM * ETA
TINY = arb(2) ** -1021            # twice the smallest normal: a result above it cannot underflow
METHOD = "proven rounding-error bound, ball arithmetic over {n} boxes"


class BoundFailure(ArithmeticError):
    """The analysis cannot bound an operation on a box (a divisor or sqrt argument that may vanish)."""


def _mag(x: arb) -> arb:
    """An exact upper bound of |x| over the ball."""
    return arb(abs(x).abs_upper())


def _nonneg(x: arb) -> arb:
    return arb(x.abs_upper())


def _lower_abs(x: arb) -> arb:
    """A lower bound of |x| over the ball (0 when the ball meets 0)."""
    if x > 0:
        return arb(x.lower())
    if x < 0:
        return arb(-x.upper())
    return arb(0)


def _max(a: arb, b: arb) -> arb:
    return a if b < a else (b if a < b else arb(max(a.upper(), b.upper())))


def _min(a: arb, b: arb) -> arb:
    return a if a < b else (b if b < a else arb(min(a.upper(), b.upper())))


def largest(*values: arb) -> arb:
    """An exact upper bound of all the balls (the worst bound over boxes)."""
    return arb(max(value.upper() for value in values))


def gamma(n) -> arb:
    """Higham's gamma_n = n u/(1 - n u): n roundings, (1 + delta_1) ... (1 + delta_n) within 1 +- gamma_n."""
    return n * U / (1 - n * U)


class FE:
    """A float64 value over a box: exact values ``v``, absolute bound ``e``, mixed bound ``r |x| + a``."""

    __slots__ = ("v", "e", "r", "a", "sign", "w", "aw", "m", "low")

    def __init__(self, v, e=0, r=None, a=None, sign=0):
        # sign: +1 / -1 when every exact value of the box has that sign (or is 0), else 0; kept apart from
        # the ball because a ball of [0, h] may reach below 0 by its rounding
        self.v = arb(v)
        self.sign = sign or (1 if self.v >= 0 else (-1 if self.v <= 0 else 0))
        if self.sign > 0 and not self.v >= 0:
            self.v = self.v.nonnegative_part()          # [0, upper]: only where the ball reaches below 0
        elif self.sign < 0 and not self.v <= 0:
            self.v = -((-self.v).nonnegative_part())
        e = _nonneg(arb(e))
        if r is None:                  # no relative information: the absolute bound is the mixed one
            r, a = arb(0), e
        self.r, self.a = _nonneg(arb(r)), _nonneg(arb(a if a is not None else 0))
        self.e = _min(e, self.r * _mag(self.v) + self.a)
        # the magnitude form |computed - exact| <= w M + aw, M = the sum of |terms| (|x| itself unless a sum or a
        # product of sums made it), m an upper bound of M: Higham's bound for sums, with no cancellation
        # penalty; set by _sum and __mul__ after construction
        self.w, self.aw, self.m = self.r, self.a, _mag(self.v)
        # a lower bound of |x| kept as an exact number: a ball [1e-9, 1] cannot carry its lower end (the
        # radius has 30 bits); set by products, squares and one-sign sums after construction
        self.low = _lower_abs(self.v)

    def _with_low(self, low) -> "FE":
        if self.low < low:
            self.low = low
        return self

    def _with_magnitude(self, w, aw, m) -> "FE":
        self.w, self.aw, self.m = w, aw, m
        return self

    @staticmethod
    def lift(x) -> "FE":
        if isinstance(x, FE):
            return x
        if isinstance(x, float) or (isinstance(x, int) and abs(x) <= 2**53):
            return FE(arb(x), 0, 0, 0)       # a float64 constant of the emitted text is exact
        raise TypeError(f"cannot lift {x!r} to a float64 value")

    def _rounded(self, value, propagated, relative, absolute, exact_op=False, underflow=True, sign=0) -> "FE":
        """fl(z) = z (1 + delta) + eta of a result z known to within ``propagated`` and ``relative |x| + absolute``."""
        if exact_op:
            return FE(value, propagated, relative, absolute, sign)
        eta = ETA if underflow and not _lower_abs(value) > TINY else 0    # a normal result does not underflow
        return FE(value, propagated + U * (_mag(value) + propagated) + eta,
                  (1 + relative) * (1 + U) - 1, absolute * (1 + U) + eta, sign)

    def __add__(self, other):
        return self._sum(FE.lift(other), 1)

    __radd__ = __add__

    def __sub__(self, other):
        return self._sum(FE.lift(other), -1)

    def __rsub__(self, other):
        return FE.lift(other) - self

    def _sum(self, other, sign):
        value = self.v + sign * other.v
        propagated = self.e + other.e
        same = self.sign != 0 and self.sign == sign * other.sign
        if same:
            relative, absolute = _max(self.r, other.r), self.a + other.a      # one sign: no cancellation
        else:
            relative, absolute = arb(0), propagated
        out = self._rounded(value, propagated, relative, absolute, underflow=False, sign=self.sign if same else 0)
        if same:
            out._with_low(arb((self.low + other.low).lower()))
        # |err| <= w_a M_a + aw_a + w_b M_b + aw_b + u |a~ + b~| <= (max w (1 + u) + u)(M_a + M_b) + (aw_a + aw_b)(1 + u)
        return out._with_magnitude(_max(self.w, other.w) * (1 + U) + U, (self.aw + other.aw) * (1 + U), self.m + other.m)

    def __neg__(self):
        return FE(-self.v, self.e, self.r, self.a, -self.sign)._with_magnitude(self.w, self.aw, self.m)

    def __abs__(self):
        return FE(abs(self.v), self.e, self.r, self.a, 1)._with_magnitude(self.w, self.aw, self.m)

    def __mul__(self, other):
        other = FE.lift(other)
        if other is self:      # a square (x*x in the emitted text, or one memoised call twice): >= 0
            m = _mag(self.v)
            low = self.low
            return self._rounded((low * low).union(m * m), 2 * m * self.e + self.e**2, 2 * self.r + self.r**2,
                                 2 * self.a * m * (1 + self.r) + self.a**2, sign=1)._with_low(
                arb((low * low * (1 - self.r) ** 2 * (1 - U)).lower()) if self.r < 1 else arb(0))
        ma, mb = _mag(self.v), _mag(other.v)
        propagated = ma * other.e + mb * self.e + self.e * other.e
        relative = self.r + other.r + self.r * other.r
        absolute = other.a * ma * (1 + self.r) + self.a * mb * (1 + other.r) + self.a * other.a
        exact = _exact_scaling(self, other)
        if self.sign and other.sign:     # interval product from the ends: a mid-radius product loses the lower end
            ends = self.low * other.low
            value = (ends.union(ma * mb)) * (self.sign * other.sign)
        else:
            value = self.v * other.v
        out = self._rounded(value, propagated, relative, absolute, exact_op=exact, sign=self.sign * other.sign)
        # |a| <= M_a: |a~ b~ - a b| <= (w_a + w_b + w_a w_b) M_a M_b + aw_a m_b (1 + w_b) + aw_b m_a (1 + w_a) + aw_a aw_b
        w = self.w + other.w + self.w * other.w
        aw = self.aw * other.m * (1 + other.w) + other.aw * self.m * (1 + self.w) + self.aw * other.aw
        if not exact:
            w, aw = (1 + w) * (1 + U) - 1, aw * (1 + U) + (0 if self.low * other.low > TINY else ETA)
        out._with_low(arb((self.low * other.low).lower()))
        return out._with_magnitude(w, aw, self.m * other.m)

    __rmul__ = __mul__

    def __truediv__(self, other):
        other = FE.lift(other)
        low = other.low
        if not low - other.e > 0:
            raise BoundFailure(f"divisor {other.v} (error {other.e}) may vanish on this box")
        quotient = self.v / other.v
        mq = _mag(quotient)
        propagated = (self.e + mq * other.e) / (low - other.e)
        floor = low * (1 - other.r) - other.a
        if floor > 0:
            relative = (self.r + other.r) * low / floor
            absolute = (self.a + mq * other.a) / floor
        else:
            relative, absolute = arb(0), propagated
        # a division by a power of two is exact unless the quotient may be subnormal (it loses bits there)
        exact = other.e == 0 and _is_power_of_two(other.v) and _lower_abs(quotient) > TINY
        return self._rounded(quotient, propagated, relative, absolute, exact_op=exact, sign=self.sign * other.sign)

    def __rtruediv__(self, other):
        return FE.lift(other) / self


def _exact_scaling(a: "FE", b: "FE") -> bool:
    """A product by an exact 2^k: exact for k >= 0 (overflow is outside every domain here), and for k < 0
    unless the product may be subnormal (it loses bits there)."""
    for constant, other in ((b, a), (a, b)):
        if constant.e == 0 and _is_power_of_two(constant.v):
            return constant.low >= 1 or constant.low * other.low > TINY
    return False


def _is_power_of_two(x: arb) -> bool:
    if not x.is_exact() or x == 0:
        return False
    mantissa, _ = abs(x).mid().man_exp()
    return abs(int(mantissa)) == 1


def _widen(fe: FE) -> arb:
    return fe.v + arb(0, 1) * fe.e


def _library(value: arb, propagated: arb, relative=None, absolute=None, sign=0) -> FE:
    """A library result: the propagated error plus the call's rounding (LIBM_REL relative, LIBM_ABS absolute)."""
    if relative is None:
        low = _lower_abs(value)
        relative, absolute = (propagated / low, arb(0)) if low > 0 else (arb(0), propagated)
    return FE(value, propagated + LIBM_REL * (_mag(value) + propagated) + LIBM_ABS,
              (1 + relative) * (1 + LIBM_REL) - 1, absolute * (1 + LIBM_REL) + LIBM_ABS, sign)


def libm(value_of, derivative_of, x: FE) -> FE:
    """sup|f'| over the widened argument times its error, plus the call's own rounding."""
    return _library(value_of(x.v), _mag(derivative_of(_widen(x))) * x.e)


def _concave_through_zero(value_of, derivative_of, x: FE) -> FE:
    """f with f(0) = 0, concave and increasing on the argument's range (sin on [0, pi/2], tanh on [0, oo)):
    f((1 + theta) x) is within |theta| f(x) of f(x), so the relative part passes unchanged."""
    slope = _mag(derivative_of(_widen(x)))
    return _library(value_of(x.v), slope * x.e, x.r, slope * x.a, sign=1)


def _increasing(function):
    """An increasing function on a ball from its values at the two ends: arb's evaluation at the midpoint with
    a radius term would give exp of [-4e19, -3e4] as a ball of radius e^(2e19)."""
    def on_ball(ball: arb) -> arb:
        if not ball.is_finite():
            return function(ball)
        return function(arb(ball.lower())).union(function(arb(ball.upper())))
    return on_ball


_exp = _increasing(lambda a: a.exp())
_expm1 = _increasing(lambda a: a.expm1())
_tanh = _increasing(lambda a: a.tanh())


def exp(x: FE) -> FE:
    """exp(x + D) = exp(x) exp(D): relative expm1(|D|) <= expm1(e_x)."""
    return _library(_exp(x.v), _mag(_exp(_widen(x))) * x.e, x.e.expm1(), arb(0), sign=1)


def expm1(x: FE) -> FE:
    """The absolute rule of :func:`libm`, and where x's error is purely relative (|x~ - x| <= r |x|) the relative
    one: expm1(x (1 + t)) - expm1(x) is at most |x t| e^max(x, x(1+t)), and |expm1(x)| >= |x| e^min(x, 0), so the
    relative change is at most r exp(max(x, 0) (1 + r) + |x| r); the smaller bound is kept."""
    out = libm(_expm1, _exp, x)
    if x.a == 0 and x.r < 1:      # a purely relative form is what the products and sqrt downstream keep
        top = arb(x.v.upper())
        growth = (arb(0) if not top > 0 else top * (1 + x.r)) + _mag(x.v) * x.r
        relative = _library(_expm1(x.v), out.e, x.r * growth.exp(), arb(0))
        if relative.r < 1:
            out = FE(out.v, _min(out.e, relative.e), relative.r, relative.a)
    return out


def tanh(x: FE) -> FE:
    if x.sign > 0:
        return _concave_through_zero(_tanh, _sech_squared, x)
    return libm(_tanh, _sech_squared, x)


def _sech_squared(a: arb) -> arb:
    """tanh' = sech^2, decreasing in |a|: [0, sech(min |a|)^2] (a product: arb's power of a ball about 0 is NaN)."""
    s = arb(_lower_abs(a)).sech()
    return arb(0).union(s * s)


def sin(x: FE) -> FE:
    """The relative rule for exact arguments in [0, pi/2] whose computed value stays in [0, pi]: sin is concave there
    with sin 0 = 0, so sin(l x) is within |l - 1| sin(x) of sin(x) for l > 1 too (below l sin x, above the chord
    to (pi, 0): (1 - (l - 1) x/(pi - x)) sin x, and x/(pi - x) <= 1)."""
    if x.sign > 0 and x.v <= arb.pi() / 2 and _widen(x) <= arb.pi():
        return _concave_through_zero(lambda a: a.sin(), lambda a: a.cos(), x)
    return libm(lambda a: a.sin(), lambda a: a.cos(), x)


def cos(x: FE) -> FE:
    return libm(lambda a: a.cos(), lambda a: a.sin(), x)


def sqrt(x: FE) -> FE:
    """Correctly rounded (relative u).  |sqrt a - sqrt b| <= |a - b|/(sqrt a + sqrt b) <= sqrt|a - b|; in the
    mixed form sqrt(x (1 +- r) +- a) is within (1 - sqrt(1 - r)) sqrt(x) + sqrt(a) of sqrt(x)."""
    if x.v < 0:
        raise BoundFailure(f"sqrt of {x.v}: negative on this box")
    negative_part = x.sign <= 0 and x.v.lower() < 0
    value = x.v.sqrt() if not negative_part else arb(0).union(arb(x.v.upper()).sqrt())
    low = arb(-1) if negative_part else arb(x.v.lower()) - x.e
    propagated = x.e / (2 * low.sqrt()) if low > 0 else x.e.sqrt()
    if x.r < 1:
        relative, absolute = 1 - (1 - x.r).sqrt(), x.a.sqrt()
    else:
        relative, absolute = arb(0), propagated
    return x._rounded(value, propagated, relative, absolute, underflow=False, sign=1)


def atan2(y: FE, x: FE) -> FE:
    """|atan2(y~, x~) - atan2(y, x)| <= sup (|x| e_y + |y| e_x)/(x^2 + y^2) over the widened balls."""
    y, x = FE.lift(y), FE.lift(x)
    wy, wx = _widen(y), _widen(x)
    low = _lower_abs(wx) * _lower_abs(wx) + _lower_abs(wy) * _lower_abs(wy)
    if not low > 0:
        raise BoundFailure("atan2 next to (0, 0) on this box")
    propagated = (_mag(wx) * y.e + _mag(wy) * x.e) / low
    if x.r < 1 and y.r < 1:
        # relative parts: atan2(y (1+a), x (1+b)) = atan2(y, x (1+b)/(1+a)), and |d atan2/d log x| =
        # |x y|/(x^2 + y^2) <= 1/2, so they move the angle by at most (|log(1+a)| + |log(1+b)|)/2;
        # then the absolute parts, with the widened balls
        split = (y.r / (1 - y.r) + x.r / (1 - x.r)) / 2 + (_mag(wx) * y.a + _mag(wy) * x.a) / low
        propagated = _min(propagated, split)
    return _library(arb.atan2(y.v, x.v), propagated)


def hypot(x: FE, y: FE) -> FE:
    """|hypot(x~, y~) - hypot(x, y)| <= e_x + e_y (hypot is 1-Lipschitz in each argument)."""
    x, y = FE.lift(x), FE.lift(y)
    low = (_lower_abs(x.v) * _lower_abs(x.v) + _lower_abs(y.v) * _lower_abs(y.v)).sqrt()
    high = (_mag(x.v) * _mag(x.v) + _mag(y.v) * _mag(y.v)).sqrt()
    return _library(low.union(high), x.e + y.e, sign=1)


def _fingerprint(x) -> tuple:
    """Equal for two FE values with the same ball, bounds and sign (an id for anything else)."""
    if not isinstance(x, FE) or not all(b.is_finite() for b in (x.v, x.e, x.r, x.a)):
        return ("id", id(x))
    exact = lambda b: (b.mid().man_exp(), b.rad().man_exp())  # noqa: E731
    return (exact(x.v), exact(x.e), exact(x.r), exact(x.a), x.sign)


class ErrorContext:
    """The float64 context (``suslov.kernel.contexts.FLOAT``) as error propagation, operation by operation.

    One instance per box: a call repeated on the same argument (``ctx.sech(x)*ctx.sech(x)``) returns the
    same object, as the float computation returns the same number, so the product is known to be a square."""

    def __init__(self):
        self._memo = {}

    def _once(self, name, function, *args):
        # keyed by the values, not the objects: ``expm1(2*g - 2*h)`` written twice in the emitted text builds two
        # equal FE arguments, and the float computation returns the same number for both (so their product is a square)
        key = (name,) + tuple(_fingerprint(a) for a in args)
        if key not in self._memo:
            self._memo[key] = (function(*args), args)      # args kept: ids of non-FE arguments stay theirs
        return self._memo[key][0]

    def tanh(self, x):
        return self._once("tanh", tanh, x)

    def sqrt(self, x):
        return self._once("sqrt", sqrt, x)

    def atan2(self, y, x):
        return atan2(y, x)

    def exp(self, x):
        return self._once("exp", exp, x)

    def expm1(self, x):
        return self._once("expm1", expm1, x)

    def hypot(self, x, y):
        return hypot(x, y)

    def tanh_sech(self, t):
        return self._once("tanh_sech", _tanh_sech, t)

    def sech(self, t):
        return self._once("sech", _sech, t)


def _tanh_sech(t: FE):
    """FLOAT.tanh_sech: a = -|t|, e = exp(a), m = expm1(a), inv = 1/(e e + 1), tanh = -(e + 1) m inv
    with t's sign, sech = 2 e inv (the same operations in the same order)."""
    a = -abs(t)
    e = exp(a)
    m = expm1(a)
    inverse = 1.0 / (e * e + 1.0)
    th = -(((e + 1.0) * m) * inverse)
    if t.v < 0:
        th = -th
    elif not t.v >= 0:      # a box meeting both signs: tanh's values of either sign, the same error
        th = FE(th.v.union(-th.v), th.e, th.r, th.a, 0)
    return th, (e * 2.0) * inverse


def _sech(t: FE) -> FE:
    """FLOAT.sech: e = exp(-|t|), 2 e/(1 + e e)."""
    e = exp(-abs(t))
    return (2.0 * e) / (1.0 + e * e)
