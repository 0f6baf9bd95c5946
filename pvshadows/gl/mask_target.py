"""The framebuffer shadow volumes are counted in, and the per-light masks it fills.

Shadow volumes are counted in a framebuffer of pvshadows' own, the size of
the renderer's viewport: a ``GL_DEPTH24_STENCIL8`` renderbuffer holds the
scene's depth (from a depth pre-pass) and the stencil count, and one
single-channel ``GL_R8`` texture per light holds the result, the *shadow
mask*: 1 where the light reaches the surface seen in the pixel, 0 where a
shadow volume holds it. Owning the framebuffer means the window needs no
stencil buffer of its own, and multisampled windows work unchanged.

Each mask texture is handed to a ``vtkTextureObject`` with
``AssignToExistingTexture``, so VTK's texture-unit manager binds it for the
receivers like any texture of its own.
"""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.framebuffer import finish_binding


class MaskTexture:
    """One light's shadow mask: an ``R8`` texture the size of the viewport.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the texture.
    width, height : int
        Size in pixels.

    Attributes
    ----------
    texture : vtk.vtkTextureObject
        VTK's handle on it, used to bind it to a texture unit.
    handle : int
        The GL texture name.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, width: int, height: int) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self.size = (int(width), int(height))
        units = window.GetTextureUnitManager()
        unit = units.Allocate()
        window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        self.handle = int(gl.glGenTextures(1))
        gl.glBindTexture(gl.GL_TEXTURE_2D, self.handle)
        gl.glTexImage2D(
            gl.GL_TEXTURE_2D, 0, gl.GL_R8, width, height, 0, gl.GL_RED, gl.GL_UNSIGNED_BYTE, None
        )
        gl.glTexParameteri(gl.GL_TEXTURE_2D, gl.GL_TEXTURE_MAX_LEVEL, 0)
        gl.glBindTexture(gl.GL_TEXTURE_2D, 0)
        units.Free(unit)
        self.texture = vtk.vtkTextureObject()
        self.texture.SetContext(window)
        self.texture.AssignToExistingTexture(self.handle, gl.GL_TEXTURE_2D)
        self.texture.SetWrapS(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetWrapT(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetMinificationFilter(vtk.vtkTextureObject.Nearest)
        self.texture.SetMagnificationFilter(vtk.vtkTextureObject.Nearest)

    def read(self) -> np.ndarray:
        """Return the mask as a uint8 array ``(height, width)``, row 0 at the bottom.

        Returns
        -------
        numpy.ndarray
            255 where lit, 0 where in a shadow volume (for tests and debugging).
        """
        gl = self._gl
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        gl.glBindTexture(gl.GL_TEXTURE_2D, self.handle)
        width, height = self.size
        pixels = np.empty((height, width), np.uint8)
        gl.glPixelStorei(gl.GL_PACK_ALIGNMENT, 1)
        gl.glGetTexImage(gl.GL_TEXTURE_2D, 0, gl.GL_RED, gl.GL_UNSIGNED_BYTE, pixels)
        gl.glBindTexture(gl.GL_TEXTURE_2D, 0)
        units.Free(unit)
        return pixels

    def release(self) -> None:
        """Delete the texture (the window's context must be current)."""
        if self.handle:
            self.texture.ReleaseGraphicsResources(self._window)
            self._gl.glDeleteTextures(1, [self.handle])
            self.handle = 0


class VolumeTarget:
    """A framebuffer with a depth-stencil renderbuffer, to which masks are attached in turn.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns it.
    width, height : int
        Size in pixels (the renderer's viewport).
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, width: int, height: int) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self.size = (int(width), int(height))
        self._renderbuffer = int(gl.glGenRenderbuffers(1))
        gl.glBindRenderbuffer(gl.GL_RENDERBUFFER, self._renderbuffer)
        gl.glRenderbufferStorage(gl.GL_RENDERBUFFER, gl.GL_DEPTH24_STENCIL8, width, height)
        gl.glBindRenderbuffer(gl.GL_RENDERBUFFER, 0)
        self._framebuffer = int(gl.glGenFramebuffers(1))
        self.stencil_bits = 8

    def bind(self, mask: MaskTexture | None) -> None:
        """Bind the framebuffer, with ``mask`` as its colour attachment (or none).

        Parameters
        ----------
        mask : MaskTexture or None
            The light's mask to write, or ``None`` for the depth pre-pass.

        Raises
        ------
        RuntimeError
            If the driver reports the framebuffer incomplete.
        """
        gl = self._gl
        state = self._window.GetState()
        state.vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        gl.glFramebufferRenderbuffer(
            gl.GL_FRAMEBUFFER,
            gl.GL_DEPTH_STENCIL_ATTACHMENT,
            gl.GL_RENDERBUFFER,
            self._renderbuffer,
        )
        gl.glFramebufferTexture2D(
            gl.GL_FRAMEBUFFER,
            gl.GL_COLOR_ATTACHMENT0,
            gl.GL_TEXTURE_2D,
            mask.handle if mask is not None else 0,
            0,
        )
        buffer = gl.GL_COLOR_ATTACHMENT0 if mask is not None else gl.GL_NONE
        finish_binding(gl, self._window, buffer, self.size, "shadow-volume")

    def release(self) -> None:
        """Delete the framebuffer and renderbuffer (the window's context must be current)."""
        if self._framebuffer:
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._gl.glDeleteRenderbuffers(1, [self._renderbuffer])
            self._framebuffer = self._renderbuffer = 0
