"""SymPy's formulas in compact Unicode, for the change list of ``build_formulas.py --diff``.

:class:`UnicodePrinter` is the statement module's text printer (written order, ``i`` for the imaginary unit, floats
as the claims write them) printing ``·`` for a product, superscript powers, ``√``, ``∂``, ``≠``, ``≤``, ``π``,
``∞``, ``|x|``, ``⟨a, b⟩``, ``a × b``, ``±``; :func:`symbol_text` writes a symbol's name as a reader does
(``I13`` -> ``I₁₃``, ``omega`` -> ``ω``, ``w_m`` -> ``w₋``, the project's :data:`SYMBOL_NAMES` through their LaTeX).
"""
from __future__ import annotations

import functools
import re

import sympy as sp
from sympy.printing.precedence import PRECEDENCE

from derivations.core.statement_printers import SYMBOL_NAMES, TextPrinter, _float_text
from derivations.output.diff_latex import GREEK, latex_text, subscript, superscript

_GREEK_ALTERNATIVES = "|".join(sorted(GREEK, key=len, reverse=True))
_SYMBOL = re.compile(rf"(?P<base>{_GREEK_ALTERNATIVES}|[A-Za-z])(?:(?P<digits>\d+)|_(?P<sub>[A-Za-z0-9]{{1,3}}))?")
_HAT = re.compile(rf"(?P<base>{_GREEK_ALTERNATIVES})hat|(?P<letter>[A-Za-z])hat_(?P<sub>[A-Za-z0-9]{{1,3}})")
CONSTANT_TEXT = {"pi": "π", "oo": "∞", "i": "i", "E": "E"}


@functools.lru_cache(maxsize=4096)
def symbol_text(name: str) -> str:
    """A symbol's name as a reader writes it: ``I13`` -> ``I₁₃``, ``omega`` -> ``ω``, ``w_m`` -> ``w₋``,
    ``a_jk`` -> ``aⱼₖ``, ``omegahat`` -> ``ω̂``; a name of another form (``float64``, ``gamma_basis``) as it is."""
    if name in SYMBOL_NAMES:
        return re.sub(r"\s*([·×])\s*", r"\1", latex_text(SYMBOL_NAMES[name]))
    if name in CONSTANT_TEXT:
        return CONSTANT_TEXT[name]
    hat = _HAT.fullmatch(name)
    if hat:
        if hat.group("base"):
            return GREEK[hat.group("base")] + "\u0302"
        return hat.group("letter") + "\u0302" + (subscript(hat.group("sub")) or "_" + hat.group("sub"))
    match = _SYMBOL.fullmatch(name)
    if not match:
        return name
    base = GREEK.get(match.group("base"), match.group("base"))
    tail = match.group("digits") or match.group("sub")
    if tail is None:
        return base
    return base + (subscript(tail) or "_" + tail)


def is_symbol_name(name: str) -> bool:
    """A name that is mathematics whatever surrounds it: one letter, a Greek name, ``I13``, ``w_m``."""
    return len(name) == 1 or symbol_text(name) != name


# -- printing SymPy objects -----------------------------------------------------------------------------

class _Hyper(sp.Function):
    """``hyper`` as written (SymPy's cancels equal parameters as it is made)."""
    nargs = 3


def _float_unicode(value) -> str:
    mantissa, _, exponent = _float_text(value).partition("e")
    if not exponent:
        return mantissa
    power = "10" + (superscript(str(int(exponent)), 6) or f"^{int(exponent)}")
    return power if mantissa == "1" else f"{mantissa}·{power}"


_RELATIONS = {"==": "=", "!=": "≠", "<=": "≤", ">=": "≥", "<": "<", ">": ">", "=": "=", "->": "→"}


def _outside_brackets(text: str, characters: str) -> bool:
    depth = 0
    for index, ch in enumerate(text):
        depth += ch in "([{⟨"
        depth -= ch in ")]}⟩"
        if depth == 0 and ch in characters and (ch != "-" or index > 0):
            return True
    return False


def _tight(text: str) -> bool:
    """``text`` reads as one factor: no operator or space outside brackets (``x₁``, ``f(a + b)``, ``(a·b)``)."""
    return bool(text) and not _outside_brackets(text, " ·×/+-=,^")


class UnicodePrinter(TextPrinter):
    """The statement's text printer (written order, ``i``, floats as written) in compact Unicode:
    ``·`` for a product, superscript powers, ``√``, ``∂``, ``≠``, ``π``, ``∞``, ``|x|``, ``⟨a, b⟩``."""

    printmethod = "_unicode_diff"   # not the classes' own _sympystr (abs_, equal): every class printed here

    def _print_Symbol(self, expr):
        return symbol_text(expr.name)

    _print_Dummy = _print_Symbol

    def _print_Pi(self, expr):
        return "π"

    def _print_Infinity(self, expr):
        return "∞"

    def _print_NegativeInfinity(self, expr):
        return "-∞"

    def _print_ComplexInfinity(self, expr):
        return "∞̃"

    def _print_Float(self, expr):
        return _float_unicode(expr)

    def _factor(self, factor, strict=False) -> str:
        text = self.parenthesize(factor, PRECEDENCE["Mul"], strict=strict)
        return text if not factor.is_Symbol or _tight(text) else f"({text})"

    def _print_Mul(self, expr):
        """Numerator and denominator as written, ``·`` between factors, one leading sign."""
        numerator, denominator = [], []
        factors = list(expr.args)
        while any(f.is_Mul for f in factors):                 # an unevaluated product of products: one product
            factors = [g for f in factors for g in (f.args if f.is_Mul else (f,))]
        if len(factors) > 1:                                  # 1 of a written 1/2 ("(1/2)" read as 1*2**-1)
            factors = [f for f in factors if f != 1] or [sp.Integer(1)]
        for factor in factors:
            if factor.is_Rational and not factor.is_Integer:
                numerator += [sp.Integer(factor.p)] if factor.p != 1 else []
                denominator.append(sp.Integer(factor.q))
            elif (factor.is_Pow and factor.exp.is_Number and factor.exp.is_negative
                  and not (factor.base.is_Integer and factor.exp.is_Integer)):   # 10**(-3) stays 10⁻³
                denominator.append(factor.base if factor.exp == -1 else
                                   sp.Pow(factor.base, -factor.exp, evaluate=False))
            else:
                numerator.append(factor)
        sign = ""
        if numerator and numerator[0].is_Number and numerator[0].is_negative:
            sign, numerator[0] = "-", -numerator[0]
            if numerator[0] == 1 and len(numerator) > 1:
                numerator.pop(0)
        top = "·".join(self._factor(f) for f in numerator) or "1"
        if not denominator:
            return sign + top
        if _outside_brackets(top, "/"):
            top = f"({top})"                                  # (∂p/∂z)/2, not ∂p/∂z/2
        bottom = "·".join(self._factor(f, strict=True) for f in denominator)
        return f"{sign}{top}/" + (bottom if _tight(bottom) else f"({bottom})")

    def _print_Pow(self, expr, rational=False):
        base, exp = expr.base, expr.exp
        shown = self.parenthesize(base, PRECEDENCE["Pow"], strict=True)
        if not _tight(shown):
            shown = f"({shown})"
        if exp == sp.S.Half:
            return "√" + shown
        if exp == -sp.S.Half:
            return "1/√" + shown
        if exp == -1 and not base.is_Integer:
            return "1/" + shown
        text = self._print(exp)
        small = superscript(text) if exp.is_Atom or exp.could_extract_minus_sign() and _tight(text[1:]) else None
        if small is not None:
            return shown + small
        return shown + "^" + (text if exp.is_Atom and not text.startswith("-") else "(" + text + ")")

    def _print_Derivative(self, expr):
        variables = list(expr.variable_count)
        order = sum(count for _, count in variables)
        top = "∂" + (superscript(str(order)) or f"^{order}") if order > 1 else "∂"
        bottom = "".join("∂" + self._print(v) + ((superscript(str(c)) or f"^{c}") if c > 1 else "")
                         for v, c in variables)
        inner = expr.expr
        body = self._print(inner) if inner.is_Atom or isinstance(inner, sp.Function) else "(" + self._print(inner) + ")"
        return f"{top}{body}/{bottom}"

    def _print_Relational(self, expr):
        op = _RELATIONS.get(expr.rel_op, expr.rel_op)
        return f"{self._print(expr.lhs)} {op} {self._print(expr.rhs)}"

    _print_Equality = _print_Unequality = _print_Relational

    def _print_Abs(self, expr):
        return "|" + self._print(expr.args[0]) + "|"

    def _print_conjugate(self, expr):
        arg = self._print(expr.args[0])
        return arg + "\u0305" if len(arg) == 1 else "conj(" + arg + ")"

    def _print_re(self, expr):
        return "Re(" + self._print(expr.args[0]) + ")"

    def _print_im(self, expr):
        return "Im(" + self._print(expr.args[0]) + ")"

    def _print_gamma(self, expr):
        return "Γ(" + ", ".join(self._print(a) for a in expr.args) + ")"

    def _print_Max(self, expr):
        return "max(" + ", ".join(self._print(a) for a in expr.args) + ")"

    def _print_Min(self, expr):
        return "min(" + ", ".join(self._print(a) for a in expr.args) + ")"

    def _print_floor(self, expr):
        return "⌊" + self._print(expr.args[0]) + "⌋"

    def _print_factorial(self, expr):
        return self.parenthesize(expr.args[0], PRECEDENCE["Func"]) + "!"

    def _print_RisingFactorial(self, expr):
        index = self._print(expr.args[1])
        return "(" + self._print(expr.args[0]) + ")" + (subscript(index) or "_" + index)

    def _print_Sum(self, expr):
        term = self.parenthesize(expr.function, PRECEDENCE["Mul"])
        for variable, low, high in reversed(expr.limits):
            below = subscript(f"{self._print(variable)}={self._print(low)}")
            above = superscript(self._print(high))
            if below is not None and above is not None:
                term = f"Σ{below}{above} {term}"
            else:
                term = f"Σ[{self._print(variable)} = {self._print(low)} … {self._print(high)}] {term}"
        return term

    def _print_hyper(self, expr):
        ap, bq, z = expr.args
        p, q = subscript(str(len(ap))) or str(len(ap)), subscript(str(len(bq))) or str(len(bq))
        return (f"{p}F{q}(" + ", ".join(self._print(a) for a in ap) + "; "
                + ", ".join(self._print(b) for b in bq) + "; " + self._print(z) + ")")

    def _print__Hyper(self, expr):
        return self._print_hyper(expr)

    def _print_MatrixBase(self, expr):
        return "[" + "; ".join(", ".join(self._print(x) for x in expr.row(i)) for i in range(expr.rows)) + "]"

    _print_ImmutableDenseMatrix = _print_MutableDenseMatrix = _print_Matrix = _print_MatrixBase

    def _print_Interval(self, expr):
        return ("(" if expr.left_open else "[") + self._print(expr.start) + ", " + self._print(expr.end) + (
            ")" if expr.right_open else "]")

    def _print_BooleanTrue(self, expr):
        return "true"

    def _print_BooleanFalse(self, expr):
        return "false"

    def _print_Function(self, expr):
        name = type(expr).__name__
        args = [self._print(a) for a in expr.args]
        if name == "inner":
            return "⟨" + ", ".join(args) + "⟩"
        if name == "cross":
            return " × ".join(self.parenthesize(a, PRECEDENCE["Mul"]) for a in expr.args)
        if name in ("pm", "mp"):
            return ("±" if name == "pm" else "∓") + self.parenthesize(expr.args[0], PRECEDENCE["Mul"])
        if name == "to":
            return f"{args[0]} → {args[1]}"
        if name == "equal":
            return " = ".join(args)
        if name == "abs_":
            return "|" + args[0] + "|"
        if name.endswith("_") and len(args) == 1 and subscript(args[0].replace(" ", "")):
            return symbol_text(name[:-1]) + subscript(args[0].replace(" ", ""))   # M_(-i): M₋ᵢ
        return symbol_text(name) + "(" + ", ".join(args) + ")"
