"""Vertex and index buffers on the GPU, drawn by pvshadows' own passes.

Casters' triangles for the depth passes, shadow volumes' vertices and
adjacency indices, and an attribute-less array for full-screen passes.
"""

from __future__ import annotations

import ctypes

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.raw_calls import raw_calls

#: ``GL_UNSIGNED_INT``, the type of every index buffer here.
_UNSIGNED_INT = 0x1405


def _pointer(array: np.ndarray) -> ctypes.c_void_p | None:
    return ctypes.c_void_p(array.ctypes.data) if array.size else None


class IndexedBuffers:
    """Vertices (float32, 3 or 4 components), one uint32 index buffer and, optionally, an int each.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    vertices : numpy.ndarray
        ``(n, k)`` positions, ``k`` 3 or 4, already in a local frame.
    indices : numpy.ndarray
        Flat indices into ``vertices``.
    rows : numpy.ndarray, optional
        ``(n,)`` an integer per vertex, read as an ``int`` attribute (a
        caster's row in :class:`~pvshadows.gl.caster_batch.CasterBatch`).
    """

    def __init__(
        self,
        window: vtk.vtkOpenGLRenderWindow,
        vertices: np.ndarray,
        indices: np.ndarray,
        rows: np.ndarray | None = None,
    ) -> None:
        self._gl = gl = opengl_for(window)
        data = np.ascontiguousarray(vertices, dtype=np.float32)
        index = np.ascontiguousarray(indices, dtype=np.uint32).ravel()
        self.components = int(data.shape[1])
        self.n_indices = int(index.size)
        self._vertices, self._indices = (int(b) for b in gl.glGenBuffers(2))
        self._rows = 0 if rows is None else int(gl.glGenBuffers(1))
        self._arrays: dict[object, int] = {}
        self._fill(self._vertices, data)
        self._fill(self._indices, index)
        if rows is not None:
            self._fill(self._rows, np.ascontiguousarray(rows, dtype=np.int32))

    @classmethod
    def of_parts(
        cls,
        window: vtk.vtkOpenGLRenderWindow,
        vertices: list[np.ndarray],
        indices: list[np.ndarray],
        rows: np.ndarray,
    ) -> IndexedBuffers:
        """Return the buffers of many meshes, their vertices and indices one after another.

        Parameters
        ----------
        window : vtk.vtkOpenGLRenderWindow
            The window whose context owns the buffers.
        vertices : list of numpy.ndarray
            Each mesh's ``(n_i, 3)`` positions.
        indices : list of numpy.ndarray
            Each mesh's flat indices, already moved past the meshes before it.
        rows : numpy.ndarray
            An integer per vertex of all of them (see the constructor).

        Returns
        -------
        IndexedBuffers
            Empty buffers for no mesh.
        """
        stacked = np.concatenate(vertices) if vertices else np.zeros((0, 3))
        index = np.concatenate(indices) if indices else np.zeros(0, dtype=np.uint32)
        return cls(window, stacked, index, rows)

    def _fill(self, buffer: int, data: np.ndarray, start: int | None = None) -> None:
        """Fill a buffer with ``data``, or write ``data`` from byte ``start`` on.

        Bound as ``GL_COPY_WRITE_BUFFER``, a target no vertex array keeps (an
        index buffer bound as ``GL_ELEMENT_ARRAY_BUFFER`` joins whatever
        vertex array is bound). The raw entry points and a pointer spare
        PyOpenGL's array conversion (ms per call).
        """
        from OpenGL.raw.GL.VERSION.GL_1_5 import glBufferData, glBufferSubData

        gl = self._gl
        target = gl.GL_COPY_WRITE_BUFFER
        gl.glBindBuffer(target, buffer)
        if start is None:
            glBufferData(target, max(data.nbytes, 4), _pointer(data), gl.GL_STATIC_DRAW)
        else:
            glBufferSubData(target, start, data.nbytes, _pointer(data))
        gl.glBindBuffer(target, 0)

    def write(
        self, first_vertex: int, vertices: np.ndarray, first_index: int, indices: np.ndarray | None
    ) -> None:
        """Write over a range of the vertices and, when given, of the indices.

        Parameters
        ----------
        first_vertex : int
            The first vertex written.
        vertices : numpy.ndarray
            ``(m, k)`` positions.
        first_index : int
            The first index written.
        indices : numpy.ndarray or None
            Flat indices (into all the vertices), or ``None`` to keep them.
        """
        data = np.ascontiguousarray(vertices, dtype=np.float32)
        self._fill(self._vertices, data, 4 * self.components * first_vertex)
        if indices is not None:
            index = np.ascontiguousarray(indices, dtype=np.uint32).ravel()
            self._fill(self._indices, index, 4 * first_index)

    def vertex_array(self, location: int, row: int = -1) -> int:
        """Return the vertex array feeding these buffers to attribute ``location`` (made once).

        Parameters
        ----------
        location : int
            The positions' attribute.
        row : int, default: -1
            The ``int`` attribute that reads the rows given at creation, or -1.

        Returns
        -------
        int
            The vertex array's name.
        """
        key: object = location if row < 0 else (location, row)
        if key not in self._arrays:
            gl = self._gl
            array = int(gl.glGenVertexArrays(1))
            gl.glBindVertexArray(array)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._vertices)
            gl.glVertexAttribPointer(
                location, self.components, gl.GL_FLOAT, gl.GL_FALSE, 0, ctypes.c_void_p(0)
            )
            gl.glEnableVertexAttribArray(location)
            if row >= 0:
                gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._rows)
                gl.glVertexAttribIPointer(row, 1, gl.GL_INT, 0, ctypes.c_void_p(0))
                gl.glEnableVertexAttribArray(row)
            gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, self._indices)
            gl.glBindVertexArray(0)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, 0)
            self._arrays[key] = array
        return self._arrays[key]

    def draw(self, program: vtk.vtkShaderProgram, mode: int, first: int, count: int) -> None:
        """Draw ``count`` indices from index ``first`` with a bound program reading ``position``.

        Parameters
        ----------
        program : vtk.vtkShaderProgram
            The bound program.
        mode : int
            GL primitive, e.g. ``GL_TRIANGLES`` or ``GL_TRIANGLES_ADJACENCY``.
        first, count : int
            Range of the index buffer to draw.
        """
        if count <= 0:
            return
        gl = raw_calls()
        gl.bind(self.vertex_array(program.FindAttributeArray("position")))
        gl.draw(mode, count, _UNSIGNED_INT, 4 * first)
        gl.bind(0)

    def release(self) -> None:
        """Delete the buffers and vertex arrays (the context must be current)."""
        gl = self._gl
        if self._arrays:
            gl.glDeleteVertexArrays(len(self._arrays), list(self._arrays.values()))
            self._arrays.clear()
        if self._vertices:
            names = [self._vertices, self._indices] + ([self._rows] if self._rows else [])
            gl.glDeleteBuffers(len(names), names)
            self._vertices = self._indices = self._rows = 0


class TriangleBuffers(IndexedBuffers):
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

    def draw_triangles(self, program: vtk.vtkShaderProgram) -> None:
        """Draw all the triangles with a bound program that reads ``in vec3 position``.

        Parameters
        ----------
        program : vtk.vtkShaderProgram
            The bound program.
        """
        self.draw(program, self._gl.GL_TRIANGLES, 0, self.n_indices)


class EmptyArray:
    """A vertex array with no attributes, for full-screen passes that use ``gl_VertexID``.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns it.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._array = int(self._gl.glGenVertexArrays(1))

    def draw_triangle(self) -> None:
        """Draw one triangle of three attribute-less vertices (a full-screen triangle)."""
        gl = self._gl
        gl.glBindVertexArray(self._array)
        gl.glDrawArrays(gl.GL_TRIANGLES, 0, 3)
        gl.glBindVertexArray(0)

    def release(self) -> None:
        """Delete the vertex array."""
        if self._array:
            self._gl.glDeleteVertexArrays(1, [self._array])
            self._array = 0


def forget_pointer_records() -> None:
    """Drop what PyOpenGL keeps for the current context's ``glVertexAttribPointer`` calls.

    PyOpenGL holds every pointer given to ``glVertexAttribPointer`` per
    context, for as long as the process lives. Ours are offsets into
    buffer objects, not client memory, so once the vertex arrays are
    deleted nothing needs them; keeping them would grow memory with every
    plotter closed.
    """
    from OpenGL import contextdata

    contextdata.cleanupContext(contextdata.getContext())
