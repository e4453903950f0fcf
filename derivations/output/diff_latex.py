"""Unicode for the change list of ``build_formulas.py --diff``: characters, and the project's hand-written LaTeX.

The errata's printed and derived forms and the formula titles of ``formulas_body.tex`` are LaTeX written by hand
(``\\frac{d}{dt}(\\mathbb I\\omega)``, ``$s_1,\\dots,s_4$``, ``Painlev\\'e``); :func:`latex_text` reads them into
the Unicode :mod:`derivations.output.diff_text` prints SymPy's formulas in (``d/dt(𝕀ω)``, ``s₁,…,s₄``,
``Painlevé``): Greek letters, sub- and superscripts (:func:`subscript`, :func:`superscript`, where Unicode has
the characters), fractions as ``a/(b + c)``, matrices as ``[a, b; c, d]``, accents as combining characters; a
command it does not know loses its backslash, so that no TeX survives.
"""
from __future__ import annotations

import functools
import re
import unicodedata

# -- characters --------------------------------------------------------------------------------------

GREEK = {
    "alpha": "α", "beta": "β", "gamma": "γ", "delta": "δ", "epsilon": "ε", "varepsilon": "ε", "zeta": "ζ",
    "eta": "η", "theta": "θ", "vartheta": "ϑ", "iota": "ι", "kappa": "κ", "lambda": "λ", "mu": "μ", "nu": "ν",
    "xi": "ξ", "pi": "π", "varpi": "ϖ", "rho": "ρ", "varrho": "ϱ", "sigma": "σ", "varsigma": "ς", "tau": "τ",
    "upsilon": "υ", "phi": "φ", "varphi": "φ", "chi": "χ", "psi": "ψ", "omega": "ω",
    "Gamma": "Γ", "Delta": "Δ", "Theta": "Θ", "Lambda": "Λ", "Xi": "Ξ", "Pi": "Π", "Sigma": "Σ",
    "Upsilon": "Υ", "Phi": "Φ", "Psi": "Ψ", "Omega": "Ω",
}
_SUP = dict(zip("0123456789+-=()", "⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁼⁽⁾"))
_SUP.update(zip("abcdefghijklmnoprstuvwxyz", "ᵃᵇᶜᵈᵉᶠᵍʰⁱʲᵏˡᵐⁿᵒᵖʳˢᵗᵘᵛʷˣʸᶻ"))
_SUP.update(zip("ABDEGHIJKLMNOPRTUVW", "ᴬᴮᴰᴱᴳᴴᴵᴶᴷᴸᴹᴺᴼᴾᴿᵀᵁⱽᵂ"))
_SUP.update(zip("βγδθφχ", "ᵝᵞᵟᶿᵠᵡ"))
_SUB = dict(zip("0123456789+-=()", "₀₁₂₃₄₅₆₇₈₉₊₋₌₍₎"))
_SUB.update(zip("aehijklmnoprstuvx", "ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ"))
_SUB.update(zip("βγρφχ", "ᵦᵧᵨᵩᵪ"))


def superscript(text: str, longest: int = 4) -> str | None:
    """``text`` in superscript characters (at most ``longest`` of them), or None if one has none."""
    if not text or len(text) > longest or any(ch not in _SUP for ch in text):
        return None
    return "".join(_SUP[ch] for ch in text)


def subscript(text: str, longest: int = 4) -> str | None:
    if not text or len(text) > longest or any(ch not in _SUB for ch in text):
        return None
    return "".join(_SUB[ch] for ch in text)


_LATEX_SYMBOLS = {
    "to": "→", "pm": "±", "mp": "∓", "infty": "∞", "partial": "∂", "sum": "Σ", "prod": "Π", "cdots": "⋯",
    "dots": "…", "ldots": "…", "leftrightarrow": "↔", "Leftrightarrow": "⇔", "iff": "⇔", "Rightarrow": "⇒",
    "implies": "⇒", "rightarrow": "→", "mapsto": "↦", "in": "∈", "langle": "⟨", "rangle": "⟩", "times": "×",
    "cdot": "·", "le": "≤", "leq": "≤", "ge": "≥", "geq": "≥", "ne": "≠", "neq": "≠", "approx": "≈", "sim": "∼",
    "equiv": "≡", "circ": "∘", "ell": "ℓ", "nabla": "∇", "forall": "∀", "exists": "∃", "mid": "|", "vert": "|",
    "setminus": "∖", "subset": "⊂", "cap": "∩", "cup": "∪", "emptyset": "∅", "neg": "¬", "wedge": "∧",
    "vee": "∨", "perp": "⊥", "parallel": "∥", "dagger": "†", "star": "⋆", "ast": "∗", "hbar": "ℏ", "Re": "ℜ",
    "Im": "ℑ", "lbrace": "{", "rbrace": "}", "prime": "′", "quad": " ", "qquad": " ", "colon": ":",
    "lvert": "|", "rvert": "|", "Vert": "‖",
}
_LATEX_DROP = {"left", "right", "big", "Big", "bigg", "Bigg", "bigl", "bigr", "Bigl", "Bigr", "biggl", "biggr",
               "displaystyle", "textstyle", "limits", "nolimits", "!"}
_LATEX_TEXT = {"text", "mathrm", "operatorname", "textrm", "mathit", "mathbf", "mathcal", "mathsf", "textit",
               "textbf", "emph", "boldsymbol", "bm", "mathfrak"}
_LATEX_ACCENTS = {"dot": "\u0307", "ddot": "\u0308", "bar": "\u0304", "overline": "\u0305", "hat": "\u0302",
                  "widehat": "\u0302", "tilde": "\u0303", "widetilde": "\u0303", "vec": "\u20d7",
                  "'": "\u0301", "`": "\u0300", '"': "\u0308", "^": "\u0302", "~": "\u0303"}
_DOUBLE_STRUCK = dict(zip("ICRQZN", "𝕀ℂℝℚℤℕ"))
_LATEX_TOKEN = re.compile(r"\\[A-Za-z]+\*?|\\.|.", re.S)


_SCRIPTS = "".join(sorted(set(_SUP.values()) | set(_SUB.values())))
_UNIT = re.compile(rf"[d∂]?(?:\d+(?:\.\d+)?|[^\W\d_][\u0300-\u036f]*)[{_SCRIPTS}]*")


def _atomic(text: str) -> bool:
    """One unit of a hand-written formula: ``x``, ``I₁₁``, ``ω̇``, ``12``, ``dt``, a bracket, a call ``f(x)``."""
    text = text.strip()
    if len(text) <= 1 or _UNIT.fullmatch(text):
        return True
    if text[0] in "([⟨|" and _closing(text) == len(text) - 1:
        return True
    call = re.match(r"[A-Za-z]+(?=\()", text)
    return bool(call) and _closing(text, call.end()) == len(text) - 1


def _closing(text: str, start: int = 0) -> int:
    """Index of the bracket (or bar) closing the one at ``text[start]``."""
    if text[start] == "|":
        end = text.find("|", start + 1)
        return end if end > 0 else len(text)
    pairs, depth = {"(": ")", "[": "]", "⟨": "⟩"}, 0
    opener = text[start]
    for index in range(start, len(text)):
        depth += text[index] == opener
        depth -= text[index] == pairs[opener]
        if depth == 0:
            return index
    return len(text)


class _Latex:
    """A small reader of the LaTeX the project writes by hand (errata forms, titles), into Unicode."""

    def __init__(self, tex: str):
        self.tokens = _LATEX_TOKEN.findall(tex)
        self.at = 0

    def next(self):
        token = self.tokens[self.at] if self.at < len(self.tokens) else None
        self.at += 1
        return token

    def argument(self) -> str:
        while self.at < len(self.tokens) and self.tokens[self.at].isspace():
            self.at += 1
        token = self.next()
        if token is None:
            return ""
        return self.token(token, [])

    def sequence(self, until: str | None = None) -> str:
        out = []
        while True:
            token = self.next()
            if token is None or token == until:
                return "".join(out)
            if until is None and token == "}":
                continue
            out.append(self.token(token, out))

    def script(self, table) -> str:
        body = self.argument()
        small = (superscript if table is _SUP else subscript)(body.replace(" ", ""), 8)
        if small is not None:
            return small
        mark = "^" if table is _SUP else "_"
        return mark + (body if len(body) == 1 else "(" + body + ")")

    def token(self, token: str, out: list) -> str:
        if token == "{":
            return self.sequence("}")
        if token == "^":
            return self.script(_SUP)
        if token == "_":
            return self.script(_SUB)
        if token in ("$", "&"):
            return "" if token == "$" else ", "
        if token == "~":
            return " "
        if token == "*":
            return "∗"
        if token.startswith("\\"):
            return self.command(token[1:])
        return token

    def environment(self, name: str) -> str:
        rows, cells, current = [], [], []
        while True:
            token = self.next()
            if token is None:
                break
            if token == "\\end":
                self.argument()
                break
            if token == "&":
                cells.append("".join(current).strip())
                current = []
            elif token == "\\\\":
                rows.append(cells + ["".join(current).strip()])
                cells, current = [], []
            else:
                current.append(self.token(token, current))
        if current or cells:
            rows.append(cells + ["".join(current).strip()])
        body = "; ".join(", ".join(r) for r in rows if any(r))
        return {"pmatrix": f"({body})", "cases": "{ " + body + " }"}.get(name, f"[{body}]")

    def command(self, name: str) -> str:
        name = name.rstrip("*")
        if name in ("frac", "tfrac", "dfrac"):
            top, bottom = self.argument(), self.argument()
            return (top if _atomic(top) else f"({top})") + "/" + (bottom if _atomic(bottom) else f"({bottom})")
        if name == "sqrt":
            if self.at < len(self.tokens) and self.tokens[self.at] == "[":
                self.at += 1
                while self.next() not in ("]", None):
                    pass
            body = self.argument()
            return "√" + (body if _atomic(body) else f"({body})")
        if name == "mathbb":
            body = self.argument()
            return "".join(_DOUBLE_STRUCK.get(ch, ch) for ch in body)
        if name in _LATEX_TEXT:
            return self.argument()
        if name in _LATEX_ACCENTS:
            body = self.argument()
            return body + _LATEX_ACCENTS[name] if len(body) == 1 else f"({body}){_LATEX_ACCENTS[name]}"
        if name == "begin":
            return self.environment(self.argument())
        if name == "end":
            self.argument()
            return ""
        if name in _LATEX_DROP:
            following = self.tokens[self.at] if self.at < len(self.tokens) else ""
            if name in ("left", "right") and following == ".":
                self.at += 1
            return ""
        if name in (" ", ",", ";", ":", ">"):
            return " "
        if name == "\\":
            return "; "
        if name in GREEK:
            return GREEK[name]
        if name in _LATEX_SYMBOLS:
            return _LATEX_SYMBOLS[name]
        if len(name) == 1 and not name.isalpha():
            return name                       # \{ \} \% \& \_ \# \$ \|
        following = self.tokens[self.at] if self.at < len(self.tokens) else ""
        return name + (" " if following[:1].isalnum() or following.startswith("\\") else "")   # \cos t, \det


@functools.lru_cache(maxsize=4096)
def latex_text(tex: str) -> str:
    """Hand-written LaTeX in Unicode: ``\\frac{d}{dt}(\\mathbb I\\omega)`` -> ``d/dt(𝕀ω)``, ``s_1,\\dots,s_4`` ->
    ``s₁,…,s₄``, ``Painlev\\'e`` -> ``Painlevé``."""
    text = unicodedata.normalize("NFC", _Latex(tex).sequence())
    return re.sub(r"[ \t]{2,}", " ", text).strip()
