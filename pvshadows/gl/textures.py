"""Depth textures that hold shadow maps, and the framebuffers that fill them.

A 2D map is VTK's own ``vtkTextureObject`` (``AllocateDepth``). VTK does not
make cube or layered depth textures for Python, so a cube is made with
PyOpenGL and handed to a ``vtkTextureObject`` with ``AssignToExistingTexture``.
Either way VTK's texture-unit manager binds the texture and sets its sampling
parameters like any texture of its own.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.framebuffer import finish_binding
from pvshadows.gl.raw_calls import image_copy


class DepthTexture:
    """A float depth texture used as a shadow map, with its own framebuffer.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the texture.
    resolution : int
        Width and height of the map (of each face for a cube) in texels.

    Attributes
    ----------
    resolution : int
        Size in texels.
    texture : vtk.vtkTextureObject
        VTK's handle on the texture, used to bind it to a texture unit.
    """

    #: OpenGL target of the texture.
    target_name = "GL_TEXTURE_2D"
    #: First layer-face the depth pass writes, and how many (six for a cube).
    layer_base, faces = 0, 1

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, resolution: int) -> None:
        self._window = window
        self._gl = opengl_for(window)
        self.resolution = resolution
        self.texture = self._create()
        self.texture.SetDepthTextureCompare(True)
        self.texture.SetDepthTextureCompareFunction(vtk.vtkTextureObject.Lequal)
        self.set_linear(False)
        self._framebuffer = int(self._gl.glGenFramebuffers(1))
        #: What the framebuffer holds attached and checked complete: ``(face,)`` (``None``
        #: for all faces), or nothing yet. It stays so until another face is asked for.
        self._attached: tuple[int | None, ...] = ()

    @property
    def target(self) -> int:
        """The OpenGL texture target."""
        return getattr(self._gl, self.target_name)

    @property
    def handle(self) -> int:
        """The OpenGL texture name."""
        return int(self.texture.GetHandle())

    def _create(self) -> vtk.vtkTextureObject:
        texture = vtk.vtkTextureObject()
        texture.SetContext(self._window)
        texture.AllocateDepth(self.resolution, self.resolution, vtk.vtkTextureObject.Float32)
        texture.SetWrapS(vtk.vtkTextureObject.ClampToBorder)
        texture.SetWrapT(vtk.vtkTextureObject.ClampToBorder)
        texture.SetBorderColor(1.0, 1.0, 1.0, 1.0)
        return texture

    def set_linear(self, linear: bool) -> None:
        """Choose nearest (one compare) or linear (hardware 2x2 compare) sampling.

        Parameters
        ----------
        linear : bool
            ``True`` for the hardware-filtered compare used by the filters.
        """
        mode = vtk.vtkTextureObject.Linear if linear else vtk.vtkTextureObject.Nearest
        self.texture.SetMinificationFilter(mode)
        self.texture.SetMagnificationFilter(mode)

    def _attach(self, face: int | None) -> None:
        gl = self._gl
        gl.glFramebufferTexture2D(
            gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, gl.GL_TEXTURE_2D, self.handle, 0
        )

    def bind_as_target(self, face: int | None = None) -> None:
        """Bind the framebuffer with this texture as its depth attachment.

        Parameters
        ----------
        face : int, optional
            For a cube: attach only this face (0..5, GL order +X, -X, +Y, -Y,
            +Z, -Z); ``None`` attaches all six as one layered attachment, for
            a geometry shader that writes ``gl_Layer``.
        """
        gl = self._gl
        state = self._window.GetState()
        state.vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        if self._attached != (face,):
            self._attached = ()
            self._attach(face)
            finish_binding(gl, self._window, gl.GL_NONE, (self.resolution,) * 2, "shadow-map")
            self._attached = (face,)
        else:
            state.vtkglViewport(0, 0, self.resolution, self.resolution)

    def bind_cleared(self, face: int | None = None) -> None:
        """Bind the framebuffer as :meth:`bind_as_target` does and clear the attached depth.

        Parameters
        ----------
        face : int, optional
            As for :meth:`bind_as_target`.
        """
        self.bind_as_target(face)
        self._gl.glClear(self._gl.GL_DEPTH_BUFFER_BIT)

    def release(self) -> None:
        """Delete the texture and framebuffer (the window's context must be current)."""
        if self._framebuffer:
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._framebuffer = 0
            self.texture.ReleaseGraphicsResources(self._window)


class CopyTarget(Protocol):
    """A depth texture, or a cube's layers of a larger one, to copy a map into."""

    @property
    def resolution(self) -> int:
        """Its size in texels."""

    @property
    def handle(self) -> int:
        """The OpenGL texture name."""

    @property
    def target(self) -> int:
        """The OpenGL texture target."""

    @property
    def layer_base(self) -> int:
        """Its first layer (a cube's first face)."""


def copy_depth(source: DepthTexture, target: CopyTarget) -> None:
    """Copy a map's depth into another map of the same size and kind, on the GPU.

    Needs ``glCopyImageSubData``
    (:func:`~pvshadows.gl.capabilities.image_copies_supported`).

    Parameters
    ----------
    source : DepthTexture
        The map copied (a cube copies its six faces).
    target : DepthTexture or CubeSlot
        Where it goes: a texture of the same kind, or a cube's slot of an array.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.gl.textures import DepthCube, copy_depth
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> source, target = DepthCube(pl.ren_win, 4), DepthCube(pl.ren_win, 4)
    >>> source.bind_cleared()
    >>> copy_depth(source, target)
    >>> bool((target.read_faces() == 1.0).all())
    True
    """
    if target.resolution != source.resolution:
        msg = f"a {source.resolution} texel map cannot be copied into a {target.resolution} one"
        raise ValueError(msg)
    size = source.resolution
    image_copy()(
        source.handle, source.target, 0, 0, 0, source.layer_base,
        target.handle, target.target, 0, 0, 0, target.layer_base,
        size, size, source.faces,
    )  # fmt: skip


class DepthMap(DepthTexture):
    """A 2D depth map (``GL_DEPTH_COMPONENT32F``) for spot and directional lights.

    Outside the map the border holds depth 1, so nothing outside a map's
    coverage is shadowed.
    """


class DepthCube(DepthTexture):
    """A six-face depth cube map (``GL_DEPTH_COMPONENT32F``) for point lights."""

    target_name = "GL_TEXTURE_CUBE_MAP"
    faces = 6

    def _create(self) -> vtk.vtkTextureObject:
        gl = self._gl
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        self._handle = int(gl.glGenTextures(1))
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, self._handle)
        for face in range(6):
            gl.glTexImage2D(
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                0,
                gl.GL_DEPTH_COMPONENT32F,
                self.resolution,
                self.resolution,
                0,
                gl.GL_DEPTH_COMPONENT,
                gl.GL_FLOAT,
                None,
            )
        # one level: complete before VTK sets its filters, as glCopyImageSubData requires
        gl.glTexParameteri(gl.GL_TEXTURE_CUBE_MAP, gl.GL_TEXTURE_MAX_LEVEL, 0)
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, 0)
        units.Free(unit)
        gl.glEnable(gl.GL_TEXTURE_CUBE_MAP_SEAMLESS)
        texture = vtk.vtkTextureObject()
        texture.SetContext(self._window)
        texture.AssignToExistingTexture(self._handle, gl.GL_TEXTURE_CUBE_MAP)
        texture.SetWrapS(vtk.vtkTextureObject.ClampToEdge)
        texture.SetWrapT(vtk.vtkTextureObject.ClampToEdge)
        texture.SetWrapR(vtk.vtkTextureObject.ClampToEdge)
        return texture

    def _attach(self, face: int | None) -> None:
        gl = self._gl
        if face is None:
            gl.glFramebufferTexture(gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, self.handle, 0)
        else:
            gl.glFramebufferTexture2D(
                gl.GL_FRAMEBUFFER,
                gl.GL_DEPTH_ATTACHMENT,
                gl.GL_TEXTURE_CUBE_MAP_POSITIVE_X + face,
                self.handle,
                0,
            )

    def read_faces(self) -> np.ndarray:
        """Return the six faces' depths as float32 ``(6, res, res)`` (for tests and debugging).

        Returns
        -------
        numpy.ndarray
            Depth (distance to the light over ``far``) per texel.
        """
        gl = self._gl
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP, self.handle)
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
        """Delete the cube and its framebuffer (the window's context must be current)."""
        handle = self.handle
        super().release()
        if handle:
            self._gl.glDeleteTextures(1, [handle])
