"""Sphinx configuration: the API reference from the numpy-style docstrings, MyST pages.

Built by ``make docs`` and by the tests (``tests/test_docs.py``) with warnings as errors,
so a broken cross-reference or a docstring that documents a parameter the function no
longer has fails the build.
"""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))

import pendulab  # noqa: E402

project = "pendulab"
author = "pendulab contributors"
copyright = f"{author}, MIT licence"  # the footer: without it alabaster prints "(c). |"
release = version = pendulab.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_nb",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
templates_path = ["_templates"]

# One page per public module, found by walking the package (private _modules are skipped).
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "none"  # the numpy-style Parameters sections say the types

numpydoc_show_class_members = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False
# PR02: a documented parameter the signature does not have (a stale docstring) is an error.
numpydoc_validation_checks = {"PR02"}

# The tutorial runs in the tests (tests/test_notebook.py); here it is shown as committed.
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
suppress_warnings = [
    "myst.header",  # the README starts at its own level
    # A module docstring's References, cited from its functions' docstrings: numpydoc
    # renames each docstring's citations, so the module's own look unreferenced.
    "ref.citation",
]

intersphinx_mapping = {}  # offline: no inventories fetched
html_theme = "alabaster"
html_title = f"pendulab {release}"
