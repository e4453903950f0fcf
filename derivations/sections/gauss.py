"""The Poisson equations of every body as Gauss's hypergeometric equation (the open problem, closed form).

Paper: eq:whole (``gamma' = gamma x omega``), eq:o12 (``omega = u tanh t + v sech t`` for any body
with I12 = 0, a = e3), eq:genhipprep and the Conclusion, which leaves the general case open.  The
paper reaches Gauss's equation only for I13 = 0 (eq:ghyp, through z = sech^2 t and a third-order
equation); here every body gets it, by a different change of variable.  Every step is an exact
zero test (:mod:`derivations.core.exact`):

1. **s = sinh t.**  ``ds/dt = cosh t``, ``tanh t = s/cosh t``, ``sech t = 1/cosh t`` and
   ``cosh^2 t = 1 + s^2`` give ``dgamma/ds = gamma x Omega(s)``, ``Omega(s) = (u s + v)/(1 + s^2)``:
   a Fuchsian system with exactly three singular points, ``s = i``, ``-i``, ``oo``, residues
   ``(u - i v)/2``, ``(u + i v)/2`` and ``-u`` (partial fractions; at infinity in ``z = 1/s``).
2. **Spinor lift.**  With ``S(w) = -(i/2) (w1 sigma3 + w2 sigma1 + w3 sigma2)`` (a Lie algebra
   isomorphism so(3) -> sl(2): ``[S(a), S(b)] = S(a x b)``), ``Psi' = -S(Omega) Psi`` lifts the
   Poisson equations: ``Psi S(gamma0) Psi^-1 = S(gamma)`` solves them (``[-S(Omega), S(g)] = S(g x
   Omega)``).  The lift is again Fuchsian with the same three points; its residues are traceless with
   eigenvalues ``+-(1/2)`` those of the cross-product residues, so the exponent differences are
   ``kappa = (i/2) w_-`` at s = i, ``mu = (i/2) w_+`` at s = -i and ``i U`` at infinity,
   ``w_-+^2 = (u -+ i v).(u -+ i v)``, ``U^2 = u.u``.
3. **Frame.**  A rotation about e3 (the cross product is covariant: ``(aR) x (bR) = (a x b)R``,
   ``det R = 1``) puts ``u = (U, 0, 0)``, ``v = (v1, v2, 0)`` with ``U v1 = u.v`` and
   ``U v2 = (u x v)_3``; for a body, ``(u x v)_3 = -I11 I22 r/(I11 I23^2 + I13^2 I22) != 0``.
4. **Scalar equation without apparent singularity.**  In that frame the residue at infinity of the
   lift is diagonal, so the off-diagonal entry of ``-S(Omega)`` is ``(i/2) v2/(1 + s^2)``: no zero in
   the finite plane.  Eliminating psi2 gives, for ``y = psi1``,
   ``y'' + 2s/(1+s^2) y' - (a' + 2 s a/(1+s^2) + a^2 + b^2) y = 0`` with ``a = (i/2)(U s + v1)/(1+s^2)``,
   ``b = (i/2) v2/(1+s^2)``: Fuchsian with the same three singular points (Riemann's equation).
5. **Gauss.**  ``z = (1 + i s)/2`` sends ``s = i, -i, oo`` to ``z = 0, 1, oo``, and
   ``y = z^(kappa/2) (1-z)^(mu/2) F(z)`` turns it into
   ``z(1-z) F'' + (C - (A+B+1) z) F' - A B F = 0``, ``A = (2 + kappa + mu + i U)/2``,
   ``B = (kappa + mu - i U)/2``, ``C = 1 + kappa``: exponent differences kappa, mu and ``1 + i U`` (the
   lift's ``i U`` shifted by the integer 1 in the component psi1, which matters for the parity test of
   Kimura's theorem, :mod:`derivations.sections.general_galois`),
   certified in ``Q(U, v1, v2, z)[kappa, mu, i]`` modulo ``kappa^2 = -w_-^2/4``, ``mu^2 = -w_+^2/4``:
   both square-root branches at once.  Every solution of the Poisson equations of every body is
   therefore a quadratic expression in ``z^(kappa/2)(1-z)^(mu/2)`` times 2F1 functions and their
   derivatives (``psi2 = (psi1' - a psi1)/b``).
6. **The body's invariants.**  ``U^2``, ``|u|^2 - |v|^2``, ``u.v`` and ``(u x v)_3`` as rational functions
   of the inertia tensor (and r = sqrt(I11 I22)), and ``w_-^2 = -conj(Lambda^2)``: the Kovalevskaya
   exponent of eq:kowal fixes the exponent difference at ``s = i``.  These are emitted
   (``_gauss_invariants``) for the general scattering angle (:mod:`derivations.sections.general_angle`).
"""
from __future__ import annotations

import sympy as sp

from derivations.core.certificates import CertificateLog
from derivations.core.differential import S, T
from derivations.core.emit import Emitted
from derivations.core.exact import Domain, Extension, certify_zero
from derivations.core.result import DerivationResult
from derivations.core.symbols import I11, I13, I22, I23, d, p, r, w1, w2
from derivations.sections.model import R_EXT

NAME = "gauss"
TITLE = "The general case in closed form: Gauss's hypergeometric equation for every body"
REQUIRES = ("model",)

j = sp.Symbol("j")                       # the imaginary unit as an extension (j^2 = -1)
s, z, F0, F1, F2 = sp.symbols("s z F F1 F2")
U, v1, v2 = sp.symbols("U v1 v2")
kappa, mu = sp.symbols("kappa mu")
u_ = sp.symbols("u1:4")
v_ = sp.symbols("v1:4", real=True)
g_ = sp.symbols("g1:4")
psi1, psi2 = sp.symbols("psi1 psi2")
I_EXT = Extension(j, sp.Integer(-1), "j = i = sqrt(-1)")
W_MINUS2 = (U - j * v1) ** 2 - v2**2     # (u - i v).(u - i v) in the frame u = (U, 0, 0)
W_PLUS2 = (U + j * v1) ** 2 - v2**2
KAPPA_EXT = Extension(kappa, -W_MINUS2 / 4, "kappa = (i/2) w_-, either root")
MU_EXT = Extension(mu, -W_PLUS2 / 4, "mu = (i/2) w_+, either root")
COMPLEX = Domain("Q(u, v, s)[i]/(i^2+1)", (I_EXT,))
TS = Domain("Q(u, v)[T][S]/(S^2+T^2-1)", (Extension(S, 1 - T**2, "S = sech t"),))
GAUSS = Domain("Q(U, v1, v2, z)[kappa, mu, i]/(kappa^2 + w_m^2/4, mu^2 + w_p^2/4, i^2+1)", (KAPPA_EXT, MU_EXT, I_EXT))
BODY = Domain("Q(I11,I22,I13,I23)[r, i]/(r^2-I11 I22, i^2+1)", (R_EXT, I_EXT))
PLAIN = Domain("Q(a, b, g)")


def spinor(w) -> sp.Matrix:
    """S(w) = -(i/2)(w1 sigma3 + w2 sigma1 + w3 sigma2), with i as the extension symbol j."""
    return -j / 2 * sp.Matrix([[w[0], w[1] - j * w[2]], [w[1] + j * w[2], -w[0]]])


def cross(a, b) -> list:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def body_invariants(u, v) -> dict:
    """U^2, |u|^2 - |v|^2, u.v and (u x v)_3 of omega = u tanh t + v sech t (u, v in the plane)."""
    return {"U2": u[0] ** 2 + u[1] ** 2, "a": u[0] ** 2 + u[1] ** 2 - v[0] ** 2 - v[1] ** 2,
            "uv": u[0] * v[0] + u[1] * v[1], "cross": u[0] * v[1] - u[1] * v[0]}


DEN = I11 * I23**2 + I13**2 * I22
# the closed forms of the invariants (their products keep every difference of inputs explicit: no cancellation)
INVARIANTS = {"U2": I11**2 * I22**2 * (I13**2 + I23**2) / DEN**2,
              "a": I11 * I22 * (I11 - I22) * (I13**2 * I22 - I11 * I23**2) / DEN**2,
              "uv": r * I11 * I13 * I22 * I23 * (I11 - I22) / DEN**2,
              "cross": -I11 * I22 * r / DEN}


def invariants_emitted(certificates: tuple = ()) -> Emitted:
    """The emitted ``_gauss_invariants(ctx, I11, I22, I13, I23)`` -> (U^2, a, b, c2): ``w_-^2 = a + i b``,
    ``b = -2 u.v``, ``c2 = (u x v)_3^2``, r = sqrt(I11) sqrt(I22).  Its code does not depend on the
    certificate keys (only its docstring names them), so the ball checks of
    :mod:`derivations.sections.general_angle` can start from it before this derivation runs."""
    i11, i22, i13, i23 = sp.symbols("I11 I22 I13 I23", positive=True)
    sub = {I11: i11, I22: i22, I13: i13, I23: i23}
    den = DEN.subs(sub)
    return Emitted("gauss_invariants", (i11, i22, i13, i23), ((r, sp.sqrt(i11) * sp.sqrt(i22)),),
                   (INVARIANTS["U2"].subs(sub), INVARIANTS["a"].subs(sub), -2 * INVARIANTS["uv"].subs(sub),
                    i11**3 * i22**3 / den**2), certificates,
                   "(U^2, a, b, c2) of a body: w_-^2 = a + i b = (u - i v).(u - i v), U^2 = u.u, c2 = (u x v)_3^2.")


# the conditions of the formulas (printed with them, and in the formula catalog)
BODY_HYPOTHESES = (r"$I_{11},I_{22}>0$", r"$I_{12}=0$", r"$(I_{13},I_{23})\ne0$")
OMEGA_HYPOTHESIS = r"$\omega=u\tanh t+v\operatorname{sech}t$, $u=(u_1,u_2,0)$, $v=(v_1,v_2,0)$ real"
FRAME_HYPOTHESIS = r"the frame $u=(U,0,0)$, $v=(v_1,v_2,0)$ (a rotation about $e_3$)"
BRANCH_HYPOTHESIS = r"$\kappa^2=-w_-^2/4$, $\mu^2=-w_+^2/4$: either root (both certified)"
# the catalog's symbols: the components of u and v (real), i, the functions of s and z, the exponent names
U_PLANE = sp.symbols("u1 u2", real=True) + (sp.Integer(0),)
V_PLANE = sp.symbols("v1 v2", real=True) + (sp.Integer(0),)
F_OF_Z = sp.Function("F")(z)
WMINUS, WPLUS, LAMBDA, D_NAME = sp.symbols("wminus wplus Lambda D")
A_NAME, B_NAME, C_NAME = sp.symbols("A B C")


def _omega_of_s() -> list:
    return [(uk * s + vk) / (1 + s**2) for uk, vk in zip(U_PLANE, V_PLANE)]


def _dots() -> tuple:
    """u.u, v.v, u.v of the plane vectors."""
    return (sum(a * a for a in U_PLANE), sum(a * a for a in V_PLANE), sum(a * b for a, b in zip(U_PLANE, V_PLANE)))


def system_expr() -> sp.Tuple:
    """gauss_system as SymPy: dgamma/ds = gamma x Omega(s) (gamma_k(s)), Omega's partial fractions, and
    Res_{s=oo} Omega ds = -lim s Omega(s) = -u (the residues of c_partial, c_infinity)."""
    gamma_s = [sp.Function(f"gamma{k}")(s) for k in (1, 2, 3)]
    omega = _omega_of_s()
    partial = [(uk - sp.I * vk) / 2 / (s - sp.I) + (uk + sp.I * vk) / 2 / (s + sp.I) for uk, vk in zip(U_PLANE, V_PLANE)]
    return sp.Tuple(sp.Eq(sp.ImmutableMatrix([[g.diff(s) for g in gamma_s]]), sp.ImmutableMatrix([cross(gamma_s, omega)]),
                          evaluate=False),
                    sp.Eq(sp.ImmutableMatrix([omega]), sp.ImmutableMatrix([partial]), evaluate=False),
                    *[sp.Eq(-sp.Limit(s * w, s, sp.oo), -uk, evaluate=False) for w, uk in zip(omega[:2], U_PLANE)])


def lift_expr() -> sp.Tuple:
    """gauss_lift as SymPy: Psi' = -S(Omega) Psi (Psi_kl(s)), Psi S(gamma0) = S(gamma) Psi (the display's
    Psi S(gamma0) Psi^-1 = S(gamma)), the exponent differences and w_-+^2, with :func:`spinor` (i for j)."""
    Psi = sp.ImmutableMatrix(2, 2, [sp.Function(f"Psi{k}{l}")(s) for k in (1, 2) for l in (1, 2)])
    S_ = lambda w: sp.ImmutableMatrix(spinor(w).subs(j, sp.I))  # noqa: E731
    gamma0 = sp.symbols("gamma01:4")
    gamma_s = [sp.Function(f"gamma{k}")(s) for k in (1, 2, 3)]
    uu, vv, uv = _dots()
    return sp.Tuple(sp.Eq(Psi.diff(s), -S_(_omega_of_s()) * Psi, evaluate=False),
                    sp.Eq(Psi * S_(gamma0), S_(gamma_s) * Psi, evaluate=False),
                    sp.Eq(kappa, sp.I / 2 * WMINUS, evaluate=False), sp.Eq(mu, sp.I / 2 * WPLUS, evaluate=False),
                    sp.Eq(sp.Symbol("Deltainfinity"), sp.I * U, evaluate=False),
                    sp.Eq(WMINUS**2, uu - vv - 2 * sp.I * uv, evaluate=False),
                    sp.Eq(WPLUS**2, uu - vv + 2 * sp.I * uv, evaluate=False))


def gauss_equation_expr() -> sp.Tuple:
    """gauss_equation as SymPy (A, B, C named; ``run`` checks the equation against the certified one)."""
    Fz = F_OF_Z
    return sp.Tuple(sp.Eq(psi1, z ** (kappa / 2) * (1 - z) ** (mu / 2) * Fz, evaluate=False),
                    sp.Eq(z, (1 + sp.I * s) / 2, evaluate=False),
                    sp.Eq(z * (1 - z) * Fz.diff(z, 2) + (C_NAME - (A_NAME + B_NAME + 1) * z) * Fz.diff(z)
                          - A_NAME * B_NAME * Fz, 0, evaluate=False),
                    sp.Eq(A_NAME, (2 + kappa + mu + sp.I * U) / 2, evaluate=False),
                    sp.Eq(B_NAME, (kappa + mu - sp.I * U) / 2, evaluate=False),
                    sp.Eq(C_NAME, 1 + kappa, evaluate=False))


def invariants_expr() -> sp.Tuple:
    """gauss_invariants as SymPy, from :data:`INVARIANTS` (D named): U^2, D, r, w_-^2 = -conj(Lambda^2) and its
    closed form ``(a - 2 i u.v)`` factored as displayed (equal to INVARIANTS' a - 2 i uv, checked here)."""
    closed = I11 * I22 * (I11 - I22) * (I13**2 * I22 - I11 * I23**2 - 2 * sp.I * r * I13 * I23) / D_NAME**2
    if sp.expand((closed.subs(D_NAME, DEN) - INVARIANTS["a"] + 2 * sp.I * INVARIANTS["uv"]) * DEN**2) != 0:
        raise ArithmeticError("the displayed w_-^2 differs from the certified invariants")
    return sp.Tuple(sp.Eq(U**2, INVARIANTS["U2"].xreplace({DEN: D_NAME}), evaluate=False),
                    sp.Eq(D_NAME, DEN, evaluate=False), sp.Eq(r, sp.sqrt(I11 * I22), evaluate=False),
                    sp.Eq(WMINUS**2, -sp.conjugate(LAMBDA**2), evaluate=False),
                    sp.Eq(WMINUS**2, closed, evaluate=False))


def exponents_expr() -> sp.Tuple:
    """gauss_exponents as SymPy: one row ``(s, z, exponents of the lift, exponents of F)`` per singular point
    (the point at infinity written ``oo``: Maple has no complex infinity), then the display's relations; the last three hold for I13 = 0 (p, d of section 4)."""
    rows = sp.Tuple(sp.Tuple(sp.I, 0, sp.Tuple(kappa / 2, -kappa / 2), sp.Tuple(0, 1 - C_NAME)),
                    sp.Tuple(-sp.I, 1, sp.Tuple(mu / 2, -mu / 2), sp.Tuple(0, C_NAME - A_NAME - B_NAME)),
                    sp.Tuple(sp.oo, sp.oo, sp.Tuple(sp.I * U / 2, -sp.I * U / 2), sp.Tuple(A_NAME, B_NAME)))
    uu, _, _ = _dots()
    return sp.Tuple(rows,
                    sp.Eq(1 - C_NAME, -kappa, evaluate=False), sp.Eq(C_NAME - A_NAME - B_NAME, -mu, evaluate=False),
                    sp.Eq(A_NAME - B_NAME, 1 + sp.I * U, evaluate=False),
                    sp.Eq(kappa, sp.I / 2 * WMINUS, evaluate=False), sp.Eq(mu, sp.I / 2 * WPLUS, evaluate=False),
                    sp.Eq(mu, -sp.conjugate(kappa), evaluate=False), sp.Eq(U, sp.sqrt(uu), evaluate=False),
                    sp.Eq(kappa, -mu, evaluate=False), sp.Eq(kappa**2, p**2 / 4, evaluate=False),
                    sp.Eq(U, sp.Abs(p) / d, evaluate=False))


def run(log: CertificateLog, options, model_result) -> DerivationResult:
    result = DerivationResult(NAME)
    u3, v3 = list(u_[:2]) + [0], list(v_[:2]) + [0]

    # 1. s = sinh t: dgamma/dt = (ds/dt) dgamma/ds with s = T/S, ds/dt = cosh t = 1/S
    s_of_t = T / S
    omega_s = [(uk * s_of_t + vk) / (1 + s_of_t**2) for uk, vk in zip(u_[:2], v_[:2])]
    c_sinh = certify_zero(log, "with $s = sinh t$: $(ds/dt) Omega(s) = u tanh t + v sech t$ for $Omega(s) = (u s + v)/(1 + s^2)$, "
                          "so $deriv(gamma, s) = cross(gamma, Omega(s))$", "eq:whole",
                          [w / S - (uk * T + vk * S) for w, uk, vk in zip(omega_s, u_[:2], v_[:2])], TS)
    partial = [(uk * s + vk) / (1 + s**2) - ((uk - j * vk) / 2 / (s - j) + (uk + j * vk) / 2 / (s + j))
               for uk, vk in zip(u_[:2], v_[:2])]
    c_partial = certify_zero(log, "$Omega(s) = ((u - i v)/2)/(s - i) + ((u + i v)/2)/(s + i)$: simple poles at $s = pm(i)$ "
                             "with residues $(u - i v)/2$, $(u + i v)/2$", "eq:whole", partial, COMPLEX)
    zeta = sp.Symbol("zeta")
    at_infinity = [-(uk / zeta + vk) / (1 + 1 / zeta**2) / zeta**2 - (-(uk + vk * zeta) / (zeta * (1 + zeta**2)))
                   for uk, vk in zip(u_[:2], v_[:2])]
    c_infinity = certify_zero(log, "in $zeta = 1/s$: $deriv(gamma, zeta) = cross(gamma, -(u + v zeta)/(zeta (1 + zeta^2)))$: a simple "
                              "pole at $s = oo$ with residue $-u$; no other singular point", "eq:whole", at_infinity,
                              Domain("Q(u, v, zeta)"))

    # 2. the spinor lift
    c_algebra = certify_zero(log, "$S(a) S(b) - S(b) S(a) = S(cross(a, b))$ for $S(w) = -(i/2)(w1 sigma3 + w2 sigma1 + w3 sigma2)$: "
                             "the Lie algebras of $SO(3, C)$ and $SL(2, C)$ are isomorphic", "derived",
                             list(spinor(u_) * spinor(g_) - spinor(g_) * spinor(u_) - spinor(cross(u_, g_))),
                             Domain("Q(a, b)[i]/(i^2+1)", (I_EXT,)))
    c_lift = certify_zero(log, "spinor lift: $deriv(Psi, s) = -S(Omega) Psi$ gives the derivative of $Psi S(g0) Psi^-1$ as the commutator of "
                          "$-S(Omega)$ and $S(g)$, which is $S(cross(g, Omega))$: the Poisson equations are the adjoint of a traceless Fuchsian system of 2 by 2 matrices",
                          "eq:whole", list(-spinor(u_) * spinor(g_) + spinor(g_) * spinor(u_) - spinor(cross(g_, u_))),
                          Domain("Q(a, b)[i]/(i^2+1)", (I_EXT,)))
    lam = sp.Symbol("lambda")
    char = (lam * sp.eye(2) + spinor(u_)).det() - (lam**2 + (u_[0] ** 2 + u_[1] ** 2 + u_[2] ** 2) / 4)
    c_half = certify_zero(log, "$det(lam + S(w)) = lam^2 + wdotw/4$: the lift's residues have eigenvalues "
                          "$pm((i/2) sqrt(wdotw))$, half the cross product's; exponent differences $kappa = (i/2) w_m$ at "
                          "$s = i$, $mu = (i/2) w_p$ at $s = -i$, $i U$ at $s = oo$", "derived", sp.expand(char),
                          Domain("Q(w, lam)[i]/(i^2+1)", (I_EXT,)))
    R = sp.Matrix([[sp.Symbol("cth"), sp.Symbol("sth"), 0], [-sp.Symbol("sth"), sp.Symbol("cth"), 0], [0, 0, 1]])
    rot = lambda vec: list(sp.Matrix([vec]) * R)  # noqa: E731
    c_frame = certify_zero(log, "$cross(a R, b R) = cross(a, b) R$ for a rotation $R$ about $e3$: in the frame $u = (U, 0, 0)$ the "
                           "Poisson equations keep their form, $U^2 = inner(u, u)$, $U v1 = inner(u, v)$, $U v2 = uxv3$", "derived",
                           [x - y for x, y in zip(cross(rot(u_), rot(g_)), rot(cross(u_, g_)))],
                           Domain("Q(a, b, sth)[cth]/(cth^2 + sth^2 - 1)",
                                  (Extension(sp.Symbol("cth"), 1 - sp.Symbol("sth") ** 2, "cos theta"),)))

    # 3. the scalar equation for y = psi1 (frame u = (U, 0, 0), v = (v1, v2, 0))
    A = -spinor([U * s + v1, v2, 0]) / (1 + s**2)
    a, b, c = A[0, 0], A[0, 1], A[1, 0]
    dpsi1, dpsi2 = a * psi1 + b * psi2, c * psi1 - a * psi2
    y1 = dpsi1
    y2 = sp.diff(a, s) * psi1 + a * dpsi1 + sp.diff(b, s) * psi2 + b * dpsi2
    P = 2 * s / (1 + s**2)
    Q = -(sp.diff(a, s) + P * a + a**2 + b * c)
    c_scalar = certify_zero(log, "$y = psi1$ of the lift solves $deriv(y, s, s) + P deriv(y, s) + Q y = 0$, $P = 2s/(1+s^2)$, "
                            "$Q = -(deriv(a, s) + P a + a^2 + b c)$: the off-diagonal $b = (i/2) v2/(1+s^2)$ has no zero, so no "
                            "apparent singularity", "derived", y2 + P * y1 + Q * psi1,
                            Domain("Q(U, v1, v2, s, psi)[i]/(i^2+1)", (I_EXT,)))
    c_bc = certify_zero(log, "$b c = -(v2/2)^2/(1+s^2)^2$ and $a^2 + b c = -OmegadotOmega/4$ (frame $u = (U,0,0)$)", "derived",
                        [b * c + (v2 / 2) ** 2 / (1 + s**2) ** 2,
                         a**2 + b * c + ((U * s + v1) ** 2 + v2**2) / (4 * (1 + s**2) ** 2)], COMPLEX)

    # 4. Moebius z = (1 + i s)/2 and the gauge z^(kappa/2) (1-z)^(mu/2): Gauss's equation
    s_of_z = j * (1 - 2 * z)                     # z = (1 + i s)/2
    dz = j / 2                                   # dz/ds
    Pz, Qz = (P.subs(s, s_of_z), Q.subs(s, s_of_z))
    lphi = kappa / (2 * z) - mu / (2 * (1 - z))  # phi'/phi, phi = z^(kappa/2) (1-z)^(mu/2)
    phi2 = sp.diff(lphi, z) + lphi**2            # phi''/phi
    L_over_phi = dz**2 * (F2 + 2 * lphi * F1 + phi2 * F0) + Pz * dz * (F1 + lphi * F0) + Qz * F0
    A_, B_, C_ = (2 + kappa + mu + j * U) / 2, (kappa + mu - j * U) / 2, 1 + kappa
    gauss = z * (1 - z) * F2 + (C_ - (A_ + B_ + 1) * z) * F1 - A_ * B_ * F0
    c_gauss = certify_zero(log, "$z = (1 + i s)/2$, $y = z^(kappa/2) (1-z)^(mu/2) F$: the scalar equation is $-1/4 "
                           "(z (1-z))^-1$ times Gauss's $z (1-z) deriv(F, z, z) + (C-(A+B+1) z) deriv(F, z) - A B F$, $A = (2+kappa+mu+i U)/2$, "
                           "$B = (kappa+mu-i U)/2$, $C = 1 + kappa$ (both roots $kappa$, $mu$ at once)", "eq:ghyp",
                           L_over_phi + gauss / (4 * z * (1 - z)), GAUSS)
    c_points = certify_zero(log, "$z = (1 + i s)/2$ sends $s = i$, $-i$ to $z = 0$, $1$ (and $oo$ to $oo$); $1 + s^2 = 4 z (1-z)$",
                            "derived", [(1 + j * j) / 2, (1 - j * j) / 2 - 1, 1 + s_of_z**2 - 4 * z * (1 - z)],
                            Domain("Q(z)[i]/(i^2+1)", (I_EXT,)))
    c_exponents = certify_zero(log, "Riemann scheme of the Gauss equation: $1 - C = -kappa$ ($z = 0$), $C - A - B = -mu$ "
                               "($z = 1$), $A - B = 1 + i U$ ($z = oo$): the lift's exponent differences $kappa$, $mu$, $i U$, the last shifted by "
                               "the integer 1 in the scalar equation of $psi1$", "derived",
                               [1 - C_ + kappa, C_ - A_ - B_ + mu, A_ - B_ - 1 - j * U], GAUSS)

    # 5. the body's invariants, from the certified omega (model)
    solution = model_result.exports["solution"]
    u = [sp.diff(solution[w], T) for w in (w1, w2)]
    v = [sp.diff(solution[w], S) for w in (w1, w2)]
    inv = body_invariants(u, v)
    c_inv = certify_zero(log, "$U^2 = I11^2 I22^2 (I13^2 + I23^2)/D^2$, $abs(u)^2 - abs(v)^2 = I11 I22 (I11 - I22)(I13^2 I22 - "
                         "I11 I23^2)/D^2$, $inner(u, v) = r I11 I13 I22 I23 (I11 - I22)/D^2$, $uxv3 = -I11 I22 r/D$, "
                         "$D = I11 I23^2 + I13^2 I22$, $uxv3^2 = I11^3 I22^3/D^2$", "eq:o12",
                         [inv[k] - INVARIANTS[k] for k in INVARIANTS] + [inv["cross"] ** 2 - I11**3 * I22**3 / DEN**2],
                         BODY)
    lam2 = (I11 * I22 * (I11 - I22) * (I11 * I23**2 - I13**2 * I22) - 2 * j * I11 * I13 * I22 * I23 * r * (I11 - I22)) / DEN**2
    w_minus2 = inv["a"] - 2 * j * inv["uv"]
    c_lambda = certify_zero(log, "$w_m^2 = inner(u - i v, u - i v) = -conjugate(Lambda^2)$ ($Lambda$: the Kovalevskaya exponent "
                            "of eq:kowal, $m3 = i sqrt(I11 I22)$); for $I13 = 0$ it is $-p^2$", "eq:kowal",
                            [w_minus2 + lam2.subs(j, -j), (w_minus2 + I22 * (I11 - I22) / I23**2).subs(I13, 0)], BODY)

    result.formula("gauss_system", "eq:whole", "The Poisson equations in $s=\\sinh t$: three singular points",
                   r"\frac{d\gamma}{ds}=\gamma\times\frac{u\,s+v}{1+s^2}=\gamma\times\Big(\frac{(u-iv)/2}{s-i}"
                   r"+\frac{(u+iv)/2}{s+i}\Big),\quad \operatorname{Res}_{s=\infty}=-u",
                   c_sinh, c_partial, c_infinity, expr=system_expr(),
                   hypotheses=[*BODY_HYPOTHESES, OMEGA_HYPOTHESIS, r"$s=\sinh t$",
                               r"$\operatorname{Res}_{s=\infty}$: of $\Omega(s)\,ds$, i.e. $-\lim_{s\to\infty}s\,\Omega(s)$"])
    result.formula("gauss_lift", "derived", "Spinor lift and exponent differences",
                   r"\Psi'=-S(\Omega)\Psi,\ S(w)=-\tfrac i2(w_1\sigma_3+w_2\sigma_1+w_3\sigma_2),\ "
                   r"\Psi S(\gamma_0)\Psi^{-1}=S(\gamma),\quad \kappa=\tfrac i2 w_-,\ \mu=\tfrac i2 w_+,\ iU,"
                   r"\quad w_\mp^2=(u\mp iv)\cdot(u\mp iv)=|u|^2-|v|^2\mp 2i\,u\cdot v",
                   c_algebra, c_lift, c_half, c_frame, expr=lift_expr(),
                   hypotheses=[*BODY_HYPOTHESES, OMEGA_HYPOTHESIS, r"$s=\sinh t$, $\Psi'=d\Psi/ds$",
                               r"$\sigma_1,\sigma_2,\sigma_3$: the Pauli matrices", r"$U=|u|$",
                               r"$w_-$, $w_+$: either square root"])
    gauss_expr = gauss_equation_expr()
    if sp.expand(gauss_expr[2].lhs.subs({sp.Symbol("A"): A_.subs(j, sp.I), sp.Symbol("B"): B_.subs(j, sp.I),
                                         sp.Symbol("C"): C_.subs(j, sp.I)})
                 - gauss.subs(j, sp.I).subs({F2: F_OF_Z.diff(z, 2), F1: F_OF_Z.diff(z), F0: F_OF_Z})) != 0:
        raise ArithmeticError("the catalog form of Gauss's equation differs from the certified one")
    result.formula("gauss_equation", "eq:ghyp", "Gauss's equation for every body",
                   r"\psi_1=z^{\kappa/2}(1-z)^{\mu/2}F(z),\ z=\tfrac{1+is}2,\quad "
                   r"z(1-z)F''+\big(C-(A+B+1)z\big)F'-ABF=0,\quad A=\tfrac{2+\kappa+\mu+iU}2,\ B=\tfrac{\kappa+\mu-iU}2,\ "
                   r"C=1+\kappa",
                   c_scalar, c_bc, c_gauss, c_points, c_exponents, expr=gauss_expr,
                   hypotheses=[*BODY_HYPOTHESES, FRAME_HYPOTHESIS, r"$s=\sinh t$, $\psi_1$: the first row of the lift $\Psi$",
                               BRANCH_HYPOTHESIS])
    result.formula("gauss_invariants", "eq:o12", "The exponents of a body",
                   [r"U^2=\frac{I_{11}^2I_{22}^2(I_{13}^2+I_{23}^2)}{D^2},\quad D=I_{11}I_{23}^2+I_{13}^2I_{22},"
                    r"\quad r=\sqrt{I_{11}I_{22}}",
                    r"w_-^2=-\overline{\Lambda^2}=\frac{I_{11}I_{22}(I_{11}-I_{22})\big(I_{13}^2I_{22}-I_{11}I_{23}^2"
                    r"-2i\,r\,I_{13}I_{23}\big)}{D^2}"], c_inv, c_lambda, expr=invariants_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$\Lambda$: the Kovalevskaya exponent of the body ($m_3=i\sqrt{I_{11}I_{22}}$)"])
    result.formula("gauss_exponents", "derived", "Table of exponents (spinor lift; Gauss's $F$)",
                   [r"s=i\ \mapsto\ z=0:\quad \pm\tfrac{\kappa}2;\quad F:\ 0,\ 1-C=-\kappa",
                    r"s=-i\ \mapsto\ z=1:\quad \pm\tfrac{\mu}2;\quad F:\ 0,\ C-A-B=-\mu",
                    r"s=\infty\ \mapsto\ z=\infty:\quad \pm\tfrac{iU}2;\quad F:\ A,\ B\quad(A-B=1+iU)",
                    r"\kappa=\tfrac i2w_-,\ \mu=\tfrac i2w_+=-\bar\kappa,\ U=|u|;\quad I_{13}=0:\ "
                    r"\kappa=-\mu=\mp\tfrac p2,\ U=\tfrac{|p|}d"], c_half, c_exponents, c_lambda, expr=exponents_expr(),
                   hypotheses=[*BODY_HYPOTHESES, r"$w_+=\overline{w_-}$ (so $\mu=-\bar\kappa$)",
                               r"$p$, $d$ of section 4 in the case $I_{13}=0$"])

    emit = [invariants_emitted((c_inv.key, c_lambda.key))]
    result.exports.update(emit=emit, certificates={"gauss": c_gauss.key, "invariants": c_inv.key,
                                                   "lambda": c_lambda.key, "lift": c_lift.key})
    return result
