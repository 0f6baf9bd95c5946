"""Read back what the renderer shows: one light's visibility per pixel.

The frame is drawn again with every receiver writing ``(visibility, 1, 0)``
and every other actor ``(0, 0, 0)`` over a black background, so the green
channel says whether a receiver is seen and red over green is the
visibility. That frame is drawn with one sample per pixel, so each pixel
shows the surface at its centre, as the reference's primary ray does: a
multisampled window would resolve a pixel on an object's outline to a
(gamma-encoded) blend of two surfaces' visibilities.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv
import vtk


def _window_pixels(window: vtk.vtkRenderWindow) -> np.ndarray:
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.ShouldRerenderOff()
    grab.ReadFrontBufferOn()
    grab.SetInputBufferTypeToRGB()
    grab.Update()
    image = grab.GetOutput()
    width, height, _ = image.GetDimensions()
    values = pv.convert_array(image.GetPointData().GetScalars())
    return values.reshape(height, width, -1)


def _renderer_box(renderer: vtk.vtkRenderer, width: int, height: int) -> tuple[slice, slice]:
    x0, y0, x1, y1 = renderer.GetViewport()
    cols = slice(round(x0 * width), round(x1 * width))
    rows = slice(round(y0 * height), round(y1 * height))
    return rows, cols


def read_visibility(
    plotter: pv.Plotter, renderer: vtk.vtkRenderer, vtk_index: int, shadows
) -> np.ndarray:
    """Draw the frame showing one light's visibility and read it back.

    Parameters
    ----------
    plotter : pyvista.Plotter
        The plotter whose window is drawn.
    renderer : vtk.vtkRenderer
        The renderer holding the light.
    vtk_index : int
        The light's index among switched-on lights.
    shadows : pvshadows.frame.RendererShadows
        The renderer's shadows, whose probe is switched for one frame.

    Returns
    -------
    numpy.ndarray
        float32 ``(H, W)``, row 0 at the top, NaN where no receiver is seen.
    """
    window = plotter.ren_win
    saved = (
        renderer.GetBackground(),
        renderer.GetGradientBackground(),
        renderer.GetTexturedBackground(),
        renderer.GetUseFXAA(),
        window.GetMultiSamples(),
    )
    renderer.SetBackground(0.0, 0.0, 0.0)
    renderer.GradientBackgroundOff()
    renderer.TexturedBackgroundOff()
    renderer.UseFXAAOff()
    window.SetMultiSamples(0)
    shadows.probe_index = vtk_index
    try:
        window.Render()
        pixels = _window_pixels(window).astype(np.float32) / 255.0
    finally:
        shadows.probe_index = -1
        renderer.SetBackground(*saved[0])
        renderer.SetGradientBackground(saved[1])
        renderer.SetTexturedBackground(saved[2])
        renderer.SetUseFXAA(saved[3])
        window.SetMultiSamples(saved[4])
        window.Render()
    rows, cols = _renderer_box(renderer, pixels.shape[1], pixels.shape[0])
    region = pixels[rows, cols][::-1]
    coverage = region[..., 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        shown = np.clip(region[..., 0] / coverage, 0.0, 1.0)
    return np.where(coverage >= 0.5, shown, np.nan).astype(np.float32)
