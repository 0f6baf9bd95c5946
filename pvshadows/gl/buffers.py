"""Vertex and index buffers holding a caster's triangles for the depth passes."""

from __future__ import annotations

import ctypes

import numpy as np
import vtk

from pvshadows.gl.binding import opengl_for


class TriangleBuffers:
    """One caster's triangles on the GPU: positions (float32) and indices (uint32).

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    points : numpy.ndarray
        ``(n, 3)`` positions, already shifted to a local origin.
    triangles : numpy.ndarray
        ``(m, 3)`` indices into ``points``.
    """

    def __init__(
        self, window: vtk.vtkOpenGLRenderWindow, points: np.ndarray, triangles: np.ndarray
    ) -> None:
        self._gl = gl = opengl_for(window)
        self.n_indices = int(triangles.size)
        self._vertices, self._indices = (int(b) for b in gl.glGenBuffers(2))
        self._arrays: dict[int, int] = {}
        positions = np.ascontiguousarray(points, dtype=np.float32)
        indices = np.ascontiguousarray(triangles, dtype=np.uint32)
        gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._vertices)
        gl.glBufferData(gl.GL_ARRAY_BUFFER, positions.nbytes, positions, gl.GL_STATIC_DRAW)
        gl.glBindBuffer(gl.GL_ARRAY_BUFFER, 0)
        gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, self._indices)
        gl.glBufferData(gl.GL_ELEMENT_ARRAY_BUFFER, indices.nbytes, indices, gl.GL_STATIC_DRAW)
        gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, 0)

    def _array_for(self, location: int) -> int:
        gl = self._gl
        if location not in self._arrays:
            array = int(gl.glGenVertexArrays(1))
            gl.glBindVertexArray(array)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._vertices)
            gl.glVertexAttribPointer(location, 3, gl.GL_FLOAT, gl.GL_FALSE, 0, ctypes.c_void_p(0))
            gl.glEnableVertexAttribArray(location)
            gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, self._indices)
            gl.glBindVertexArray(0)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, 0)
            self._arrays[location] = array
        return self._arrays[location]

    def draw(self, program: vtk.vtkShaderProgram) -> None:
        """Draw the triangles with a bound program that reads ``in vec3 position``.

        Parameters
        ----------
        program : vtk.vtkShaderProgram
            The bound program.
        """
        gl = self._gl
        gl.glBindVertexArray(self._array_for(program.FindAttributeArray("position")))
        gl.glDrawElements(gl.GL_TRIANGLES, self.n_indices, gl.GL_UNSIGNED_INT, ctypes.c_void_p(0))
        gl.glBindVertexArray(0)

    def release(self) -> None:
        """Delete the buffers and vertex arrays (the context must be current)."""
        gl = self._gl
        if self._arrays:
            gl.glDeleteVertexArrays(len(self._arrays), list(self._arrays.values()))
            self._arrays.clear()
        if self._vertices:
            gl.glDeleteBuffers(2, [self._vertices, self._indices])
            self._vertices = self._indices = 0
