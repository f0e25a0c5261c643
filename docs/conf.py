"""Sphinx configuration: the API reference built from the docstrings (`make docs`; CI builds it
with -W, so a warning fails the build)."""

import os
import sys

sys.path.insert(0, os.path.abspath("../src"))

project = "roughcontact"
author = "roughcontact contributors"
copyright = "2026, roughcontact contributors"
extensions = ["sphinx.ext.autodoc", "myst_parser"]
# the guides are Markdown (MyST); dollar maths and heading anchors as GitHub renders them
myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "description"
# numba-compiled kernels and the workflow's plotting stack are not part of the API reference
autodoc_mock_imports = ["matplotlib", "snakemake", "yaml", "jsonschema"]
exclude_patterns = ["_build"]
html_theme = "alabaster"
nitpicky = False
suppress_warnings = ["toc.not_readable"]

# The docstrings are written as plain text with Unicode mathematics (|x| is an absolute value,
# indentation lays out formulas), not reStructuredText: show each verbatim, exactly as help()
# does, instead of letting docutils misread it. Signatures, members and the page structure
# still come from autodoc.


def _verbatim(app, what, name, obj, options, lines):
    if any(line.strip() for line in lines):
        lines[:] = ["::", ""] + [f"    {line}" for line in lines] + [""]


def setup(app):
    app.connect("autodoc-process-docstring", _verbatim)
