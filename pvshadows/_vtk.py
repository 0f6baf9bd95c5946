"""VTK's classes, from the few VTK modules PyVista has loaded already.

``import vtk`` loads every one of VTK's Python modules: 2.3 s here after
PyVista, more than the rest of the first ``pl.shadows`` together. pvshadows'
modules ``from pvshadows import _vtk as vtk`` instead and write ``vtk.vtkActor``
as before: a name is looked up in the modules below (which PyVista's plotting
loads anyway), and only a name found in none of them imports all of ``vtk``.

Examples
--------
>>> from pvshadows import _vtk as vtk
>>> vtk.vtkActor.__module__
'vtkmodules.vtkRenderingCore'
"""

from __future__ import annotations

import importlib
from typing import Any

_MODULES = (
    "vtkCommonCore",
    "vtkCommonMath",
    "vtkCommonDataModel",
    "vtkCommonExecutionModel",
    "vtkRenderingCore",
    "vtkRenderingOpenGL2",
)


def __getattr__(name: str) -> Any:
    """Return VTK's ``name``, from the first of :data:`_MODULES` that has it, else from ``vtk``.

    Parameters
    ----------
    name : str
        A VTK class or constant, e.g. ``"vtkActor"`` or ``"VTK_PBR"``.

    Returns
    -------
    Any
        It, kept in this module so the next lookup is a plain attribute read.
    """
    if name.startswith("__"):
        raise AttributeError(name)
    for module in _MODULES:
        value = getattr(importlib.import_module(f"vtkmodules.{module}"), name, None)
        if value is not None:
            break
    else:
        import vtk

        value = getattr(vtk, name)
    globals()[name] = value
    return value
