"""Sphinx-gallery support for the pvshadows examples.

The examples run off screen and save their pictures into the current folder
(``pl.screenshot("name.png")``), and one plotter often spans several cells.
PyVista's own scraper screenshots and closes every plotter at the end of each
cell, which would end such a script at its first cell. The scraper here shows,
after each cell, the PNG files the cell wrote (sphinx-gallery runs each
example in its own folder) — or, for a cell that wrote none, the picture of
each plotter it showed with ``pl.show()`` — and leaves the plotters open for
the cells that follow; :func:`close_plotters` closes them when the example
ends. So the gallery shows exactly the pictures a user running the script
gets. Matplotlib figures left open go through sphinx-gallery's own
``"matplotlib"`` scraper.

Sphinx-gallery finds these by name (``"gallery_support.scraper"``), so the
configuration stays picklable.
"""

from __future__ import annotations

import shutil
import time
from pathlib import Path

import pyvista as pv
from PIL import Image

#: The order of the gallery; scripts not named here follow, by file name.
ORDER = (
    "bulb_room.py",
    "terrain_low_sun.py",
    "soft_shadows.py",
    "shadow_volumes.py",
    "planar_shadows.py",
    "demo_scene.py",
    "accuracy_vs_time.py",
)


class SavedPictures:
    """Sphinx-gallery image scraper: the pictures a cell saved; plotters stay open."""

    def __init__(self) -> None:
        self.started = time.time()
        self._files: dict[Path, int] = {}
        self._shown: dict[str, object] = {}

    def __repr__(self) -> str:
        return "<gallery_support.SavedPictures>"

    def start(self) -> None:
        """Forget what was shown: a new example starts."""
        self.started = time.time()
        self._files.clear()
        self._shown.clear()

    def _new_files(self, folder: Path) -> list[Path]:
        found = []
        for path in folder.glob("*.png"):
            stamp = path.stat().st_mtime_ns
            if stamp >= self.started * 1e9 and self._files.get(path) != stamp:
                self._files[path] = stamp
                found.append((stamp, path))
        return [path for _, path in sorted(found)]

    def _shown_pictures(self) -> list:
        found = []
        for key, plotter in list(pv.plotting.plotter._ALL_PLOTTERS.items()):
            image = getattr(plotter, "last_image", None)
            if image is not None and self._shown.get(key) is not image:
                self._shown[key] = image
                found.append(image)
        return found

    def __call__(self, block, block_vars, gallery_conf) -> str:
        from sphinx_gallery.scrapers import figure_rst

        names = []
        files = self._new_files(Path(block_vars["src_file"]).parent)
        shown = self._shown_pictures()
        for source in files:
            target = next(block_vars["image_path_iterator"])
            shutil.copyfile(source, target)
            names.append(target)
        if not files:
            for image in shown:
                target = next(block_vars["image_path_iterator"])
                Image.fromarray(image).save(target)
                names.append(target)
        return figure_rst(names, gallery_conf["src_dir"])


#: The scraper instance ``image_scrapers`` names.
scraper = SavedPictures()


def close_plotters(gallery_conf, fname) -> None:
    """Close every plotter left open, before and after each example (``reset_modules``)."""
    pv.close_all()
    scraper.start()


class GalleryOrder:
    """Sort key of the examples: :data:`ORDER` first, then the rest by file name."""

    def __init__(self, src_dir: str) -> None:
        self.src_dir = src_dir

    def __repr__(self) -> str:
        return "<gallery_support.GalleryOrder>"

    def __call__(self, filename: str) -> tuple[int, str]:
        name = Path(filename).name
        return (ORDER.index(name) if name in ORDER else len(ORDER), name)
