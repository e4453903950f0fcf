"""The two printers of a :class:`~derivations.core.statement.Statement`'s mathematics (issue 35).

:class:`TextPrinter` is SymPy's ``StrPrinter`` in the written order (``certificates.json``, the terminal, the diff;
``=`` for an equation, ``i`` for the imaginary unit); :class:`MathPrinter` the project's
:class:`~derivations.core.typeset.FormulaPrinter` with its symbol names (the LaTeX documents).  Floats print as they
are written in the claims (``1e-15``, ``10^{-15}``), not as Python's repr.
"""
from __future__ import annotations

import sympy as sp
from sympy.printing.precedence import PRECEDENCE
from sympy.printing.str import StrPrinter

from derivations.core.typeset import FormulaPrinter

# Symbols whose LaTeX differs from SymPy's default reading of the name (``I11`` -> ``I_{11}``,
# ``gamma1`` -> ``\gamma_{1}``, ``rho_i`` -> ``\rho_{i}``, ``Fhat_k`` -> ``\hat{F}_{k}`` are SymPy's own).
SYMBOL_NAMES = {
    "w1": r"\omega_{1}", "w2": r"\omega_{2}", "w3": r"\omega_{3}",
    "g1": r"\gamma_{1}", "g2": r"\gamma_{2}", "g3": r"\gamma_{3}",
    "lam": r"\lambda", "lambda": r"\lambda",
    "Deltapsi": r"\Delta\psi", "Delta_psi": r"\Delta\psi",
    "gammaI": r"\gamma^{(1)}", "gammaII": r"\gamma^{(2)}", "gammaIII": r"\gamma^{(3)}",
    "g1_inf": r"\gamma_{1}^{\infty}", "eps": r"\varepsilon",
    "w_m": r"w_{-}", "w_p": r"w_{+}", "Id": r"\mathrm{Id}", "Den": r"Den", "P1t": r"\tilde{P}_{1}",
    "A0": r"A_{0}", "t0": r"t_{0}", "s0": r"s_{0}",
    "tau_p": r"\tau'", "Wp": r"W'", "Cp": r"C'", "sth": r"\sin\theta", "cth": r"\cos\theta",
    "Iinv": r"I^{-1}", "uxv3": r"(u \times v)_{3}", "wdotw": r"w \cdot w", "OmegadotOmega": r"\Omega \cdot \Omega",
    "shx": r"\sinh x", "chx": r"\cosh x", "sy": r"\sin y", "cy": r"\cos y",
}


def _float_text(value) -> str:
    """A float as written: ``1e-15``, ``0.25``, ``1e8`` (not ``100000000.0``)."""
    short = repr(float(value))
    mantissa, exponent = f"{float(value):e}".split("e")
    mantissa = mantissa.rstrip("0").rstrip(".")
    scientific = f"{mantissa}e{int(exponent)}"
    return scientific if len(scientific) < len(short) and float(scientific) == float(value) else short


class TextPrinter(StrPrinter):
    """``sstr`` in the written order, an equation as ``a = b``."""

    def __init__(self):
        super().__init__({"order": "none"})

    def _print_Equality(self, expr):
        return f"{self._print(expr.lhs)} = {self._print(expr.rhs)}"

    def _print_Unequality(self, expr):
        return f"{self._print(expr.lhs)} != {self._print(expr.rhs)}"

    def _print_Tuple(self, expr):
        return "(" + ", ".join(self._print(a) for a in expr.args) + ")"

    def _print_ImaginaryUnit(self, expr):
        return "i"

    def _print_gamma(self, expr):   # the Gamma function; "gamma" reads back as the Poisson vector's symbol
        return f"Gamma({self._print(expr.args[0])})"

    def _print_Float(self, expr):
        return _float_text(expr)


class MathPrinter(FormulaPrinter):
    """The project's formula printer in the written order with the project's symbol names."""

    def __init__(self):
        super().__init__({"order": "none", "symbol_names": {}})

    def _print_Symbol(self, expr, style="plain"):
        name = SYMBOL_NAMES.get(expr.name)
        return name if name is not None else super()._print_Symbol(expr, style)

    def _print_Mul(self, expr):
        flat = [f for a in expr.args for f in (a.args if a.is_Mul else (a,))]   # (-1*x)*y**-1 as written
        if flat[0].is_Number and flat[0].is_negative and len(flat) > 1:
            rest = ([-flat[0]] if flat[0] != -1 else []) + flat[1:]
            return "- " + self._print(sp.Mul(*rest, evaluate=False) if len(rest) > 1 else rest[0])
        return super()._print_Mul(expr)

    def _print_Pow(self, expr):
        if expr.base.is_Integer and expr.exp.is_Integer and expr.exp < 0:
            return f"{self._print(expr.base)}^{{{self._print(expr.exp)}}}"   # 10^{-90}, not 1/10^90 written out
        return super()._print_Pow(expr)

    def _print_Float(self, expr):
        mantissa, _, exponent = _float_text(expr).partition("e")   # as written: 1e-15, 2.5e8, 0.25
        if not exponent:
            return mantissa
        power = f"10^{{{int(exponent)}}}"
        return power if mantissa == "1" else f"{mantissa} \\cdot {power}"

    def _print_Tuple(self, expr):
        return r"\left(" + ", ".join(self._print(a) for a in expr.args) + r"\right)"

    # the real and imaginary parts as operator names (SymPy's ``\operatorname{re}`` reads as a word ``re``)
    def _print_re(self, expr, exp=None):
        return self._do_exponent(r"\operatorname{Re}{%s}" % self.parenthesize(expr.args[0], PRECEDENCE["Atom"]), exp)

    def _print_im(self, expr, exp=None):
        return self._do_exponent(r"\operatorname{Im}{%s}" % self.parenthesize(expr.args[0], PRECEDENCE["Atom"]), exp)
