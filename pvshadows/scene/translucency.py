"""How much light a caster lets through: what its opacity leaves."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import vtk


def transmittance(actor: vtk.vtkActor) -> float:
    """Return the share of light one surface of an actor lets through: ``1 - opacity``.

    Parameters
    ----------
    actor : vtk.vtkActor
        A caster.

    Returns
    -------
    float
        From 0 (opaque) to 1 (fully transparent).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.translucency import transmittance
    >>> pl = pv.Plotter(off_screen=True)
    >>> transmittance(pl.add_mesh(pv.Sphere(), opacity=0.25))
    0.75
    """
    return 1.0 - min(max(float(actor.GetProperty().GetOpacity()), 0.0), 1.0)
