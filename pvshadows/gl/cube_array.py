"""The depth cubes of many point lights as layers of one cube map array.

A receiver then reads every point light through one sampler in one GLSL
loop, so its shader holds each filter once, however many lights shadow it
(``glsl/shadow_cube_array.glsl``); with one ``samplerCubeShadow`` per light
the driver compiles one filter per light (32 lights with 4-tap PCF: about 11
s per shader variant on llvmpipe). Each light holds a *slot*: six layers of
the array, filled like a cube of its own. The array grows (doubling, the
cubes already drawn copied across) when a light needs a slot and none is
free, and goes when no light holds one.
"""

from __future__ import annotations

from types import ModuleType

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.capabilities import extension_names, gl_version, image_copies_supported
from pvshadows.gl.framebuffer import finish_binding


def cube_arrays_supported(gl: ModuleType) -> bool:
    """Tell whether the current context has cube map arrays and image copies.

    Parameters
    ----------
    gl : module
        ``OpenGL.GL`` for the current context.

    Returns
    -------
    bool
        ``True`` for OpenGL 4.3 or later, or where both
        ``GL_ARB_texture_cube_map_array`` and ``GL_ARB_copy_image`` are there.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.cube_array import cube_arrays_supported
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> cube_arrays_supported(opengl_for(pl.ren_win))  # Mesa's OpenGL 4.5
    True
    """
    if gl_version(gl) >= (4, 3):
        return True
    return image_copies_supported(gl) and "GL_ARB_texture_cube_map_array" in extension_names(gl)


class CubeArray:
    """A ``GL_TEXTURE_CUBE_MAP_ARRAY`` of float depth cubes, handed out one slot per light.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the array.
    resolution : int
        Texels per side of every face.

    Attributes
    ----------
    resolution : int
        Texels per side of every face.
    capacity : int
        Cubes the array holds now.
    texture : vtk.vtkTextureObject or None
        VTK's handle on the array (binds it to units, sets compare and
        filtering); ``None`` while no slot is held.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, resolution: int) -> None:
        self._window = window
        self._gl = opengl_for(window)
        self.resolution = resolution
        self.capacity = 0
        self.texture: vtk.vtkTextureObject | None = None
        self._handle = 0
        self._framebuffer = 0
        #: The array attached whole to the framebuffer and checked complete (0: none).
        self._attached = 0
        #: Slots held by lights.
        self.taken: set[int] = set()
        self._retired: list[tuple[vtk.vtkTextureObject, int]] = []
        #: Times the array was made or grown (for tests: one per doubling).
        self.allocations = 0

    def take(self, wanted: int = 1) -> int:
        """Hand out a free slot, growing the array when none is free.

        Parameters
        ----------
        wanted : int, default: 1
            Slots the array should hold at least once it grows (the lights
            that may need one this frame), so a first frame allocates once.

        Returns
        -------
        int
            The slot: cube ``slot`` of the array, layers ``6 * slot`` to
            ``6 * slot + 5``.
        """
        free = [slot for slot in range(self.capacity) if slot not in self.taken]
        if not free:
            old = self.capacity
            self._grow(max(2 * old, old + 1, wanted))
            free = [old]
        self.taken.add(free[0])
        return free[0]

    def give_back(self, slot: int) -> None:
        """Free a slot; the array goes when no slot is held.

        Parameters
        ----------
        slot : int
            A slot from :meth:`take`.
        """
        self.taken.discard(slot)
        if not self.taken:
            self.release()

    @property
    def handle(self) -> int:
        """The OpenGL texture name of the array now."""
        return self._handle

    def _grow(self, capacity: int) -> None:
        gl = self._gl
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        handle = int(gl.glGenTextures(1))
        target = gl.GL_TEXTURE_CUBE_MAP_ARRAY
        gl.glBindTexture(target, handle)
        size = self.resolution
        gl.glTexImage3D(
            target,
            0,
            gl.GL_DEPTH_COMPONENT32F,
            size,
            size,
            6 * capacity,
            0,
            gl.GL_DEPTH_COMPONENT,
            gl.GL_FLOAT,
            None,
        )
        # one level: complete before VTK sets its filters, as glCopyImageSubData requires
        gl.glTexParameteri(target, gl.GL_TEXTURE_MAX_LEVEL, 0)
        gl.glBindTexture(target, 0)
        units.Free(unit)
        if self._handle:
            layers = 6 * self.capacity
            gl.glCopyImageSubData(
                self._handle, target, 0, 0, 0, 0, handle, target, 0, 0, 0, 0, size, size, layers
            )
            # units may still point at the old array this frame: delete it after the frame
            assert self.texture is not None
            self._retired.append((self.texture, self._handle))
        gl.glEnable(gl.GL_TEXTURE_CUBE_MAP_SEAMLESS)
        texture = vtk.vtkTextureObject()
        texture.SetContext(self._window)
        texture.AssignToExistingTexture(handle, target)
        for wrap in (texture.SetWrapS, texture.SetWrapT, texture.SetWrapR):
            wrap(vtk.vtkTextureObject.ClampToEdge)
        texture.SetDepthTextureCompare(True)
        texture.SetDepthTextureCompareFunction(vtk.vtkTextureObject.Lequal)
        texture.SetMinificationFilter(vtk.vtkTextureObject.Nearest)
        texture.SetMagnificationFilter(vtk.vtkTextureObject.Nearest)
        if not self._framebuffer:
            self._framebuffer = int(gl.glGenFramebuffers(1))
        self.texture, self._handle, self.capacity = texture, handle, capacity
        self._attached = 0  # a name GL hands out again may be a new texture
        self.allocations += 1

    def bind_cleared(self, slot: int, face: int | None = None, *, clear: bool = True) -> None:
        """Bind the framebuffer on one slot, its faces cleared to depth 1.

        Parameters
        ----------
        slot : int
            The light's slot.
        face : int, optional
            Attach only this face (0..5, GL order +X, -X, +Y, -Y, +Z, -Z) and
            clear it; ``None`` clears the slot's six faces and attaches the
            whole array as one layered attachment, for a geometry shader that
            writes ``gl_Layer = 6 * slot + face``.
        clear : bool, default: True
            ``False`` binds without clearing (to draw over what the faces hold).
        """
        gl = self._gl
        self._window.GetState().vtkglBindFramebuffer(gl.GL_FRAMEBUFFER, self._framebuffer)
        size = (self.resolution, self.resolution)
        # an array holding this slot only is cleared whole through the layered attachment
        alone = face is None and self.capacity == 1
        layered = face is None and (alone or not clear)
        if layered and self._attached == self._handle:  # attached and checked last time
            self._window.GetState().vtkglViewport(0, 0, *size)
            if clear:
                gl.glClear(gl.GL_DEPTH_BUFFER_BIT)
            return
        self._attached = 0
        faces = () if layered else range(6) if face is None else (face,)
        for order, each in enumerate(faces):
            gl.glFramebufferTextureLayer(
                gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, self._handle, 0, 6 * slot + each
            )
            if order == 0:  # one layer complete means every layer of the array is
                finish_binding(gl, self._window, gl.GL_NONE, size, "shadow-map")
            if clear:
                gl.glClear(gl.GL_DEPTH_BUFFER_BIT)
        if face is None:
            gl.glFramebufferTexture(gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, self._handle, 0)
            finish_binding(gl, self._window, gl.GL_NONE, size, "shadow-map")
            self._attached = self._handle
            if alone and clear:
                gl.glClear(gl.GL_DEPTH_BUFFER_BIT)

    def read_faces(self, slot: int) -> np.ndarray:
        """Return one slot's six faces as float32 ``(6, res, res)`` (for tests and debugging).

        Parameters
        ----------
        slot : int
            The light's slot.

        Returns
        -------
        numpy.ndarray
            Depth (distance to the light over ``far``) per texel.
        """
        gl = self._gl
        size = self.resolution
        layers = np.empty((6 * self.capacity, size, size), np.float32)
        units = self._window.GetTextureUnitManager()
        unit = units.Allocate()
        self._window.GetState().vtkglActiveTexture(gl.GL_TEXTURE0 + unit)
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP_ARRAY, self._handle)
        gl.glGetTexImage(
            gl.GL_TEXTURE_CUBE_MAP_ARRAY, 0, gl.GL_DEPTH_COMPONENT, gl.GL_FLOAT, layers
        )
        gl.glBindTexture(gl.GL_TEXTURE_CUBE_MAP_ARRAY, 0)
        units.Free(unit)
        return layers[6 * slot : 6 * slot + 6].copy()

    def end_frame(self) -> None:
        """Delete the arrays this one grew out of (no unit points at them after the frame)."""
        for texture, handle in self._retired:
            texture.ReleaseGraphicsResources(self._window)
            self._gl.glDeleteTextures(1, [handle])
        self._retired.clear()

    def release(self) -> None:
        """Delete the array and its framebuffer (the window's context must be current)."""
        self.end_frame()
        if self._framebuffer:
            self._gl.glDeleteFramebuffers(1, [self._framebuffer])
            self._framebuffer = 0
        if self.texture is not None:
            self.texture.ReleaseGraphicsResources(self._window)
            self._gl.glDeleteTextures(1, [self._handle])
        self.texture, self._handle, self.capacity, self._attached = None, 0, 0, 0
        self.taken.clear()


class CubeSlot:
    """One light's cube in a :class:`CubeArray`, drawn and bound like a cube of its own.

    Parameters
    ----------
    array : CubeArray
        The array.
    wanted : int, default: 1
        Passed to :meth:`CubeArray.take`.

    Attributes
    ----------
    slot : int
        The cube's index in the array (its layer in GLSL's ``vec4(direction, layer)``).
    """

    def __init__(self, array: CubeArray, wanted: int = 1) -> None:
        self._array = array
        self.slot = array.take(wanted)

    @property
    def resolution(self) -> int:
        """Texels per side of each face."""
        return self._array.resolution

    @property
    def layer_base(self) -> int:
        """First layer-face of the slot, for the depth pass's ``gl_Layer``."""
        return 6 * self.slot

    @property
    def texture(self) -> vtk.vtkTextureObject:
        """VTK's handle on the whole array (to bind it to a unit)."""
        assert self._array.texture is not None  # a held slot keeps the array
        return self._array.texture

    @property
    def target(self) -> int:
        """The OpenGL texture target."""
        return int(self._array._gl.GL_TEXTURE_CUBE_MAP_ARRAY)

    @property
    def handle(self) -> int:
        """The OpenGL texture name of the array."""
        return self._array.handle

    def bind_cleared(self, face: int | None = None) -> None:
        """Bind the framebuffer on this cube, cleared (see :meth:`CubeArray.bind_cleared`)."""
        self._array.bind_cleared(self.slot, face)

    def bind_as_target(self, face: int | None = None) -> None:
        """Bind the framebuffer on this cube without clearing it, to draw over what it holds."""
        self._array.bind_cleared(self.slot, face, clear=False)

    def read_faces(self) -> np.ndarray:
        """Return the six faces' depths as float32 ``(6, res, res)`` (for tests and debugging)."""
        return self._array.read_faces(self.slot)

    def release(self) -> None:
        """Give the slot back to the array."""
        self._array.give_back(self.slot)
