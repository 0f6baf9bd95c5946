"""The transmittance companions of shadow maps, for lights whose casters include translucent ones.

A companion has the depth map's size and texel grid (a 2D texture beside a
:class:`~pvshadows.gl.textures.DepthMap`, a cube beside a
:class:`~pvshadows.gl.textures.DepthCube`) and holds ``GL_RGBA32F``: in red,
the product of the ``1 - opacity`` of every translucent surface over the
texel, and in alpha the nearest one's linear depth, both 1 where none lies
(``glsl/transmittance.frag``). Made with PyOpenGL, handed to a
``vtkTextureObject`` with ``AssignToExistingTexture`` so VTK's texture-unit
manager binds it for the receivers; it is attached as the colour of its own
framebuffer, which has no depth attachment.
"""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.framebuffer import finish_binding


class TransmittanceTexture:
    """A 2D ``RGBA32F`` transmittance companion with its own framebuffer.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns it.
    resolution : int
        Width and height (of each face for a cube) in texels, the depth map's.

    Attributes
    ----------
    resolution : int
        Size in texels.
    texture : vtk.vtkTextureObject
        VTK's handle on it, used to bind it to a texture unit.
    handle : int
        The GL texture name.
    """

    #: OpenGL target of the texture.
    target_name = "GL_TEXTURE_2D"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, resolution: int) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self.resolution = resolution
        target = getattr(gl, self.target_name)
        units = window.GetTextureUnitManager()
        unit = units.Allocate()
        window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        self.handle = int(gl.glGenTextures(1))
        gl.glBindTexture(target, self.handle)
        for image in self._images():
            gl.glTexImage2D(
                image, 0, gl.GL_RGBA32F, resolution, resolution, 0, gl.GL_RGBA, gl.GL_FLOAT, None
            )
        gl.glTexParameteri(target, gl.GL_TEXTURE_MAX_LEVEL, 0)
        gl.glBindTexture(target, 0)
        units.Free(unit)
        self.texture = vtk.vtkTextureObject()
        self.texture.SetContext(window)
        self.texture.AssignToExistingTexture(self.handle, target)
        for wrap in (self.texture.SetWrapS, self.texture.SetWrapT, self.texture.SetWrapR):
            wrap(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetMinificationFilter(vtk.vtkTextureObject.Nearest)
        self.texture.SetMagnificationFilter(vtk.vtkTextureObject.Nearest)
        self._framebuffer = int(gl.glGenFramebuffers(1))

    def _images(self) -> list[int]:
        return [self._gl.GL_TEXTURE_2D]

    def _attach(self, face: int | None) -> None:
        gl = self._gl
        gl.glFramebufferTexture2D(
            gl.GL_FRAMEBUFFER, gl.GL_COLOR_ATTACHMENT0, gl.GL_TEXTURE_2D, self.handle, 0
        )

    def bind_as_target(self, face: int | None = None) -> None:
        """Bind the framebuffer with this texture as its colour and a viewport of its size.

        Parameters
        ----------
        face : int, optional
            For a cube: attach only this face (0..5, GL order +X, -X, +Y, -Y,
            +Z, -Z); ``None`` attaches all six as one layered attachment, for
            a geometry shader that writes ``gl_Layer``.

        Raises
        ------
        RuntimeError
            If the driver reports the framebuffer incomplete.
        """
        gl = self._gl
        self._window.GetState().vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        self._attach(face)
        size = (self.resolution, self.resolution)
        finish_binding(gl, self._window, gl.GL_COLOR_ATTACHMENT0, size, "transmittance")

    def read(self) -> np.ndarray:
        """Return the texels as float32 ``(images, res, res, 4)`` (for tests and debugging).

        Returns
        -------
        numpy.ndarray
            One image for a 2D companion, six (GL face order) for a cube; red
            the transmittance, alpha the nearest translucent depth.
        """
        gl = self._gl
        target = getattr(gl, self.target_name)
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        gl.glBindTexture(target, self.handle)
        images = self._images()
        texels = np.empty((len(images), self.resolution, self.resolution, 4), np.float32)
        for number, image in enumerate(images):
            gl.glGetTexImage(image, 0, gl.GL_RGBA, gl.GL_FLOAT, texels[number])
        gl.glBindTexture(target, 0)
        units.Free(unit)
        return texels

    def release(self) -> None:
        """Delete the texture and framebuffer (the window's context must be current)."""
        if self._framebuffer:
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._framebuffer = 0
            self.texture.ReleaseGraphicsResources(self._window)
            self._gl.glDeleteTextures(1, [self.handle])


class TransmittanceCube(TransmittanceTexture):
    """A six-face ``RGBA32F`` transmittance companion of a point light's depth cube."""

    target_name = "GL_TEXTURE_CUBE_MAP"

    def _images(self) -> list[int]:
        return [self._gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face for face in range(6)]

    def _attach(self, face: int | None) -> None:
        gl = self._gl
        if face is None:
            gl.glFramebufferTexture(gl.GL_FRAMEBUFFER, gl.GL_COLOR_ATTACHMENT0, self.handle, 0)
        else:
            gl.glFramebufferTexture2D(
                gl.GL_FRAMEBUFFER,
                gl.GL_COLOR_ATTACHMENT0,
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                self.handle,
                0,
            )
