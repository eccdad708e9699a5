"""Sphinx configuration of the rotorlab documentation (built by ``tests/unit/test_docs.py``).

Build: ``python -m sphinx -W -b html docs docs/_build/html`` from the repository root. The
tutorials are MyST notebooks (text files), executed by myst-nb at every build; the case-file
reference and the built-in case pages are generated from the pydantic schema and the case files
by the local extension ``_ext/rotorlab_docs.py``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
SRC = DOCS.parent / "src"
# The docs describe this checkout: autodoc imports it, and so do the tutorials' kernels.
sys.path.insert(0, str(SRC))
sys.path.insert(0, str(DOCS / "_ext"))
os.environ["PYTHONPATH"] = os.pathsep.join(
    [str(SRC), *filter(None, os.environ.get("PYTHONPATH", "").split(os.pathsep))])

import rotorlab  # noqa: E402

project = "rotorlab"
author = "the rotorlab authors"
copyright = "the rotorlab authors, MIT licence"
release = version = rotorlab.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "rotorlab_docs",
]
exclude_patterns = ["_build", "jupyter_execute", ".jupyter_cache"]
# Furo: a content column wide enough for the code cells, which scroll rather than being cut off.
html_theme = "furo"
html_static_path = ["_static"]
html_css_files = ["rotorlab.css"]  # code cells of up to 100 characters fit the column
smartquotes = False  # keys and values are quoted as in the files
html_title = f"rotorlab {release}"

# API reference: numpydoc-style docstrings through napoleon, members in source order.
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_param = False  # types as text: "float", "array_like, shape (n,)" are not links
napoleon_use_ivar = True  # "Attributes" as fields: a property documented there is not a second object
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the docstrings state types (and units)
autosummary_generate = False

# Tutorials: MyST notebooks executed at every build; an error in a cell fails the build.
nb_execution_mode = "force"
nb_execution_timeout = 300
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True  # files the tutorials write stay out of the source tree
myst_enable_extensions = ["dollarmath", "colon_fence"]
suppress_warnings = ["mystnb.unknown_mime_type"]
