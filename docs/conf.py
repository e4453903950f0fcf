"""Sphinx configuration: API reference (autodoc + numpydoc) and an example gallery (sphinx-gallery).

Build (from the repository root, after ``pip install -c constraints.txt -e ".[docs]"``)::

    sphinx-build -W -b html docs docs/_build/html

The gallery scripts in ``docs/examples/`` are executed during the build (about 10 s in all);
``-D plot_gallery=0`` builds the pages without running them.  Nothing here downloads anything
(no intersphinx), so the build works offline.
"""
from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

# Document the checkout this file belongs to (an editable install points there anyway).
_REPO = Path(__file__).resolve().parents[1]
if (_REPO / "suslov" / "__init__.py").is_file() and str(_REPO) not in sys.path:
    sys.path.insert(0, str(_REPO))

project = "suslov-certified"
author = "suslov-certified contributors"
copyright = "the suslov-certified contributors (MIT licence)"  # noqa: A001 (Sphinx's name)
release = version = "0.1.0"

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "myst_parser",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
myst_heading_anchors = 3

exclude_patterns = ["_build", "**.ipynb_checkpoints"]
templates_path: list[str] = []
html_theme = "alabaster"
html_theme_options = {"description": "Certified formulas for the nonholonomic Suslov problem",
                      "fixed_sidebar": True, "page_width": "1100px"}
html_static_path: list[str] = []
html_show_sourcelink = False

# autodoc: the public API of the generated module is its __all__, listed by topic in api/formulas.rst
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True
# keep ``ArrayLike`` short in signatures (NumPy's alias expands to a screenful of private types)
autodoc_type_aliases = {"ArrayLike": "numpy.typing.ArrayLike"}

# numpydoc: render the docstrings, validate nothing (they are prose with formulas, paper labels
# and error bounds, not Parameters sections), no autosummary stubs for class members
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

sphinx_gallery_conf = {
    "examples_dirs": ["examples"],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/plot_",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "show_memory": False,
    "min_reported_time": 1,
    "write_computation_times": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "show_signature": False,
}
