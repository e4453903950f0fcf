"""Results that display themselves in a notebook, and the example notebook (issue 47).

The objects returned by :mod:`suslov.validated` (``galois_group``, ``local_behaviour``, ``hypergeometric_form``,
``scattering_angle_enclosure`` by both methods, ``monodromy``) and by ``suslov.simulate`` show themselves in
Jupyter as SymPy's and pandas' objects do.  Checked here for a few bodies -- the general body
I = (5/4, 1, 3/10, -1/2), the special case p = 3, d = 1 (I11 = c^2 = 2, I22 = 1, I13 = 0, I23 = -I22 d/p = -1/3),
p = 2 and p = 10/3 on the same line:

* every ``_repr_latex_`` is one ``$...$`` formula that compiles with pdflatex in a minimal document (amsmath,
  amssymb), and so do the catalog entries' (``suslov.catalog``) when the generated tree has its catalog;
* every ``_repr_html_`` parses (html.parser, tags balanced) and says what it should, checked against an independent
  route: the verdicts against the paper's theorems (odd p: Liouvillian and meromorphic; p = 2: logarithmic), the
  angles against ``general_scattering_angle_mp`` at 60 digits to the printed radius, Gauss's A, B, C against the
  exact invariants (A - B = 1 + iU with U^2 = u.u from the emitted closed form of omega), the simulator's figures
  as PNG images.

The example ``docs/examples/plot_catalog_tour.py`` (a sphinx-gallery script, run by the docs build) is committed as
the notebook ``docs/examples/catalog_tour.ipynb``, made from it by sphinx-gallery's own converter without outputs:
the committed file must equal a fresh conversion (regenerate it with ``python tests/test_notebook_reprs.py``), and
its code cells must run in order in one namespace, each cell's last expression displayed as Jupyter would.
"""
import ast
import base64
import contextlib
import copy
import io
import json
import re
import runpy
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import mpmath
import pytest

import suslov
from suslov import validated

ROOT = Path(__file__).resolve().parents[1]
SCRIPT = ROOT / "docs" / "examples" / "plot_catalog_tour.py"
NOTEBOOK = ROOT / "docs" / "examples" / "catalog_tour.ipynb"
BODIES = {"general": ("5/4", 1, "3/10", "-1/2"), "p3_d1": (2, 1, 0, "-1/3"), "p2": (2, 1, 0, "-1/2"),
          "p10_3": (2, 1, 0, "-0.3")}
# the paper's theorems, not the package: on I13 = 0 (d = 1, p = 1/|I23|) odd p is Liouvillian with meromorphic
# solutions (Theorems 3.1, 6.1), even p has logarithms (Conjecture 1, proved by the build), any other p branches;
# u.v != 0 (I13 I23 (I11 - I22) != 0) is never Liouvillian and branches
EXPECTED = {"general": ("SO(3,C)", False, "branching", None), "p3_d1": ("reducible", True, "meromorphic", 3),
            "p2": ("SO(3,C)", False, "logarithmic", 2), "p10_3": ("SO(3,C)", False, "branching", None)}


@pytest.fixture(scope="module")
def objects():
    """name -> a result object of suslov.validated (a few bodies, both enclosure methods, two monodromies)."""
    made = {}
    for name, body in BODIES.items():
        made[f"galois_group[{name}]"] = validated.galois_group(*body)
        made[f"local_behaviour[{name}]"] = validated.local_behaviour(*body)
        made[f"hypergeometric_form[{name}]"] = validated.hypergeometric_form(*body, dps=25)
        made[f"scattering_angle_enclosure[{name}]"] = validated.scattering_angle_enclosure(*body, dps=30)
    made["scattering_angle_enclosure[general, integration]"] = validated.scattering_angle_enclosure(
        *BODIES["general"], dps=10, method="integration")
    for name in ("general", "p3_d1"):
        made[f"monodromy[{name}]"] = validated.monodromy(*BODIES[name], dps=12)
    return made


SIMULATED = {"p3_d1": {"body": {"p": 3, "d": 1}, "motion": {"time": [-4, 4], "samples": 41},
                       "effects": {"compute": ["omega", "scattering_angle", "scattering_angle_enclosure",
                                               "galois_group", "local_behaviour"], "figures": ["omega_plane"]}},
             "general": {"body": {"inertia": [["5/4", 0, "3/10"], [0, 1, "-1/2"], ["3/10", "-1/2", "3/2"]]},
                         "motion": {"time": [-4, 4], "samples": 41},
                         "effects": {"compute": ["scattering_angle", "scattering_angle_enclosure", "galois_group",
                                                 "local_behaviour"]}},
             "sweep": {"sweep": {"I11": 2.0, "I22": 1.0, "I33": 1.5, "I13": [0.0, 0.3], "I23": [-0.5, 0.4]},
                       "effects": {"compute": ["scattering_angle", "galois_group"], "figures": ["map"]}}}


@pytest.fixture(scope="module")
def simulated():
    return {name: suslov.simulate(scene, workers=1) for name, scene in SIMULATED.items()}


# --- LaTeX -----------------------------------------------------------------------------------------------------------

def compile_latex(snippets: dict, directory: Path) -> None:
    """Compile ``snippets`` (name -> LaTeX) as paragraphs of one minimal document; fail naming the snippet of the
    first error pdflatex reports."""
    if shutil.which("pdflatex") is None:
        pytest.skip("pdflatex not installed (Debian: apt-get install texlive-latex-base)")
    lines, owner = [r"\documentclass{article}", r"\usepackage{amsmath,amssymb}", r"\begin{document}"], {}
    for name, latex in snippets.items():
        lines.append(f"% {name}")
        owner[len(lines) + 1] = name
        lines += [latex, r"\par"]
    lines.append(r"\end{document}")
    (directory / "reprs.tex").write_text("\n".join(lines) + "\n", encoding="utf-8")
    done = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "-no-shell-escape", "reprs.tex"],
                          cwd=directory, capture_output=True, text=True, timeout=300, check=False)
    log = (directory / "reprs.log").read_text(encoding="utf-8", errors="replace")
    errors = [line for line in log.splitlines() if line.startswith("!")]
    where = re.search(r"^l\.(\d+)", log, re.MULTILINE)
    culprit = owner.get(int(where.group(1)), "?") if where else "?"
    assert done.returncode == 0 and errors == [], f"{culprit}: {errors[:3]}\n{log[-1500:]}"
    assert (directory / "reprs.pdf").stat().st_size > 1000


def test_every_latex_repr_is_one_formula_that_compiles(objects, tmp_path):
    snippets = {name: obj._repr_latex_() for name, obj in objects.items()}
    for name, latex in snippets.items():
        unescaped = latex.replace(r"\$", "")
        assert latex.startswith("$") and latex.endswith("$") and unescaped.count("$") == 2, name
        assert latex.count("{") == latex.count("}"), name
    compile_latex(snippets, tmp_path)


def test_catalog_entries_latex_compiles(tmp_path):
    try:
        from suslov import catalog
    except (FileNotFoundError, ImportError) as error:
        pytest.skip(f"no catalog.json in the generated tree in use yet (it will be committed with the catalog): "
                    f"{error}")
    snippets = {entry.id: entry._repr_latex_() for entry in catalog.entries()}
    assert snippets
    compile_latex(snippets, tmp_path)


def test_latex_names_the_groups_in_math(objects):
    for name, (group, liouvillian, kind, lam) in EXPECTED.items():
        latex = objects[f"galois_group[{name}]"]._repr_latex_()
        assert (r"\mathrm{SO}(2,\mathbb{C})" if liouvillian else r"\mathrm{SO}(3,\mathbb{C})") in latex, name
        assert (r"\text{Liouvillian}" if liouvillian else r"\text{not Liouvillian}") in latex, name
        local = objects[f"local_behaviour[{name}]"]._repr_latex_()
        assert kind in local and (lam is None or f"\\Lambda = {lam}" in local), (name, local)
    assert r"\mathrm{SO}(3,\mathbb{C})" in objects["monodromy[general]"]._repr_latex_()
    assert r"\frac{85000}{25921}" in objects["hypergeometric_form[general]"]._repr_latex_()   # U^2, exact


# --- HTML ------------------------------------------------------------------------------------------------------------

class Page(HTMLParser):
    """The text, the images and the tag structure of an HTML fragment (unbalanced tags are errors)."""

    VOID = frozenset({"br", "img", "hr", "wbr", "meta", "link", "input", "col", "area", "base", "source", "track",
                      "embed"})

    def __init__(self, markup: str):
        super().__init__(convert_charrefs=True)
        self.stack, self.parts, self.images, self.errors, self.bold, self.rows = [], [], [], [], [], []
        self.feed(markup)
        self.close()
        assert self.errors == [] and self.stack == [], (self.errors, self.stack)
        self.text = "".join(self.parts)

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.images.append(dict(attrs))
        if tag == "tr":
            self.rows.append([])
        if tag in ("td", "th") and self.rows:
            self.rows[-1].append("")
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):   # <img ... />: a start tag that is also its end
        self.handle_starttag(tag, attrs)
        if tag not in self.VOID:
            self.handle_endtag(tag)

    def handle_endtag(self, tag):
        if not self.stack or self.stack[-1] != tag:
            self.errors.append(f"</{tag}> closes {self.stack[-1:]}")
        else:
            self.stack.pop()

    def handle_data(self, data):
        self.parts.append(data)
        if "td" in self.stack and self.rows and self.rows[-1]:
            self.rows[-1][-1] += data
        if self.stack and self.stack[-1] == "b":
            self.bold.append(data)

    def cells(self) -> dict:
        """The rows of the tables: first cell -> second cell (text)."""
        return {row[0].strip(): row[1].strip() for row in self.rows if len(row) >= 2}


def test_every_html_repr_parses(objects, simulated):
    for name, obj in [*objects.items(), *simulated.items()]:
        page = Page(obj._repr_html_())
        assert page.text.strip(), name


def test_galois_group_html_states_the_verdict(objects):
    for name, (group, liouvillian, _, lam) in EXPECTED.items():
        result = objects[f"galois_group[{name}]"]
        page = Page(result._repr_html_())
        assert page.bold[0] == group and f"group='{group}'" in str(result), name
        assert ("not Liouvillian" in page.text) == (not liouvillian) and result.reason in page.text, name
        assert (f"w_-^2 = -{lam}^2" in result._repr_latex_()) == (liouvillian and lam is not None), name


def test_local_behaviour_html_states_the_kind(objects):
    for name, (_, _, kind, _) in EXPECTED.items():
        page = Page(objects[f"local_behaviour[{name}]"]._repr_html_())
        assert page.bold == [kind], name


BALL = re.compile(r"\[(-?[0-9.]+(?:e[+-]?\d+)?) ± ([0-9.]+(?:e[+-]?\d+)?)\]")


def angle_ball(text: str) -> tuple:
    """(midpoint, radius) as printed after "Δψ ∈" in ``text``, as mpf at 60 digits."""
    match = BALL.search(text[text.index("Δψ ∈"):])
    return mpmath.mpf(match.group(1)), mpmath.mpf(match.group(2))


def test_enclosure_html_angle_matches_the_mp_route_to_the_printed_digits(objects):
    with mpmath.workdps(60):
        for name, body in BODIES.items():
            reference = suslov.general_scattering_angle_mp(*body, dps=60)
            for key in (f"scattering_angle_enclosure[{name}]", f"scattering_angle_enclosure[{name}, integration]"):
                if key not in objects:
                    continue
                result = objects[key]
                page = Page(result._repr_html_())
                mid, rad = angle_ball(page.text)
                assert abs(mid - reference) <= rad, (key, mid, rad, reference)
                assert rad < 10.0 ** (-9 if "integration" in key else -29), key
                assert BALL.search(page.text).group(1) in result._repr_latex_(), key   # the same digits in LaTeX
                method = "validated integration" if "integration" in key else "closed form"
                assert method in page.text, key


def test_hypergeometric_html_agrees_with_the_exact_invariants(objects):
    # p = 3, d = 1: kappa = -3/2, U = 3: A = 1 + 3i/2, B = -3i/2, C = -1/2, all exact
    special = Page(objects["hypergeometric_form[p3_d1]"]._repr_html_()).cells()
    assert (special["A"], special["B"], special["C"]) == ("1 + 1.5 i", "-1.5 i", "-0.5")
    # general body, from the printed balls: A - B = 1 + iU with U^2 = u.u of the emitted closed form of omega (not
    # the exact invariants' route), and C = 1 + kappa
    form = objects["hypergeometric_form[general]"]
    rows = Page(form._repr_html_()).cells()
    kappa = next(value for key, value in rows.items() if key.startswith("κ"))
    (a_im, a_rad), = BALL.findall(rows["A"])
    (b_im, b_rad), = BALL.findall(rows["B"])
    (c_re, c_rad), _ = BALL.findall(rows["C"])
    (k_re, k_rad), _ = BALL.findall(kappa)
    assert rows["A"].startswith("1 + [") and rows["U2 (exact)"] == "85000/25921"
    u, _ = validated.omega_coefficients(*BODIES["general"])
    with mpmath.workdps(40):
        u_squared = u[0] ** 2 + u[1] ** 2
        U = mpmath.sqrt(mpmath.mpf(85000) / 25921)
        assert abs(mpmath.mpf(u_squared.mid().str(40, radius=False)) - U**2) < 1e-12
        assert abs(mpmath.mpf(a_im) - mpmath.mpf(b_im) - U) <= mpmath.mpf(a_rad) + mpmath.mpf(b_rad)
        assert abs(mpmath.mpf(c_re) - 1 - mpmath.mpf(k_re)) <= mpmath.mpf(c_rad) + mpmath.mpf(k_rad)
    assert rows["Re w-2 (exact)"] == "-11125/25921" and rows["Im w-2 (exact)"] == "15000/25921 sqrt(5/4)"


def test_monodromy_html_states_the_exact_verdict_and_every_certificate(objects):
    for name in ("general", "p3_d1"):
        result = objects[f"monodromy[{name}]"]
        markup = result._repr_html_()
        page = Page(markup)
        assert page.bold[0] == validated.galois_group(*BODIES[name]).group == EXPECTED[name][0], name
        assert markup.count("<td style='text-align:left'><b>") == len(result.certificates), name   # one row each
        assert all(f"M({point}), midpoints:" in page.text for point in ("x=0", "x=i", "x=-i", "x=oo")), name


def test_simulate_result_html_shows_values_and_inline_figures(simulated):
    special = Page(simulated["p3_d1"]._repr_html_())
    assert len(special.images) == 1 and special.images[0]["alt"] == "omega_plane"
    source = special.images[0]["src"]
    assert source.startswith("data:image/png;base64,")
    assert base64.b64decode(source.split(",", 1)[1]).startswith(b"\x89PNG\r\n\x1a\n")
    assert "reducible" in special.bold and "meromorphic" in special.bold
    printed = float(re.search(r"Δψ = ([0-9.e+-]+) rad", special.text).group(1))
    assert printed == float(suslov.scattering_angle_mp(3, 1, dps=30))   # odd p: pi, to the last printed digit

    general = Page(simulated["general"]._repr_html_())
    assert general.images == [] and "SO(3,C)" in general.bold and "branching" in general.bold
    with mpmath.workdps(60):
        reference = suslov.general_scattering_angle_mp(*BODIES["general"], dps=60)
        value, error = re.search(r"Δψ = ([0-9.e+-]+) rad \(error estimate ([0-9.e+-]+)\)", general.text).groups()
        assert abs(mpmath.mpf(value) - reference) <= mpmath.mpf(error)
        mid, rad = angle_ball(general.text)
        assert abs(mid - reference) <= rad < 1e-30

    sweep = Page(simulated["sweep"]._repr_html_())
    assert [image["alt"] for image in sweep.images] == ["map"] and "table: 4 rows" in sweep.text


def test_simulate_result_html_without_matplotlib_names_the_extra(simulated, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", None)
    page = Page(simulated["p3_d1"]._repr_html_())
    assert page.images == [] and "[sim] extra (matplotlib not installed)" in page.text
    assert "pip install 'suslov-certified[sim]'" in page.text and "reducible" in page.bold


# --- the example notebook --------------------------------------------------------------------------------------------

def gallery_conf() -> dict:
    """The docs build's sphinx-gallery configuration (docs/conf.py), with sphinx-gallery's defaults filled in."""
    pytest.importorskip("sphinx_gallery")
    from sphinx_gallery.gen_gallery import _fill_gallery_conf_defaults

    conf = runpy.run_path(str(ROOT / "docs" / "conf.py"))["sphinx_gallery_conf"]
    return _fill_gallery_conf_defaults(copy.deepcopy(conf), app=None)


def notebook_of(script: Path) -> dict:
    """The notebook sphinx-gallery makes of ``script`` (its own converter, no outputs); the Python patch version
    in the metadata is left out, so the committed file does not change with the interpreter (Jupyter writes it
    back when the notebook is saved)."""
    from sphinx_gallery.notebook import jupyter_notebook
    from sphinx_gallery.py_source_parser import split_code_and_text_blocks

    _, blocks = split_code_and_text_blocks(str(script))
    notebook = jupyter_notebook(blocks, gallery_conf(), script.parent)
    notebook["metadata"]["language_info"].pop("version", None)
    return notebook


def write_notebook() -> None:
    """Regenerate docs/examples/catalog_tour.ipynb from the script (``python tests/test_notebook_reprs.py``)."""
    from sphinx_gallery.notebook import save_notebook

    save_notebook(notebook_of(SCRIPT), NOTEBOOK)


def test_committed_notebook_is_the_conversion_of_the_script():
    assert NOTEBOOK.is_file(), "docs/examples/catalog_tour.ipynb missing: python tests/test_notebook_reprs.py"
    committed = json.loads(NOTEBOOK.read_text(encoding="utf-8"))
    assert committed == notebook_of(SCRIPT), "the notebook drifted from the script: python tests/test_notebook_reprs.py"
    assert all(cell.get("outputs", []) == [] and cell.get("execution_count") is None for cell in committed["cells"])


def test_gallery_runs_the_script_and_not_the_notebook():
    conf = gallery_conf()
    pattern = re.compile(conf["filename_pattern"])
    assert pattern.search(f"{SCRIPT.parent}/{SCRIPT.name}")   # sphinx-gallery matches the full path
    assert NOTEBOOK.suffix not in conf["example_extensions"] and not re.search(conf["ignore_pattern"], SCRIPT.name)


def test_notebook_cells_run_in_order_in_one_namespace(tmp_path, monkeypatch):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(tmp_path)
    cells = [cell for cell in json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"] if cell["cell_type"] == "code"]
    assert len(cells) >= 6
    namespace: dict = {"__name__": "__main__"}
    shown = []
    with contextlib.redirect_stdout(io.StringIO()) as out:
        for i, cell in enumerate(cells):
            tree = ast.parse("".join(cell["source"]), f"<cell {i}>")
            last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
            exec(compile(tree, f"<cell {i}>", "exec"), namespace)   # noqa: S102 (the notebook's own cells)
            if last is not None:   # the cell's value, displayed as Jupyter would: its richest representation
                value = eval(compile(ast.Expression(last.value), f"<cell {i}>", "eval"), namespace)
                for method in ("_repr_html_", "_repr_latex_"):
                    if hasattr(value, method):
                        shown.append(getattr(value, method)())
    printed = out.getvalue()
    assert "SO(3,C) | Liouvillian: False" in printed and "Liouvillian for p = [1, 3, 5, 7]" in printed
    assert len(shown) >= 8 and all(isinstance(s, str) and s for s in shown)
    assert plt.get_fignums(), "the last cell draws the figure"
    plt.close("all")


if __name__ == "__main__":
    write_notebook()
    print(f"wrote {NOTEBOOK.relative_to(ROOT)}")
