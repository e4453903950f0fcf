"""build_formulas.py --diff OLD: change lists between generated trees and the latexdiff PDF (issue 14)."""
import json
import os
import re
import shutil
import subprocess

import pytest

import build_formulas
from derivations.output import diff
from derivations.output.pipeline import GENERATED, ROOT


def copy_of_generated(tmp_path):
    target = tmp_path / "old"
    shutil.copytree(GENERATED, target, ignore=shutil.ignore_patterns("__pycache__", "*.pdf", "*.log", "*.aux"))
    return target


def test_identical_trees_report_nothing(tmp_path):
    old = copy_of_generated(tmp_path)
    result = diff.compare(old, GENERATED)
    assert result.empty()
    assert "no formula, table, certificate or erratum changed" in diff.report(result, "old", "new")
    assert result.files == {"added": [], "removed": [], "changed": []}


def test_changes_are_named_by_what_a_reader_recognises(tmp_path):
    old = copy_of_generated(tmp_path)
    body = (old / "formulas_body.tex").read_text(encoding="utf-8")
    # an older version with a different F_1 on the normalised solution and a missing p = 7 integral
    body = body.replace(r"F_1=\frac{(I_{11}I_{22})^2}{D}", r"F_1=\frac{1}{D}", 1)
    start = body.index(r"\paragraph{$p=7$")
    body = body[:start] + body[body.index(r"\paragraph", start + 1):]
    (old / "formulas_body.tex").write_text(body, encoding="utf-8")
    document = json.loads((old / "certificates.json").read_text(encoding="utf-8"))
    document["certificates"][0]["outcome"] = "unknown"
    removed = document["certificates"].pop(5)
    document["errata"][0]["status"] = "confirmed"
    (old / "certificates.json").write_text(json.dumps(document), encoding="utf-8")
    (old / "per_p_table.tex").write_text("% an older table\n", encoding="utf-8")

    result = diff.compare(old, GENERATED)
    changed = result.formulas["changed"]
    assert len(changed) == 1 and changed[0].endswith("Energy on the normalised solution ($D=I_{13}^2I_{22}+I_{23}^2I_{11}$)")
    assert [k.split(" / ")[1] for k in result.formulas["added"]] == ["$p=7$ (one monomial per line)"]
    assert result.formulas["removed"] == []
    assert [c["claim"] for c in result.certificates["added"]] == [removed["claim"]]
    assert [(a["outcome"], b["outcome"]) for a, b in result.certificates["changed"]] == [("unknown", "pass")]
    assert [(a["label"], a["status"], b["status"]) for a, b in result.errata["changed"]] == [
        (document["errata"][0]["label"], "confirmed", "corrected")]
    assert [name for name, _, _ in result.tables] == ["per_p_table.tex"]
    text = diff.report(result, "old", "new")
    assert "formula added" in text and "certificate changed" in text and "erratum changed" in text


def test_renumbered_certificate_keys_are_not_changes(tmp_path):
    old = copy_of_generated(tmp_path)
    document = json.loads((old / "certificates.json").read_text(encoding="utf-8"))
    for entry in document["errata"]:
        entry["certificates"] = [key + "0" for key in entry["certificates"]]
    (old / "certificates.json").write_text(json.dumps(document), encoding="utf-8")
    result = diff.compare(old, GENERATED)
    assert result.empty()
    assert result.files["changed"] == ["certificates.json"]   # the file still differs, and is named
    assert "file changed: certificates.json" in diff.report(result, "old", "new")


def test_bad_old_is_a_clear_error(tmp_path, capsys):
    assert build_formulas.main(["--diff", "no-such-revision"]) == 2
    assert "neither a directory nor a git revision" in capsys.readouterr().err
    (tmp_path / "empty").mkdir()
    assert build_formulas.main(["--diff", str(tmp_path / "empty")]) == 2
    assert "not a generated tree" in capsys.readouterr().err


def test_missing_latexdiff_is_named(tmp_path, monkeypatch):
    monkeypatch.setattr(diff.shutil, "which", lambda name: None if name == "latexdiff" else "/usr/bin/" + name)
    with pytest.raises(diff.DiffError, match="apt-get install latexdiff"):
        diff.latexdiff_pdf(copy_of_generated(tmp_path), GENERATED, tmp_path / "out")


def older_tree_with_one_formula_changed(tmp_path):
    """A copy of generated/ whose F_1 differs (needs latexdiff and pdflatex: skipped without, failed under CI)."""
    if shutil.which("latexdiff") is None or shutil.which("pdflatex") is None:
        if os.environ.get("CI"):
            pytest.fail("latexdiff/pdflatex not found under CI: .ci/run must install latexdiff and texlive-latex-base")
        pytest.skip("latexdiff or pdflatex not installed (apt-get install latexdiff texlive-latex-base)")
    old = copy_of_generated(tmp_path)
    body = (old / "formulas_body.tex").read_text(encoding="utf-8")
    (old / "formulas_body.tex").write_text(body.replace(r"\frac{(I_{11}I_{22})^2}{D}", r"\frac{1}{D}", 1),
                                           encoding="utf-8")
    return old


def test_git_revision_and_latexdiff_pdf(tmp_path, capsys):
    old = older_tree_with_one_formula_changed(tmp_path)
    pdf = diff.diff_trees(str(old), GENERATED, ROOT, tmp_path / "diff", echo=print)
    assert pdf.is_file() and pdf.stat().st_size > 10_000
    marked = (tmp_path / "diff" / "suslov_formulas-diff.tex").read_text(encoding="utf-8")
    body = marked.split(r"\begin{document}", 1)[1]   # the preamble defines the markers; the body must use them
    assert body.count(r"\DIFdelbegin") >= 1 and body.count(r"\DIFaddbegin") >= 1
    assert "formula changed" in capsys.readouterr().out
    # a git revision is read with git show, nothing checked out
    tree = diff.materialise("HEAD", ROOT, tmp_path / "head")
    assert (tree / "suslov_formulas.tex").is_file()


def test_reworded_claim_is_one_reworded_certificate_not_added_and_removed(tmp_path):
    old = copy_of_generated(tmp_path)
    document = json.loads((old / "certificates.json").read_text(encoding="utf-8"))
    original = document["certificates"][3]["claim"]
    document["certificates"][3]["claim"] = original.replace("e", "E", 2) + " (older wording)"
    (old / "certificates.json").write_text(json.dumps(document), encoding="utf-8")
    result = diff.compare(old, GENERATED)
    assert result.certificates["added"] == [] and result.certificates["removed"] == []
    assert [b["claim"] for _, b in result.certificates["reworded"]] == [original]
    assert "certificate reworded" in diff.report(result, "old", "new")


def test_a_table_whose_certificate_keys_alone_changed_is_unchanged(tmp_path):
    old = copy_of_generated(tmp_path)
    table = (old / "monodromy_tables.tex").read_text(encoding="utf-8")
    shifted = re.sub(r"\\certkey\{([a-z_]+):(\d+)\}", lambda m: rf"\certkey{{{m.group(1)}:{int(m.group(2)) + 7:03d}}}",
                     table)
    assert shifted != table
    (old / "monodromy_tables.tex").write_text(shifted, encoding="utf-8")
    assert diff.compare(old, GENERATED).tables == []


def test_latexdiff_marks_a_changed_formula_and_a_changed_certificate(tmp_path):
    old = older_tree_with_one_formula_changed(tmp_path)
    table = (old / "certificates_table.tex").read_text(encoding="utf-8")
    key = next(line for line in table.splitlines() if r"\certkey{" in line).split(r"\certkey{")[1].split("}")[0]
    (old / "certificates_table.tex").write_text(table.replace(r"\certkey{" + key + "}", r"\certkey{old:999}", 1),
                                                encoding="utf-8")
    diff.diff_trees(str(old), GENERATED, ROOT, tmp_path / "diff", echo=lambda text: None)
    formulas, certificates = ((tmp_path / "diff" / name).read_text(encoding="utf-8").split(r"\begin{document}", 1)[1]
                              for name in ("suslov_formulas-diff.tex", "certificates-diff.tex"))
    assert (tmp_path / "diff" / "certificates-diff.pdf").is_file()
    assert r"\DIFadd{\frac{(I_{11}I_{22})^2}{D}" in formulas          # the changed formula, marked
    assert re.search(r"\\certkey\{[^\n]*\\DIFadd\{", certificates)     # the changed key, marked inside \certkey


def git_names(old: str) -> set:
    listed = subprocess.run(["git", "-C", str(ROOT), "diff", "--name-only", old, "--", "generated/"],
                            capture_output=True, text=True, check=True).stdout.split()
    return {name[len("generated/"):] for name in listed if name[len("generated/"):] not in diff.VOLATILE}


@pytest.mark.parametrize("old", ["7b151a6", "HEAD~3"])
def test_files_named_are_the_files_git_diff_names(tmp_path, old):
    """Two real revisions: the files --diff lists are exactly those git diff lists (issue 35: three were missing)."""
    if subprocess.run(["git", "-C", str(ROOT), "cat-file", "-e", old], capture_output=True).returncode != 0:
        pytest.skip(f"{old} is not in this clone (shallow?)")
    tree = diff.materialise(old, ROOT, tmp_path / "old")
    result = diff.compare(tree, GENERATED)
    named = set(result.files["added"] + result.files["removed"] + result.files["changed"])
    assert named == git_names(old)
    text = diff.report(result, old, "generated")
    assert all(f"file {kind}: {name}" in text for kind, names in result.files.items() for name in names)


def test_a_file_only_on_one_side_is_named(tmp_path):
    old = copy_of_generated(tmp_path)
    (old / "galois_group_table.tex").unlink()
    (old / "obsolete_table.tex").write_text("% gone since\n", encoding="utf-8")
    result = diff.compare(old, GENERATED)
    assert result.files["added"] == ["galois_group_table.tex"] and result.files["removed"] == ["obsolete_table.tex"]
