"""VTK's own shadows (``Plotter.enable_shadows()``), measured the same way for comparison.

VTK's shadow-map pass offers no way to read its shadow factor, so it is
inferred from three frames of the same view: the plain frame, the frame with
VTK's shadows, and the frame with the light at zero intensity (switching it
off would make VTK light the scene with a default light). Where the light
adds anything, visibility is the share of its contribution that is left.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

from pvshadows import _vtk as vtk

#: Smallest contribution of the light (0..1 colour) for a pixel to be judged.
MIN_CONTRIBUTION = 4.0 / 255.0


def _frame(plotter: pv.Plotter) -> np.ndarray:
    plotter.render()
    image = plotter.screenshot(return_img=True)
    assert image is not None
    return image.astype(np.float64).mean(axis=2) / 255.0


def builtin_visibility(plotter: pv.Plotter, light: vtk.vtkLight) -> np.ndarray:
    """Return the visibility VTK's ``enable_shadows()`` shows for one light, per pixel.

    Parameters
    ----------
    plotter : pyvista.Plotter
        A plotter that has rendered, without pvshadows enabled.
    light : pyvista.Light
        The light to judge; other lights should be off.

    Returns
    -------
    numpy.ndarray
        float32 ``(H, W)`` like ``pl.shadows.visibility()``: 0 where VTK's
        shadow removes the light, 1 where it keeps it, NaN where the light
        adds too little to judge.
    """
    plain = _frame(plotter)
    intensity = light.GetIntensity()
    light.SetIntensity(0.0)
    ambient = _frame(plotter)
    light.SetIntensity(intensity)
    plotter.enable_shadows()  # type: ignore[call-arg]  # pyvista: decorated, self untyped
    try:
        shadowed = _frame(plotter)
    finally:
        plotter.disable_shadows()  # type: ignore[call-arg]  # pyvista: decorated, self untyped
        plotter.render()
    added = plain - ambient
    with np.errstate(invalid="ignore", divide="ignore"):
        visibility = np.clip((shadowed - ambient) / added, 0.0, 1.0)
    return np.where(added > MIN_CONTRIBUTION, visibility, np.nan).astype(np.float32)
