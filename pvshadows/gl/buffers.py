"""Vertex and index buffers on the GPU, drawn by pvshadows' own passes.

Casters' triangles for the depth passes, shadow volumes' vertices and
adjacency indices, and an attribute-less array for full-screen passes.
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.caster_batch import MIN_CASTERS, CasterBatch
from pvshadows.gl.raw_calls import raw_calls

#: ``GL_UNSIGNED_INT``, the type of every index buffer here.
_UNSIGNED_INT = 0x1405


def _pointer(array: np.ndarray) -> ctypes.c_void_p | None:
    return ctypes.c_void_p(array.ctypes.data) if array.size else None


class IndexedBuffers:
    """Vertices (float32, 3 or 4 components) and one uint32 index buffer on the GPU.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    vertices : numpy.ndarray
        ``(n, k)`` positions, ``k`` 3 or 4, already in a local frame.
    indices : numpy.ndarray
        Flat indices into ``vertices``.
    """

    def __init__(
        self, window: vtk.vtkOpenGLRenderWindow, vertices: np.ndarray, indices: np.ndarray
    ) -> None:
        self._gl = gl = opengl_for(window)
        data = np.ascontiguousarray(vertices, dtype=np.float32)
        index = np.ascontiguousarray(indices, dtype=np.uint32).ravel()
        self.components = int(data.shape[1])
        self.n_indices = int(index.size)
        self._vertices, self._indices = (int(b) for b in gl.glGenBuffers(2))
        self._arrays: dict[int, int] = {}
        gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._vertices)
        # The raw entry point and a pointer spare PyOpenGL's array conversion (ms per call).
        from OpenGL.raw.GL.VERSION.GL_1_5 import glBufferData

        glBufferData(gl.GL_ARRAY_BUFFER, max(data.nbytes, 4), _pointer(data), gl.GL_STATIC_DRAW)
        gl.glBindBuffer(gl.GL_ARRAY_BUFFER, 0)
        gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, self._indices)
        glBufferData(
            gl.GL_ELEMENT_ARRAY_BUFFER, max(index.nbytes, 4), _pointer(index), gl.GL_STATIC_DRAW
        )
        gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, 0)

    def vertex_array(self, location: int) -> int:
        """Return the vertex array feeding these buffers to attribute ``location`` (made once)."""
        gl = self._gl
        if location not in self._arrays:
            array = int(gl.glGenVertexArrays(1))
            gl.glBindVertexArray(array)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, self._vertices)
            gl.glVertexAttribPointer(
                location, self.components, gl.GL_FLOAT, gl.GL_FALSE, 0, ctypes.c_void_p(0)
            )
            gl.glEnableVertexAttribArray(location)
            gl.glBindBuffer(gl.GL_ELEMENT_ARRAY_BUFFER, self._indices)
            gl.glBindVertexArray(0)
            gl.glBindBuffer(gl.GL_ARRAY_BUFFER, 0)
            self._arrays[location] = array
        return self._arrays[location]

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
            gl.glDeleteBuffers(2, [self._vertices, self._indices])
            self._vertices = self._indices = 0


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


@dataclass(frozen=True)
class CasterDraws:
    """The casters one pass draws, side by side: one object per pass, not one per caster.

    Attributes
    ----------
    buffers : sequence of IndexedBuffers
        Each caster's triangles on the GPU.
    model_to_light : numpy.ndarray
        ``(n, 4, 4)`` float64: each caster's buffer coordinates to the light's space.
    culls : sequence of {"front", "back", None}
        Each caster's side of its triangles not to draw.
    batch : CasterBatch or None
        The snapshot's small casters in one vertex array, when there is one.
    rows : numpy.ndarray or None
        ``(n,)`` each caster's row in ``batch``, -1 for one drawn on its own.
    """

    buffers: Sequence[IndexedBuffers]
    model_to_light: np.ndarray
    culls: Sequence[str | None]
    batch: CasterBatch | None = None
    rows: np.ndarray | None = None

    def __len__(self) -> int:
        return len(self.buffers)

    def subset(self, keep: np.ndarray) -> CasterDraws:
        """Return the casters where ``keep`` (an ``(n,)`` bool array) is true.

        Parameters
        ----------
        keep : numpy.ndarray
            Which casters to keep.

        Returns
        -------
        CasterDraws
            Those casters, in the same order.
        """
        chosen = np.flatnonzero(keep).tolist()
        return CasterDraws(
            [self.buffers[i] for i in chosen],
            self.model_to_light[chosen],
            [self.culls[i] for i in chosen],
            self.batch,
            None if self.rows is None else self.rows[chosen],
        )

    def batched(self) -> np.ndarray:
        """Return which casters a pass draws through :attr:`batch`.

        Returns
        -------
        numpy.ndarray
            ``(n,)`` bool: the batch's casters, when the pass draws at least
            :data:`~pvshadows.gl.caster_batch.MIN_CASTERS` of them; else none.
        """
        if self.batch is None or self.rows is None:
            return np.zeros(len(self), dtype=bool)
        inside = self.rows >= 0
        return inside if int(inside.sum()) >= MIN_CASTERS else np.zeros(len(self), dtype=bool)


def draw_casters(
    programs: Callable[[bool], vtk.vtkShaderProgram],
    casters: CasterDraws,
    cull: Callable[[str | None], None],
) -> None:
    """Draw casters' triangles: the batched ones in a few calls, the others one by one.

    Parameters
    ----------
    programs : callable
        Binds and returns the pass's program, given whether it draws the
        batch (built with ``BATCHED``) or casters one by one (reading
        ``uniform mat4 modelToLight``), its other uniforms set.
    casters : CasterDraws
        What to draw: buffers, matrices and sides to cull.
    cull : callable
        Sets the side to cull (:class:`pvshadows.passes.gl_state.FaceCulling`).
    """
    if not len(casters):
        return
    batched = casters.batched()
    every, some = bool(batched.all()), bool(batched.any())
    if not every:
        draw_one_by_one(programs(False), casters.subset(~batched) if some else casters, cull)
    if some:
        part = casters if every else casters.subset(batched)
        assert part.batch is not None and part.rows is not None  # batched() said so
        part.batch.draw(programs(True), part.rows, part.model_to_light, part.culls, cull)


def draw_one_by_one(
    program: vtk.vtkShaderProgram,
    casters: CasterDraws,
    cull: Callable[[str | None], None],
) -> None:
    """Draw casters' triangles, each with its own ``mat4`` uniform, in few Python calls.

    Every caster's matrix is converted to float32 columns in one numpy call
    and set by location with the raw ``glUniformMatrix4fv``; each caster then
    costs that call, its vertex array's binding, its draw and a culling
    call when its side differs from the last caster's. Drawing casters one
    ``vtkShaderProgram.SetUniformMatrix4x4v`` at a time cost about three
    times as much.

    Parameters
    ----------
    program : vtk.vtkShaderProgram
        The bound program: ``in vec3 position`` and ``uniform mat4 modelToLight``.
    casters : CasterDraws
        What to draw: buffers, matrices and sides to cull.
    cull : callable
        Sets the side to cull (:class:`pvshadows.passes.gl_state.FaceCulling`).
    """
    gl = raw_calls()
    location = program.FindUniform("modelToLight")
    position = program.FindAttributeArray("position")
    columns = np.ascontiguousarray(casters.model_to_light.transpose(0, 2, 1), dtype=np.float32)
    base = columns.ctypes.data
    set_matrix, bind, draw = gl.matrix, gl.bind, gl.draw
    triangles = 0x0004  # GL_TRIANGLES
    side: str | bool | None = False  # not a side: the first caster sets culling
    for i, (buffers, culled) in enumerate(zip(casters.buffers, casters.culls, strict=True)):
        if not buffers.n_indices:
            continue
        set_matrix(location, 1, 0, base + 64 * i)
        if culled != side:
            cull(culled)
            side = culled
        bind(buffers.vertex_array(position))
        draw(triangles, buffers.n_indices, _UNSIGNED_INT, None)
    bind(0)


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
