"""Differences between two generated trees, as researchers diff a paper (``build_formulas.py --diff OLD``).

OLD is a generated directory or a git revision (its ``generated/`` is read with ``git show``,
nothing is checked out).  The report names what changed, by what a reader recognises:

* **files**: every generated file that differs from OLD's, or exists on one side only (the set
  ``git diff --name-only OLD -- generated/`` lists, apart from the volatile timing files and TeX
  by-products, :data:`VOLATILE`), compared byte for byte;

* **formulas**: the paragraphs of ``formulas_body.tex`` (one per derived formula, keyed by
  section and title): added, removed, changed;
* **tables**: the per-p, errata, monodromy, Galois, basis and integral tables: which changed,
  with the number of rows added and removed;
* **tables**: compared with the certificate keys blanked (``\\certkey{...}`` holds a sequence
  number that shifts when a certificate is inserted elsewhere: a change of keys alone is not a
  change of a table);
* **certificates**: from ``certificates.json``, matched by (derivation, paper label, claim), not
  by key (keys are sequence numbers and shift when a certificate is inserted); the unmatched ones
  of one (derivation, label) are paired first by meaning (the same words and, formula by formula,
  the same mathematics for SymPy: :func:`~derivations.output.diff_text.same_meaning`) -- a claim
  only *reprinted* (``i*pi*(1/2)`` then, ``pi*i/2`` now) is counted, not listed, unless its outcome
  or method changed -- then by claim similarity (``difflib`` ratio >= 0.6, best pairs first) and
  reported as *reworded*, with any change of outcome or method; what is left is added or removed;
* **errata** rows by label: added, removed, changed (status, printed form, derived form, note; a
  note only reprinted is counted with the claims).

The report (:func:`report`) is for a reader: every formula of a claim, method or note in Unicode
(:func:`~derivations.output.diff_text.render`: ``∂p/∂z``, ``I₁₃ ≠ 0``, ``π·i/2``, never ``**`` or
``Derivative(``), the LaTeX of titles and errata forms too, lines wrapped at 100 columns, old and new
side by side with the words that differ (``changed: «20» → «4»``).

Then ``latexdiff --flatten`` marks the changes in the formulas document and in the certificates
document (``--append-textcmd=certkey``, so a changed key is marked too, not hidden inside the
command's argument) and pdflatex compiles both into OUTDIR (default ``build/diff/``, outside the
tracked tree).  Debian: ``apt-get install latexdiff``.
"""
from __future__ import annotations

import difflib
import json
import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

from derivations.core.paper_numbers import current_names
from derivations.output.diff_latex import latex_text
from derivations.output.diff_text import changed_words, meaning, render, same_meaning, wrap

DOCUMENT = "suslov_formulas.tex"
DOCUMENTS = (DOCUMENT, "certificates.tex")   # the PDFs latexdiff marks
REWORDED = 0.6                               # claim similarity above which an unmatched pair is one claim reworded
TABLES = ("errata_table.tex", "per_p_table.tex", "monodromy_tables.tex", "galois_tables.tex", "galois_group_table.tex", "basis_tables.tex",
          "integrals_table.tex")


# written by every build but machine- and run-dependent (timings, float measurements, cache hits): untracked
VOLATILE = ("certificate_costs.json", "certificate_measurements.json", "cache_report.json", "certificate_costs.tex")


class DiffError(RuntimeError):
    """OLD cannot be read, or latexdiff/pdflatex is missing or failed; the message says which."""


@dataclass
class TreeDiff:
    files: dict = field(default_factory=lambda: {"added": [], "removed": [], "changed": []})
    formulas: dict = field(default_factory=lambda: {"added": [], "removed": [], "changed": []})
    tables: list = field(default_factory=list)
    certificates: dict = field(default_factory=lambda: {"added": [], "removed": [], "changed": [], "reworded": []})
    errata: dict = field(default_factory=lambda: {"added": [], "removed": [], "changed": []})
    reprinted: list = field(default_factory=list)   # ("certificate" or "erratum", old, new): same meaning, new print

    def empty(self) -> bool:
        """No formula, table, certificate or erratum changed (files may still differ: renumbered keys, claims
        reprinted without change of meaning)."""
        return not (self.tables or any(self.formulas.values()) or any(self.certificates.values())
                    or any(self.errata.values()))


def materialise(old: str, repository: Path, into: Path) -> Path:
    """The OLD tree as a directory: OLD itself if it is one, else ``git show REV:generated/*`` into ``into``."""
    candidate = Path(old)
    if candidate.is_dir():
        if not (candidate / DOCUMENT).is_file():
            raise DiffError(f"--diff {old}: directory without {DOCUMENT} (not a generated tree)")
        return candidate
    listing = subprocess.run(["git", "-C", str(repository), "ls-tree", "-r", "--name-only", f"{old}:generated"],
                             capture_output=True, text=True, check=False)
    if listing.returncode != 0:
        raise DiffError(f"--diff {old}: neither a directory nor a git revision with a generated/ tree "
                        f"({listing.stderr.strip().splitlines()[-1] if listing.stderr.strip() else 'git failed'})")
    into.mkdir(parents=True, exist_ok=True)
    for name in listing.stdout.splitlines():   # every tracked file: the file list must see them all
        blob = subprocess.run(["git", "-C", str(repository), "show", f"{old}:generated/{name}"],
                              capture_output=True, check=True)
        (into / name).parent.mkdir(parents=True, exist_ok=True)
        (into / name).write_bytes(blob.stdout)
    if not (into / DOCUMENT).is_file():
        raise DiffError(f"--diff {old}: that revision has no generated/{DOCUMENT}")
    return into


# numbered (gather) or not (gather*): the label and number commands are not part of the formula
_DISPLAY = re.compile(r"\\begin\{(gather|equation)(\*?)\}(.*?)\\end\{\1\2\}", re.S)
_NUMBERING = re.compile(r"\\(?:notag|nonumber)\b|\\label\{[^}]*\}")


def _braced(text: str, start: int) -> str:
    """The argument of the brace group opening at ``text[start]`` (nested braces kept)."""
    depth = 0
    for index in range(start, len(text)):
        depth += (text[index] == "{") - (text[index] == "}")
        if depth == 0:
            return text[start + 1:index]
    return text[start + 1:]


def formula_paragraphs(body: str) -> dict[str, str]:
    """``section / title`` -> the displayed mathematics of that formula, from ``formulas_body.tex``.

    Only the display is compared (whitespace ignored): certificate keys are sequence numbers and
    shift when a certificate is added elsewhere, which changes no formula.
    """
    out, section = {}, ""
    marks = sorted([(m.start(), "section") for m in re.finditer(r"\\section\{", body)]
                   + [(m.start(), "paragraph") for m in re.finditer(r"\\paragraph\{", body)])
    for index, (position, kind) in enumerate(marks):
        title = _braced(body, body.index("{", position))
        if kind == "section":
            section = title
            continue
        end = marks[index + 1][0] if index + 1 < len(marks) else len(body)
        display = _DISPLAY.search(body, position, end)
        out[f"{section} / {title}"] = "".join(_NUMBERING.sub("", display.group(3)).split()) if display else ""
    return out


def _pair_reworded(removed: list, added: list) -> tuple[list, list, list]:
    """Pairs (old, new) of one (derivation, label) whose claims are similar (ratio >= REWORDED), best first;
    returns (pairs, still removed, still added)."""
    candidates = []
    for i, a in enumerate(removed):
        for j, b in enumerate(added):
            if (a["derivation"], a["label"]) == (b["derivation"], b["label"]):
                ratio = difflib.SequenceMatcher(None, a["claim"], b["claim"]).ratio()
                if ratio >= REWORDED:
                    candidates.append((-ratio, i, j))
    pairs, used_old, used_new = [], set(), set()
    for _, i, j in sorted(candidates):
        if i not in used_old and j not in used_new:
            pairs.append((removed[i], added[j]))
            used_old.add(i)
            used_new.add(j)
    return (pairs, [a for i, a in enumerate(removed) if i not in used_old],
            [b for j, b in enumerate(added) if j not in used_new])


_CERTKEY = re.compile(r"\\certkey\{[^{}]*\}")


def _table_lines(text: str) -> list[str]:
    return [_CERTKEY.sub(r"\\certkey{}", line) for line in text.splitlines()]


def _read(directory: Path, name: str) -> str:
    path = directory / name
    return path.read_text(encoding="utf-8") if path.is_file() else ""


def tree_files(directory: Path) -> set[str]:
    """The generated files of a tree (relative paths), without volatile files, caches and TeX by-products."""
    from derivations.output.pdf import is_byproduct
    directory = Path(directory)
    return {path.relative_to(directory).as_posix() for path in directory.rglob("*")
            if path.is_file() and "__pycache__" not in path.parts and path.name not in VOLATILE
            and not is_byproduct(path.name)}


def compare(old: Path, new: Path) -> TreeDiff:
    """What changed from the tree ``old`` to the tree ``new``."""
    result = TreeDiff()
    left, right = tree_files(old), tree_files(new)
    result.files["added"] = sorted(right - left)
    result.files["removed"] = sorted(left - right)
    result.files["changed"] = sorted(name for name in left & right
                                     if (Path(old) / name).read_bytes() != (Path(new) / name).read_bytes())
    before, after = (formula_paragraphs(_read(d, "formulas_body.tex")) for d in (old, new))
    result.formulas["added"] = [k for k in after if k not in before]
    result.formulas["removed"] = [k for k in before if k not in after]
    result.formulas["changed"] = [k for k in after if k in before and after[k] != before[k]]
    for name in TABLES:
        a, b = _table_lines(_read(old, name)), _table_lines(_read(new, name))
        if a != b:
            ops = list(difflib.ndiff(a, b))
            result.tables.append((name, sum(o.startswith("+ ") for o in ops), sum(o.startswith("- ") for o in ops)))
    docs = [json.loads(_read(d, "certificates.json") or "{}") for d in (old, new)]
    docs[0] = _current_names(docs[0])
    _compare_certificates(result, *(d.get("certificates", []) for d in docs))
    e_old, e_new = ({e["label"]: e for e in d.get("errata", [])} for d in docs)
    result.errata["added"] = [e_new[k] for k in e_new if k not in e_old]
    result.errata["removed"] = [e_old[k] for k in e_old if k not in e_new]
    for k in (k for k in e_new if k in e_old):
        if erratum_fields(e_old[k], e_new[k]):
            result.errata["changed"].append((e_old[k], e_new[k]))
        elif e_old[k].get("note") != e_new[k].get("note"):
            result.reprinted.append(("erratum", e_old[k], e_new[k]))
    return result


def _current_names(document: dict) -> dict:
    """An older tree's certificates and errata with the statements' old names replaced by the printed ones
    (issue 46 renamed four: ``Theorem 5.2`` is ``Theorem 5.4``), so that a renamed label is not a change."""
    def renamed(record: dict) -> dict:
        return {k: current_names(v) if isinstance(v, str) else v for k, v in record.items()}

    return {**document, "certificates": [renamed(c) for c in document.get("certificates", [])],
            "errata": [renamed(e) for e in document.get("errata", [])]}


def _same_result(a: dict, b: dict) -> bool:
    """The same outcome by the same method (its formulas compared by meaning, not by print)."""
    return a["outcome"] == b["outcome"] and same_meaning(a["method"], b["method"])


def _pair_same_meaning(removed: list, added: list) -> tuple[list, list, list]:
    """Pairs (old, new) of one (derivation, label) whose claims say the same (:func:`same_meaning`: the words and,
    formula by formula, the mathematics); returns (pairs, still removed, still added)."""
    def words(c: dict) -> tuple:   # what two claims of the same meaning share: their words, their number of formulas
        prose, formulas = meaning(c["claim"])
        return prose, len(formulas)

    candidates = {}
    for j, b in enumerate(added):
        candidates.setdefault((b["derivation"], b["label"]), []).append(j)
    pairs, used = [], set()
    for a in removed:
        for j in candidates.get((a["derivation"], a["label"]), []):   # only claims of one label are compared
            if j not in used and words(a) == words(added[j]) and same_meaning(a["claim"], added[j]["claim"]):
                pairs.append((a, added[j]))
                used.add(j)
                break
    paired = {id(a) for a, _ in pairs}
    return pairs, [a for a in removed if id(a) not in paired], [b for j, b in enumerate(added) if j not in used]


def _compare_certificates(result: TreeDiff, old: list, new: list) -> None:
    """Certificates matched by (derivation, label, claim); the unmatched paired first by meaning (a claim SymPy
    prints differently: reprinted, or changed if its outcome or method changed), then by similarity (reworded)."""
    c_old, c_new = ({(c["derivation"], c["label"], c["claim"]): c for c in d} for d in (old, new))
    same, removed, added = _pair_same_meaning([c_old[k] for k in c_old if k not in c_new],
                                              [c_new[k] for k in c_new if k not in c_old])
    reworded, removed, added = _pair_reworded(removed, added)
    result.certificates.update(added=added, removed=removed, reworded=reworded)
    order = {id(c): index for index, c in enumerate(new)}
    pairs = sorted([(c_old[k], c_new[k]) for k in c_new if k in c_old] + same, key=lambda pair: order[id(pair[1])])
    for a, b in pairs:
        if not _same_result(a, b):
            result.certificates["changed"].append((a, b))
        elif a["claim"] != b["claim"] or a["method"] != b["method"]:
            result.reprinted.append(("certificate", a, b))


def _latex_key(text) -> str:
    return "".join(str(text or "").split())


def erratum_fields(a: dict, b: dict) -> list[str]:
    """What changed in an erratum row: status, printed form, derived form (their LaTeX, spaces aside), note (by
    meaning: a note SymPy prints differently is not a changed note)."""
    fields = ["status"] if a.get("status") != b.get("status") else []
    fields += [name for key, name in (("printed", "printed form"), ("derived", "derived form"))
               if _latex_key(a.get(key)) != _latex_key(b.get(key))]
    if not same_meaning(str(a.get("note") or ""), str(b.get("note") or "")):
        fields.append("note")
    return fields


def _shown(text) -> str:
    return render(text, keep_together=True)


def _label(item: dict) -> str:
    return item["label"].replace("->", "→")   # t->z: the paper's label, read


def _certificate_line(kind: str, c: dict, outcome: bool = True) -> list[str]:
    return wrap(f"certificate {kind}: [{_label(c)}] {_shown(c['claim'])}" + (f" ({c['outcome']})" if outcome else ""))


def _result(c: dict) -> str:
    return f"{c['outcome']} ({_shown(c['method'])})"


def _old_and_new(what: str, old: str, new: str) -> list[str]:
    """``old{what}: ...``, ``new{what}: ...`` and, if few words differ, which (``changed: «20» → «4»``)."""
    lines = wrap(f"old{what}: {old}", indent=6, hanging=len(what) + 5) + wrap(f"new{what}: {new}", indent=6,
                                                                              hanging=len(what) + 5)
    summary = changed_words(old, new)
    return lines + (wrap(f"changed: {summary}", indent=6, hanging=9) if summary else [])


def _result_change(a: dict, b: dict) -> list[str]:
    """How a certificate's outcome or method changed: the words that differ, or both in full."""
    if a["outcome"] == b["outcome"]:
        summary = changed_words(_shown(a["method"]), _shown(b["method"]))
        if summary:
            return wrap(f"method changed (outcome still {b['outcome']}): {summary}", indent=6, hanging=4)
    return wrap("old: " + _result(a), indent=6, hanging=5) + wrap("new: " + _result(b), indent=6, hanging=5)


def _reprinted_line(diff: TreeDiff) -> list[str]:
    if not diff.reprinted:
        return []
    certificates = sum(kind == "certificate" for kind, _, _ in diff.reprinted)
    notes = len(diff.reprinted) - certificates
    parts = ([f"{certificates} certificate" + "s" * (certificates != 1)] if certificates else []) + (
        [f"{notes} errata note" + "s" * (notes != 1)] if notes else [])
    what = " and ".join(parts)
    return wrap(f"{what} reprinted without change of meaning (the same words and, by SymPy, the same formulas, "
                f"printed differently): not listed")


def report(diff: TreeDiff, old_name: str, new_name: str) -> str:
    """The change list for a reader: formulas in Unicode (no program text), lines of at most
    :data:`~derivations.output.diff_text.WIDTH` columns, old and new side by side where something changed."""
    lines = [f"{old_name} → {new_name}:"]
    for kind, items in diff.files.items():
        lines += [f"  file {kind}: {name}" for name in items]
    if diff.empty():
        summary = _reprinted_line(diff)
        if len(lines) == 1 and not summary:
            return "\n".join(wrap(f"{old_name} → {new_name}: no file differs; no formula, table, certificate or "
                                   "erratum changed", indent=0))
        return "\n".join(lines + wrap("no formula, table, certificate or erratum changed") + summary)
    for kind, items in diff.formulas.items():
        for key in items:
            lines += wrap(f"formula {kind}: {latex_text(key)}")
    lines += [f"  table changed: {name} (+{plus} -{minus} lines)" for name, plus, minus in diff.tables]
    for c in diff.certificates["added"]:
        lines += _certificate_line("added", c)
    for c in diff.certificates["removed"]:
        lines += _certificate_line("removed", c, outcome=False)
    for a, b in diff.certificates["reworded"]:
        lines += wrap(f"certificate reworded: [{_label(b)}]") + _old_and_new("", _shown(a["claim"]), _shown(b["claim"]))
        if not _same_result(a, b):
            lines += _result_change(a, b)
    for a, b in diff.certificates["changed"]:
        lines += _certificate_line("changed", b, outcome=False) + _result_change(a, b)
    for e in diff.errata["added"]:
        lines += wrap(f"erratum added: {_label(e)} ({e['status']}): {_shown(e.get('note') or '')}")
    lines += [f"  erratum removed: {_label(e)}" for e in diff.errata["removed"]]
    for a, b in diff.errata["changed"]:
        fields = erratum_fields(a, b)
        status = f"status {a['status']} → {b['status']}" if "status" in fields else f"still {b['status']}"
        changed = [f for f in fields if f != "status"]
        lines += wrap(f"erratum changed: {_label(b)} ({status}" + (f"; {', '.join(changed)} changed" if changed else "")
                      + ")")
        for key, name in (("printed", "printed form"), ("derived", "derived form")):
            if name in fields:
                lines += wrap(f"old {name}: {latex_text(a.get(key) or '')}", indent=6, hanging=4)
                lines += wrap(f"new {name}: {latex_text(b.get(key) or '')}", indent=6, hanging=4)
        if "note" in fields:
            lines += _old_and_new(" note", _shown(a.get("note") or ""), _shown(b.get("note") or ""))
        else:
            lines += wrap("note (unchanged): " + _shown(b.get("note") or ""), indent=6, hanging=10)
    return "\n".join(lines + _reprinted_line(diff))


def latexdiff_pdf(old: Path, new: Path, outdir: Path, document: str = DOCUMENT) -> Path:
    """``latexdiff --flatten`` of one document (certificate keys marked too), compiled into ``outdir``."""
    for tool, package in (("latexdiff", "latexdiff"), ("pdflatex", "texlive-latex-base")):
        if shutil.which(tool) is None:
            raise DiffError(f"{tool} not found (Debian: apt-get install {package})")
    outdir = Path(outdir).resolve()
    outdir.mkdir(parents=True, exist_ok=True)
    marked = subprocess.run(["latexdiff", "--flatten", "--append-textcmd=certkey",
                             str(Path(old).resolve() / document), str(Path(new).resolve() / document)],
                            capture_output=True, text=True, check=False, timeout=600)
    if marked.returncode != 0:
        raise DiffError(f"latexdiff failed: {marked.stderr.strip()[-500:]}")
    source = outdir / (Path(document).stem + "-diff.tex")
    source.write_text(marked.stdout, encoding="utf-8")
    for _ in range(2):
        run = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", source.name], cwd=outdir,
                             capture_output=True, text=True, check=False, timeout=600)
        if run.returncode != 0:
            raise DiffError(f"pdflatex failed on {source}; see {source.with_suffix('.log')}")
    return source.with_suffix(".pdf")


def diff_trees(old: str, new: Path, repository: Path, outdir: Path | None, echo=print) -> Path | None:
    """Print the change list with ``echo``, then write the latexdiff PDF (unless ``outdir`` is None).

    Raises :class:`DiffError` naming what is missing or what failed.
    """
    with tempfile.TemporaryDirectory(prefix="suslov-diff-") as tmp:
        old_tree = materialise(old, repository, Path(tmp) / "old")
        echo(report(compare(old_tree, new), old, str(new)))
        if outdir is None:
            return None
        pdfs = [latexdiff_pdf(old_tree, new, outdir, document) for document in DOCUMENTS
                if (old_tree / document).is_file() and (Path(new) / document).is_file()]
        return pdfs[0]
