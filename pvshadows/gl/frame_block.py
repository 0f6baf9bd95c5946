"""The receivers' uniform block: what changes with the camera, set once per frame.

Each light's view-to-light matrix changes whenever the camera moves, and
every receiver reads it. Held as a per-receiver uniform, a camera move would
cost one call per receiver and light; held in one uniform buffer
(``glsl/frame_block.glsl``), it costs one upload per frame whatever the
number of receivers.

The block sits at binding point 0, where GL puts every program's blocks
until told otherwise: so the very first frame of a receiver, drawn with a
program VTK has just compiled, reads it, with no call per program. VTK's
own OpenGL code uses no uniform blocks; the buffer is bound there at the
start of each of the renderer's frames, after pvshadows' own passes.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for

#: The uniform buffer binding point of the block: every program's default.
BINDING = 0


class FrameBlock:
    """One uniform buffer holding every shadowed light's view-to-light matrix.

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

    def update(self, matrices: Mapping[int, object]) -> None:
        """Send this frame's matrices (by VTK light index) and bind the block.

        The buffer holds at least 8 rows, and twice the rows asked for
        whenever more are: never fewer than any receiver's block declares.

        Parameters
        ----------
        matrices : dict
            ``(4, 4)`` view-to-light matrices by light index; the rows of
            other lights are zero.
        """
        from OpenGL.raw.GL.VERSION.GL_1_5 import glBufferData
        from OpenGL.raw.GL.VERSION.GL_3_0 import glBindBufferBase

        gl = self._gl
        self._capacity = max(self._capacity, 2 * (max(matrices, default=-1) + 1))
        block = np.zeros((self._capacity, 4, 4), dtype=np.float32)
        for index, matrix in matrices.items():
            block[index] = np.asarray(matrix).T  # GLSL reads matrices by columns
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
