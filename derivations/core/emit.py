"""Emit certified expressions as Python functions of a number context (``ctx``).

A closed form is emitted once, as ``def _name(ctx, arg, ...)`` whose elementary functions
come from ``ctx`` (``ctx.tanh``, ``ctx.sech``, ``ctx.sqrt``, ``ctx.atan2``, ``ctx.exp``, ``ctx.expm1``; ``sqrt(x^2 + 1)`` as ``ctx.hypot(x, 1)``, which
cannot overflow): the module
evaluates it with ``suslov.kernel.contexts.FLOAT`` (NumPy) or ``MP`` (mpmath), and the
build's round trip (:mod:`derivations.output.roundtrip`) evaluates the *same emitted text* with a
SymPy context and compares it with the certified expression exactly.

An :class:`Emitted` holds the certified expressions, the bindings that tie extension
symbols to functions of the arguments (``T = tanh t``, ``S = sech t``,
``c = sqrt(d^2+1)``: the relations under which the certificates were made) and the
argument list.  Printing goes through SymPy's ``PythonCodePrinter`` with integer powers
written as products (they work on floats, arrays and mpmath numbers alike) and the known
functions routed to ``ctx``: no string surgery.
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.printing.pycode import PythonCodePrinter

from derivations.core import flint_factor

__all__ = ["Emitted", "emit_source"]


class _ContextPrinter(PythonCodePrinter):
    """Arithmetic for floats, arrays and mpmath; tanh/sech/sqrt/atan2/Abs through ``ctx``."""

    _CTX = {"tanh": "ctx.tanh", "sech": "ctx.sech", "atan2": "ctx.atan2", "exp": "ctx.exp", "expm1": "ctx.expm1"}

    def _print_Function(self, expr):
        name = type(expr).__name__
        if name in self._CTX:
            return f"{self._CTX[name]}({', '.join(self._print(a) for a in expr.args)})"
        return super()._print_Function(expr)

    _print_tanh = _print_sech = _print_atan2 = _print_exp = _print_expm1 = _print_Function

    def _print_Pow(self, expr, rational=False):
        base, exp = expr.as_base_exp()
        if exp == sp.Rational(1, 2):
            terms = sp.Add.make_args(base)
            if len(terms) == 2 and sp.Integer(1) in terms:   # sqrt(x^2 + 1): hypot, finite for |x| up to 1e308
                square = next(t for t in terms if t != 1)
                if square.is_Pow and square.exp == 2:
                    return f"ctx.hypot({self._print(square.base)}, 1)"
            return f"ctx.sqrt({self._print(base)})"
        if exp.is_Integer and exp > 0:
            factors = [self.parenthesize(base, sp.printing.precedence.PRECEDENCE["Mul"])] * int(exp)
            return factors[0] if exp == 1 else "(" + "*".join(factors) + ")"
        if exp.is_Integer and exp < 0:
            return "1/" + self._print(sp.Pow(base, -exp, evaluate=False))
        raise ValueError(f"cannot emit the power {expr}: only integer powers and square roots")

    def _print_Abs(self, expr):
        return f"abs({self._print(expr.args[0])})"


def _source(expr) -> str:
    return _ContextPrinter({"standard": "python3"}).doprint(sp.sympify(expr))


@dataclass
class Emitted:
    """A certified formula to emit: ``_name(ctx, *args) -> outputs``.

    ``bindings``: (symbol, expression in the arguments) pairs evaluated first, in order;
    ``outputs``: the certified expressions in the arguments and the bound symbols;
    ``certificates``: keys of the certificates that cover the expressions.
    """

    name: str
    args: tuple
    bindings: tuple
    outputs: tuple
    certificates: tuple = ()
    doc: str = ""
    linear_in: tuple = ()

    def _binding_lines(self, bindings) -> list[str]:
        """``T, S = ctx.tanh_sech(t)`` where tanh and sech of one argument are bound together (one exp)."""
        lines, pending = [], list(bindings)
        while pending:
            symbol, value = pending.pop(0)
            partner = next((b for b in pending if isinstance(value, sp.tanh) and isinstance(b[1], sp.sech)
                            and b[1].args == value.args), None)
            if partner is not None:
                pending.remove(partner)
                lines.append(f"    {symbol}, {partner[0]} = ctx.tanh_sech({_source(value.args[0])})")
            else:
                lines.append(f"    {symbol} = {_source(value)}")
        return lines

    def source(self) -> str:
        """The function's text.  With ``linear_in`` (bound symbols such as T = tanh t, S = sech t) each
        output is written as sum k_i m_i with the coefficients k_i (free of those symbols) computed first:
        for scalar parameters and array t that costs one array product per term (an evaluation-order
        rewrite, declared as data; the round trip checks the printed text against the certified expression)."""
        lines = [f"def _{self.name}(ctx, {', '.join(str(a) for a in self.args)}):"]
        lines.append(f'    """{self.doc}')
        lines.append("")
        lines.append(f'    Emitted from the certified expression; certificates: {", ".join(self.certificates) or "-"}.')
        lines.append('    """')
        late = [b for b in self.bindings if b[0] in self.linear_in]
        lines += self._binding_lines([b for b in self.bindings if b[0] not in self.linear_in])
        if self.linear_in:
            outputs, count = [], 0
            for expr in self.outputs:
                terms = []
                for monomial, coefficient in sp.Poly(sp.expand(expr), *self.linear_in).terms():
                    lines.append(f"    k{count} = {_source(flint_factor.factor(coefficient))}")
                    factor = sp.Mul(*(s**e for s, e in zip(self.linear_in, monomial)))
                    terms.append(f"k{count}" + ("" if factor == 1 else f"*{_source(factor)}"))
                    count += 1
                outputs.append(" + ".join(terms) or "0")
        else:
            outputs = [_source(e) for e in self.outputs]
        lines += self._binding_lines(late)
        lines.append("    return " + (outputs[0] if len(outputs) == 1 else "(" + ", ".join(outputs) + ")"))
        return "\n".join(lines) + "\n"

    def substituted(self) -> list:
        """The outputs with the bindings substituted (expressions in the arguments only)."""
        out = list(self.outputs)
        for symbol, value in reversed(self.bindings):
            out = [sp.sympify(e).subs(symbol, value) for e in out]
        return out


def emit_source(items) -> dict:
    """``{name: source}`` for the template."""
    return {item.name: item.source() for item in items}


def emitted_formulas(build) -> dict:
    """``{name: Emitted}`` of every derivation that ran in ``build`` (their exports["emit"])."""
    return {item.name: item for name in build.names for item in build.results[name].exports.get("emit", ())}
