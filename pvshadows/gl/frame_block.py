"""The receivers' uniform block: each light's matrices and parameters, set once per frame.

Each light's view-to-light matrix changes whenever the camera moves, its
parameters (far distance, texel size, cone, a sun's fit) whenever it or its
casters move, and every receiver reads them. Held as per-receiver uniforms,
such a frame would cost one call per receiver and light; held in one uniform
buffer (``glsl/frame_block.glsl``: one ``PvsLight`` per VTK light index), it
costs one upload per frame whatever the number of receivers.

The block sits at binding point 0, where GL puts every program's blocks
until told otherwise: so the very first frame of a receiver, drawn with a
program VTK has just compiled, reads it, with no call per program. VTK's
own OpenGL code uses no uniform blocks; the buffer is bound there at the
start of each of the renderer's frames, after pvshadows' own passes.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for

_EYE = np.eye(4)
#: The uniform buffer binding point of the block: every program's default.
BINDING = 0


class LightEntry(NamedTuple):
    """One light's ``PvsLight`` entry of the frame's uniform block (``glsl/frame_block.glsl``).

    Attributes
    ----------
    view_to_light : numpy.ndarray
        ``(4, 4)``: view coordinates to the light's space.
    pack : tuple
        The four columns of the pack: params, cone, bias and filter
        (radius in texels, taps, layer in a cube array, 0).
    light_to_clip : numpy.ndarray or None
        ``(4, 4)``: light space to a spot map's clip space; ``None`` for
        the identity.
    """

    view_to_light: np.ndarray
    pack: tuple
    light_to_clip: np.ndarray | None


class FrameBlock:
    """One uniform buffer holding every shadowed light's ``PvsLight`` entry.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffer.

    Attributes
    ----------
    uploads : int
        Times the matrices changed and were sent to the GPU.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._buffer = int(self._gl.glGenBuffers(1))
        self._capacity = 8
        self._data = b""
        self.uploads = 0

    def update(self, entries: Mapping[int, LightEntry]) -> None:
        """Send this frame's entries (by VTK light index) and bind the block.

        The buffer holds at least 8 entries, and twice the entries asked for
        whenever more are: never fewer than any receiver's block declares.

        Parameters
        ----------
        entries : dict
            Each light's entry by its index
            (:func:`pvshadows.shaders.library.take_light_entries`); the
            entries of other lights are zero.
        """
        from OpenGL.raw.GL.VERSION.GL_1_5 import glBufferData
        from OpenGL.raw.GL.VERSION.GL_3_0 import glBindBufferBase

        gl = self._gl
        self._capacity = max(self._capacity, 2 * (max(entries, default=-1) + 1))
        block = np.zeros((self._capacity, 3, 4, 4), dtype=np.float32)
        # GLSL reads matrices by columns: each stored matrix is the transpose
        for index, (view_to_light, pack, light_to_clip) in entries.items():
            block[index, 0] = view_to_light.T
            block[index, 1] = pack
            block[index, 2] = _EYE if light_to_clip is None else light_to_clip.T
        data = block.tobytes()
        if data != self._data:
            gl.glBindBuffer(gl.GL_UNIFORM_BUFFER, self._buffer)
            glBufferData(gl.GL_UNIFORM_BUFFER, len(data), data, gl.GL_DYNAMIC_DRAW)
            gl.glBindBuffer(gl.GL_UNIFORM_BUFFER, 0)
            self._data = data
            self.uploads += 1
        glBindBufferBase(gl.GL_UNIFORM_BUFFER, BINDING, self._buffer)

    def release(self) -> None:
        """Delete the buffer."""
        if self._buffer:
            self._gl.glDeleteBuffers(1, [self._buffer])
            self._buffer = 0
