"""Where VTK actually draws a renderer's geometry this frame: origin and size in pixels.

A renderer's viewport in the window is not always the rectangle its actors
are drawn into. ``pl.screenshot(scale=N)`` (``vtkWindowToImageFilter``)
draws the image in tiles: the window reports N times its size, and each
tile is drawn at the window's real size with the camera's window centre and
view angle changed for that tile (``vtkViewport::GetTiledSizeAndOrigin``).
``pl.enable_anti_aliasing("ssaa")`` (``vtkSSAAPass``) draws the renderer
into a framebuffer of its own, ``sqrt(5)`` times larger each way, from the
origin; eye-dome lighting and the other image passes
(``vtkImageProcessingPass``) draw into a framebuffer of the renderer's own
size, from the origin. Screen-space masks (shadow volumes, planar shadows)
are built in this rectangle, so that a receiver's ``gl_FragCoord`` finds
its own pixel in them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pvshadows import _vtk as vtk

#: How much larger each way ``vtkSSAAPass`` draws than its target (VTK's ``sqrt(5.0)``).
SSAA_FACTOR = math.sqrt(5.0)


@dataclass(frozen=True)
class RenderTarget:
    """The pixel rectangle a renderer's geometry is drawn into.

    Attributes
    ----------
    origin : tuple of int
        Lower-left corner in the bound framebuffer, in pixels.
    size : tuple of int
        Width and height in pixels.
    """

    origin: tuple[int, int]
    size: tuple[int, int]


def _passes(renderer: vtk.vtkRenderer) -> list[vtk.vtkRenderPass]:
    chain: list[vtk.vtkRenderPass] = []
    current = vtk.vtkRenderer.GetPass(renderer)
    while current is not None and len(chain) < 64:
        chain.append(current)
        delegate = getattr(current, "GetDelegatePass", None)
        current = delegate() if delegate is not None else None
    return chain


def tiled_viewport(renderer: vtk.vtkRenderer) -> RenderTarget:
    """Return the renderer's part of the current tile, as ``vtkViewport::GetTiledSizeAndOrigin``.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer (in a window).

    Returns
    -------
    RenderTarget
        Its origin and size in the window's framebuffer for this tile (the
        whole window when no tiled image is being drawn).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.render_target import tiled_viewport
    >>> pl = pv.Plotter(off_screen=True, window_size=(400, 300), shape=(1, 2))
    >>> tiled_viewport(pl.renderers[1])
    RenderTarget(origin=(200, 0), size=(200, 300))
    """
    # VTK's own methods, called on the class: PyVista's wrappers check every attribute
    window = vtk.vtkRenderer.GetVTKWindow(renderer)
    width, height = vtk.vtkWindow.GetSize(window)
    tile = vtk.vtkWindow.GetTileViewport(window)
    port = vtk.vtkViewport.GetViewport(renderer)

    def clamp(value: float) -> float:
        return min(max(value, 0.0), 1.0)

    u0, v0 = clamp(port[0] - tile[0]), clamp(port[1] - tile[1])
    u1 = min(clamp(port[2] - tile[0]), tile[2] - tile[0])
    v1 = min(clamp(port[3] - tile[1]), tile[3] - tile[1])
    x0, y0 = int(u0 * width + 0.5), int(v0 * height + 0.5)
    x1, y1 = int(u1 * width + 0.5), int(v1 * height + 0.5)
    return RenderTarget((x0, y0), (max(x1 - x0, 0), max(y1 - y0, 0)))


def render_target(renderer: vtk.vtkRenderer) -> RenderTarget:
    """Return where the renderer's actors are drawn in this frame.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer about to be drawn (call it from its ``StartEvent``).

    Returns
    -------
    RenderTarget
        The tiled viewport in the window; with a ``vtkSSAAPass`` in the
        renderer's passes, that size times :data:`SSAA_FACTOR` (rounded
        down, as VTK does) from the origin; with any other image pass, the
        same size from the origin.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.render_target import render_target
    >>> pl = pv.Plotter(off_screen=True, window_size=(400, 300))
    >>> pl.enable_anti_aliasing("ssaa")
    >>> render_target(pl.renderer)
    RenderTarget(origin=(0, 0), size=(894, 670))
    """
    viewport = tiled_viewport(renderer)
    chain = _passes(renderer)
    if any(isinstance(p, vtk.vtkSSAAPass) for p in chain):
        width, height = viewport.size
        return RenderTarget((0, 0), (int(width * SSAA_FACTOR), int(height * SSAA_FACTOR)))
    if any(isinstance(p, vtk.vtkImageProcessingPass) for p in chain):
        return RenderTarget((0, 0), viewport.size)
    return viewport
