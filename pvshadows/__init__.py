"""Real-time shadows for PyVista scenes, measured against ray-traced visibility.

Importing the package registers the ``shadows`` plotter component, so every
:class:`pyvista.Plotter` has ``pl.shadows``. Installing it does the same
through the ``pyvista.plotter_components`` entry point, without an import.

Examples
--------
>>> import pyvista as pv
>>> import pvshadows
>>> pl = pv.Plotter(off_screen=True)
>>> pl.shadows.enabled
False
"""

from __future__ import annotations

import pyvista as pv

from pvshadows.component import ShadowsComponent

__version__ = "0.1.0"
__all__ = ["ShadowsComponent", "__version__"]

pv.register_plotter_component("shadows")(ShadowsComponent)
