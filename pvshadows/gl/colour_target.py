"""A framebuffer with one colour attachment and nothing else, to draw masks into.

Planar shadows need no depth and no stencil: each light's mask
(:class:`pvshadows.gl.mask_target.MaskTexture`) is attached in turn and
drawn with the camera's projection, at the size of the renderer's viewport.
"""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.framebuffer import finish_binding
from pvshadows.gl.mask_target import MaskTexture


class ColourTarget:
    """A framebuffer object to which masks are attached in turn.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns it.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self._framebuffer = int(gl.glGenFramebuffers(1))

    def bind(self, mask: MaskTexture) -> None:
        """Bind the framebuffer with ``mask`` as its colour, and a viewport of the mask's size.

        Parameters
        ----------
        mask : MaskTexture
            The mask to draw into.

        Raises
        ------
        RuntimeError
            If the driver reports the framebuffer incomplete.
        """
        gl = self._gl
        state = self._window.GetState()
        state.vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        gl.glFramebufferTexture2D(
            gl.GL_FRAMEBUFFER, gl.GL_COLOR_ATTACHMENT0, gl.GL_TEXTURE_2D, mask.handle, 0
        )
        finish_binding(gl, self._window, gl.GL_COLOR_ATTACHMENT0, mask.size, "planar-shadow")

    def release(self) -> None:
        """Delete the framebuffer (the window's context must be current)."""
        if self._framebuffer:
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._framebuffer = 0
