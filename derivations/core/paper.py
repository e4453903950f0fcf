"""The paper's printed formulas, transcribed once, with their equation labels.

Source: the paper's LaTeX source, arXiv:0902.0079 (Fedorov, Maciejewski,
Przybylska, *The Poisson equations in the nonholonomic Suslov problem*; docs/citing.md).
Nothing here is used to *produce* an emitted formula: the derivations derive,
then compare with these transcriptions, and the comparison goes into the
errata table.  Each entry keeps the printed LaTeX verbatim (for the table) and
a SymPy transcription (for the comparison).

Square roots printed as ``sqrt(I22/I11)`` and ``sqrt(I11/I22)`` are written
with ``r = sqrt(I11*I22)`` (``I11, I22 > 0``): ``sqrt(I22/I11) = r/I11`` and
``sqrt(I11/I22) = r/I22``; the printed ``+-`` is ``r -> -r``.
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from derivations.core.differential import S, T
from derivations.core.symbols import (
    I11,
    I13,
    I22,
    I23,
    I33,
    c,
    d,
    g1,
    g2,
    g3,
    p,
    r,
    w1,
    w2,
)


@dataclass(frozen=True)
class Printed:
    label: str
    latex: str
    where: str


EP326 = Printed(
    "ep3.26",
    r"\frac{d}{dt}(\mathbb I\omega)=\langle\mathbb I\omega,a\rangle\,\omega\times\mathbb I^{-1}a",
    "section 1",
)

# gen12: omega1' = I22 (I13 w1 + I23 w2) w2,  omega2' = -I11 (I13 w1 + I23 w2) w1
GEN12 = Printed(
    "gen12",
    r"\dot\omega_1=I_{22}(I_{13}\omega_1+I_{23}\omega_2)\omega_2,\quad"
    r"\dot\omega_2=-I_{11}(I_{13}\omega_1+I_{23}\omega_2)\omega_1",
    "section 2",
)
GEN12_FIELD = {
    w1: I22 * (I13 * w1 + I23 * w2) * w2,
    w2: -I11 * (I13 * w1 + I23 * w2) * w1,
}

WHOLE = Printed(
    "eq:whole",
    r"\dot\gamma_1=-\omega_2\gamma_3,\ \dot\gamma_2=\omega_1\gamma_3,\ "
    r"\dot\gamma_3=\omega_2\gamma_1-\omega_1\gamma_2",
    "section 2",
)
WHOLE_FIELD = {g1: -w2 * g3, g2: w1 * g3, g3: w2 * g1 - w1 * g2}

# eq:o12 / c's with A = 1, written in T = tanh t, S = sech t:
# (e^t - e^-t)/(e^t + e^-t) = T, 1/(e^t + e^-t) = S/2.
_D = I13**2 * I22 + I23**2 * I11
C_S = Printed(
    "c's",
    r"a=\frac{I_{23}}{D},\ b=-a\frac{I_{13}}{I_{23}},\ c_1=\pm\frac{2I_{13}}{D}\sqrt{\frac{I_{22}}{I_{11}}},\ "
    r"c_2=\pm\frac{2I_{23}}{D}\sqrt{\frac{I_{11}}{I_{22}}},\ D=I_{13}^2I_{22}+I_{23}^2I_{11}",
    "section 2, Remark 2.1",
)


def printed_o12(sign1: int = 1, sign2: int = 1) -> dict:
    """Printed general solution; ``sign1``/``sign2`` are the two printed ``+-``."""
    a = I23 / _D
    b = -a * I13 / I23
    c1 = sign1 * 2 * I13 / _D * (r / I11)
    c2 = sign2 * 2 * I23 / _D * (r / I22)
    return {w1: a * T + c1 / 2 * S, w2: b * T + c2 / 2 * S}


ENLEV = Printed("eq:enlev", r"F_1=\frac{1}{I_{13}^2I_{22}+I_{23}^2I_{11}}", "section 2")
ENLEV_VALUE = 1 / _D

# omegas: w1 = a tanh t, w2 = -2ac/(e^t+e^-t) = -a c sech t,
# a = (I22 I33 - I23^2)/I23, c = sqrt(I11/I22).
OMEGAS = Printed(
    "omegas",
    r"\omega_1=a\tanh t,\ \omega_2=-ac\,\mathrm{sech}\,t,\ a=\frac{I_{22}I_{33}-I_{23}^2}{I_{23}},\ "
    r"c=\sqrt{I_{11}/I_{22}}",
    "section 4",
)
OMEGAS_A = (I22 * I33 - I23**2) / I23

# eq:sysfin with the printed +- in the first equation
SYSFIN = Printed(
    "eq:sysfin",
    r"\dot\omega_1=\pm\frac{d}{p(d^2+1)}\omega_2^2,\ \dot\omega_2=-\frac{d}{p}\omega_1\omega_2",
    "section 4",
)


def printed_sysfin(sign: int) -> dict:
    return {w1: sign * d / (p * (d**2 + 1)) * w2**2, w2: -d / p * w1 * w2}


CCALKI = Printed(
    "eq:ccalki",
    r"F_1=(d^2+1)\omega_1^2+\omega_2^2,\ F_2=\gamma_1^2+\gamma_2^2+\gamma_3^2",
    "section 4",
)
CCALKI_F1 = (d**2 + 1) * w1**2 + w2**2
CCALKI_F2 = g1**2 + g2**2 + g3**2

F1_VALUE_SENTENCE = Printed(
    "eq:ccalki (text)",
    r"\text{on the solutions one has } F_1=a^2c^2=\ \text{(sentence breaks off)}",
    "section 4, after eq:ccalki",
)

LIMIT_TEXT = Printed(
    "omegas (text)",
    r"t\to\pm\infty:\ \text{rotation about }(1,0,0)\text{ with angular velocity }\mp a",
    "section 4, steady-state rotations",
)

NECC1 = Printed(
    "eq:necc1",
    r"I_{13}=0,\ \frac{I_{11}-I_{22}}{I_{11}I_{22}(I_{11}I_{22}I_{33}-1)}=p^2",
    "Theorem 3.2",
)
NECC1_P2 = (I11 - I22) / (I11 * I22 * (I11 * I22 * I33 - 1))

# proof of Proposition 4.1: I23^2 from eq:necc1 as a quadratic, and I22 I33 - I23^2 for the root with sign -
PROP41 = Printed(
    "Proposition 4.1 (proof)",
    r"I_{23}^2=\frac{I_{22}}{2(I_{11}-I_{22})}\Big(p^2+2I_{33}(I_{11}-I_{22})\pm p\sqrt{p^2+4I_{33}(I_{11}-I_{22})}\Big),"
    r"\ I_{22}I_{33}-I_{23}^2=\frac{I_{22}}{2(I_{11}-I_{22})}\Big(-p^2+p\sqrt{p^2+2I_{33}(I_{11}-I_{22})}\Big)",
    "section 4, Proposition 4.1",
)

AM2 = Printed(
    "eq:am2",
    r"A_0=\begin{bmatrix}0&0&-\frac{ip\sqrt{d^2+1}}{d}\\0&0&\frac{p}{d}\\"
    r"\frac{ip\sqrt{d^2+1}}{d}&-\frac{p}{d}&0\end{bmatrix}",
    "section 3.2",
)
AM2_MATRIX = sp.Matrix(
    [[0, 0, -sp.I * p * c / d], [0, 0, p / d], [sp.I * p * c / d, -p / d, 0]]
)

P23 = Printed(
    "eq:p23",
    r"P_3:=\frac{d}{p}\Big(\frac{1}{d^2+1}\frac{\partial P_1}{\partial\omega_1}\omega_2-"
    r"\frac{\partial P_1}{\partial\omega_2}\omega_1\Big),\ P_2:=-\frac{d}{p}\frac{\omega_2}{\omega_1}"
    r"\Big(\frac{1}{d^2+1}\frac{\partial P_3}{\partial\omega_1}\omega_2-\frac{\partial P_3}{\partial\omega_2}"
    r"\omega_1\Big)+\frac{\omega_2}{\omega_1}P_1",
    "Theorem 6.2",
)

POL_SOL = Printed(
    "pol_sol",
    r"\mathcal F_1(z)=1+\sum_{j=1}^{(p-1)/2}\frac{(2j-1)!!}{(2j)!!}\frac{d^{2j}(p^2-1)\cdots(p^2-(2j-1)^2)}"
    r"{(d^2+p^2)\cdots((2j-1)d^2+p^2)}z^j",
    "section 5.1",
)

P1_INTEGRAL = Printed(
    "p = 1 integral",
    r"F_3=d\omega_1\gamma_1+\frac{d}{d^2+1}\omega_2\gamma_2-\frac{d^2}{d^2+1}\omega_2\gamma_3",
    "section 6.3",
)
P1_INTEGRAL_F3 = d * w1 * g1 + d / (d**2 + 1) * w2 * g2 - d**2 / (d**2 + 1) * w2 * g3

GENHIPPREP = Printed(
    "eq:genhipprep",
    r"a_0=(d^2+1)p^2\omega_1,\ a_1=dp(2(d^2+1)\omega_1^2-\omega_2^2),\ a_2=(d^2+1)\omega_1[(d^2+p^2)\omega_1^2"
    r"+p^2\omega_2^2],\ a_3=-dp\omega_2^2[(d^2+1)\omega_1^2+\omega_2^2]",
    "section 5.1 (a'ss)",
)
GAMMA_1 = Printed(
    "eq:gamma_1",
    r"b_1=\frac2z+\frac1{z-1},\ b_2=\frac{-p^2(z-1)+d^2(1+z(-6-p^2(z-1)+4z))}{4d^2(z-1)^2z^2},\ "
    r"b_3=\frac{(d^2+1)p^2}{8d^2(z-1)^2z^2}",
    "section 5.1",
)
GENHIP = Printed(
    "eq:genhip",
    r"z^2(1-z)u'''+\tfrac12(4-9z)zu''+[\tfrac14(1+\tfrac{p^2}{d^2})+\tfrac14(p^2-13)z]u'+\tfrac18(p^2-1)u=0",
    "section 5.1",
)
PARAM = Printed(
    "eq:param",
    r"\alpha_1=\tfrac12,\ \alpha_2=\tfrac{1+p}2,\ \alpha_3=\tfrac{1-p}2,\ \beta_{1,2}=\frac{d\mp ip}{2d}",
    "section 5.1",
)
POCHHAMMER = Printed("eq:ghyp", r"(a)_k=a(a+1)\cdots(a+k),\ (a)_0=1", "section 5.1, after eq:ghyp")

GAM1 = Printed(
    "gam1",
    r"\gamma_1^{(1)}=\frac{e^t-e^{-t}}{(e^t+e^{-t})^p}\sum_k a_k(e^t+e^{-t})^{p-1-2k},\ a_k=4^k\frac{(2k-1)!!}{(2k)!!}"
    r"\frac{d^{2k}(p^2-1)\cdots(p^2-(2k-1)^2)}{(d^2+p^2)\cdots((2k-1)d^2+p^2)}",
    "Theorem 6.1",
)
GAM2 = Printed(
    "gam2",
    r"\gamma_1^{(2)}=\frac{e^{(1-\frac{ip}{d})t}}{(1+e^{2t})^p}\sum_k b_ke^{2kt},\ b_k\text{ from }a=\tfrac{2-p}2"
    r"+\tfrac{ip}{2d},\ c=\tfrac32+\tfrac{ip}{2d}",
    "Theorem 6.1",
)

EXAMPLE_P1 = Printed(
    "example p = 1",
    r"\gamma^{(1)}=(\tanh t,-\tfrac{\operatorname{sech}t}{c},\tfrac{d\operatorname{sech}t}{c}),\ "
    r"\gamma^{(2)}=(\cos\tfrac td\operatorname{sech}t,\tfrac{\cos\frac td\tanh t-d\sin\frac td}{c},"
    r"-\tfrac{d\cos\frac td\tanh t+\sin\frac td}{c}),\ \gamma^{(3)}=\dots",
    "section 6.2",
)
EXAMPLE_P3 = Printed(
    "example p = 3",
    r"\gamma^{(1)}=\alpha\big(c(9+d^2-4d^2\operatorname{sech}^2t)\tanh t,\dots\big),\ \alpha=\frac1{c(d^2+9)},\ "
    r"\gamma^{(2)},\gamma^{(3)}\text{ in }e^t,\cosh,\cos\tfrac{3t}d,\sin\tfrac{3t}d",
    "section 6.2",
)


def printed_example(p: int, t, d, ops=None):
    """The printed real solutions for p = 1 and p = 3 (rows gamma^(1..3)), evaluated with mpmath, or with
    ``ops`` (an object with sqrt, sech, tanh, cos, sin, exp, cosh, sinh: the exact substitution x = e^t of
    ``derivations.sections.printed_examples`` uses this same transcription)."""
    import mpmath

    mp = mpmath if ops is None else ops

    c = mp.sqrt(d * d + 1)
    S, T = mp.sech(t), mp.tanh(t)
    if p == 1:
        C, Sn = mp.cos(t / d), mp.sin(t / d)
        return [[T, -S / c, d * S / c],
                [C * S, (C * T - d * Sn) / c, -(d * C * T + Sn) / c],
                [Sn * S, (Sn * T + d * C) / c, -(d * Sn * T - C) / c]]
    if p == 3:
        a = 1 / (c * (d * d + 9))
        E, E2, E4 = mp.exp(t), mp.exp(2 * t), mp.exp(4 * t)
        C, Sn = mp.cos(3 * t / d), mp.sin(3 * t / d)
        ch, sh, ch2 = mp.cosh(t), mp.sinh(t), mp.cosh(2 * t)
        pre = a / (E2 + 1) ** 3
        dd = d * d
        return [
            [a * c * (9 + dd - 4 * dd * S**2) * T, a * (4 * dd * S**2 - 9 * (dd + 1)) * S,
             a * d * (3 * (dd + 1) - 4 * dd * S**2) * S],
            [pre * (-2 * c * E * ((dd * (3 - 10 * E2 + 3 * E4) - 9 * (1 + E2) ** 2) * C + 12 * d * (E4 - 1) * Sn)),
             pre * 4 * E**3 * (d * ((dd - 15) * ch2 + 9 + dd) * ch * Sn + ((9 - 7 * dd) * ch2 + 9 + dd) * sh * C),
             pre * 4 * E**3 * (((7 * dd - 9) * ch2 - 9 - 17 * dd) * ch * Sn + d * ((dd - 15) * ch2 - 15 - 7 * dd) * sh * C)],
            [pre * (2 * c * E * ((dd * (3 - 10 * E2 + 3 * E4) - 9 * (E2 + 1) ** 2) * Sn + 12 * d * (1 - E4) * C)),
             pre * 4 * E**3 * (d * ((dd - 15) * ch2 + 9 + dd) * ch * C + ((7 * dd - 9) * ch2 - 9 - dd) * sh * Sn),
             -pre * 4 * E**3 * (((9 - 7 * dd) * ch2 + 9 + 17 * dd) * ch * C + d * ((dd - 15) * ch2 - 15 - 7 * dd) * sh * Sn)],
        ]
    raise ValueError(f"p={p}: the paper prints examples for p = 1 and p = 3 only")

POLY_F2 = Printed(
    "poly_F2",
    r"\hat F=\sum_{k}\frac{(a_\pm)_k(b_\pm)_k}{(c_\pm)_kk!}\frac{(2dk+d+pi)(4dk-dp\pm ip)}{dp-2dk\mp ip}(-y)^k",
    "section 5.1",
)

EQ_D = Printed(
    "eq:d",
    r"\bar\omega_1=\frac1{I_{11}I_{23}+iI_{13}\sqrt{I_{11}I_{22}}},\ \bar\omega_2=-\frac1{I_{13}I_{22}-iI_{23}"
    r"\sqrt{I_{11}I_{22}}},\ \bar\gamma=0",
    "section 3.1",
)
NECCG1 = Printed("eq:neccg1", r"I_{13}I_{23}(I_{11}-I_{22})=0", "section 3.1")
NECCG12 = Printed(
    "eq:neccg12",
    r"\frac{(I_{11}-I_{22})(I_{11}I_{23}^2-I_{22}I_{13}^2)}{I_{11}I_{22}(I_{11}I_{22}I_{33}-1)^2}=p^2",
    "section 3.1",
)
NECC11 = Printed(
    "eq:necc11",
    r"I_{23}=0,\ \frac{I_{11}-I_{22}}{I_{11}I_{22}(I_{11}I_{22}I_{33}-1)}=-p^2",
    "Theorem 3.2",
)
LINA = Printed(
    "eq:lina",
    r"\omega_1\to-\omega_2,\ \omega_2\to-\omega_1,\ \gamma_1\leftrightarrow\gamma_2,\ I_{11}\leftrightarrow I_{22},"
    r"\ I_{13}\leftrightarrow I_{23}",
    "section 3",
)

AM1 = Printed(
    "eq:am1",
    r"A_0=\begin{bmatrix}0&0&-b+\frac i2c_2\\0&0&a+\frac i2c_1\\b-\frac i2c_2&-a+\frac i2c_1&0\end{bmatrix}",
    "section 3.2",
)
THEOREM31 = Printed(
    "Theorem 3.2",
    r"\text{all solutions meromorphic iff }I_{13}=0,\ \tfrac{I_{11}-I_{22}}{I_{11}I_{22}(I_{11}I_{22}I_{33}-1)}=p^2"
    r"\text{ or }I_{23}=0,\ \dots=-p^2,\ p\in\mathbb Z^*",
    "Theorem 3.2, Theorem 3.5",
)

NECCG2 = Printed("eq:neccg2", r"ac_1+bc_2=0,\ c_1^2+c_2^2-4(a^2+b^2)=4p^2", "section 3.1, Remark")
NECC2 = Printed("eq:necc2", r"c_1=b=0,\ c_2^2-4a^2=4p^2", "Theorem 3.2")

RIG = Printed("eq:rig", r"\dot u=A+Bu+Cu^2,\ A=\tfrac12(\omega_2-i\omega_1),\ B=-i\omega_3,\ C=\tfrac12(\omega_2+i\omega_1)",
              "section 5.2")
RZEDU = Printed(
    "eq:2rzedu",
    r"p(z)=\frac{z^2(z^2+4icz-4)-1}{z(z^2+1)(z^2+2icz-1)},\ q(z)=\frac{p^2}{4(c^2-1)}\frac1{z^2}+\frac{p^2}{(z^2+1)^2}",
    "section 5.2",
)
RLIN = Printed("eq:rlin", r"r=\frac PQ,\ P=\sum_{i=0}^8p_iz^i,\ Q=4(c^2-1)z^2(z^2+1)^2(2cz-i(z^2-1))^2",
               "section 5.2")
DELTAI = Printed("eq:Deltai", r"\Delta_0=\Delta_5=i\frac pd,\ \Delta_1=\Delta_2=p,\ \Delta_3=\Delta_4=2", "section 5.2")

# Section 5.1, "Monodromy for F1(z) and the angle Delta psi", and Theorem 5.4.
GAM_0 = Printed("gam_0", r"\gamma_1=-\sqrt{1-z}\;{}_3F_2\Big(\tfrac12,\tfrac{1+p}2,\tfrac{1-p}2;"
                r"\tfrac12-\tfrac{ip}{2d},\tfrac12+\tfrac{ip}{2d};z\Big)", "section 5.1, Lemma")
MONODROMY_FACTOR = Printed("Prop. 5.1", r"\mathcal F_1\to\mathcal F_1-2i\exp(\beta_1+\beta_2-\alpha_1-\alpha_2-\alpha_3)"
                           r"(\sigma_1\mathcal F_1+\sigma_2\mathcal F_2+\sigma_3\mathcal F_3)", "section 5.1")
LIMIT_GAMMA1 = Printed("angle (limit)", r"\lim_{t\to\infty}\gamma_1=1-2i\exp(\pi i/2)\sigma_1"
                       r"=1-2\frac{\cos^2(\pi p/2)}{\cos^2(\pi ip/(2q))}", "section 5.1, before Theorem 5.4")
ANGLE = Printed("Theorem 5.4", r"\cos\frac{\Delta\psi}2=\frac{\cos(\pi p/2)}{\cos(\pi ip/(2q))}", "Theorem 5.4")
ANGLE_P = Printed("Theorem 5.4 (p)", r"d=\sqrt{\frac{I_{11}-I_{22}}{I_{22}}},\ "
                  r"p=\sqrt{\frac{I_{11}-I_{22}}{I_{11}I_{22}(I_{11}I_{22}I_{33}-1)}}", "Theorem 5.4")
ANGLE_P2 = NECC1_P2
SS_LIMIT_TEXT = Printed("ss (text)", r"\gamma(t)\to(\cos\Delta\psi,\ \sin\Delta\psi\cos at,\ \sin\Delta\psi\sin at)^T,"
                        r"\ t\to+\infty", "section 4, after eq. ss")


CONCLUSION_EVEN = Printed(
    "Conclusion",
    r"I_{13}=0,\ p\ \text{even}:\ \text{all solutions meromorphic},\ \text{not Liouvillian}",
    "Conclusion",
)

# proof of Proposition 4.1: "one can check that I11^2 - (J2 - J3)^2 > 0" for the root with sign -
PROP41_TRIANGLE = Printed(
    "Proposition 4.1 (proof, triangle)",
    r"I_{11}^2-(J_2-J_3)^2>0",
    "section 4, proof of Proposition 4.1",
)
