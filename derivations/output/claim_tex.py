"""The build's ASCII claims and notes typeset as text with mathematics (issue 26: "LaTeX claims
typeset as mathematics, 0 ASCII operators in the documents' claims and errata").

Certificates state their claims in the ASCII the build writes (``certificates.json`` keeps it, and
tests match it); the LaTeX documents show the same claim with its formulas as mathematics:
``(I11 I22)^2`` becomes ``$(I_{11} I_{22})^{2}$``, ``-+`` a ``\\mp``, ``R^T e`` an ``R^{T} e``,
``d**2`` a ``d^{2}``, ``gamma^(1) -> (-1,0,0) as t -> -oo`` a ``\\gamma^{(1)}\\to(-1,0,0)`` then
prose then ``t\\to-\\infty``.

Method: the text is cut into tokens (words, identifiers, numbers, operators, brackets, labels
such as ``eq:whole`` and code names such as ``gamma_basis_mp``); a token is *prose* when it is
an English word (letters only, not a symbol of the paper: not a single letter, not a Greek name,
not a function name), otherwise mathematics.  Maximal runs of mathematical tokens (with the
spaces between them) become one ``$...$``; prose, labels and code names stay text (escaped; labels
and code in typewriter type).  Inside a run: identifiers get subscripts (``I11`` -> ``I_{11}``,
``rho_i`` -> ``\\rho_{i}``, ``P1~`` -> ``\\tilde P_{1}``), Greek names and functions their
macros, ``^`` takes the following group, number or identifier as its exponent, ``sqrt(...)`` and
``hat(...)`` become ``\\sqrt{...}`` and ``\\hat{...}``, ``oo`` is ``\\infty``, a standalone ``x``
between two operands is ``\\times``, and ``->``, ``+-``, ``-+``, ``<=``, ``>=``, ``!=``, ``*`` their
symbols.  Nothing is dropped: every token of the claim has its image (``tests/test_claim_tex.py``
checks that every digit of every claim survives, and that no ASCII operator is left in the text).
"""
from __future__ import annotations

import functools
import re

GREEK = {name: "\\" + name for name in (
    "alpha", "beta", "gamma", "delta", "Delta", "zeta", "eta", "theta", "lambda", "Lambda", "mu", "nu", "xi",
    "pi", "rho", "sigma", "tau", "phi", "varphi", "psi", "omega", "Omega", "chi", "Gamma")}
GREEK["eps"] = "\\varepsilon"
FUNCTIONS = {"sin": "\\sin", "cos": "\\cos", "tan": "\\tan", "sinh": "\\sinh", "cosh": "\\cosh", "tanh": "\\tanh",
             "exp": "\\exp", "log": "\\log", "ln": "\\ln", "det": "\\det", "deg": "\\deg", "lim": "\\lim",
             "min": "\\min", "max": "\\max", "sum": "\\sum", "Re": "\\operatorname{Re}", "Im": "\\operatorname{Im}",
             "sech": "\\operatorname{sech}", "diag": "\\operatorname{diag}", "rank": "\\operatorname{rank}",
             "tr": "\\operatorname{tr}", "atan2": "\\operatorname{atan2}", "arg": "\\arg", "coth": "\\coth",
             "csch": "\\operatorname{csch}"}
SYMBOLS = {".": "\\cdot ", "->": "\\to ", "+-": "\\pm ", "-+": "\\mp ", "<=": "\\le ", ">=": "\\ge ", "!=": "\\ne ", "*": "\\cdot ",
           "**": "^", "<": "<", ">": ">", "|": "|", "=": "=", "+": "+", "-": "-", "/": "/", "'": "'"}
# words of two or three letters that are symbols where the claims use them (``ip`` = i p, ``dk``, ``mw``)
SHORT_SYMBOLS = {"ip", "dk", "dp", "mw", "Id", "SO", "PSL", "oo", "rt", "dt", "Den"}
CODE = re.compile(r"eq:[A-Za-z0-9_.]*[A-Za-z0-9_](?:/[A-Za-z]+)?(?:'s)?|ep\d+\.\d+"
                  r"|[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)+(?:\(\))?(?:'s)?|_[a-z][A-Za-z0-9_]+")
TOKEN = re.compile(
    r"(?P<code>" + CODE.pattern + r")"
    r"|(?P<number>\d+(?:\.\d+)?(?:e[-+]?\d+)?(?![A-Za-z_]))"
    r"|(?P<dims>\d+x\d+)"
    r"|(?P<hyper>\dF\d)"
    r"|(?P<hyphenated>[A-Za-z]{2,}(?:-[A-Za-z]{2,})+)"
    r"|(?P<word>[A-Za-z][A-Za-z0-9]*~?(?:'s(?![A-Za-z]))?)"
    r"|(?P<numword>\d+[A-Za-z][A-Za-z0-9]*)"
    r"|(?P<op>\*\*|->|\+-|-\+|<=|>=|!=|[-+*/^=<>|'~]|(?<=[A-Za-z0-9)])\.(?=[A-Za-z(]))"
    r"|(?P<open>[(\[{])|(?P<close>[)\]}])|(?P<punct>[,;:.!?])|(?P<space>\s+)|(?P<other>.)")
# identifiers with a subscript after an underscore (``rho_i``, ``Fhat_k``, ``P_i``), not code names
SUBSCRIPTED = re.compile(r"(?:[A-Za-z]|[A-Z][a-z]*hat|" + "|".join(GREEK) + r")_[A-Za-z0-9]{1,2}~?")
TEXT_ESCAPE = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{",
               "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "<": r"\textless{}",
               ">": r"\textgreater{}", "|": r"\textbar{}"}


def _escape(text: str) -> str:
    return "".join(TEXT_ESCAPE.get(ch, ch) for ch in text)


def _is_math_word(word: str, glued: bool, next_op: bool) -> bool:
    """A word token is mathematics: a symbol of the paper, not English prose.  ``glued``: the word
    touches an operator or bracket (``at+varphi``, ``rt(w)``); ``next_op``: the next token after
    spaces is an operator (``a = p/d``)."""
    core = word.rstrip("~")
    if "-" in core or core.endswith("'s"):
        return False                                   # hyphenated prose, possessives
    letters = re.fullmatch(r"([A-Za-z]+)(\d*)", core)
    if letters is None:
        return False
    name, digits = letters.groups()
    if name in GREEK or name in FUNCTIONS or name in ("sqrt", "hat") or core in SHORT_SYMBOLS:
        return True
    if name.endswith("hat") and len(name) == 4:        # Fhat
        return True
    if len(name) == 1:
        # the article "a" (and "A" opening a sentence) stays prose unless it stands in a formula
        return name not in "aA" or bool(digits) or glued or next_op
    if len(name) <= 3 and glued:
        return True
    return bool(digits) and len(name) <= 2


def _identifier(word: str) -> str:
    """LaTeX of one identifier: subscripts from trailing digits or ``_x``, Greek, hats, tildes."""
    tilde = word.endswith("~")
    word = word.rstrip("~")
    if re.fullmatch(r"d[A-Z][A-Za-z]*\d*", word):       # dF3: the differential of F3
        return "d" + _identifier(word[1:] + ("~" if tilde else ""))
    sub = ""
    match = re.fullmatch(r"([A-Za-z]+?)(\d+)", word)
    if "_" in word:
        word, sub = word.split("_", 1)
    elif match and match.group(1) not in ("ep",):
        word, sub = match.groups()
    if word in GREEK:
        body = GREEK[word]
    elif word in FUNCTIONS:
        body = FUNCTIONS[word]
    elif word == "oo":
        body = "\\infty"
    elif len(word) == 4 and word.endswith("hat"):
        body = "\\hat " + word[0]
    elif len(word) > 1 and word not in SHORT_SYMBOLS:
        body = "\\mathrm{" + word + "}"
    elif word in ("SO", "PSL", "Id", "Den"):
        body = "\\mathrm{" + word + "}"
    else:
        body = word
    if tilde:
        body = "\\tilde " + (body if len(body) == 1 else "{" + body + "}")
    return body + ("_{" + sub + "}" if sub else "")


def _number(text: str) -> str:
    mantissa, _, exponent = text.partition("e")
    if not exponent:
        return text
    exponent = exponent.lstrip("+")
    return ("10" if mantissa == "1" else mantissa + "\\cdot 10") + "^{" + exponent + "}"


def _tokens(text: str) -> list:
    return [(m.lastgroup, m.group()) for m in TOKEN.finditer(text)]


def _exponent_end(tokens: list, i: int) -> int:
    """The index after the exponent that starts at ``tokens[i]`` (a sign, then a bracketed group, a
    number with at most one glued letter such as ``2p``, or one identifier)."""
    if i < len(tokens) and tokens[i][1] in ("+", "-"):
        i += 1
    if i >= len(tokens):
        return i
    kind, text = tokens[i]
    if kind == "open":
        depth = 0
        for j in range(i, len(tokens)):
            depth += tokens[j][0] == "open"
            depth -= tokens[j][0] == "close"
            if depth == 0:
                return j + 1
        return len(tokens)
    if kind == "number" and i + 1 < len(tokens) and tokens[i + 1][0] == "word" and len(tokens[i + 1][1]) == 1:
        return i + 2
    return i + 1


def _math(tokens: list) -> str:
    """LaTeX (without the dollars) of a run of mathematical tokens."""
    out, i = [], 0
    opened = []                      # for each open bracket: the closing string to emit
    while i < len(tokens):
        kind, text = tokens[i]
        following = tokens[i + 1][1] if i + 1 < len(tokens) else ""
        if kind == "space":
            out.append(" ")
        elif kind == "word" and text in ("sqrt", "hat") and following == "(":
            out.append("\\sqrt{" if text == "sqrt" else "\\hat{")
            opened.append("}")
            i += 1
        elif kind == "word":
            out.append(_identifier(text))
        elif kind == "code":
            out.append(_identifier(text) if SUBSCRIPTED.fullmatch(text) else "\\texttt{" + _escape(text) + "}")
        elif kind == "number":
            out.append(_number(text))
        elif kind == "dims":
            a, b = text.split("x")
            out.append(a + "\\times " + b)
        elif kind == "hyper":
            out.append("{}_{" + text[0] + "}F_{" + text[2] + "}")
        elif kind == "numword":
            digits, letters = re.fullmatch(r"(\d+)(.*)", text).groups()
            out.append(digits + _identifier(letters))
        elif kind == "timesop":
            out.append("\\times ")
        elif kind == "op" and text in ("^", "**"):
            end = _exponent_end(tokens, i + 1)
            group = tokens[i + 1:end]
            if group and group[0][1] == "{" and group[-1][1] == "}":
                group = group[1:-1]            # e^{...}: the braces are the exponent's own
            out.append("^{" + _math(group) + "}")
            i = end
            continue
        elif kind == "op" and text == "~":
            out.append("\\sim ")
        elif kind == "op":
            out.append(SYMBOLS[text])
        elif kind == "open" and text == "{":          # a set (exponent groups are taken with the ^)
            out.append("\\{")
            opened.append("\\}")
        elif kind == "open":
            out.append(text)
            opened.append(")" if text == "(" else "]")
        elif kind == "quote":
            out.append("\\text{'}")
        elif kind == "close":
            if text == "}" and (not opened or opened[-1] not in ("}", "\\}")):
                out.append("\\}")
            else:
                out.append(opened.pop() if opened else text)
        elif kind == "punct":
            out.append(text + ("\\allowbreak " if text == "," else ""))
        else:
            out.append(_escape(text))
        i += 1
    # a sqrt( or hat( whose parenthesis closes outside the run: close the LaTeX group here
    out.extend(closing for closing in reversed(opened) if closing == "}")
    return "".join(out)


MATH_OPERAND = ("word", "number", "code", "numword", "dims", "hyper")


def _classify(tokens: list) -> list:
    """(kind, text, role) per token, role one of "prose", "math", "break" (text that ends a formula:
    spaces, ':' ';' '.', quotes) or "glue" (spaces and commas, which a formula may contain)."""
    out = []
    for i, (kind, text) in enumerate(tokens):
        before = tokens[i - 1] if i else ("space", " ")
        after = tokens[i + 1] if i + 1 < len(tokens) else ("space", " ")
        nxt = next((t for t in tokens[i + 1:] if t[0] != "space"), ("space", " "))
        if kind == "op" and text == "'" and before[0] not in ("word", "close", "op", "code") or \
                kind == "op" and text == "'" and before == ("op", "="):
            out.append(("quote", text, "break"))            # a quotation mark, not a prime
            continue
        if kind == "word":
            glued = before[0] == "op" or after[0] == "op" or after == ("open", "(") or (
                text in ("a", "A") and after[0] in ("punct", "close"))   # "(a; b; z)": never the article
            previous = next((t for t in reversed(out) if t[0] != "space"), None)
            if text in ("a", "A") and previous and previous[2] == "math" and (
                    previous[0] in MATH_OPERAND or previous[1] in ")]}"):
                glued = True                               # "w x I^-1 a": the vector a, not the article
            math = _is_math_word(text, glued, nxt[0] == "op" and nxt[1] != "'")
            out.append((kind, text, "math" if math else "prose"))
        elif kind in ("hyphenated", "other"):
            out.append((kind, text, "prose"))
        elif kind == "code":
            out.append((kind, text, "math" if SUBSCRIPTED.fullmatch(text) else "prose"))
        elif kind == "space" or (kind == "punct" and text == ","):
            out.append((kind, text, "glue"))
        elif kind == "punct":
            out.append((kind, text, "break"))
        else:
            out.append((kind, text, "math"))
    # a standalone x between two mathematical operands is the product sign (``-(I11 I22) x printed
    # eq:d``, ``w x I^-1 a``, ``{...} x d``); ``by x and``, ``x = i``, ``(x^2)`` keep the variable
    for i, (kind, text, _) in enumerate(out):
        if kind != "word" or text != "x" or not (0 < i < len(out) - 1) or out[i - 1][0] != "space" \
                or out[i + 1][0] != "space":
            continue
        before = next((t for t in reversed(out[:i]) if t[0] != "space"), None)
        after = next((t for t in out[i + 1:] if t[0] != "space"), None)
        if before and after and (before[2] == "math" and (before[0] in MATH_OPERAND or before[1] in ")]}")) \
                and (after[0] in MATH_OPERAND + ("hyphenated",) or after[1] in "([{"):
            out[i] = ("timesop", text, "math")
    return out


def claim_latex(claim) -> str:
    """The claim (or note) as LaTeX text with its formulas as inline mathematics.

    >>> print(claim_latex("Re Lambda^2 = (I11 I22)^2 x printed eq:neccg12"))
    $\\operatorname{Re} \\Lambda^{2} = (I_{11} I_{22})^{2} \\times$ printed \\texttt{eq:neccg12}
    """
    return _claim_latex(str(claim))


@functools.lru_cache(maxsize=4096)
def _claim_latex(claim: str) -> str:
    """:func:`claim_latex` of a string, once per distinct text (the templates ask about four times per claim)."""
    pieces, run = [], []

    def flush():
        tail = []
        while run and (run[-1][2] == "glue" or run[-1][0] == "open"):
            tail.insert(0, run.pop())
        head = []
        while run and (run[0][2] == "glue" or run[0][0] == "close"):
            head.append(run.pop(0))
        pieces.append(_text(head))
        if run:
            mathematical = any(k not in ("space", "punct", "open", "close") and
                               not (k == "number" and "e" not in t) for k, t, _ in run)
            pieces.append("$" + _math([(k, t) for k, t, _ in run]).strip() + "$" if mathematical else _text(run))
        pieces.append(_text(tail))
        run.clear()

    for kind, text, role in _classify(_tokens(claim)):
        if role in ("prose", "break"):
            flush()
            pieces.append("\\texttt{" + _escape(text) + "}" if kind == "code" else _escape(text))
        elif role == "glue" and not run:
            pieces.append(_escape(text))
        else:
            run.append((kind, text, role))
    flush()
    return "".join(pieces)


def _text(tokens: list) -> str:
    return "".join(_escape(token[1]) for token in tokens)
