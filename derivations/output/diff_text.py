"""The change list of ``build_formulas.py --diff`` for a human reader: formulas in Unicode, meaning compared.

``certificates.json`` stores a claim, a method or an erratum's note as plain text: prose as written and the
mathematics as SymPy's ``StrPrinter`` prints it (``Derivative(p, z)*(1/2) + p**2/4``, ``Ne(I13, 0)``).  That is
program text, and two builds whose printer differs (``i*pi*(1/2)`` against ``pi*i/2``) print the same claim
differently.  This module reads such text back:

* :func:`segments` splits it into prose and formula spans (the ``$...$`` of the statement's source are not
  stored: a span is what SymPy's printer writes -- operands joined by spaced operators ``a + b``, ``x = y``,
  products ``a*b``, powers, calls ``f(x)``, names such as ``I13`` or ``omega``);
* :func:`render` prints every formula span in compact Unicode (``(∂p/∂z)/2 + p²/4``, ``I₁₃ ≠ 0``, ``i·π/2``,
  ``√(1 - z)``, ``10⁻¹⁴``): the span is parsed with the statement module's own reading (SymPy's parser,
  ``evaluate=False``, the written form kept) and printed by
  :class:`~derivations.output.diff_unicode.UnicodePrinter`; a span SymPy cannot read has its program tokens
  replaced one by one (:func:`_substitute`), so that none survives (:func:`program_text` finds them; the tests
  run it on every line of the report);
* :func:`meaning` is what two texts must share to say the same thing: the prose, word for word, and each
  formula as SymPy evaluates it (structural equality, else ``simplify(a - b) == 0`` for small ones):
  :func:`same_meaning` is how the diff tells a claim *reprinted* from a claim *reworded*;
* :func:`wrap` fills a report item to :data:`WIDTH` columns, :func:`changed_words` names the words that differ.
"""
from __future__ import annotations

import difflib
import functools
import re
import textwrap
import warnings

import sympy as sp
from sympy.parsing.sympy_parser import parse_expr

from derivations.core.statement import _PARSER_GLOBALS, _TRANSFORMATIONS, CONSTANTS, FUNCTIONS, _names
from derivations.output.diff_latex import superscript
from derivations.output.diff_unicode import (_RELATIONS, UnicodePrinter, _float_unicode, _Hyper, is_symbol_name,
                                             symbol_text)

WIDTH = 100          # columns of the report (textwrap)
SIMPLIFY_OPS = 40    # formulas up to this many operations (both sides) are compared by simplify(a - b) == 0

# -- reading a formula span -------------------------------------------------------------------------------

_TOKEN = re.compile(r"\*\*|<=|>=|!=|==|->|\+-|-\+|[A-Za-z_]\w*|\d+(?:\.\d+)?(?:[eE][-+]?\d+)?|\s+|.", re.S)
_RELATION_TOKENS = ("<=", ">=", "!=", "==", "->", "=", "<", ">")


def _split_relations(text: str) -> tuple[list[str], list[str]]:
    """The sides and the relation operators at bracket depth 0: ``a <= b = c`` -> [a, b, c], [<=, =]."""
    sides, ops, depth, start = [], [], 0, 0
    for match in _TOKEN.finditer(text):
        token = match.group()
        depth += token in "([{⟨"
        depth -= token in ")]}⟩" and depth > 0
        if depth == 0 and token in _RELATION_TOKENS:
            sides.append(text[start:match.start()])
            ops.append(token)
            start = match.end()
    sides.append(text[start:])
    return sides, ops


_NAME = re.compile(r"[A-Za-z_]\w*")


def _juxtaposed_words(text: str) -> bool:
    """Two names side by side of which one is a word (``the solution``): prose, not a product to parse."""
    names = [m for m in _TOKEN.finditer(text) if not m.group().isspace()]
    for a, b in zip(names, names[1:]):
        if a.end() == b.start() or not all(_NAME.fullmatch(m.group()) for m in (a, b)):
            continue
        if not all(is_symbol_name(n) or n in FUNCTIONS or n in CONSTANTS for n in (a.group(), b.group())):
            return True
    return False


_HAND_WRITTEN = re.compile(r"[A-Za-z0-9)][+-][A-Za-z0-9(]")
_FLOAT = re.compile(r"\d+(?:\.\d+)?[eE][-+]?\d+")


# what SymPy's printer never writes and Python code would: an attribute, a dunder name, a string, a statement
# (SymPy's parser evaluates the text, and an OLD directory given to --diff is anyone's file)
_NOT_A_FORMULA = re.compile(r"\.\s*[A-Za-z_]|__|['\"\\;:`@]|\b(?:lambda|import|exec|eval)\b")


def _parse_side(text: str, evaluate: bool):
    """One side of a formula as SymPy reads it (``evaluate=False``: as written), or ValueError for text that is not
    SymPy's printing: braces (TeX, a set), a ``+`` or ``-`` without spaces, prose words side by side, and
    anything :data:`_NOT_A_FORMULA` matches (never evaluated)."""
    text = text.strip()
    if (not text or "+-" in text or "-+" in text or "{" in text or _HAND_WRITTEN.search(_FLOAT.sub("0", text))
            or _NOT_A_FORMULA.search(text) or _juxtaposed_words(text)):
        raise ValueError(text)
    local = {**_names(text), **FUNCTIONS, **CONSTANTS}
    for name in ("Eq", "Ne", "Lt", "Le", "Gt", "Ge"):   # SymPy's printed relations (Ne(I13, 0)): the parser's own
        local.pop(name, None)
    if not evaluate:
        local["hyper"] = _Hyper
    with warnings.catch_warnings():   # Python's compiler on text that is not a formula (Q(x)[y, z]): it fails below
        warnings.simplefilter("ignore")
        value = parse_expr(text, local_dict=local, global_dict=dict(_PARSER_GLOBALS),
                           transformations=_TRANSFORMATIONS, evaluate=evaluate)
    if isinstance(value, tuple):
        value = sp.Tuple(*value)
    if not isinstance(value, sp.Basic) or isinstance(value, sp.logic.boolalg.BooleanAtom):
        raise ValueError(text)
    return value if evaluate else _written(value)


def _written(expr):
    """Numbers read with ``evaluate=False`` folded as the statement module does (``(1/2)`` is 1/2, ``-3`` is -3,
    ``1/x`` is not 1*x**-1), the rest as written: a sum of numbers cut from prose (``1 + 2`` of ``1 + 2 sigma1``)
    stays a sum, a product keeps its order (``i*pi*(1/2)`` prints ``i·π/2``)."""
    if not isinstance(expr, sp.Basic) or not expr.args or isinstance(expr, sp.MatrixBase):
        return expr
    args = tuple(_written(a) for a in expr.args)
    if isinstance(expr, (sp.Mul, sp.Pow)) and all(a.is_Rational for a in args) and not (expr.is_Pow and args[1] != -1):
        return expr.func(*args)
    if isinstance(expr, sp.Mul) and args[0] == 1 and len(args) == 2:
        return args[1]
    if args == expr.args:
        return expr
    if isinstance(expr, (sp.Add, sp.Mul, sp.Pow, sp.Function)):
        return expr.func(*args, evaluate=False)
    return expr.func(*args)


@functools.lru_cache(maxsize=8192)
def formula_text(span: str) -> str:
    """One formula span in Unicode: parsed and printed by :class:`UnicodePrinter`, else token by token."""
    sides, ops = _split_relations(span)
    try:
        printed = [UnicodePrinter().doprint(_parse_side(side, evaluate=False)) for side in sides]
    except Exception:   # SymPy's parser raises whatever its generated code raises
        if len(sides) > 1:
            printed = [formula_text(side.strip()) for side in sides]
        else:
            return _substitute(span)
    out = printed[0]
    for op, side in zip(ops, printed[1:]):
        out += f" {_RELATIONS[op]} {side}"
    return out


def _matching(text: str, start: int) -> int:
    """Index of the bracket closing the one at ``text[start]`` (len(text) if none)."""
    depth = 0
    for index in range(start, len(text)):
        depth += text[index] in "([{⟨"
        depth -= text[index] in ")]}⟩"
        if depth == 0:
            return index
    return len(text)


def _arguments(text: str) -> list[str]:
    """``a, f(b, c), d`` -> [a, f(b, c), d] (commas at depth 0)."""
    out, depth, start = [], 0, 0
    for index, ch in enumerate(text):
        depth += ch in "([{⟨"
        depth -= ch in ")]}⟩"
        if ch == "," and depth == 0:
            out.append(text[start:index])
            start = index + 1
    return [a.strip() for a in out + [text[start:]]]


def _call(name: str, inside: str) -> str:
    """A call SymPy could not read, in Unicode: ``Ne(a, b)`` -> ``a ≠ b``, ``sqrt(x)`` -> ``√(x)``."""
    args = _arguments(inside)
    shown = [formula_text(a) for a in args]
    relation = {"Eq": "=", "Ne": "≠", "Lt": "<", "Le": "≤", "Gt": ">", "Ge": "≥"}
    if name in relation and len(shown) == 2:
        return f"{shown[0]} {relation[name]} {shown[1]}"
    if name == "sqrt":
        return "√(" + ", ".join(shown) + ")"
    if name in ("abs", "Abs"):
        return "|" + ", ".join(shown) + "|"
    if name == "inner":
        return "⟨" + ", ".join(shown) + "⟩"
    if name == "cross":
        return "(" + " × ".join(shown) + ")"
    if name in ("pm", "mp"):
        return ("±" if name == "pm" else "∓") + "(" + ", ".join(shown) + ")"
    if name == "Derivative" and len(shown) >= 2:
        return "∂(" + shown[0] + ")/" + "".join("∂" + v for v in shown[1:])
    if name == "conjugate":
        return "conj(" + ", ".join(shown) + ")"
    renamed = {"re": "Re", "im": "Im", "Max": "max", "Min": "min", "Sum": "Σ", "hyper": "F", "Gamma": "Γ",
               "Matrix": "", "Tuple": "", "Rational": "", "Integer": "", "Float": "", "Symbol": "", "oo": "∞"}
    return renamed.get(name, symbol_text(name)) + "(" + ", ".join(shown) + ")"


def _substitute(text: str) -> str:
    """Program text SymPy cannot read, token by token: calls as in :func:`_call`, names by :func:`symbol_text`,
    ``**`` as a superscript (or ``^``), ``*`` as ``·``, ``<=``, ``!=``, ``->``, ``+-`` as ``≤``, ``≠``, ``→``, ``±``."""
    out, index = [], 0
    tokens = {"<=": "≤", ">=": "≥", "!=": "≠", "==": "=", "->": "→", "+-": "±", "-+": "∓", "*": "·", "$": ""}
    while index < len(text):
        match = _TOKEN.match(text, index)
        token, index = match.group(), match.end()
        if re.fullmatch(r"[A-Za-z_]\w*", token):
            if index < len(text) and text[index] == "(":
                close = _matching(text, index)
                out.append(_call(token, text[index + 1:close]))
                index = close + 1
            else:
                out.append(symbol_text(token))
        elif re.fullmatch(r"\d+(?:\.\d+)?[eE][-+]?\d+", token):
            out.append(_float_unicode(sp.Float(token)))
        elif token in ("**", "^"):
            after = _TOKEN.match(text, index)
            if after and after.group() == "(":
                close = _matching(text, index)
                exponent, index = formula_text(text[index + 1:close]), close + 1
            elif after and after.group() == "-" and re.match(r"\d+", text[after.end():]):
                digits = re.match(r"\d+", text[after.end():]).group()
                exponent, index = "-" + digits, after.end() + len(digits)
            elif after:
                exponent, index = symbol_text(after.group()), after.end()
            else:
                exponent = ""
            small = superscript(exponent)
            out.append(small if small is not None else "^" + (exponent if len(exponent) == 1 else f"({exponent})"))
        elif token in "([" and _matching(text, index - 1) < len(text):
            close = _matching(text, index - 1)
            out.append(token + ", ".join(formula_text(a) for a in _arguments(text[index:close])) + text[close])
            index = close + 1
        else:
            out.append(tokens.get(token, token))
    return "".join(out)


# -- prose and formula spans ------------------------------------------------------------------------------

_ANGLE = re.compile(r"<(?=[^\s=])([^<>]*?)(?<=[^\s=-])>")   # <a, b> written by hand; SymPy spaces its < and >
_OPERATORS = {"+", "-", "=", "!=", "<=", ">=", "<", ">", "==", "->", "+-", "*", "/", "±", "→", "≤", "≥", "≠"}
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
_CALL = re.compile(r"[-+]?[A-Za-z_]\w*\(")
_TRAIL = re.compile(r"[,;:.]+$")
_PROSE_OPERATORS = {"->": "→", "<=": "≤", ">=": "≥", "!=": "≠", "+-": "±", "==": "="}


def _chunks(text: str) -> list[tuple[str, str]]:
    """``(chunk, whitespace after)``: split at whitespace outside brackets."""
    out, depth, start, index = [], 0, 0, 0
    while index < len(text):
        ch = text[index]
        if ch.isspace() and depth == 0:
            end = index
            while index < len(text) and text[index].isspace():
                index += 1
            out.append((text[start:end], text[end:index]))
            start = index
            continue
        depth += ch in "([{⟨"
        depth -= ch in ")]}⟩" and depth > 0
        index += 1
    if start < len(text):
        out.append((text[start:], ""))
    return [(c, s) for c, s in out if c] or [("", text)]


def _is_group(core: str) -> bool:
    return core[:1] in "([{⟨" and _matching(core, 0) == len(core) - 1


def _mathy(core: str) -> bool:
    if not core or core in _OPERATORS or _is_group(core):
        return False
    if _NUMBER.fullmatch(core) or _CALL.match(core) or re.search(r"[*^=<>/]", core):
        return True
    name = core.lstrip("+-")
    return bool(re.fullmatch(r"[A-Za-z_]\w*", name)) and is_symbol_name(name)


def _group_items_alternate(core: str) -> bool:
    """A bracket group that can be an operand: its words are separated by operators (``(u - i*v)``)."""
    parts = [c for c, _ in _chunks(core[1:-1])]
    return all((a in _OPERATORS) != (b in _OPERATORS) for a, b in zip(parts, parts[1:]))


@functools.lru_cache(maxsize=8192)
def segments(text: str) -> tuple:
    """``(("prose", ...), ("math", ...), ...)``: the formula spans of a plain-text claim or note and the prose
    between them, whitespace kept (the prose as written but for ``->``, ``<=``, ``+-`` and primed symbols
    ``gamma'`` in Unicode; a hand-written ``<a, b>`` is read as ``⟨a, b⟩``)."""
    out = []
    chunks = _chunks(_ANGLE.sub(r"⟨\1⟩", text))
    index = 0

    def core_of(chunk: str) -> str:
        return chunk if _NUMBER.fullmatch(chunk) else _TRAIL.sub("", chunk)

    def operand(k: int) -> bool:   # chunk k can stand next to an operator in a formula
        if k >= len(chunks):
            return False
        core = core_of(chunks[k][0])
        if core in _OPERATORS:
            return False
        if _is_group(core):
            return _group_items_alternate(core)
        return _mathy(core) or bool(re.fullmatch(r"[-+]?[A-Za-z_]\w*", core))

    def joins(k: int) -> bool:   # chunk k, an operator, an operand: one formula goes on
        return (core_of(chunks[k][0]) == chunks[k][0] and k + 2 < len(chunks) and chunks[k + 1][0] in _OPERATORS
                and operand(k + 2))

    while index < len(chunks):
        chunk, space = chunks[index]
        core = core_of(chunk)
        if not (_mathy(core) or (operand(index) and joins(index))):
            if _is_group(core):
                out += [("prose", core[0]), *segments(core[1:-1]), ("prose", core[-1] + chunk[len(core):] + space)]
            else:
                primed = re.fullmatch(r"([A-Za-z_]\w*)('+)([,;:.]*)", chunk)   # gamma' = ...
                if primed and is_symbol_name(primed.group(1)):
                    chunk = symbol_text(primed.group(1)) + primed.group(2) + primed.group(3)
                out.append(("prose", _PROSE_OPERATORS.get(chunk, chunk) + space))
            index += 1
            continue
        last = index
        while joins(last):
            last += 2
        formula = "".join(c + s for c, s in chunks[index:last]) + chunks[last][0]
        trail = len(chunks[last][0]) - len(core_of(chunks[last][0]))
        out.append(("math", formula[:len(formula) - trail]))
        out.append(("prose", formula[len(formula) - trail:] + chunks[last][1]))
        index = last + 1
    merged = []
    for kind, piece in out:
        if merged and kind == "prose" and merged[-1][0] == "prose":
            merged[-1] = ("prose", merged[-1][1] + piece)
        elif piece or kind == "math":
            merged.append((kind, piece))
    return tuple(merged)


@functools.lru_cache(maxsize=8192)
def render(text, keep_together: bool = False) -> str:
    """A claim, method or note with every formula in Unicode (:func:`formula_text`), the prose as written.
    ``keep_together``: the spaces :func:`wrap` must not break at are no-break spaces (a formula of up to
    :data:`UNBROKEN` characters, inside brackets in a longer one)."""
    return "".join((_unbroken(formula_text(piece)) if keep_together else formula_text(piece)) if kind == "math"
                   else piece for kind, piece in segments(str(text)))


UNBROKEN = 30
_NO_BREAK = "\u00a0"


def _unbroken(formula: str) -> str:
    if len(formula) <= UNBROKEN:
        return formula.replace(" ", _NO_BREAK)
    out, depth = [], 0
    for ch in formula:
        depth += ch in "([{⟨"
        depth -= ch in ")]}⟩"
        out.append(_NO_BREAK if ch == " " and depth > 0 else ch)
    return "".join(out)


_PROGRAM = re.compile(
    r"\*|<=|>=|!=|==|->|\$|\\[A-Za-z]+|\b(?:oo|zoo)\b"
    r"|\b(?:Derivative|Integral|Ne|Eq|Lt|Le|Gt|Ge|sqrt|Abs|abs|conjugate|Rational|Integer|Float|Symbol|Function|"
    r"Matrix|Tuple|Sum|Max|Min|pm|mp|inner|cross|RisingFactorial|hyper|re|im|Piecewise|Mul|Add|Pow)\(")


def program_text(line: str) -> list[str]:
    """The program tokens left in ``line`` (``**``, ``*``, ``Derivative(``, ``Ne(``, ``sqrt(``, ``oo``, ``<=``,
    ``->``, a TeX command, ...): empty for a line a reader can read."""
    return [m.group() for m in _PROGRAM.finditer(line)]


# -- meaning ---------------------------------------------------------------------------------------------

class _Derivative(sp.Function):
    """A derivative kept as a name: ``simplify`` would take ``Derivative(p, z)`` of a symbol ``p`` for 0 (the
    claims' symbols depend on their variables without saying so)."""


def _exact(expr):
    """Floats as the decimals they print (``1.5e-14`` and ``1.5/10**14`` are one number); derivatives inert."""
    floats = {f: sp.Rational(str(f)) for f in expr.atoms(sp.Float)}
    expr = expr.xreplace(floats) if floats else expr
    if expr.has(sp.Derivative):
        expr = expr.replace(lambda e: isinstance(e, sp.Derivative), lambda e: _Derivative(*e.args))
    return expr


@functools.lru_cache(maxsize=8192)
def _formula_meaning(span: str):
    """``("math", relation operators, sides as SymPy evaluates them)``; for a span SymPy cannot read
    (``Q(x)[c]/(c**2 - 1)``), ``("text", pieces)``: its tokens without spaces, each bracket's arguments read in turn."""
    sides, ops = _split_relations(span)
    try:
        values = [_exact(_parse_side(s, True)) for s in sides]
        if len(values) == 1 and isinstance(values[0], sp.core.relational.Relational):   # Ne(I13, 0) is I13 != 0
            relation = values[0]
            ops, values = [relation.rel_op], [relation.lhs, relation.rhs]
        return ("math", tuple("=" if op == "==" else op for op in ops), tuple(values))
    except Exception:   # SymPy's parser raises whatever its generated code raises
        pass
    pieces, index = [], 0
    while index < len(span):
        token = _TOKEN.match(span, index).group()
        index += len(token)
        if token in "([" and _matching(span, index - 1) < len(span):
            close = _matching(span, index - 1)
            pieces.append((token, tuple(_formula_meaning(a) for a in _arguments(span[index:close]))))
            index = close + 1
        elif not token.isspace():
            pieces.append(token)
    return ("text", tuple(pieces))


@functools.lru_cache(maxsize=8192)
def meaning(text: str) -> tuple:
    """(the prose with a mark for each formula, whitespace normalised; the formulas' meanings).  Formulas with
    only spaces between them are read as one (``1 + 2 sigma1`` written by hand is ``1 + 2*sigma1``)."""
    prose, spans = [], []
    pieces = list(segments(text))
    for index, (kind, piece) in enumerate(pieces):
        if kind == "math":
            if spans and prose[-1].isspace() and pieces[index - 2][0] == "math":
                spans[-1] += prose.pop() + piece
                continue
            prose.append("\0")
            spans.append(piece)
        else:
            prose.append(piece)
    return " ".join("".join(prose).split()), tuple(_formula_meaning(span) for span in spans)


def _equal(a, b) -> bool:
    if a == b:
        return True
    if isinstance(a, sp.Number) and isinstance(b, sp.Number):
        return False
    if isinstance(a, sp.Tuple) and isinstance(b, sp.Tuple):
        return len(a) == len(b) and all(_equal(x, y) for x, y in zip(a.args, b.args))
    if not (isinstance(a, sp.Expr) and isinstance(b, sp.Expr)):
        return False
    try:
        difference = a - b
        if sp.expand(difference) == 0:
            return True
        return sp.count_ops(a) + sp.count_ops(b) <= SIMPLIFY_OPS and sp.simplify(difference) == 0
    except Exception:   # an operation SymPy cannot carry out on the two: not shown equal
        return False


@functools.lru_cache(maxsize=8192)
def _formulas_equal(a, b) -> bool:
    if a == b:
        return True
    if a[0] != b[0] or len(a[-1]) != len(b[-1]):
        return False
    if a[0] == "math":
        return a[1] == b[1] and all(_equal(x, y) for x, y in zip(a[2], b[2]))
    for x, y in zip(a[1], b[1]):
        if isinstance(x, str) or isinstance(y, str):
            if x != y:
                return False
        elif x[0] != y[0] or len(x[1]) != len(y[1]) or not all(_formulas_equal(u, v) for u, v in zip(x[1], y[1])):
            return False
    return True


def same_meaning(old: str, new: str) -> bool:
    """The same words and, formula by formula, the same mathematics (SymPy's evaluation, then simplify)."""
    if old == new:
        return True
    (p, f), (q, g) = meaning(old), meaning(new)
    return p == q and len(f) == len(g) and all(_formulas_equal(x, y) for x, y in zip(f, g))


# -- layout ----------------------------------------------------------------------------------------------

def changed_words(old: str, new: str, regions: int = 4) -> str | None:
    """The words that differ, ``«20 seeded bodies» → «4 seeded bodies»; «10⁻⁹⁰» → «10⁻²⁰»``, or None when more
    than ``regions`` places or more than half of the words differ (then the two texts say it better)."""
    a, b = old.split(), new.split()
    matcher = difflib.SequenceMatcher(None, a, b, autojunk=False)
    edits = [op for op in matcher.get_opcodes() if op[0] != "equal"]
    if not edits or len(edits) > regions or sum(max(i2 - i1, j2 - j1) for _, i1, i2, j1, j2 in edits) * 2 > max(
            len(a), len(b)):
        return None
    return "; ".join(f"«{' '.join(a[i1:i2])}» → «{' '.join(b[j1:j2])}»" if i1 < i2 and j1 < j2 else
                     (f"«{' '.join(b[j1:j2])}» added" if j1 < j2 else f"«{' '.join(a[i1:i2])}» removed")
                     for _, i1, i2, j1, j2 in edits)


def wrap(text: str, indent: int = 2, hanging: int = 4) -> list[str]:
    """``text`` filled to :data:`WIDTH` columns, its first line indented by ``indent``, the others by
    ``indent + hanging``; no line breaks at a no-break space (:func:`render` with ``keep_together``)."""
    lines = textwrap.wrap(text, width=WIDTH, initial_indent=" " * indent, subsequent_indent=" " * (indent + hanging),
                          break_on_hyphens=False, break_long_words=True) or [" " * indent]
    return [line.replace(_NO_BREAK, " ") for line in lines]   # textwrap breaks at ASCII whitespace only

