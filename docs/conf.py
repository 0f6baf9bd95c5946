"""Sphinx configuration for the pvshadows documentation."""

import os
import sys

if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import pvshadows

project = "pvshadows"
author = "pvshadows developers"
release = version = pvshadows.__version__
extensions = ["sphinx.ext.autodoc", "numpydoc"]
numpydoc_show_class_members = False
html_theme = "pydata_sphinx_theme"
html_title = "pvshadows"
exclude_patterns = ["_build"]
