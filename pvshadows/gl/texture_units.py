"""Keep the textures pvshadows binds for a frame bound until the receivers draw."""

from __future__ import annotations

from pvshadows import _vtk as vtk

#: ``GL_TEXTURE0``: unit ``n`` is ``GL_TEXTURE0 + n``.
GL_TEXTURE0 = 0x84C0


def park_active_unit(window: vtk.vtkOpenGLRenderWindow) -> int:
    """Make a texture unit that holds none of the frame's textures the active one.

    Several of VTK's render passes (eye-dome lighting, SSAO, ...) create and
    resize their textures on whatever unit is active when they run, without
    allocating one. Left on the unit of the last shadow texture bound for the
    frame, they would replace it there before the receivers read it. Call
    this after binding every texture of the frame.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context is current.

    Returns
    -------
    int
        The unit made active (free: no texture is allocated to it), or -1
        when every unit is taken (the active unit is then left as it is).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.texture_units import park_active_unit
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> park_active_unit(pl.ren_win) >= 0
    True
    """
    units = window.GetTextureUnitManager()
    unit = units.Allocate()
    if unit < 0:
        return -1
    units.Free(unit)
    window.GetState().vtkglActiveTexture(GL_TEXTURE0 + unit)
    return unit
