"""Claims as mathematics: words and SymPy objects, typeset by SymPy (issue 35).

A certificate's claim, method and detail, an erratum's note and a derivation's note are
:class:`Statement` objects: a sequence of *parts*, each either prose (a ``str``) or mathematics (a
SymPy object, or a :class:`Ring`).  Nothing is guessed from the text:

* the LaTeX documents print prose escaped as text and every mathematical part with the project's
  :class:`~derivations.core.typeset.FormulaPrinter` (SymPy's ``LatexPrinter``; symbol names set once
  in :data:`SYMBOL_NAMES`, written order kept: ``order="none"``), inside ``$...$``;
* ``certificates.json``, the terminal and the diff print the plain text: prose as written,
  mathematics by SymPy's ``StrPrinter`` (``sstr``; ``=`` for an equation).

A statement is written in the source as one string whose formulas stand between dollar signs,
``"det I = 1 fixes $I33 = (1 + I11 I23^2 + I22 I13^2)/(I11 I22)$"``: each dollar span is read by
SymPy's own parser (``parse_expr`` with implicit multiplication and application, ``^`` as power,
``=`` as an equation, ``evaluate=False`` so that the written form is kept) into a SymPy object when
the statement is made; a span SymPy cannot read is an error naming the span.  A program name in prose
(a function of the emitted module, a library's type) stands between backticks, ```first_integral```: it
is set in typewriter type (:class:`Code`) and never read as mathematics.  No TeX is written by hand.  A string without dollar signs is prose only (what a branch that still writes plain claims
produces): it is typeset as text, so any program syntax in it shows in the PDF, where
``tests/test_pdf_text.py`` finds it.

Rings (the domains of ``derivations.core.exact``) are :class:`Ring` parts, written in the same form
(:func:`ring`): ``Q(I11, I22)[r]/(r^2 - I11 I22)`` typesets as :math:`\\mathbb{Q}(I_{11}, I_{22})[r]/(r^2 - I_{11} I_{22})`.
"""
from __future__ import annotations

import functools
import tokenize
from dataclasses import dataclass, field
from io import StringIO

import sympy as sp
from sympy.parsing.sympy_parser import (
    convert_equals_signs,
    convert_xor,
    function_exponentiation,
    implicit_application,
    implicit_multiplication,
    parse_expr,
    standard_transformations,
)

from derivations.core.statement_printers import SYMBOL_NAMES, MathPrinter, TextPrinter  # noqa: F401 (the tests')

# -- notation -------------------------------------------------------------------------------------

def _powered(latex):
    """A ``_latex`` method that also takes the exponent SymPy's printer hands to a function raised to a power."""
    def method(self, printer, exp=None):
        body = latex(self, printer)
        if exp is None:
            return body
        bracketed = body.endswith((r"\right)", r"\right|", r"\right\rangle"))
        return (body if bracketed else r"\left(" + body + r"\right)") + "^{" + exp + "}"
    return method


class _Named(sp.Function):
    """A function printed ``\\name(args)`` in LaTeX and ``name(args)`` in text."""

    tex_name = ""

    @_powered
    def _latex(self, printer):
        return self.tex_name + r"\left(" + ", ".join(printer._print(a) for a in self.args) + r"\right)"


def _named(name: str, tex: str, latex_method=None):
    members = {"tex_name": tex}
    if latex_method is not None:
        members["_latex"] = _powered(latex_method)
    cls = type(name, (_Named,), members)
    globals()[name] = cls          # a module attribute of its own name: it pickles (worker processes)
    return cls


# a program's names written as the mathematics they compute (the text keeps the name: it says how it is evaluated)
def _expm1_latex(self, printer):
    return r"\left(e^{" + printer._print(self.args[0]) + r"} - 1\right)"


def _atan2_latex(self, printer):
    y, x = (printer._print(a) for a in self.args)
    y = y if self.args[0].is_Atom else r"\left(" + y + r"\right)"
    return r"\arg\left(" + x + r" + i\, " + y + r"\right)"


class inner(sp.Function):
    """``<a, b>``: the scalar product."""

    @_powered
    def _latex(self, printer):
        return r"\left\langle " + ", ".join(printer._print(a) for a in self.args) + r"\right\rangle"


class cross(sp.Function):
    """``a x b``: the cross product (``cross(a, b)`` in text)."""

    @_powered
    def _latex(self, printer):
        return r" \times ".join(printer.parenthesize(a, 50) for a in self.args)


class pm(sp.Function):
    """``+-a``: both signs (``mp``: the opposite sign of a ``pm`` nearby)."""

    sign = r"\pm"

    @_powered
    def _latex(self, printer):
        return self.sign + " " + printer.parenthesize(self.args[0], 50)


class mp(pm):
    sign = r"\mp"


class equal(sp.Function):
    """``a = b = c``: a chain of equalities (SymPy's ``Eq`` takes two sides)."""

    @_powered
    def _latex(self, printer):
        return " = ".join(printer._print(a) for a in self.args)

    def _sympystr(self, printer):
        return " = ".join(printer._print(a) for a in self.args)


class to(sp.Function):
    """``t -> a``: a limit process (``to(t, -oo)``)."""

    @_powered
    def _latex(self, printer):
        return printer._print(self.args[0]) + r" \to " + printer._print(self.args[1])


def _abs_latex(self, printer):
    return r"\left|" + printer._print(self.args[0]) + r"\right|"


# ``|a|`` of a vector or a symbol without SymPy's evaluation (``Abs`` of a positive symbol drops it);
# a module attribute of its class name, so that it pickles
abs_ = type("abs_", (sp.Function,), {"_latex": _powered(_abs_latex), "_sympystr": lambda self, printer: f"abs({printer._print(self.args[0])})"})


FUNCTIONS = {
    "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log, "sin": sp.sin, "cos": sp.cos, "tan": sp.tan,
    "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh, "sech": sp.sech, "coth": sp.coth, "csch": sp.csch,
    "expm1": _named("expm1", "", _expm1_latex), "Abs": sp.Abs, "abs": abs_, "re": sp.re, "im": sp.im,
    "Re": sp.re, "Im": sp.im, "conjugate": sp.conjugate, "Gamma": sp.gamma, "hyper": sp.hyper,
    "det": _named("det", r"\det"), "diag": _named("diag", r"\operatorname{diag}"),
    "rank": _named("rank", r"\operatorname{rank}"), "tr": _named("tr", r"\operatorname{tr}"),
    "deg": _named("deg", r"\deg"), "Res": _named("Res", r"\operatorname{Res}"),
    "atan2": _named("atan2", "", _atan2_latex), "SO": _named("SO", r"\mathrm{SO}"),
    "PSL": _named("PSL", r"\mathrm{PSL}"), "SL": _named("SL", r"\mathrm{SL}"),
    "Derivative": sp.Derivative, "deriv": lambda f, *v: sp.Derivative(f, *v, evaluate=False),
    "Matrix": sp.Matrix, "Sum": sp.Sum, "factorial": sp.factorial, "RisingFactorial": sp.RisingFactorial,
    "inner": inner, "cross": cross, "pm": pm, "mp": mp, "to": to, "equal": equal, "Max": sp.Max, "Min": sp.Min,
    "floor": sp.floor, "binomial": sp.binomial, "Tuple": sp.Tuple, "Interval": sp.Interval,
}
CONSTANTS = {"i": sp.I, "pi": sp.pi, "oo": sp.oo, "E": sp.E, "True": sp.true, "False": sp.false}
# what the parser's generated code needs besides the names above
_PARSER_GLOBALS = {name: getattr(sp, name) for name in ("Symbol", "Integer", "Float", "Rational", "Function", "Add", "Mul", "Pow", "Tuple")}


def _written_relation(kind):
    """``kind(a, b)`` as written (``convert_equals_signs`` emits a plain ``Eq(a, b)``, whose evaluation asked SymPy's
    assumptions whether it holds: a quarter of a cold build's main process): a formula to print, not to decide."""
    return lambda lhs, rhs, **_: kind(lhs, rhs, evaluate=False)


_PARSER_GLOBALS.update({name: _written_relation(getattr(sp, name)) for name in ("Eq", "Ne", "Lt", "Le", "Gt", "Ge")})
_TRANSFORMATIONS = standard_transformations + (implicit_multiplication, implicit_application,
                                               function_exponentiation, convert_xor, convert_equals_signs)


def _fold(expr):
    """``1/2``, ``-3``, ``2^-1`` read with ``evaluate=False`` are trees of integers (``1*2**-1``):
    fold every subtree without symbols into its number, keep everything else as written."""
    if not isinstance(expr, sp.Basic) or not expr.args or isinstance(expr, sp.MatrixBase):
        return expr
    args = tuple(_fold(a) for a in expr.args)
    # a power only as 1/n: 10^-90 stays a power, not a 91-digit fraction
    if isinstance(expr, (sp.Add, sp.Mul, sp.Pow)) and all(a.is_Rational for a in args) and not (
            expr.is_Pow and args[1] != -1):
        return expr.func(*args)
    if isinstance(expr, sp.Mul) and args[0] == 1 and len(args) == 2:
        return args[1]                                     # "1/x" read as 1*x**-1
    # a signed or fractional product without functions (evaluation would rewrite exp(i pi/2) as i), evaluated
    if isinstance(expr, sp.Mul) and not any(a.has(sp.Function, sp.Derivative) for a in args) and any(
            a == -1 or (a.is_Mul and a.args[0] == -1) or (a.is_Rational and not a.is_Integer) for a in args):
        return sp.Mul(*(sp.Pow(*a.args) if a.is_Pow else a for a in args))   # "-x/y" read as (-1*x)*y**-1: a signed product, printed "- x/y"
    if args == expr.args:
        return expr
    if isinstance(expr, (sp.Add, sp.Mul, sp.Pow, sp.Function)):   # exp(-i pi/2) stays written, not -i
        return expr.func(*args, evaluate=False)
    return expr.func(*args)


def _names(span: str) -> dict:
    """Every name in ``span`` that is not a function or a constant, as a plain symbol (SymPy's own
    names such as ``S``, ``N``, ``gamma`` or ``Lambda`` would otherwise be taken as its objects)."""
    names = {}
    tokens = list(tokenize.generate_tokens(StringIO(span).readline))
    for token, after in zip(tokens, tokens[1:] + [None]):
        if token.type == tokenize.NAME and token.string not in FUNCTIONS and token.string not in CONSTANTS:
            # ``G1(0)``, ``rt(w)``: a name glued to its parenthesis is a function; ``I11 (I11 - I22)`` a product
            glued = after is not None and after.string == "(" and after.start == token.end
            names[token.string] = sp.Function(token.string) if glued else sp.Symbol(token.string)
    return names


def _equals_signs(text: str) -> list[int]:
    """Positions of the ``=`` at bracket depth 0 that are equations (not ``<=``, ``>=``, ``!=``, ``==``)."""
    found, depth = [], 0
    for k, ch in enumerate(text):
        depth += ch in "([{"
        depth -= ch in ")]}"
        if ch == "=" and depth == 0 and text[k - 1:k] not in ("<", ">", "!", "=") and text[k + 1:k + 2] != "=":
            found.append(k)
    return found


@functools.lru_cache(maxsize=8192)
def math(span: str):
    """The SymPy object of one formula written in SymPy's syntax (``^`` a power, products by juxtaposition,
    ``=`` an equation, ``a, b`` a tuple)."""
    text = span.strip()
    signs = _equals_signs(text)
    if len(signs) > 1:           # a = b = c
        bounds = [-1] + signs + [len(text)]
        try:
            return equal(*(math(text[a + 1:b]) for a, b in zip(bounds, bounds[1:])))
        except ValueError as exc:
            raise ValueError(f"formula {span!r} is not SymPy syntax: {exc}") from None
    try:
        local = {**_names(text), **FUNCTIONS, **CONSTANTS}
        value = parse_expr(text, local_dict=local, global_dict=dict(_PARSER_GLOBALS),
                           transformations=_TRANSFORMATIONS, evaluate=False)
    except Exception as exc:   # SymPy's parser raises whatever its generated code raises
        raise ValueError(f"formula {span!r} is not SymPy syntax: {type(exc).__name__}: {exc}") from None
    if isinstance(value, tuple):
        value = sp.Tuple(*value)
    if not isinstance(value, sp.Basic):
        raise ValueError(f"formula {span!r} reads as {type(value).__name__}, not a SymPy object")
    if isinstance(value, sp.logic.boolalg.BooleanAtom):   # SymPy decided the relation: the formula is gone
        raise ValueError(f"formula {span!r} evaluates to {value}: write it so that it stays a formula")
    return _fold(value)


# -- printing -------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Code:
    """A program name in prose (a function of the emitted module, a library's type): written ```name```
    in a statement, set in typewriter type, never read as mathematics."""

    name: str


def text_of(part) -> str:
    if isinstance(part, str):
        return part
    if isinstance(part, Code):
        return part.name
    if isinstance(part, Ring):
        return part.text()
    return TextPrinter().doprint(part)


def tex_of(part) -> str:
    if isinstance(part, str):
        return tex_escape(part)
    if isinstance(part, Code):
        return r"\texttt{" + tex_escape(part.name) + "}"
    if isinstance(part, Ring):
        return part.tex(inline=True)
    return "$" + MathPrinter().doprint(part) + "$"


_TEX_SPECIALS = {
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
    "<": r"\textless{}", ">": r"\textgreater{}",
}


def tex_escape(text) -> str:
    """Plain text for TeX (prose parts; a prose-only statement)."""
    return "".join(_TEX_SPECIALS.get(ch, ch) for ch in str(text))


# -- rings ----------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Ring:
    """``base(fields...)[adjoined...]/(relations)``: a field of fractions ``Q(x, y)`` (one group per
    ``(...)``), polynomial rings over it (one group per ``[...]``) and the ideal of the relations.
    ``note`` is prose after the ring (``(python-flint fmpq_mpoly)``)."""

    base: str
    groups: tuple           # (("(" or "["), (SymPy objects...)) in order
    relations: tuple = ()
    note: "Statement | str" = ""
    source: str = field(default="", compare=False, repr=False)   # the name :func:`ring` read it from

    def __reduce__(self):
        # pickled as the name it was read from (a Statement's parts go to worker processes and back): the
        # parts themselves are SymPy objects made with evaluate=False, which unpickling evaluates, so the
        # relation i^2 + 1 of Q[x,d,i]/(i^2+1), i the imaginary unit, came back as 0
        if self.source:
            return (ring, (self.source,))
        return (Ring, (self.base, self.groups, self.relations, self.note))

    def text(self) -> str:
        out = self.base + "".join(
            (o + ", ".join(text_of(g) for g in gens) + (")" if o == "(" else "]")) for o, gens in self.groups)
        if self.relations:
            out += "/(" + ", ".join(text_of(r) for r in self.relations) + ")"
        return out + text(self.note)

    def tex(self, inline: bool = False) -> str:
        printer = MathPrinter()
        out = (r"\mathbb{%s}" % self.base) + "".join(
            (o + ", ".join(printer.doprint(g) for g in gens) + (")" if o == "(" else "]")) for o, gens in self.groups)
        if self.relations:
            out += "/(" + ", ".join(printer.doprint(r) for r in self.relations) + ")"
        return "$" + out + "$" + tex(self.note) if inline else out

    def expressions(self) -> list:
        return [g for _, gens in self.groups for g in gens] + list(self.relations)


def _split_groups(text: str, name: str) -> tuple[list, str]:
    """``(a, b)[c]/(r)rest`` -> [("(", "a, b"), ("[", "c"), ("/", "r")], rest: brackets matched by depth."""
    groups, i = [], 0
    pairs = {"(": ")", "[": "]"}
    while i < len(text):
        opener = text[i]
        if opener == "/" and text[i + 1:i + 2] == "(":
            opener, i = "/", i + 1
        elif opener not in pairs:
            break
        start, depth, j = i + 1, 0, i
        while j < len(text):
            depth += text[j] in "([" and 1 or 0
            depth -= text[j] in ")]" and 1 or 0
            if depth == 0:
                break
            j += 1
        if depth:
            raise ValueError(f"ring {name!r}: unbalanced brackets")
        groups.append((opener, text[start:j]))
        i = j + 1
    return groups, text[i:]


def _items(text: str) -> list:
    value = math(text)
    return list(value.args) if isinstance(value, sp.Tuple) else [value]


@functools.lru_cache(maxsize=1024)
def ring(name: str) -> Ring:
    """The :class:`Ring` written ``Q(I11, I22)[r]/(r^2 - I11 I22)`` (``Z[...]`` for integers); a statement
    may follow the ring after a space (`` (python-flint, numerators over $(1 + x^2)^p$)``)."""
    if not name or name[0] not in "QZ" or name[1:2] not in ("(", "["):
        raise ValueError(f"ring {name!r}: expected Q(...) or Z[...] first")
    groups, rest = _split_groups(name[1:], name)
    relations = ()
    if groups and groups[-1][0] == "/":
        relations = tuple(_items(groups.pop()[1]))
    if rest and not rest.startswith(" "):
        raise ValueError(f"ring {name!r}: unexpected {rest!r} after the ring")
    return Ring(name[0], tuple((o, tuple(_items(body))) for o, body in groups), relations, say(rest) if rest else "",
                source=name)


# -- statements -----------------------------------------------------------------------------------

class Statement:
    """Words and mathematics: ``parts`` is a tuple of ``str`` (prose), SymPy objects and rings."""

    __slots__ = ("parts", "source", "_printed")

    def __init__(self, *parts, source: str | None = None):
        self.source = source        # the "words $formula$" text it was read from (pickled as that)
        self._printed = {}          # "text"/"tex" -> the printed form (parts never change once made)
        flat = []
        for part in parts:
            if isinstance(part, Statement):
                flat.extend(part.parts)
            elif isinstance(part, (str, Ring, Code, sp.Basic)):
                flat.append(part)
            elif isinstance(part, (int, sp.MatrixBase)):
                flat.append(sp.sympify(part))
            else:
                raise TypeError(f"statement part {part!r} is {type(part).__name__}: give text, a SymPy object or a Ring")
        self.parts = tuple(p for p in flat if not (isinstance(p, str) and p == ""))

    def __reduce__(self):
        if self.source is not None:
            return (say, (self.source,))
        return (_from_parts, (self.parts,))

    def _print(self, how: str, part_printer) -> str:
        if how not in self._printed:   # the certificates document and each render print it again
            self._printed[how] = "".join(part_printer(p) for p in self.parts)
        return self._printed[how]

    def text(self) -> str:
        return self._print("text", text_of)

    def tex(self) -> str:
        return self._print("tex", tex_of)

    def expressions(self) -> list:
        """The mathematical parts (rings as their generators and relations)."""
        out = []
        for part in self.parts:
            if isinstance(part, Ring):
                out.extend(part.expressions())
            elif not isinstance(part, (str, Code)):
                out.append(part)
        return out

    def __add__(self, other):
        return Statement(self, other)

    def __str__(self) -> str:
        return self.text()

    def __repr__(self) -> str:
        return f"Statement{self.parts!r}"

    def __eq__(self, other):
        return isinstance(other, Statement) and self.parts == other.parts

    def __hash__(self):
        return hash(self.parts)

    def startswith(self, prefix: str) -> bool:
        return self.text().startswith(prefix)

    def __contains__(self, item: str) -> bool:
        return item in self.text()


def say(source) -> Statement:
    """The statement written ``"words $formula$ words ..."`` (see the module docstring); a
    :class:`Statement` is returned as it is.  ``$$`` stands for a literal dollar sign in prose."""
    if isinstance(source, Statement):
        return source
    if not isinstance(source, str):
        raise TypeError(f"a statement is text with $formulas$, got {type(source).__name__}")
    return _say(source)


@functools.lru_cache(maxsize=8192)
def _say(source: str) -> Statement:
    pieces = source.replace("$$", "\0").split("$")
    if len(pieces) % 2 == 0:
        raise ValueError(f"statement {source!r}: an odd number of $ (a formula is not closed)")
    parts = []
    for k, piece in enumerate(pieces):
        piece = piece.replace("\0", "$")
        if k % 2 == 0:   # prose, with `program names` between backticks
            names = piece.split("`")
            if len(names) % 2 == 0:
                raise ValueError(f"statement {source!r}: an odd number of ` (a program name is not closed)")
            parts.extend(Code(name) if j % 2 else name for j, name in enumerate(names))
        elif piece.strip().startswith(("Q(", "Z[", "Q[")):
            parts.append(ring(piece.strip()))
        else:
            parts.append(math(piece))
    return Statement(*parts, source=source)


def _from_parts(parts) -> Statement:
    return Statement(*parts)


def text(value) -> str:
    """Plain text of a statement or a string (JSON, terminal)."""
    return value.text() if isinstance(value, Statement) else str(value)


def tex(value) -> str:
    """LaTeX of a statement, or of text written ``"words $formula$"``."""
    return say(str(value) if not isinstance(value, Statement) else value).tex()
