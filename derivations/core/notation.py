"""The symbols of the formulas document and what each means there: its notation index (issue 46).

The symbols' TeX is set once, by the printer (:data:`derivations.core.statement_printers.SYMBOL_NAMES`) and by
the derivations' displays; this module says what they *mean*.  :data:`NOTATION` has one :class:`Symbol` per line
of the index: its TeX, its meaning (one line of TeX prose; ``[[key]]`` names a display of the formulas
document and prints as its number, a link), the label field of the paper where the paper defines it
(:mod:`derivations.core.paper_numbers` prints it as the paper's number; empty where the symbol is the
project's), the regular expressions of its spellings in the documents' mathematics (to find the display that
uses it first) and the printer's names it stands for.  Where the paper reuses a letter (``z`` is
:math:`\\operatorname{sech}^2 t`, :math:`e^t` and :math:`(1+is)/2` in three sections; ``s`` is
:math:`\\sinh t` and an abbreviation of one evaluation form), the one line says every meaning, each with
the display it holds in: one symbol, one line.

:data:`OMITTED` lists the printer's names that occur in the document but get no line of their own, each with
the reason.  ``tests/test_notation_index.py`` checks that every name of ``SYMBOL_NAMES`` whose TeX occurs in the
rendered ``formulas_body.tex`` has a line or a reason, that no symbol has two lines, that every line's
spellings occur in the document and every line compiles.

:func:`index_rows` turns the table into the rows of ``templates/notation.tex.j2`` for one build: the paper's
printed numbers, and the display (its number) where the symbol first occurs, from the formulas of that build.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

from derivations.core.paper_numbers import printed_numbers


@dataclass(frozen=True)
class Symbol:
    """One line of the notation index."""

    tex: str                       # the symbol as the index prints it (mathematics, without dollars)
    meaning: str                   # TeX prose, one line; [[key]]: the number of the display ``key``
    paper: str = ""                # label field of the paper's definition ("" for the project's own symbols)
    spellings: tuple = ()          # regular expressions of the symbol in the documents' mathematics
    printer: tuple = ()            # the SYMBOL_NAMES entries this line stands for
    where: str = ""                # where it is used when no display of the formulas has it (TeX)


_ = r"(?<![\\A-Za-z])"             # a letter standing alone: not part of a word or a control sequence
_END = r"(?![A-Za-z])"


def _letter(ch: str, after: str = r"(?![A-Za-z_(])") -> str:
    """A single letter used as a symbol: not in a word, a control sequence or ``\\mathbb``/``\\mathcal``."""
    return r"(?<![\\A-Za-z0-9])(?<!\\mathbb )(?<!\\mathcal )(?<!\\mathbb\{)" + ch + after


NOTATION: tuple[Symbol, ...] = (
    Symbol(r"\mathbb I", r"the inertia tensor, in a body frame whose third axis is the constraint vector $a=e_3$",
           "3.25", (r"\\mathbb\s*\{?I" + _END,)),
    Symbol(r"I_{jk}", r"the entries of $\mathbb I$; the frame is rotated about $e_3$ so that $I_{12}=0$, and "
           r"$\det\mathbb I=1$ (a scale) gives $I_{33}$ [[i33]]", "section 2", (_ + r"I_\{?[123][123]",)),
    Symbol(r"e_1,e_2,e_3", r"the axes of the body frame; $e_3=a$", "gen12", (_ + r"e_\{?[123]",)),
    Symbol(r"a", r"the constraint vector, $a=e_3$, so $\omega_3=0$ [[euler]]; also the coefficient of $\tanh t$ in "
           r"$\omega_1$ ($a=p/d$ when $I_{13}=0$) [[omegas]], [[am1]]; in [[no_painleve]] an entry of the "
           r"lift's matrix, with $b$", "gen12", (_letter("a"),)),
    Symbol(r"b,\ c_1,c_2", r"with $a$, the coefficients of the general solution: $\omega_1=a\tanh t+\frac{c_1}2"
           r"\operatorname{sech}t$, $\omega_2=b\tanh t+\frac{c_2}2\operatorname{sech}t$ [[am1]]; in "
           r"[[no_painleve]] an entry of the lift's matrix, with $a$", "c's",
           (_letter("b"), _ + r"c_\{?[12]\}?(?![0-9])")),
    Symbol(r"\omega", r"the angular velocity in the body frame, $\omega=(\omega_1,\omega_2,0)$; $\bar\omega$: "
           r"the Darboux point [[darboux]]; $\hat\omega$: the matrix of $x\mapsto\omega\times x$", "gen12",
           (r"\\omega" + _END,), ("w1", "w2", "w3")),
    Symbol(r"\lambda", r"the multiplier of the constraint [[lambda]]; in [[A0]] the unknown of the "
           r"characteristic polynomial", "3.25", (r"\\lambda" + _END,), ("lam", "lambda")),
    Symbol(r"\gamma", r"the Poisson vector: a unit vector fixed in space, in the body frame, "
           r"$\gamma=(\gamma_1,\gamma_2,\gamma_3)$; $\bar\gamma$ its value at the Darboux point; $\gamma_0$ its "
           r"initial value [[gauss_lift]]", "eq:whole", (r"\\gamma(?!\^\{?\()" + _END,), ("g1", "g2", "g3")),
    Symbol(r"\gamma^{(1)},\gamma^{(2)},\gamma^{(3)}", r"the orthonormal basis of solutions of the Poisson equations "
           r"for odd $p$ [[basis1]]", "gam1, gam2, gam3", (r"\\gamma\^\{?\(",), ("gammaI", "gammaII", "gammaIII")),
    Symbol(r"e,\ R,\ Q", r"$e$ a unit vector fixed in space and $R$ the rotation of the body: $\gamma=R^Te$, "
           r"$\dot R=R\hat\omega$ [[poisson]]; in [[basis1]] $\gamma^{(2)}$, $\gamma^{(3)}$ are made of $R$ and $Q$; in [[rlin]] "
           r"$r=P/Q$", "eq:whole", (_letter("R"), _letter("Q"), r"\\frac\s*PQ", r"R\^T\s*e")),
    Symbol(r"t,\ t_0", r"the time; $t_0$ the free constant of time of the general solution ($t_0=0$) [[o12]] and the poles "
           r"$t_0=i\pi/2+i\pi k$ of $\omega$ [[A0]]", "eq:o12", (_letter("t", r"(?![A-Za-z(])"),), ("t0",)),
    Symbol(r"r", r"$r=\pm\sqrt{I_{11}I_{22}}$, either branch [[o12]]; $r(z)$: the coefficient of the reduced form "
           r"$y''=r(z)y$ [[rlin]]", "", (_letter("r", r"(?![A-Za-z_])"),)),
    Symbol(r"D", r"$D=I_{13}^2I_{22}+I_{23}^2I_{11}$, zero only at the equilibrium $I_{13}=I_{23}=0$", "c's",
           (_letter("D"),)),
    Symbol(r"A,\ B,\ C", r"$A=1$: the rate of the general solution [[o12]]; the coefficients of the Riccati form "
           r"[[riccati]]; the parameters of Gauss's equation [[gauss_equation]]", "eq:ABC",
           (_letter("A"), _letter("B"), _letter("C"))),
    Symbol(r"A(t),\ A_0", r"the matrix of the Poisson equations as a linear system in $t$ and its residue at "
           r"$t_0=i\pi/2$ [[A0]]", "eq:am1", (_ + r"A\(t\)", _ + r"A_\{?0\}?"), ("A0",)),
    Symbol(r"A(x),\ C(w)", r"the Poisson equations in $x=e^t$: $d\gamma/dx=\gamma A(x)$, with $\gamma C(w)="
           r"\gamma\times w$ [[fuchs]]", "", (_ + r"A\(x\)", _ + r"C\(w\)")),
    Symbol(r"A_1,\ B_1", r"the coefficients of the linear equation of the Riccati form [[riccati]]", "eq:lin",
           (_ + r"[AB]_\{?1\}?",)),
    Symbol(r"F_1,F_2,F_3", r"the first integrals: the energy $F_1=I_{11}\omega_1^2+I_{22}\omega_2^2$, "
           r"$F_2=|\gamma|^2$ [[integrals]], and for odd $p$ the polynomial $F_3=P_1\gamma_1+P_2\gamma_2+P_3\gamma_3$ "
           r"(its table)", "section 2", (_ + r"(?<!\{\}_2)(?<![0-9])F_\{?[123]",)),
    Symbol(r"F,\ \mathcal F_1", r"$F(z)$: the solution of Gauss's equation in the lift's first row "
           r"[[gauss_equation]]; ${}_2F_1$, ${}_3F_2$: hypergeometric series; $\mathcal F_1$: the polynomial of "
           r"[[recipe]]", "eq:3F2", (_letter("F", r"(?![A-Za-z_])"), r"\\mathcal\s*\{?F", r"\}_\{?[23]\}?F")),
    Symbol(r"P_1,P_2,P_3", r"the coefficients of $F_3$ for odd $p$: polynomials in $\omega_1,\omega_2$ [[P1]]",
           "eq:p1, eq:p23", (_ + r"P_\{?[123]",)),
    Symbol(r"P", r"an odd integer with $w_-^2=-P^2$ [[general_galois]]; in [[rlin]] the numerator of $r$",
           "", (_letter("P", r"(?![A-Za-z_(])"), r"\\frac\s*PQ")),
    Symbol(r"L", r"the derivation $L=\frac{\omega_2}{d^2+1}\partial_{\omega_1}-\omega_1\partial_{\omega_2}$ "
           r"[[recipe]]", "eq:p23", (_letter("L"),)),
    Symbol(r"p", r"the parameter of the case $I_{13}=0$: $p=-I_{22}d/I_{23}$, $p^2=I_{22}(I_{11}-I_{22})/I_{23}^2$, "
           r"and $\Lambda=p$ [[pmap]]; $p(z)$: a coefficient of the reduced form [[rlin]]", "eq:necc1",
           (_letter("p", r"(?![A-Za-z_])"),)),
    Symbol(r"d", r"the second parameter of the case $I_{13}=0$: $d=\sqrt{I_{11}/I_{22}-1}>0$ [[pmap]]",
           "eq:cpr", (_letter("d", r"(?![A-Za-z_])"),)),
    Symbol(r"c", r"$c=\sqrt{d^2+1}$, $c^2=I_{11}/I_{22}$ (the branch $-c$ solves too) [[pmap]]; in "
           r"[[general_angle_stable]] $c=|\cos\frac{\pi Y}2|$ (defined there)", "eq:cpr",
           (_letter("c", r"(?![A-Za-z_])"),)),
    Symbol(r"m_3", r"$m_3=I_{13}\bar\omega_1+I_{23}\bar\omega_2=ir$ at the Darboux point [[darboux]]", "eq:d",
           (_ + r"m_\{?3",)),
    Symbol(r"K,\ \mathrm{Id}", r"the Kovalevskaya matrix at the Darboux point, with eigenvalues $-1,1,2,1\pm\Lambda$ "
           r"[[exponents]], and the identity; in the first integrals' table $K=p(d^2+1)$", "section 3.1",
           (_letter("K"), r"\\mathrm\{Id\}"), ("Id",)),
    Symbol(r"\Lambda", r"the Kovalevskaya exponent: $1\pm\Lambda$ are exponents [[exponents]], "
           r"$\Lambda^2=-w_-^2$ [[gauss_invariants]], $\Lambda=p$ when $I_{13}=0$; $\bar\Lambda$ its conjugate",
           "eq:kowal", (r"\\Lambda" + _END,)),
    Symbol(r"\rho", r"exponents: $0,\pm\rho_2$ at a pole [[am1]], $\rho_{1,2,3}$ of $C(w)$ [[exponents_fuchs]]; "
           r"$\rho_k$ the coefficient of $(z-s_k)^{-2}$ in $r$ [[deltas]]", "eq:ro", (r"\\rho" + _END,)),
    Symbol(r"S", r"the matrix with $S^{-1}A_0S$ diagonal [[S]]; $S(w)=-\frac i2(w_1\sigma_3+w_2\sigma_1+w_3\sigma_2)$ "
           r"[[gauss_lift]]", "eq:am2", (_letter("S", r"(?![A-Za-z_])"),)),
    Symbol(r"z", r"the argument of each reduced equation: $z=\operatorname{sech}^2t$ [[gamma_1]], $z=e^t$ "
           r"[[rlin]], $z=(1+is)/2$ [[gauss_equation]]", "t->z", (_letter("z", r"(?![A-Za-z_])"),)),
    Symbol(r"a_0,\dots,a_3;\ b_1,b_2,b_3", r"the coefficients of the third-order equation for $\gamma_1$ in $t$ "
           r"[[genhipprep]] and in $z$ [[gamma_1]]", "a'ss", (_ + r"[ab]_\{?[0-3]",)),
    Symbol(r"\alpha,\ \beta", r"the parameters of the ${}_3F_2$ [[param]]", "eq:param", (r"\\alpha|\\beta",)),
    Symbol(r"u,\ v", r"$\omega=u\tanh t+v\operatorname{sech}t$, $u=(u_1,u_2,0)$, $v=(v_1,v_2,0)$: $\omega\to\pm u$ "
           r"as $t\to\pm\infty$ [[fuchs]]; $(u\times v)_3$ the third entry of $u\times v$; in [[genhip]] "
           r"$u=\gamma_1/\sqrt{z-1}$ and in [[riccati]] the unknown of the Riccati form", "",
           (_letter("u", r"(?![A-Za-z(])"), _letter("v", r"(?![A-Za-z(])")), ("uxv3",)),
    Symbol(r"U", r"$U=|u|$ [[gauss_lift]]", "", (_letter("U", r"(?![A-Za-z_])"),)),
    Symbol(r"w,\ w_\mp", r"$w$ a vector in $C(w)$, $S(w)$, and $w\cdot w$ [[exponents_fuchs]]; "
           r"$w_\mp$ a square root of $w_\mp^2=(u\mp iv)\cdot(u\mp iv)$ [[gauss_lift]]; in [[riccati]] the "
           r"unknown of the linear equation", "", (_letter("w", r"(?![A-Za-z])"),), ("w_m", "w_p", "wdotw")),
    Symbol(r"X,\ Y", r"$w_-=X+iY$, the root with $X\ge0$ [[general_angle_stable]]", "",
           (_letter("X", r"(?![A-Za-z_])"), _letter("Y", r"(?![A-Za-z_])"))),
    Symbol(r"\kappa,\ \mu", r"$\kappa=\frac i2w_-$, $\mu=\frac i2w_+$: the exponent differences of the spinor lift "
           r"at $s=i$ and $s=-i$ [[gauss_lift]]", "", (r"\\kappa" + _END, r"\\mu" + _END)),
    Symbol(r"s", r"$s=\sinh t$ [[gauss_system]]; in [[general_angle_stable]] $s=|\sin\frac{\pi Y}2|$ (defined "
           r"there)", "", (_letter("s", r"(?![A-Za-z_])"),)),
    Symbol(r"s_0,\dots,s_5", r"the singular points of the reduced form in $z=e^t$: $s_0=0$, $s_{1,2}=\pm i$, "
           r"$s_{3,4}=-i(c\pm d)$, $s_5=\infty$ [[deltas]]", "eq:Q", (_ + r"s_\{?[0-5]",), ("s0",)),
    Symbol(r"\Delta_k", r"the exponent difference at $s_k$ [[deltas]]", "eq:Deltai", (r"\\Delta_",)),
    Symbol(r"x,\ y", r"$x=e^t$ [[fuchs]]; $y$ the unknown of $y''=r(z)y$ [[rlin]]; in [[angle_stable]] "
           r"$x=\pi|p|/(2d)$ and $y=\pi p/2$ (defined there)", "",
           (_letter("x", r"(?![A-Za-z])"), _letter("y", r"(?![A-Za-z])")), ("shx", "chx", "sy", "cy")),
    Symbol(r"\Omega,\ \Psi,\ \psi_1", r"$\Omega(s)=(us+v)/(1+s^2)$ [[gauss_system]]; the spinor lift $\Psi$, "
           r"$\Psi'=-S(\Omega)\Psi$, and $\psi_1$ its first row [[gauss_lift]]", "",
           (r"\\Omega" + _END, r"\\Psi" + _END, r"\\psi_")),
    Symbol(r"\sigma_1,\sigma_2,\sigma_3", r"the Pauli matrices [[gauss_lift]]", "", (r"\\sigma_",)),
    Symbol(r"\tau", r"$\tau=2\cos(\pi\kappa)$ [[general_angle]]", "", (r"\\tau" + _END,)),
    Symbol(r"g,\ h,\ q", r"$h=\frac{\pi U}2$, $g=\frac{\pi(U-X)}2$, $q=\tanh^2h+s^2\operatorname{sech}^2h$ "
           r"[[general_angle_stable]]; $q(z)$: a coefficient of the reduced form [[rlin]]", "",
           (_letter("g", r"(?![A-Za-z])"), _letter("h", r"(?![A-Za-z])"), _letter("q", r"(?![A-Za-z])"))),
    Symbol(r"\Delta\psi", r"the scattering angle: the angle in space between the axes $u/|u|$ of the limit "
           r"rotations as $t\to-\infty$ and as $t\to+\infty$, in $[0,\pi]$ [[angle]]", "angle",
           (r"\\Delta\s*\\psi",), ("Deltapsi", "Delta_psi")),
    Symbol(r"n", r"the body axis $u/|u|$ of the limit rotations ($n=e_1$ when $I_{13}=0$ and $p/d>0$)", "",
           (_letter("n", r"(?![A-Za-z])"),), where=r"page~1"),
    Symbol(r"M,\ N", r"the local monodromy of the spinor lift, and $\mathrm{Ad}(M)$ the rotation by which it turns the Poisson "
           r"solutions; $N\ne0$, $N^2=0$ [[pole_theorem_proof]]", "", (_letter("M"), _letter("N"))),
    Symbol(r"\mathrm{Gal}", r"the differential Galois group of the Poisson equations over $\mathbb C(e^t)$ "
           r"[[general_galois]]", "", (r"\\mathrm\{Gal\}",)),
    Symbol(r"\mathrm{SO}(3,\mathbb C)", r"the complex rotations; $\mathrm{SO}(2,\mathbb C)$ those about $u/|u|$; "
           r"$\mathrm{SL}(2,\mathbb C)$ the group of the spinor lift [[general_galois]]", "",
           (r"(?<![A-Za-z])S[OL]\}?\(",)),
    Symbol(r"k,\ l,\ m", r"integers: the poles $t_0=i\pi/2+i\pi k$ [[pole_theorem]], $l$ in "
           r"[[general_galois_proof]], $m$ in [[recipe]]; in the table of logarithms $m$ is the parameter of "
           r"$d=\frac{m^2-1}{2m}$", "", (_letter("k", r"(?![A-Za-z])"),
           _letter("l", r"(?![A-Za-z])"), _letter("m", r"(?![A-Za-z_])"))),
)

# printer names whose TeX occurs in the formulas document without a line of their own, and why
OMITTED = {
    "cth": r"$\cos\theta$: the catalog's, no document prints $\theta$",
    "sth": r"$\sin\theta$: the catalog's, no document prints $\theta$",
}


# -- reading the documents' mathematics ------------------------------------------------------------

def _normal(tex: str) -> str:
    """TeX without blanks and with one-token scripts unbraced: ``t_{0}`` and ``t_0`` read alike."""
    tex = re.sub(r"\s+", "", tex)
    return re.sub(r"([_^])\{(\\?[A-Za-z0-9+\-]|\\[A-Za-z]+)\}", r"\1\2", tex)


def occurs(tex: str, document: str) -> bool:
    """Whether the TeX ``tex`` (a printer's symbol) occurs in ``document``, spaces and one-token braces aside
    (not as the start of a longer control sequence: ``\\lambda`` is not in ``\\lambdabar``)."""
    needle = _normal(tex)
    return re.search(re.escape(needle) + (r"(?![A-Za-z])" if needle[-1:].isalpha() else ""),
                     _normal(document)) is not None


def _group_end(text: str, start: int) -> int:
    """The index after the brace group opening at ``text[start]``."""
    depth = 0
    for k in range(start, len(text)):
        depth += (text[k] == "{") - (text[k] == "}")
        if depth == 0:
            return k + 1
    return len(text)


def math_of_text(tex: str) -> str:
    """The mathematics of TeX prose: its ``$...$`` parts, joined by blanks."""
    return " ".join(re.findall(r"(?<!\\)\$([^$]*)(?<!\\)\$", tex))


def math_of_display(tex: str) -> str:
    """The mathematics of a display: the prose of ``\\text{...}`` and ``\\parbox{..}{...}`` left out, their
    ``$...$`` kept."""
    out, i = [], 0
    for match in re.finditer(r"\\(text|parbox\{[^}]*\})\{", tex):
        if match.start() < i:
            continue
        end = _group_end(tex, match.end() - 1)
        out += [tex[i:match.start()], " ", math_of_text(tex[match.end():end - 1]), " "]
        i = end
    return "".join(out + [tex[i:]])


def formula_math(formula) -> str:
    """All the mathematics a formula of the document prints: its title's, its hypotheses' and its display."""
    return " ".join([math_of_text(formula.title), *(math_of_text(h) for h in formula.hypotheses),
                     math_of_display(formula.latex)])


def first_use(symbol: Symbol, formulas) -> str | None:
    """The key of the first formula (in the document's order) whose mathematics has one of the symbol's spellings."""
    patterns = [re.compile(s) for s in symbol.spellings]
    for formula in formulas:
        text = formula_math(formula)
        if any(p.search(text) for p in patterns):
            return formula.key
    return None


_DISPLAY = re.compile(r"\[\[([^\]]+)\]\]")
_RUN = re.compile(r"\[\[[^\]]+\]\](?:,\s*\[\[[^\]]+\]\])*")


def displays(symbol: Symbol) -> list[str]:
    """The formula keys the meaning refers to (``[[key]]``)."""
    return _DISPLAY.findall(symbol.meaning)


def _clauses(meaning: str) -> list[str]:
    """The clauses of a meaning: split at the semicolons outside its mathematics."""
    out, start, inside = [], 0, False
    for k, ch in enumerate(meaning):
        if ch == "$" and (k == 0 or meaning[k - 1] != "\\"):
            inside = not inside
        elif ch == ";" and not inside:
            out.append(meaning[start:k].strip())
            start = k + 1
    return out + [meaning[start:].strip()]


def meaning_tex(symbol: Symbol, numbers: dict) -> str:
    """The meaning with each ``[[key]]`` as a link to the display and its number.  In a build without some of the
    displays (a partial ``--only`` build), a clause whose displays are all missing says a use the document does not
    have and is left out, and a missing display of a kept clause is left out with its blank and a comma after it."""
    def links(m):              # a run of references, "[[a]], [[b]]": the ones this build has
        shown = [rf"\hyperlink{{formula.{key}}}{{({numbers[key]})}}" for key in _DISPLAY.findall(m.group(0))
                 if key in numbers]
        return ", ".join(shown) if shown else "\0"
    kept = []
    for clause in _clauses(symbol.meaning):
        keys = _DISPLAY.findall(clause)
        if keys and not any(key in numbers for key in keys):
            continue
        kept.append(re.sub(r"\(\s*\)", "", re.sub(r"\s*\0", "", _RUN.sub(links, clause))))
    return "; ".join(kept)


def index_rows(formulas: list, numbers: dict) -> list[dict]:
    """The rows of the notation index for the formulas of one build (``numbers``: formula key -> display number):
    ``symbol``, ``meaning`` (TeX), ``paper`` (the paper's printed numbers, or empty) and ``first`` (the number of
    the first display using the symbol, as a link; else the symbol's ``where``).  A symbol that no display of the
    build uses and that has no ``where`` (in a partial build) gets no row."""
    rows = []
    for symbol in NOTATION:
        key = first_use(symbol, formulas)
        first = rf"\hyperlink{{formula.{key}}}{{({numbers[key]})}}" if key in numbers else symbol.where
        meaning = meaning_tex(symbol, numbers)
        if first and meaning:      # a symbol a partial build's document does not use has no line there
            rows.append({"symbol": symbol.tex, "meaning": meaning, "paper": ", ".join(printed_numbers(symbol.paper)),
                         "first": first})
    return rows
