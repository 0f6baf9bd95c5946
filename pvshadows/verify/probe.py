"""Read back what the renderer shows: one light's visibility per pixel.

The frame is drawn again with every receiver writing ``(visibility, 1, 0)``
and every other actor ``(0, 0, 0)`` over a black background, so the green
channel says whether a receiver is seen and red over green is the
visibility. That frame is drawn with one sample per pixel, so each pixel
shows the surface at its centre, as the reference's primary ray does: a
multisampled window would resolve a pixel on an object's outline to a
(gamma-encoded) blend of two surfaces' visibilities. SSAA's larger
framebuffer averages the channels like the samples of one pixel, so the green
one is then the share of the pixel covered by a receiver.

Image passes that recolour the finished frame (eye-dome lighting, SSAO,
blur, depth of field: ``vtkImageProcessingPass``) are left out of that
frame: they change colours, not where shadows fall, and would turn the
visibility they are given into something else. SSAA stays, since it changes
which surface each pixel shows. A scaled read (``scale=N``) draws the frame
in tiles exactly as ``pl.screenshot(scale=N)`` does.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv

from pvshadows import _vtk as vtk


def _window_pixels(window: vtk.vtkRenderWindow, scale: int) -> np.ndarray:
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.SetScale(scale)
    grab.FixBoundaryOn()
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


class FrameFailedError(RuntimeError):
    """The frame to read was drawn without shadows because pvshadows failed in it."""


def require_drawn(renderers: list) -> None:
    """Raise if the last frame of any of ``renderers`` failed and was drawn without shadows.

    Parameters
    ----------
    renderers : list of pvshadows.pipeline.frame.RendererShadows
        The renderers to check.

    Raises
    ------
    FrameFailedError
        Saying which light and pass failed, and the error.
    """
    for renderer in renderers:
        failure = renderer.last_frame.failure
        if renderer.error is not None and failure is not None:
            msg = (
                f"the last frame has no shadows to read: {failure} "
                "(pl.shadows.last_frame says the same)"
            )
            raise FrameFailedError(msg) from renderer.error


class _WithoutImagePasses:
    """Take the renderer's image passes out of its pass chain, and put them back."""

    def __init__(self, renderer: vtk.vtkRenderer) -> None:
        self._renderer = renderer
        self._top = renderer.GetPass()
        chain: list[vtk.vtkRenderPass] = []
        current = self._top
        while current is not None and len(chain) < 64:
            chain.append(current)
            delegate = getattr(current, "GetDelegatePass", None)
            current = delegate() if delegate is not None else None
        self._kept = [p for p in chain if not isinstance(p, vtk.vtkImageProcessingPass)]
        self._changed = len(self._kept) != len(chain)
        self._delegates = [p.GetDelegatePass() for p in self._kept[:-1]]

    def __enter__(self) -> None:
        if not self._changed:
            return
        self._renderer.SetPass(self._kept[0] if self._kept else None)
        for outer, inner in zip(self._kept, self._kept[1:], strict=False):
            outer.SetDelegatePass(inner)

    def __exit__(self, *exc: object) -> None:
        if not self._changed:
            return
        for outer, inner in zip(self._kept, self._delegates, strict=False):
            outer.SetDelegatePass(inner)
        self._renderer.SetPass(self._top)


def read_visibility(
    plotter: pv.Plotter, renderer: vtk.vtkRenderer, vtk_index: int, shadows, scale: int = 1
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
    shadows : pvshadows.pipeline.frame.RendererShadows
        The renderer's shadows, whose probe is switched for one frame.
    scale : int, default: 1
        Draw the frame ``scale`` times larger each way, in tiles, as
        ``pl.screenshot(scale=scale)`` does.

    Returns
    -------
    numpy.ndarray
        float32 ``(H, W)`` (times ``scale``), row 0 at the top, NaN where no
        receiver is seen.
    """
    window = plotter.ren_win
    assert window is not None
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
        with _WithoutImagePasses(renderer):
            window.Render()
            require_drawn([shadows])
            pixels = _window_pixels(window, scale).astype(np.float32) / 255.0
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
