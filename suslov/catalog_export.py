"""The catalog's formulas as Mathematica and Maple text, and back (``suslov catalog export``).

Printers: SymPy's Mathematica and Maple code printers (``sympy.printing.mathematica``,
``sympy.printing.maple``), corrected where they print something the target system reads differently:

* Mathematica: ``Derivative`` as ``D[f[t], t]`` (SymPy wraps it in ``Hold``); Mathematica's builtin
  one-letter symbols (``C``, ``D``, ``E``, ``I``, ``K``, ``N``, ``O``) and ``Pi`` as symbols of the
  paper are renamed ``CSym``, ``DSym``, ... (:data:`MATHEMATICA_RENAMED`, listed in each exported file).
* Maple: ``GAMMA`` for the Gamma function (Maple's ``gamma`` is Euler's constant), ``hypergeom`` for
  ``hyper``, ``arctan(y, x)`` for ``atan2``, ``abs``, ``Re``, ``Im``, matrices as ``Matrix([[...]])``;
  Maple's protected ``D``, ``I``, ``O``, ``Pi``, ``gamma`` as symbols renamed likewise.

Checks (``tests/test_catalog.py``): the Mathematica text is parsed back by SymPy's independent
Mathematica parser (``sympy.parsing.mathematica.parse_mathematica``, a tokenizer and grammar of its
own, sharing nothing with the printer) and compared with the certified expression; the Maple text is
parsed back by :func:`parse_maple` below -- Python's tokenizer through ``sympy.parse_expr`` with Maple's
names bound to SymPy's functions, lists and equations split by bracket depth -- and compared likewise.
The comparison (:func:`same`) is structural, then ``simplify(a - b) == 0`` for each component.
"""
from __future__ import annotations

import re

from suslov.extras import require

__all__ = ["sympy_module", "mathematica", "maple", "parse_mathematica_back", "parse_maple", "same", "assumptions",
           "MATHEMATICA_RENAMED", "MAPLE_RENAMED"]

def sympy_module():
    """SymPy, or the one-line error naming the ``[catalog]`` extra (a core install has no SymPy)."""
    require("catalog", "a catalog entry's SymPy form (entry.expr and its exports)")
    import sympy

    return sympy


_sympy = sympy_module

MATHEMATICA_RENAMED = {name: name + "Sym" for name in ("C", "D", "E", "I", "K", "N", "O", "Pi")}
MAPLE_RENAMED = {name: name + "Sym" for name in ("D", "I", "O", "Pi", "gamma")}


def _printers():
    sp = _sympy()
    from sympy.printing.maple import MapleCodePrinter
    from sympy.printing.mathematica import MCodePrinter

    class Mathematica(MCodePrinter):
        def _print_Symbol(self, expr):
            return MATHEMATICA_RENAMED.get(expr.name, expr.name)

        def _print_Derivative(self, expr):
            variables = ", ".join(self._print(v) if n == 1 else "{%s, %d}" % (self._print(v), n)
                                  for v, n in expr.variable_count)
            return "D[%s, %s]" % (self._print(expr.expr), variables)

        def _print_sech(self, expr):
            return "Sech[%s]" % self._print(expr.args[0])

        def _print_conjugate(self, expr):
            return "Conjugate[%s]" % self._print(expr.args[0])

        def _print_Product(self, expr):
            return "Product[%s, %s]" % (self._print(expr.function), ", ".join(
                "{%s}" % ", ".join(map(self._print, limit)) for limit in expr.limits))

        def _print_Sum(self, expr):
            return "Sum[%s, %s]" % (self._print(expr.function), ", ".join(
                "{%s}" % ", ".join(map(self._print, limit)) for limit in expr.limits))

        def _print_Limit(self, expr):
            e, z, z0, direction = expr.args
            side = "" if z0.is_infinite else ', Direction -> "%s"' % ("FromAbove" if str(direction) == "+"
                                                                         else "FromBelow")
            return "Limit[%s, %s -> %s%s]" % (self._print(e), self._print(z), self._print(z0), side)

        def _print_re(self, expr):
            return "Re[%s]" % self._print(expr.args[0])

        def _print_im(self, expr):
            return "Im[%s]" % self._print(expr.args[0])

    class Maple(MapleCodePrinter):
        def _print_Symbol(self, expr):
            return MAPLE_RENAMED.get(expr.name, expr.name)

        def _print_gamma(self, expr):
            return "GAMMA(%s)" % self._print(expr.args[0])

        def _print_hyper(self, expr):
            return "hypergeom([%s], [%s], %s)" % (", ".join(map(self._print, expr.ap)),
                                                   ", ".join(map(self._print, expr.bq)), self._print(expr.argument))

        def _print_atan2(self, expr):
            return "arctan(%s, %s)" % (self._print(expr.args[0]), self._print(expr.args[1]))

        def _print_Abs(self, expr):
            return "abs(%s)" % self._print(expr.args[0])

        def _print_Product(self, expr):
            (k, a, b), = expr.limits
            return "product(%s, %s = %s .. %s)" % tuple(map(self._print, (expr.function, k, a, b)))

        def _print_Sum(self, expr):
            (k, a, b), = expr.limits
            return "sum(%s, %s = %s .. %s)" % tuple(map(self._print, (expr.function, k, a, b)))

        def _print_Limit(self, expr):
            e, z, z0, direction = expr.args
            side = "" if z0.is_infinite else (", right" if str(direction) == "+" else ", left")
            return "limit(%s, %s = %s%s)" % (self._print(e), self._print(z), self._print(z0), side)

        def _print_re(self, expr):
            return "Re(%s)" % self._print(expr.args[0])

        def _print_im(self, expr):
            return "Im(%s)" % self._print(expr.args[0])

        def _print_MatrixBase(self, expr):
            rows = ", ".join("[%s]" % ", ".join(self._print(x) for x in expr.row(i)) for i in range(expr.rows))
            return "Matrix([%s])" % rows

        _print_ImmutableDenseMatrix = _print_MutableDenseMatrix = _print_MatrixBase

        def _print_Tuple(self, expr):
            return "[%s]" % ", ".join(self._print(x) for x in expr)

    del sp
    return Mathematica, Maple


def mathematica(expr) -> str:
    """``expr`` as Mathematica (Wolfram Language) input text."""
    return _printers()[0]().doprint(expr)


def maple(expr) -> str:
    """``expr`` as Maple input text."""
    return _printers()[1]().doprint(expr)


def assumptions(expr, system: str) -> list[str]:
    """The domains SymPy knows of ``expr``'s symbols, as Mathematica or Maple conditions (``d > 0``, ...)."""
    renamed = MATHEMATICA_RENAMED if system == "mathematica" else MAPLE_RENAMED
    out = []
    for symbol in sorted(expr.free_symbols, key=lambda s: s.name):
        name = renamed.get(symbol.name, symbol.name)
        if symbol.is_positive:
            out.append(f"{name} > 0")
        elif symbol.is_integer:
            out.append(f"Element[{name}, Integers]" if system == "mathematica" else f"{name}::integer")
        elif symbol.is_real:
            out.append(f"Element[{name}, Reals]" if system == "mathematica" else f"{name}::real")
        if symbol.is_real and symbol.is_nonzero and not symbol.is_positive:
            out.append(f"{name} != 0" if system == "mathematica" else f"{name} <> 0")
    return out


_KEYWORDS = ("lambda", "is", "in", "if", "or", "and", "not", "def", "del", "as", "for")


def _protected(like) -> tuple[str, ...]:
    """Names a parser would not read as plain symbols: Python keywords, and ``like``'s symbols named like a
    SymPy object (``Lambda``, ``beta``, ``S``, ...)."""
    sp = _sympy()
    clashing = {s.name for s in like.atoms(sp.Symbol) if hasattr(sp, s.name)}
    return tuple(sorted(set(_KEYWORDS) | clashing))


def _protect(text: str, names: tuple[str, ...], suffix: str) -> str:
    return re.sub(r"\b(%s)\b" % "|".join(map(re.escape, names)), lambda m: m.group(1) + suffix, text)


def _restore(value, like):
    """``value`` (parsed back) with the symbols of ``like`` put back by name (with their assumptions)."""
    sp = _sympy()
    # atoms, not free_symbols: a limit's or derivative's variable is bound, and is restored too
    by_name = {s.name: s for s in like.atoms(sp.Symbol)}
    return value.xreplace({s: by_name[s.name] for s in value.atoms(sp.Symbol) if s.name in by_name})


def parse_mathematica_back(text: str, like):
    """Mathematica text -> SymPy with SymPy's own Mathematica parser; names as in ``like``."""
    sp = _sympy()
    from sympy.parsing.mathematica import parse_mathematica

    # SymPy's parser hands atoms to Python's: a symbol named like a Python keyword or a SymPy object (Lambda,
    # beta, ...) is carried under another name
    protected = _protected(like)
    value = parse_mathematica(_protect(text, protected, "KwSym"))
    back = {v: k for k, v in MATHEMATICA_RENAMED.items()}
    back.update({w + "KwSym": w for w in protected})
    back["Infinity"] = sp.oo
    value = value.xreplace({s: sp.sympify(back[s.name]) if s.name == "Infinity" else sp.Symbol(back[s.name])
                            for s in value.free_symbols if s.name in back})
    functions = {"Gamma": sp.gamma, "Sech": sp.sech, "Conjugate": sp.conjugate, "Re": sp.re, "Im": sp.im, "Abs": sp.Abs,
                 "D": lambda f, *v: sp.Derivative(f, *v),
                 "HypergeometricPFQ": lambda a, b, z: sp.hyper(a, b, z),
                 "Product": sp.Product, "Sum": sp.Sum, "Factorial2": sp.factorial2, "Factorial": sp.factorial,
                 "Limit": lambda e, rule, *direction: sp.Limit(e, *rule.args, *(
                     ("+" if "Above" in str(direction[0].args[1]) else "-",) if direction else ()))}
    value = value.replace(lambda e: isinstance(e, sp.core.function.AppliedUndef) and e.func.__name__ in functions,
                          lambda e: functions[e.func.__name__](*e.args))
    return _restore(_tuples(value), like)


def _tuples(value):
    sp = _sympy()
    if isinstance(value, (tuple, list)):
        return sp.Tuple(*[_tuples(v) for v in value])
    return value


def _split(text: str, separator: str) -> list[str]:
    parts, depth, start = [], 0, 0
    for at, ch in enumerate(text):
        depth += (ch in "([{") - (ch in ")]}")
        if depth == 0 and text.startswith(separator, at):
            before, after = text[at - 1:at], text[at + len(separator):at + len(separator) + 1]
            if separator == "=" and (before in ":<>" or after == "="):
                continue
            parts.append(text[start:at])
            start = at + len(separator)
    return parts + [text[start:]]


def parse_maple(text: str, like):
    """Maple text -> SymPy (lists, equations, matrices, the functions :func:`maple` prints); names as in ``like``."""
    sp = _sympy()
    from sympy.parsing.sympy_parser import convert_xor, parse_expr, standard_transformations

    text = text.strip()
    if text.startswith("[") and text.endswith("]"):
        inner = text[1:-1].strip()
        return sp.Tuple(*[parse_maple(part, like) for part in _split(inner, ",")]) if inner else sp.Tuple()
    sides = _split(text, "=")
    if len(sides) == 2:
        return sp.Eq(parse_maple(sides[0], like), parse_maple(sides[1], like), evaluate=False)
    back = {v: k for k, v in MAPLE_RENAMED.items()}
    names = {"Matrix": lambda rows: sp.ImmutableMatrix(rows), "GAMMA": sp.gamma, "Pi": sp.pi, "I": sp.I,
             "infinity": sp.oo, "doublefactorial": sp.factorial2, "factorial": sp.factorial, "sum": sp.Sum, "product": sp.Product, "limit": lambda e, z, z0, side: sp.Limit(e, z, z0, *(
                 ("+" if str(side) == "right" else "-",) if str(side) else ())),
             "hypergeom": lambda a, b, z: sp.hyper(a, b, z), "diff": sp.Derivative, "abs": sp.Abs, "Re": sp.re,
             "Im": sp.im, "conjugate": sp.conjugate, "sqrt": sp.sqrt, "exp": sp.exp, "ln": sp.log,
             "arctan": lambda *a: sp.atan2(*a) if len(a) == 2 else sp.atan(a[0]), "sech": sp.sech,
             "tanh": sp.tanh, "cosh": sp.cosh, "sinh": sp.sinh, "cos": sp.cos, "sin": sp.sin}
    names.update({renamed: sp.Symbol(original) for renamed, original in back.items()})
    source = _protect(text, _protected(like), "_kw_")
    # diff(f, t$3) is the third derivative
    source = _maple_ranges(re.sub(r"(\w+)\$(\d+)", r"\1, \2", source))
    value = parse_expr(source, local_dict=names, transformations=standard_transformations + (convert_xor,))
    value = value.xreplace({s: sp.Symbol(s.name[:-4]) for s in value.free_symbols if s.name.endswith("_kw_")})
    return _restore(value, like)


def _closing(text: str, start: int) -> int:
    depth = 0
    for at in range(start, len(text)):
        depth += (text[at] in "([{") - (text[at] in ")]}")
        if depth == 0:
            return at
    raise ValueError(f"unbalanced parentheses in {text!r}")


def _maple_ranges(text: str) -> str:
    """``sum(f, k = a .. b)`` -> ``sum(f, (k, a, b))`` and ``limit(f, t = x0, right)`` -> ``limit(f, t, x0,
    'right')``: Maple's equations inside a call, which Python's grammar reads as keyword arguments."""
    out, at = [], 0
    for match in re.finditer(r"\b(sum|product|limit)\(", text):
        if match.start() < at:
            continue
        close = _closing(text, match.end() - 1)
        args = _split(text[match.end():close], ",")
        variable, point = (part.strip() for part in args[1].split(" = ", 1))
        if match.group(1) == "limit":
            side = args[2].strip() if len(args) > 2 else ""
            rewritten = f"{_maple_ranges(args[0])}, {variable}, {_maple_ranges(point)}, '{side}'"
        else:
            low, high = (_maple_ranges(x) for x in point.split(" .. ", 1))
            rewritten = f"{_maple_ranges(args[0])}, ({variable}, {low}, {high})"
        out.append(text[at:match.end()] + rewritten + ")")
        at = close + 1
    return "".join(out) + text[at:]


def same(a, b) -> bool:
    """``a`` and ``b`` are the same formula: equal structure, each component equal (``simplify(x - y) == 0``)."""
    sp = _sympy()
    if a == b:
        return True
    if isinstance(a, sp.MatrixBase) and isinstance(b, (tuple, sp.Tuple)):   # a parsed nested list
        b = sp.ImmutableMatrix([list(row) for row in b])
    if isinstance(a, sp.Tuple) and isinstance(b, (tuple, sp.Tuple)) or isinstance(a, sp.MatrixBase) and isinstance(b, sp.MatrixBase):
        return getattr(a, "shape", len(a)) == getattr(b, "shape", len(b)) and all(
            same(x, y) for x, y in zip(list(a), list(b)))
    if isinstance(a, sp.Equality) and isinstance(b, sp.Equality):
        return same(a.lhs, b.lhs) and same(a.rhs, b.rhs)
    if isinstance(a, sp.Expr) and isinstance(b, sp.Expr):
        difference = (a - b).doit() if a.has(sp.Derivative) or b.has(sp.Derivative) else a - b
        try:
            return difference == 0 or sp.cancel(difference) == 0 or sp.simplify(difference) == 0
        except (TypeError, ValueError):   # SymPy could not decide: not shown equal
            return False
    return False
