"""Depth textures that hold shadow maps, and the framebuffers that fill them.

The GL texture is made with PyOpenGL (VTK does not wrap cube or layered
depth textures for Python) and handed to a ``vtkTextureObject`` with
``AssignToExistingTexture``, so VTK's texture-unit manager binds it and sets
its sampling parameters like any texture of its own.
"""

from __future__ import annotations

from typing import Any

import vtk

from pvshadows.gl.binding import opengl_for


class DepthCube:
    """A six-face depth cube map (``GL_DEPTH_COMPONENT32F``) with its framebuffer.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the texture.
    resolution : int
        Width and height of each face in texels.

    Attributes
    ----------
    resolution : int
        Face size in texels.
    texture : vtk.vtkTextureObject
        VTK's handle on the cube, used to bind it to a texture unit.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, resolution: int) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self.resolution = resolution
        units = window.GetTextureUnitManager()
        unit = units.Allocate()
        state = window.GetState()
        state.vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        self._handle = int(gl.glGenTextures(1))
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, self._handle)
        for face in range(6):
            gl.glTexImage2D(
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                0,
                gl.GL_DEPTH_COMPONENT32F,
                resolution,
                resolution,
                0,
                gl.GL_DEPTH_COMPONENT,
                gl.GL_FLOAT,
                None,
            )
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, 0)
        units.Free(unit)
        gl.glEnable(gl.GL_TEXTURE_CUBE_MAP_SEAMLESS)
        self.texture = vtk.vtkTextureObject()
        self.texture.SetContext(window)
        self.texture.AssignToExistingTexture(self._handle, gl.GL_TEXTURE_CUBE_MAP)
        self.texture.SetWrapS(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetWrapT(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetWrapR(vtk.vtkTextureObject.ClampToEdge)
        self.texture.SetDepthTextureCompare(True)
        self.texture.SetDepthTextureCompareFunction(vtk.vtkTextureObject.Lequal)
        self.set_linear(False)
        self._framebuffer = int(gl.glGenFramebuffers(1))

    def set_linear(self, linear: bool) -> None:
        """Choose nearest (one compare) or linear (hardware 2x2 compare) sampling.

        Parameters
        ----------
        linear : bool
            ``True`` for the hardware-filtered compare used by PCF.
        """
        mode = vtk.vtkTextureObject.Linear if linear else vtk.vtkTextureObject.Nearest
        self.texture.SetMinificationFilter(mode)
        self.texture.SetMagnificationFilter(mode)

    def bind_as_target(self, face: int | None = None) -> None:
        """Bind the framebuffer with the cube as its depth attachment.

        Parameters
        ----------
        face : int, optional
            Attach only this face (0..5, GL order +X, -X, +Y, -Y, +Z, -Z).
            ``None`` attaches all six as one layered attachment, for a
            geometry shader that writes ``gl_Layer``.
        """
        gl = self._gl
        state = self._window.GetState()
        state.vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        if face is None:
            gl.glFramebufferTexture(gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, self._handle, 0)
        else:
            gl.glFramebufferTexture2D(
                gl.GL_FRAMEBUFFER,
                gl.GL_DEPTH_ATTACHMENT,
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                self._handle,
                0,
            )
        gl.glDrawBuffer(gl.GL_NONE)
        gl.glReadBuffer(gl.GL_NONE)
        status = gl.glCheckFramebufferStatus(gl.GL_FRAMEBUFFER)
        if status != gl.GL_FRAMEBUFFER_COMPLETE:
            msg = f"the depth-cube framebuffer is incomplete (status 0x{int(status):x})"
            raise RuntimeError(msg)
        state.vtkglViewport(0, 0, self.resolution, self.resolution)

    def read_faces(self) -> Any:
        """Return the six faces' depths as a float32 array ``(6, res, res)``.

        Returns
        -------
        numpy.ndarray
            Depth (distance to the light over ``far``) per texel, for tests
            and debugging.
        """
        import numpy as np

        gl = self._gl
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, self._handle)
        faces = np.empty((6, self.resolution, self.resolution), np.float32)
        for face in range(6):
            gl.glGetTexImage(
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                0,
                gl.GL_DEPTH_COMPONENT,
                gl.GL_FLOAT,
                faces[face],
            )
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, 0)
        units.Free(unit)
        return faces

    def release(self) -> None:
        """Delete the texture and framebuffer (the window's context must be current)."""
        if self._handle:
            self.texture.ReleaseGraphicsResources(self._window)
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._gl.glDeleteTextures(1, [self._handle])
            self._handle = 0
            self._framebuffer = 0
