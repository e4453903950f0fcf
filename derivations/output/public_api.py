"""The public functions of the generated module: signatures, docstrings and the runtime call each makes.

Rendered by ``templates/suslov_formulas.py.j2`` (one thin function per entry) so that the template
holds only what is emitted and this text lives in an ordinary module.  A docstring is the emitted
function's documentation: formula, paper label, error bound and a runnable example (the docs build and
``tests/test_docs.py`` run the examples); ``{scattering_certificates}`` is filled in by the build with
the keys of Theorem 5.4's certificates.  Each ``call`` passes the emitted functions and data
(``_omega``, ``INTEGRAL_PS``, ``_BASIS_SIGMA``, ...) to ``suslov.runtime``.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PublicFunction:
    name: str
    parameters: str
    returns: str
    doc: str
    call: str


def sections(scattering_certificates: str) -> list[tuple[str, list[PublicFunction]]]:
    """(section title, functions) in module order, docstrings completed with the build's data."""
    return [(title, [PublicFunction(f.name, f.parameters, f.returns,
                                    f.doc.replace("{scattering_certificates}", scattering_certificates), f.call)
                     for f in functions]) for title, functions in SECTIONS]


SECTIONS = [
    ('angular velocity', [
        PublicFunction(
            'omega',
            't: ArrayLike, p: ArrayLike, d: ArrayLike',
            'tuple[np.ndarray | np.float64, np.ndarray | np.float64]',
            r"""Angular velocity of the Suslov problem in the case I13 = 0 (paper: ``omegas``).

    Derived and certified formula (rate A = 1, energy F1 = p^2 (d^2+1)/d^2)::

        omega1(t) =  (p/d) tanh t
        omega2(t) = -(p/d) sqrt(d^2+1) sech t

    the solution of ``eq:sysfin`` (with the + sign, the only one consistent with the Euler
    equations) that tends to the steady rotations (+-p/d, 0) as t -> +-oo.  ``p`` real,
    non-zero; ``d > 0`` with ``d^2 = I11/I22 - 1``.

    ``t``, ``p`` and ``d`` broadcast like NumPy arrays; returns two float64 arrays of the
    broadcast shape (two ``np.float64`` when every argument is a scalar, as ufuncs do).  No overflow for any t.  Error bound (proven from the emitted code, rounding
    model with libm calls within 4 ulp, for every t, d in [1e-3, 1e3]): ``5e-15 |omega_i| +
    1e-300 (|p|/d) sqrt(d^2+1)`` per component (the second term where sech t underflows).

    >>> w1, w2 = omega([0.0, 1.0], 3, [0.5, 2.0])
    >>> float(w1[0]), round(float(w1[1]), 12)   # (3/2) tanh 1
    (0.0, 1.142391233934)
    """,
            '_angular.omega(_omega, t, p, d)'),
        PublicFunction(
            'omega_mp',
            't, p, d, dps: int | None = None',
            'tuple',
            r"""mpmath twin of :func:`omega` at ``dps`` significant digits (default ``mpmath.mp.dps``; scalars).

    Arguments: int, float, ``Fraction``, ``mpmath.mpf`` or a decimal string (``"0.1"`` is
    exactly one tenth).  Returns a pair of ``mpmath.mpf`` that print their ``dps`` digits
    (``mpmath.nstr(x, n)`` for another number of digits).

    >>> mpmath.nstr(omega_mp("0.25", 3, "0.5", dps=30)[0], 20)   # 6 tanh(1/4)
    '1.4695119744222547757'
    """,
            '_angular.omega_mp(_omega, t, p, d, dps)'),
        PublicFunction(
            'omega_general',
            't: ArrayLike, I11: ArrayLike, I22: ArrayLike, I13: ArrayLike, I23: ArrayLike,\n                  branch: int = 1',
            'tuple[np.ndarray | np.float64, np.ndarray | np.float64]',
            r"""General solution of the reduced Euler equations (paper ``eq:o12``, ``c's``, corrected).

    Inertia tensor with I12 = 0 (frame choice), constraint axis a = (0, 0, 1); the
    equations derived from d/dt(I omega) = I omega x omega + lambda a are::

        omega1' = -(I13 omega1 + I23 omega2) omega2 / I11
        omega2' =  (I13 omega1 + I23 omega2) omega1 / I22

    (only I11, I22, I13, I23 enter; the printed ``gen12`` is this field times -I11 I22).
    The normalised solution (rate A = 1) with r = branch sqrt(I11 I22) and
    D = I13^2 I22 + I23^2 I11 is::

        omega1 = (-I11 I22 I23 tanh t + I22 I13 r sech t) / D
        omega2 = ( I11 I22 I13 tanh t + I11 I23 r sech t) / D

    Any other solution is lambda omega(lambda (t - t0)).  All arguments but ``branch``
    broadcast; returns two float64 arrays (``np.float64`` for scalar arguments).  Error bound (proven from the emitted code, rounding
    model with libm calls within 4 ulp, for every t and ``I11``, ``I22``, ``max(|I13|, |I23|)`` at
    least 1e-3 of the largest entry): absolute ``6e-15 B + 1e-300``,
    ``B = (I11 I22 |I23| + I22 |I13| r + I11 I22 |I13| + I11 |I23| r)/D``.

    >>> w1, w2 = omega_general(0.0, 2.0, 1.0, 0.3, 0.5)
    >>> round(float(w1), 12), round(float(w2), 12)   # (I22 I13, I11 I23) sqrt(2)/D at t = 0, D = 0.59
    (0.719091641885, 2.396972139615)
    """,
            '_angular.omega_general(_omega_general, t, I11, I22, I13, I23, branch)'),
        PublicFunction(
            'omega_general_mp',
            't, I11, I22, I13, I23, branch: int = 1, dps: int | None = None',
            'tuple',
            r"""mpmath twin of :func:`omega_general` (scalars; strings for exact decimals), at ``dps`` digits
    (default: ``mpmath.mp.dps``).""",
            '_angular.omega_general_mp(_omega_general, t, I11, I22, I13, I23, branch, dps)'),
    ]),
    ('first integrals (shared recipe)', [
        PublicFunction(
            'first_integral_coefficients',
            'p: int, d',
            'dict',
            r"""Exact coefficients of P1, P2, P3 for odd p and rational d (Theorem 6.2, corrected).

    ``d`` is an int, a ``Fraction``, a float (its exact binary value) or a string such as
    ``"3/2"``.  Returns ``{"P1": [...], "P2": [...], "P3": [...]}`` with
    ``P_i = sum_k a[k] omega1^(p-k) omega2^k`` and ``a[k]`` exact fractions (``Fraction``).
    Normalisation (paper eq:p1): P1 = omega1 Q, Q = F1^((p-1)/2) F(omega2^2/F1), F(0) = 1,
    so P1 = omega1^p (d^2+1)^((p-1)/2) + ...; not rescaled.

    >>> first_integral_coefficients(1, "1/2")["P3"]
    [Fraction(0, 1), Fraction(-2, 5)]
    """,
            '_integrals.first_integral_coefficients(_integral_core, INTEGRAL_PS, p, d)'),
        PublicFunction(
            'first_integral',
            'p: int, d: ArrayLike, omega1: ArrayLike, omega2: ArrayLike, gamma1: ArrayLike,\n                   gamma2: ArrayLike, gamma3: ArrayLike',
            'np.ndarray | np.float64',
            r"""Polynomial first integral F3 = P1 g1 + P2 g2 + P3 g3 of eq:sysfin + Poisson (odd p; Theorem 6.2).

    P1, P2, P3 are homogeneous of degree p in (omega1, omega2):
    P1 = omega1 F1^((p-1)/2) F(omega2^2/F1) with F1 = (d^2+1) omega1^2 + omega2^2 and F the
    terminating 3F2(1/2, (1+p)/2, (1-p)/2; (d-ip)/(2d), (d+ip)/(2d); z) (F(0) = 1),
    P3 = -(d/p) L P1, P2 = (omega2/omega1)(P1 - (d/p) L P3),
    L = omega2/(d^2+1) d/domega1 - omega1 d/domega2.  (The printed eq:p23 has the wrong
    sign in P3 and pol_sol wrong coefficients: see the errata.)

    ``d`` and the five state arguments broadcast; returns float64 (an array, or ``np.float64`` for scalar arguments).  The coefficients are
    computed exactly from the float d and rounded once (cached per (p, d)); evaluated as
    ``s^p sum_i P_i(omega/s) gamma_i`` with ``s = max(|omega1|, |omega2|)`` and Horner's rule in
    the ratio of modulus <= 1 (``suslov.kernel.horner.combination``), the powers of two of s^p
    and of the coefficients' scale applied once at the end (no intermediate over- or
    underflow).  Error bound (proven from the evaluation's operations, rounding model with
    libm's pow within 4 ulp, BLAS sums in any order; ``derivations.proofs.integral_proof``):
    absolute ``2e-15 (p+1) s^p sum_i |gamma_i| sum_k |a_ik| + 5e-324`` (proven: (3p+14) u in
    place of 2e-15 (p+1); the last term: a result in float64's subnormal range) wherever
    ``|gamma_i| <= 1`` and ``sum_i |gamma_i| sum_k |a_ik| >= 2^-600 max |a_ik|`` (beyond, an
    underflow inside the scaled sum may exceed it).  Raises ValueError for even, non-integer or uncertified p,
    d <= 0, non-finite input, and when the value overflows float64 (use
    :func:`first_integral_mp` then).

    >>> w1, w2 = omega(0.3, 3, 0.5)
    >>> round(float(first_integral(3, 0.5, w1, w2, 1.0, 0.0, 0.0)), 6)   # P1 = w1 (F1 + c1 w2^2), F1 = 45
    70.872832
    """,
            '_integrals.first_integral(_integral_core, INTEGRAL_PS, p, d, omega1, omega2, gamma1, gamma2, gamma3)'),
        PublicFunction(
            'first_integral_mp',
            'p: int, d, omega1, omega2, gamma1, gamma2, gamma3, dps: int | None = None',
            '',
            r"""mpmath twin of :func:`first_integral` (scalars) at ``dps`` digits (default: ``mpmath.mp.dps``);
    coefficients exact in d.

    >>> mpmath.nstr(first_integral_mp(1, "0.5", 1, 2, "0.6", "0.8", 0, dps=30), 25)   # w1 g1 + w2 g2/(d^2+1)
    '1.88'
    """,
            '_integrals.first_integral_mp(_integral_core, INTEGRAL_PS, p, d, omega1, omega2, gamma1, gamma2, gamma3,\n                                       dps)'),
    ]),
    ('the orthonormal basis (shared recipe)', [
        PublicFunction(
            'gamma_basis',
            't: ArrayLike, p: int, d: ArrayLike',
            'np.ndarray',
            r"""Real orthonormal basis of solutions of the Poisson equations for odd p (Theorem 6.1, corrected).

    Returns an array of shape ``broadcast(t, d).shape + (3, 3)`` whose rows are gamma^(1),
    gamma^(2), gamma^(3) at time t, for omega(t) = ((p/d) tanh t, -(p/d) sqrt(d^2+1) sech t)
    (see :func:`omega`).  Conventions (certified by the build):

    * gamma^(1)(t) -> (-1, 0, 0) as t -> -oo and (+1, 0, 0) as t -> +oo (the boundary
      condition ``ss``), gamma^(1)_1 = tanh t F1(sech^2 t);
    * gamma^(2) - i sigma gamma^(3) = e^{i (p/d) t} V(t) with V -> (0, 1, i sigma) as t -> -oo
      (sigma = -1 for every odd p certified so far, ``_BASIS_SIGMA``);
    * the rows are orthonormal and the matrix is a rotation (det +1).

    Any solution of the Poisson equations is ``C @ gamma_basis(t, p, d)`` for a constant row
    vector ``C``.  ``p`` is one odd integer (3 and 3.0 both accepted); ``t`` and ``d``
    broadcast.  Evaluated as trigonometric polynomials in th = 2 arctan(e^-t) whose
    coefficients have sum of moduli at most sqrt(4p + 2) (no cancellation for large p, no overflow,
    no removable singularity at t = 0); coefficients enclosed once per (p, d) in python-flint balls
    and cached.  The phase (p/d) t is reduced in double-double arithmetic below 5.3e7 and enclosed
    in python-flint balls beyond, so no digits are lost for any t.  Error bound (proven from the
    run-time code, rounding model with libm calls within 4 ulp, for ``d`` in [1e-3, 1e3] and every
    ``t``, both phase branches): absolute ``1e-14 (p+1)^1.5`` in every entry.

    >>> B = gamma_basis([-40.0, 0.0, 40.0], 3, 0.5)
    >>> [round(float(v), 12) for v in B[:, 0, 0]]
    [-1.0, 0.0, 1.0]
    """,
            '_basis.gamma_basis(_basis_core, _BASIS_SIGMA, BASIS_PS, t, p, d)'),
        PublicFunction(
            'gamma_basis_mp',
            't, p: int, d, dps: int | None = None',
            '',
            r"""mpmath twin of :func:`gamma_basis` for scalar ``t`` and ``d``: a 3x3 ``mpmath.matrix`` (rows gamma^(i)).

    Arguments as in :func:`omega_mp` (strings for exact decimals).  The series coefficients
    are ball midpoints within 10^-(max(dps, 40) + 10) of the exact ones for this d (python-flint
    ball arithmetic, the precision raised until the balls are that narrow, cached per (p, d,
    dps)); the series and the phase are summed in mpmath at dps + 10 digits and the result is
    rounded to ``dps`` digits.

    >>> M = gamma_basis_mp("0.3", 1, "0.5", dps=30)
    >>> mpmath.nstr(mpmath.det(M), 25), bool(abs(M[0, 0] - math.tanh(0.3)) < 1e-15)   # a rotation; gamma1 = tanh t
    ('1.0', True)
    """,
            '_basis.gamma_basis_mp(_basis_core, _BASIS_SIGMA, BASIS_PS, t, p, d, dps)'),
    ]),
    ('scattering angle (Theorem 5.4)', [
        PublicFunction(
            'scattering_angle',
            'p: ArrayLike, d: ArrayLike',
            'np.ndarray | np.float64',
            r"""Angle Delta psi in [0, pi] between the axes of the limit steady rotations (Theorem 5.4, corrected).

    Case I13 = 0, omega as in :func:`omega`, any real ``p`` (not only integers) and
    ``d > 0``.  With the boundary condition ``ss`` (gamma -> (-1, 0, 0) as t -> -oo) the
    body axis e1 of the rotation at t -> -oo and the one at t -> +oo make the angle::

        cos(Delta psi / 2) = |cos(pi p/2)| / cosh(pi p/(2 d)),   cos(Delta psi) = -gamma1(+oo)

    (the paper's undefined ``q`` is ``d``; odd p gives Delta psi = pi).  Certified:
    {scattering_certificates}.

    Evaluated as ``2 atan2(sqrt(tanh^2 x + s^2 sech^2 x), c sech x)`` with
    ``x = pi |p|/(2d)`` and ``s``, ``c`` = ``|sin|``, ``|cos|`` of ``pi p/2`` with p reduced
    exactly (``suslov.kernel.phase.half_pi_parts``): no arccos near 1, no overflow for
    small d, accurate for p within 1e-12 of an integer.  ``p``, ``d`` broadcast (scalars give ``np.float64``).  Error
    bound (proven from the emitted code, rounding model with libm calls within 4 ulp, for
    ``pi |p|/(2d) <= 1024``): absolute 1.5e-14.

    >>> round(float(scattering_angle(2.0, 1.0)), 12)   # 2 arccos(1/cosh(pi))
    2.968844459491
    """,
            '_angle.scattering_angle(_scattering_angle, p, d)'),
        PublicFunction(
            'scattering_angle_mp',
            'p, d, dps: int | None = None',
            '',
            r"""mpmath twin of :func:`scattering_angle` (scalars; strings for exact decimals) at ``dps`` digits
    (default: ``mpmath.mp.dps``).

    >>> mpmath.nstr(scattering_angle_mp(1, "0.7", dps=30), 25)   # odd p: pi
    '3.141592653589793238462643'
    """,
            '_angle.scattering_angle_mp(_scattering_angle, p, d, dps)'),
        PublicFunction(
            'scattering_angle_ball',
            'p, d, dps: int | None = None, prec: int | None = None',
            '',
            r"""Ball enclosure (python-flint ``arb``) of the closed form of :func:`scattering_angle`.

    The same emitted expression evaluated in ball arithmetic at ``prec`` bits or ``dps`` digits (default:
    ``mpmath.mp.prec``, as the mp twins follow ``mpmath.mp.dps``): the ball contains
    the exact value of Theorem 5.4's angle at the given p, d.  ``p``, ``d``: ints, Fractions or
    decimal strings (exact), or floats (their binary value); scalars.  For the angle of a body
    whose p, d are not known exactly, or of a general body (I13 != 0), see
    :func:`suslov.validated.scattering_angle_enclosure` (validated integration).

    >>> ball = scattering_angle_ball(2, 1, prec=100)   # 2 arccos(1/cosh(pi)), to 100 bits
    >>> ball.rad() < 1e-28, round(float(ball.mid()), 12)
    (True, 2.968844459491)
    """,
            '_angle.scattering_angle_ball(_scattering_angle, p, d, dps, prec)'),
    ]),
    ('scattering angle of every body (closed form)', [
        PublicFunction(
            'general_scattering_angle',
            'I11: ArrayLike, I22: ArrayLike, I13: ArrayLike, I23: ArrayLike',
            'np.ndarray | np.float64',
            r"""Scattering angle Delta psi of any body (paper's frame: I12 = 0, a = e3), in closed form.

    With s = sinh t the Poisson equations of every body are Gauss's hypergeometric equation
    (certified: ``gauss``), and the angle between the limit rotation axes is ::

        cos^2(Delta psi/2) = [cosh(pi U) |tau|^2 - Re(tau^2)] / (2 sinh^2(pi U)),
        tau = 2 cos(pi kappa),  kappa = (i/2) w_-,  w_-^2 = (u - i v).(u - i v),  U = |u|

    for omega = u tanh t + v sech t (eq:o12); for I13 = 0 it is Theorem 5.4 (corrected), certified
    exactly.  Evaluated in a form with no cancellation and no overflow (``_general_angle``); the
    entries broadcast like NumPy arrays (scalars give ``np.float64``), I11, I22 > 0, not I13 = I23 = 0 (the equilibrium).
    Error bound, proven from the run-time code (rounding model, libm calls within 4 ulp) for
    I11, I22 >= 2^-20 times the largest entry and pi U/2 <= 7e13, in mixed form: the result is within
    400 u (u = 2^-53) of the exact angle at h, g, Y within relative 200 u of those (h = pi U/2,
    g = pi (U - X)/2, ``w_- = X + i Y``) of a body whose entries are within relative 2u (1 + u) of the
    given ones.  The angle depends on Y modulo 2, so the forward error grows with ``|Y|``; sampled
    against :func:`general_scattering_angle_mp` (numeric evidence) it is within ``1e-13 (1 + |Y|)``.

    >>> round(float(general_scattering_angle(1.25, 1, 0.3, -0.5)), 12)
    2.9591441765
    """,
            '_general.general_scattering_angle(_gauss_invariants, _general_angle, I11, I22, I13, I23)'),
        PublicFunction(
            'general_scattering_angle_mp',
            'I11, I22, I13, I23, dps: int | None = None',
            '',
            r"""mpmath twin of :func:`general_scattering_angle` (scalars; strings for exact decimals) at ``dps``
    digits (default: ``mpmath.mp.dps``).

    >>> mpmath.nstr(general_scattering_angle_mp("5/4", 1, "3/10", "-1/2", dps=30), 25)
    '2.959144176500328519'
    """,
            '_general.general_scattering_angle_mp(_gauss_invariants, _general_angle, I11, I22, I13, I23, dps)'),
        PublicFunction(
            'general_scattering_angle_ball',
            'I11, I22, I13, I23, dps: int | None = None, prec: int | None = None',
            '',
            r"""Ball enclosure (python-flint ``arb``) of the closed form of :func:`general_scattering_angle`
    at ``prec`` bits or ``dps`` digits (default: ``mpmath.mp.prec``): ints, Fractions or decimal strings
    are exact, floats their binary value.  The validated-integration route that checks it is
    :func:`suslov.validated.scattering_angle_enclosure` with ``method="integration"``.

    >>> ball = general_scattering_angle_ball("5/4", 1, "3/10", "-1/2", prec=1000)
    >>> ball.rad() < 1e-290, round(float(ball.mid()), 12)
    (True, 2.9591441765)
    """,
            '_general.general_scattering_angle_ball(_gauss_invariants, _general_angle, I11, I22, I13, I23, dps, prec)'),
    ]),
    ('numeric inertia tensors', [
        PublicFunction(
            'special_case_parameters',
            'I: ArrayLike, tol: float = 1e-9',
            'SpecialCase',
            r"""(p, d, frame) of a body with I13 = 0 (within ``tol``), chaining into the closed forms.

    Sign convention: the frame is the paper's (a = e3, I12 = 0, I11 >= I22, det I = 1),
    turned by pi about e3 when needed so that I23 < 0; then p = -I22 d/I23 > 0 and
    d = sqrt(I11/I22 - 1) (the certified inverse of eq:necc1's substitution), and
    :func:`omega`, :func:`gamma_basis` and :func:`first_integral` with these (p, d) describe
    the body's motion in ``frame`` (columns: its axes in the given frame).  Raises
    ValueError when I13 is not zero or I11 = I22 (d = 0).

    >>> p, d, R = special_case_parameters([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]])
    >>> round(p, 12), round(d, 12)
    (2.0, 1.0)
    """,
            '_bodies.special_case_parameters(_special_parameters, I, tol)'),
        PublicFunction(
            'kovalevskaya_exponents',
            'I: ArrayLike',
            'np.ndarray',
            r"""The five Kovalevskaya exponents -1, 1, 2, 1 + Lambda, 1 - Lambda (paper section 3.1, derived).

    ``I`` is a symmetric positive-definite 3x3 inertia tensor in any body frame whose third
    axis is the constraint vector a = (0, 0, 1); the function normalises det I = 1 and
    rotates about a to make I12 = 0 (the exponents do not depend on either).  Computed for
    the equations derived from d/dt(I w) = I w x w + lambda a (not the printed gen12) at the
    Darboux point with m3 = I13 w1 + I23 w2 = i sqrt(I11 I22); the conjugate point gives
    the conjugate exponents.  Returns a complex NumPy array of length 5.

    >>> np.round(kovalevskaya_exponents([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]]).real, 9)
    array([-1.,  1.,  2.,  3., -1.])
    """,
            '_bodies.kovalevskaya_exponents(_lambda_squared, I)'),
        PublicFunction(
            'meromorphy',
            'I: ArrayLike, tol: float = 1e-9',
            'Meromorphy',
            r"""Which case of Theorem 3.2 (corrected) holds for a numeric inertia tensor.

    In the frame of :func:`kovalevskaya_exponents` (I12 = 0, I11 >= I22): ``case`` is
    ``"I13=0"``, ``"I23=0"`` or ``"neither"`` (relative tolerance ``tol``); ``p_squared``
    is Lambda^2 (complex in the case "neither"); ``p`` = sqrt(p_squared) when it is real
    and >= 0, else None; ``odd`` is True when p is within ``tol`` of an odd integer.

    Derived (and certified, with exact Frobenius recursions) for the equations of motion
    from d/dt(I w) = I w x w + lambda a: all solutions of the Poisson equations are
    meromorphic iff I13 = 0 and ``p = sqrt(I22 (I11 - I22))/|I23|`` is an *odd* integer (I23 = 0
    gives p^2 <= 0 in this frame).  The paper's eq:necc1 differs by the factor (I11 I22)^2
    and admits even p, for which logarithms appear.

    >>> meromorphy([[2.0, 0, 0], [0, 1.0, 0.5], [0, 0.5, 1.5]]).case
    'I13=0'
    """,
            '_bodies.meromorphy(_lambda_squared, _p_squared_i13_zero, _p_squared_i23_zero, I, tol)'),
    ]),
]
