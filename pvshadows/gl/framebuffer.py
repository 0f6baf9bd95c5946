"""The last step of binding one of pvshadows' framebuffers: buffers, completeness, viewport."""

from __future__ import annotations

from types import ModuleType

from pvshadows import _vtk as vtk


def finish_binding(
    gl: ModuleType,
    window: vtk.vtkOpenGLRenderWindow,
    buffer: int,
    size: tuple[int, int],
    what: str,
) -> None:
    """Select the bound framebuffer's draw and read buffer, check it, and set the viewport.

    Call it after binding the framebuffer and attaching its images.

    Parameters
    ----------
    gl : module
        ``OpenGL.GL`` for the window's platform.
    window : vtk.vtkOpenGLRenderWindow
        The window whose context is current; its state tracks the viewport.
    buffer : int
        ``GL_COLOR_ATTACHMENT0`` to draw colour, ``GL_NONE`` for depth or stencil only.
    size : tuple of int
        Width and height of the attached images.
    what : str
        The framebuffer's name in the error, for example ``"shadow-map"``.

    Raises
    ------
    RuntimeError
        If the driver reports the framebuffer incomplete, with its status.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.framebuffer import finish_binding
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> GL = opengl_for(pl.ren_win)
    >>> pl.ren_win.GetState().vtkglBindFramebuffer(GL.GL_FRAMEBUFFER, GL.glGenFramebuffers(1))
    >>> finish_binding(GL, pl.ren_win, GL.GL_NONE, (8, 8), "empty")
    Traceback (most recent call last):
    ...
    RuntimeError: the empty framebuffer is incomplete (status 0x8cd7)
    """
    gl.glDrawBuffer(buffer)
    gl.glReadBuffer(buffer)
    status = gl.glCheckFramebufferStatus(gl.GL_FRAMEBUFFER)
    if status != gl.GL_FRAMEBUFFER_COMPLETE:
        msg = f"the {what} framebuffer is incomplete (status 0x{int(status):x})"
        raise RuntimeError(msg)
    window.GetState().vtkglViewport(0, 0, *size)
