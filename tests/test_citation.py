"""How to cite (issue 47): ``CITATION.cff`` and the BibTeX of ``docs/citing.md`` say the same thing.

The paper is cited as arXiv:0902.0079 in both, with the same title and authors; the BibTeX page is in the
Sphinx toctree and linked from the README; the licence is the SPDX expression of ``pyproject.toml``; and
no tracked file points a reader to the paper's copy outside the repository (``shared/``).
"""
import re
import subprocess
import tomllib
from pathlib import Path

import yaml   # PyYAML: in the test extra through myst-parser and dask (pinned in constraints.txt)

ROOT = Path(__file__).resolve().parents[1]
CITING = ROOT / "docs" / "citing.md"


def bibtex_entries() -> dict:
    text = CITING.read_text(encoding="utf-8")
    entries = {}
    for block in re.findall(r"```bibtex\n(.*?)```", text, flags=re.S):
        key = re.match(r"@\w+\{([^,]+),", block).group(1)
        fields = {name.lower(): " ".join(value.split()) for name, value in
                  re.findall(r"^\s*(\w+)\s*=\s*\{(.*?)\},?\s*$", block, flags=re.S | re.M)}
        entries[key] = fields
    return entries


def plain(text: str) -> str:
    """BibTeX's case-protecting braces dropped, spaces normalised, lower case."""
    return " ".join(text.replace("{", "").replace("}", "").split()).lower()


def test_citation_cff_and_bibtex_cite_the_same_paper():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    (paper,) = cff["references"]
    bib = bibtex_entries()["FedorovMaciejewskiPrzybylska2009"]
    assert plain(bib["title"]) == plain(paper["title"])
    names = [f"{a['family-names']}, {a['given-names']}" for a in paper["authors"]]
    assert bib["author"].split(" and ") == names
    assert bib["eprint"] == "0902.0079" and bib["archiveprefix"] == "arXiv" and str(paper["year"]) == bib["year"]
    assert {"type": "other", "value": "arXiv:0902.0079"}.items() <= paper["identifiers"][0].items()
    assert bib["doi"] == paper["identifiers"][1]["value"] == "10.48550/arXiv.0902.0079"


def test_software_entry_matches_the_package():
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text(encoding="utf-8"))
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    assert cff["version"] == project["version"] and cff["license"] == project["license"] == "MIT"
    assert project["license-files"] == ["LICENSE"] and (ROOT / "LICENSE").read_text().startswith("MIT License")
    assert f"Version {project['version']}" in bibtex_entries()["suslov-certified"]["note"]


def test_citing_page_is_reachable():
    assert re.search(r"^\s+citing$", (ROOT / "docs" / "index.rst").read_text(encoding="utf-8"), flags=re.M)
    assert "(docs/citing.md)" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_no_tracked_file_points_outside_the_repository_for_the_paper():
    files = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"], cwd=ROOT,
                           capture_output=True, text=True, check=True).stdout.split("\0")
    needle, pointing = "shared" + "/paper", []   # written in two parts so that this file does not match itself
    for name in filter(None, files):
        path = ROOT / name
        if path.suffix in {".py", ".md", ".rst", ".cff", ".toml", ".j2", ".tex", ".txt"} and path.is_file():
            if needle in path.read_text(encoding="utf-8", errors="replace"):
                pointing.append(name)
    assert pointing == [], pointing
