"""Sphinx configuration for the pvshadows documentation.

Build with ``sphinx-build -b html docs docs/_build/html``. The build runs every
gallery script in ``examples/`` off screen, the bench (``pvshadows bench``)
and the script that draws the "How it works" figures. For a faster build
while working on the pages, ``PVSHADOWS_DOCS_BENCH=quick`` runs a quick bench
and ``PVSHADOWS_DOCS_BENCH=reuse`` keeps the last one (see
``docs/_ext/pvshadows_docs.py``).
"""

import os
import sys
from pathlib import Path

if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import matplotlib

matplotlib.use("Agg")

import pyvista

import pvshadows

sys.path.insert(0, str(Path(__file__).parent / "_ext"))

# Off screen; plotters shown with pl.show() keep their picture for the scraper.
pyvista.BUILDING_GALLERY = True
pyvista.OFF_SCREEN = True

project = "pvshadows"
author = "pvshadows developers"
copyright = "pvshadows developers"
release = version = pvshadows.__version__

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "pvshadows_docs",
]

numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
autodoc_typehints = "none"

sphinx_gallery_conf = {
    "examples_dirs": "../examples",
    "gallery_dirs": "gallery",
    # Run every script, not only those named plot_*.py.
    "filename_pattern": r"\.py$",
    "within_subsection_order": "gallery_support.GalleryOrder",
    # The PNG files each cell saved (see docs/_ext/gallery_support.py), then matplotlib figures.
    "image_scrapers": ("gallery_support.scraper", "matplotlib"),
    "reset_modules": ("matplotlib", "gallery_support.close_plotters"),
    "reset_modules_order": "both",
    "remove_config_comments": True,
    "download_all_examples": False,
    "min_reported_time": 0,
}

html_theme = "pydata_sphinx_theme"
html_title = "pvshadows"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
html_static_path = ["_static"]
html_css_files = ["pvshadows.css"]
exclude_patterns = ["_build", "_generated"]
