"""The paper's printed equation, theorem and section numbers, for the labels our formulas cite.

The paper: Yu. N. Fedorov, A. J. Maciejewski, M. Przybylska, "The Poisson equations in the
nonholonomic Suslov problem: integrability, meromorphic and hypergeometric solutions",
arXiv:0902.0079 (2009).  A formula's ``label`` field (:class:`derivations.core.result.DerivedFormula`)
names what it derives in the paper's own LaTeX labels (``eq:o12``, ``c's``, ``gam1``), or in words
(``Theorem 5.4``, ``section 2``, ``Conclusion``); a reader of the paper sees neither, only the printed
numbers.  :data:`PRINTED` maps each such name to what the paper prints, and :func:`printed_numbers`
reads a whole label field.

How the numbers were found (transcribed once from the paper's LaTeX source; nothing here reads it).
The source is ``\\documentclass[11pt]{article}`` with amsmath and amsthm, ``\\numberwithin{equation}
{section}`` and ``\\numberwithin{theorem}{section}``, so:

* equations print as (section.n), the counter reset by every numbered ``\\section`` (``\\section*``
  and ``\\subsection`` do not reset it).  ``equation`` takes one number (its ``split``/``aligned``
  inside included); ``align`` and ``gather`` take one per row of the top level, except the rows
  with ``\\nonumber``/``\\notag``; starred environments, ``\\[...\\]`` and ``$$...$$`` take none.  A label
  gets the number of the row it stands in (``\\label{eq:o12}`` opens the first row of a two-row
  ``gather``: (2.7); ``\\label{c's}`` ends the second: (2.8));
* ``theorem``, ``lemma``, ``proposition``, ``remark`` and ``problem`` share one counter, reset per
  section.  Hence the Problem that opens Section 3 is Problem 3.1 and the meromorphy theorem
  (``\\label{pro:necc}``) prints as **Theorem 3.2**; in Section 5 Proposition 5.1, Lemma 5.2 and
  Proposition 5.3 come before the scattering-angle theorem (``\\label{angle}``): **Theorem 5.4**; the even-p
  Galois group (``\\label{pro:a}``) is **Proposition 5.8**;
* ``conjecture`` has a counter of its own, not numbered within sections: the only one is **Conjecture 1**.

The project's label fields name statements as the paper prints them (``Theorem 3.2``, ``Theorem 5.4``,
``Proposition 5.8``, ``Conjecture 1``).  Revisions before issue 46 counted differently in four places
(``Theorem 3.1``, ``Theorem 5.2``, ``Proposition 5.4``, ``Conjecture 5.2``); those names still map to the
printed ones, so ``--diff`` against an old tree reads its labels.  Checked by hand: (1.2) for ``3.25``,
(2.7)/(2.8) for ``eq:o12``/``c's``, (3.1)/(3.2) for the two rows of the ``align`` of ``eq:necc1``/``eq:necc11``,
(3.6) for ``eq:d``, (5.7) for ``eq:genhip``, (5.25) for ``gam_0`` (an ``align`` whose first row is
``\\nonumber``), (6.1)-(6.3) for ``gam1``-``gam3`` (an ``align`` with an unnumbered second row), Theorem 3.5
and Theorem 6.2.

``eq:kowal`` is no label of the paper: the project's name for the Kovalevskaya exponents ``1 +- Lambda``,
the roots of the characteristic polynomial (3.7) of ``K(d)`` (``Lambda`` itself stands in the unnumbered
display after it); it maps to (3.7).  Labels with no printed number (``derived``: derived here, not in the
paper; ``example p = 1``; ``Kovalevskaya matrix``, the unnumbered display before (3.7)) are **skipped** by
:func:`printed_numbers` and returned by :func:`unnumbered`.  A trailing qualifier in parentheses
(``Theorem 5.4 (p)``, ``ss (text)``, ``Proposition 4.1 (proof, triangle)``) is the project's: the part
is looked up without it.  Labels inside the paper's figures (placed before ``\\caption``, so they
refer to nothing printed) are left out.
"""
from __future__ import annotations

import re

# every \label of the paper's numbered equations, in the paper's order
_EQUATIONS = {
    "Poisson": "(1.1)", "3.25": "(1.2)", "ep3.26": "(1.3)", "eq:ps": "(1.4)",
    "gen12": "(2.1)", "eq:whole": "(2.2)", "eq:whole1": "(2.4)", "eq:liny": "(2.5)", "eq:o12": "(2.7)",
    "c's": "(2.8)", "eq:enlev": "(2.9)",
    "eq:necc1": "(3.1)", "eq:necc11": "(3.2)", "eq:lina": "(3.3)", "eq:necc2": "(3.4)", "eq:d": "(3.6)",
    "eq:neccg1": "(3.8)", "eq:neccg12": "(3.9)", "eq:neccg2": "(3.10)", "eq:at": "(3.11)", "eq:am1": "(3.12)",
    "eq:ro": "(3.13)", "eq:linb": "(3.14)", "eq:lincons": "(3.15)", "eq:cpr": "(3.16)", "eq:am2": "(3.17)",
    "omegas": "(4.1)", "eq:sysfin": "(4.2)", "eq:ccalki": "(4.3)", "ss": "(4.4)",
    "eq:genhipprep": "(5.2)", "a'ss": "(5.3)", "t->z": "(5.4)", "eq:gamma_1": "(5.5)", "eq:genhip": "(5.7)",
    "eq:3F2": "(5.8)", "eq:param": "(5.9)", "eq:nFn-1": "(5.10)", "eq:ghyp": "(5.11)", "gen_sol_u": "(5.12)",
    "eq:sol3F2": "(5.13)", "pol_sol": "(5.14)", "F_23_splitted": "(5.15)", "abc": "(5.16)",
    "alpha,beta": "(5.17)", "splits": "(5.18)", "eq:fferd": "(5.19)", "eq:expsol": "(5.20)",
    "eq:expsol1": "(5.21)", "poly_F": "(5.22)", "poly_F2": "(5.23)", "F_23_pol": "(5.24)", "gam_0": "(5.25)",
    "eq:ryba": "(5.27)", "eq:ui": "(5.28)", "eq:gi": "(5.29)", "eq:rig": "(5.30)", "eq:ABC": "(5.31)",
    "eq:r2": "(5.34)", "eq:lin": "(5.35)", "eq:2rzedu": "(5.39)", "eq:rlin": "(5.41)", "eq:Q": "(5.46)",
    "eq:Deltai": "(5.47)", "eq:expono": "(5.48)",
    "gam1": "(6.1)", "gam2": "(6.2)", "gam3": "(6.3)", "asymp": "(6.4)", "eq:gam3": "(6.5)",
    "eq:liniowiec": "(6.6)", "eq:p1": "(6.9)", "eq:p23": "(6.10)", "eq:dp3": "(6.11)", "eq:partial": "(6.12)",
    "eq:ordin": "(6.13)", "p_23": "(6.14)", "eq:syfint": "(6.15)", "eq:chan": "(6.16)",
}

# the \label of numbered statements and sections
_STATEMENTS = {
    "A=1": "Remark 2.1", "pro:necc": "Theorem 3.2", "thm:bar": "Theorem 3.4", "angle": "Theorem 5.4",
    "lem:dar": "Lemma 5.5", "prop:1": "Proposition 5.6", "pro:a": "Proposition 5.8", "merom_gam_1": "Theorem 6.1",
    "ssec:spec": "Section 4", "sec:solhyper": "Section 5.1", "mer_sol": "Section 6",
}

# the project's names of four statements before issue 46, and the printed names its labels use now
RENAMED = {"Theorem 3.1": "Theorem 3.2", "Theorem 5.2": "Theorem 5.4", "Proposition 5.4": "Proposition 5.8",
           "Conjecture 5.2": "Conjecture 1"}
_RENAMED = re.compile(r"\b(%s)\b" % "|".join(re.escape(k) for k in RENAMED))


def current_names(text: str) -> str:
    """``text`` (a label field, a claim, a note of an older tree) with the statements' old names replaced by the
    printed ones (``Theorem 5.2`` -> ``Theorem 5.4``): what ``--diff`` compares an old tree's texts in.

    >>> current_names("Theorem 5.2 (p), eq:o12"), current_names("as in Theorem 5.4")
    ('Theorem 5.4 (p), eq:o12', 'as in Theorem 5.4')
    """
    return _RENAMED.sub(lambda m: RENAMED[m.group(1)], text)


# the statements in the words the project's label fields use, and the printed statement each means
_NAMES = {
    "Remark 2.1": "Remark 2.1", "Problem 3.1": "Problem 3.1",
    "Theorem 3.1": "Theorem 3.2", "Theorem 3.2": "Theorem 3.2",   # the meromorphy theorem (pro:necc)
    "Remark 3.3": "Remark 3.3", "Theorem 3.4": "Theorem 3.4", "Theorem 3.5": "Theorem 3.5",
    "Proposition 4.1": "Proposition 4.1",
    "Proposition 5.1": "Proposition 5.1", "Prop. 5.1": "Proposition 5.1", "Lemma 5.2": "Lemma 5.2",
    "Proposition 5.3": "Proposition 5.3",
    "Theorem 5.2": "Theorem 5.4", "Theorem 5.4": "Theorem 5.4",   # the scattering angle (angle)
    "Lemma 5.5": "Lemma 5.5", "Proposition 5.6": "Proposition 5.6", "Proposition 5.7": "Proposition 5.7",
    "Proposition 5.4": "Proposition 5.8", "Proposition 5.8": "Proposition 5.8",   # even p: SL(2, C) (pro:a)
    "Conjecture 5.2": "Conjecture 1", "Conjecture 1": "Conjecture 1",   # s1, s2 logarithmic iff p even
    "Theorem 5.9": "Theorem 5.9", "Theorem 6.1": "Theorem 6.1", "Theorem 6.2": "Theorem 6.2",
    "Conclusion": "Section 6.4",   # \subsection{Conclusion}, the fourth of Section 6
    "eq:kowal": "(3.7)",           # the project's label: the characteristic polynomial of K(d), roots 1 +- Lambda
}

# sections and subsections as printed ("section 2" in a label field -> "Section 2")
_SECTIONS = ("1", "2", "3", "3.1", "3.2", "4", "5", "5.1", "5.2", "6", "6.1", "6.2", "6.3", "6.4")

PRINTED: dict[str, str] = {**_EQUATIONS, **_STATEMENTS, **_NAMES,
                           **{f"section {s}": f"Section {s}" for s in _SECTIONS},
                           **{f"Section {s}": f"Section {s}" for s in _SECTIONS}}

_QUALIFIER = re.compile(r"\s*\([^()]*\)\s*$")


def _parts(label_field: str) -> list[str]:
    """The labels of a label field: split at the commas outside parentheses, blanks stripped, empty parts dropped.

    A paper label with a comma of its own (``alpha,beta``) is kept whole, and so is a qualifier with commas
    (``Proposition 4.1 (proof, triangle)``).
    """
    field = label_field.strip()
    if field in PRINTED:
        return [field]
    parts, depth, start = [], 0, 0
    for k, ch in enumerate(field + ","):
        depth += (ch == "(") - (ch == ")")
        if ch == "," and depth <= 0:
            parts.append(field[start:k].strip())
            start = k + 1
    return [part for part in parts if part]


def _lookup(part: str) -> str | None:
    if part in PRINTED:
        return PRINTED[part]
    base = _QUALIFIER.sub("", part)
    return PRINTED.get(base)


def printed_numbers(label_field: str) -> list[str]:
    """The paper's printed numbers of the labels in ``label_field``, in order, without repeats.

    Parts with no printed number are skipped (:func:`unnumbered` returns them).

    >>> printed_numbers("eq:o12, c's")
    ['(2.7)', '(2.8)']
    >>> printed_numbers("Theorem 5.2 (p)"), printed_numbers("derived"), printed_numbers("section 2")
    (['Theorem 5.4'], [], ['Section 2'])
    """
    out: list[str] = []
    for part in _parts(label_field):
        number = _lookup(part)
        if number is not None and number not in out:
            out.append(number)
    return out


def printed_parts(label_field: str) -> list[tuple[str, str | None]]:
    """Each part of ``label_field`` with what the paper prints for it (its qualifier kept), or None.

    >>> printed_parts("Theorem 5.2 (p), derived")
    [('Theorem 5.2 (p)', 'Theorem 5.4 (p)'), ('derived', None)]
    """
    out = []
    for part in _parts(label_field):
        number = _lookup(part)
        qualifier = _QUALIFIER.search(part) if part not in PRINTED else None
        out.append((part, None if number is None else number + (" " + qualifier.group(0).strip() if qualifier else "")))
    return out


def unnumbered(label_field: str) -> list[str]:
    """The parts of ``label_field`` that the paper prints no number for (``derived``, ``example p = 1``).

    >>> unnumbered("example p = 1, eq:d"), unnumbered("derived")
    (['example p = 1'], ['derived'])
    """
    return [part for part in _parts(label_field) if _lookup(part) is None]


# a letter standing alone in a qualifier, ``(p)``, or in an equation, ``p = 1``: the paper's variable, not a word
_VARIABLE = re.compile(r"(?<=\()([a-z])(?=\))|\b([a-z] = -?\d+(?:/\d+)?)\b")


def label_statement(text: str) -> str:
    """A printed label (a number with its qualifier, or a label the paper prints no number for) as statement
    text, its variables and equations between dollar signs (:func:`derivations.core.statement.say`), so that a
    document typesets them as mathematics.

    >>> label_statement("Theorem 5.4 (p)"), label_statement("example p = 1"), label_statement("p = 1 integral")
    ('Theorem 5.4 ($p$)', 'example $p = 1$', '$p = 1$ integral')
    >>> label_statement("Proposition 4.1 (proof, triangle)"), label_statement("derived here")
    ('Proposition 4.1 (proof, triangle)', 'derived here')
    """
    return _VARIABLE.sub(lambda m: "$" + m.group(0) + "$", text)
