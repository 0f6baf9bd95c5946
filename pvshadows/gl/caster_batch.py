"""Many small casters in one set of buffers, drawn by a depth pass in a few calls.

Drawn one by one, a caster costs a pass its matrix, its vertex array's
binding and its draw: about 4 microseconds of CPU each, 4 ms a pass over
1 000 casters. Here every caster of up to :data:`SMALL` triangles shares one
vertex buffer, one index buffer and one vertex array; each vertex also
carries its caster's row, and the vertex stage reads that caster's matrix
from a uniform array (``BATCHED`` in ``glsl/map_depth.vert`` and
``glsl/cube_depth.vert``). A pass then sets the
matrices of a chunk of rows in one call and draws the chunk's casters with
one ``glMultiDrawElements`` per side to cull: a few calls for any number of
casters. Positions and matrices are the float32 values the one-by-one draw
uses, so the depths written are the same.

A caster's triangles stay in the batch while only its pose changes; new
points of the same size are written over its own range; any other change
of the casters builds the batch again.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from itertools import compress

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.raw_calls import raw_calls
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import CASTERS, Snapshot

#: Casters of at most this many triangles go into the batch; a bigger one is
#: drawn on its own, where its draw call is a small part of its cost.
SMALL = 65_536
#: A pass draws through the batch from this many of its casters on.
MIN_CASTERS = 16
#: The most rows one chunk of matrices holds.
MAX_CHUNK = 256
_UNSIGNED_INT, _TRIANGLES = 0x1405, 0x0004
#: The sides to cull, by the small integers that stand for them.
_SIDE_NAMES = (None, "front", "back")


def chunk_rows(
    window: vtk.vtkOpenGLRenderWindow, vectors: int = 0, *, geometry: bool = False
) -> int:
    """Return how many casters' uniforms a stage can hold in one set of arrays.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        A window whose context is current.
    vectors : int, default: 0
        ``vec4`` uniforms per caster besides its matrix.
    geometry : bool, default: False
        Whether the geometry stage reads them (the vertex stage otherwise).

    Returns
    -------
    int
        ``GL_MAX_VERTEX_UNIFORM_COMPONENTS`` (or ``GL_MAX_GEOMETRY_...``),
        less room for the pass's other uniforms, over the floats of one
        caster's uniforms, at most :data:`MAX_CHUNK` and at least 8.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.caster_batch import chunk_rows
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> 8 <= chunk_rows(pl.ren_win) <= 256
    True
    """
    gl = opengl_for(window)
    limit = (
        gl.GL_MAX_GEOMETRY_UNIFORM_COMPONENTS if geometry else gl.GL_MAX_VERTEX_UNIFORM_COMPONENTS
    )
    components = int(gl.glGetIntegerv(limit))
    return int(min(MAX_CHUNK, max(8, (components - 64) // (16 + 4 * vectors))))


def worth_batching(casters: int) -> bool:
    """Return whether so many casters are drawn through a batch (:data:`MIN_CASTERS` or more).

    Parameters
    ----------
    casters : int
        Casters of a scene, or of a pass, that the batch could hold.

    Returns
    -------
    bool
        ``True`` from :data:`MIN_CASTERS` on.

    Examples
    --------
    >>> from pvshadows.gl.caster_batch import worth_batching
    >>> worth_batching(4), worth_batching(500)
    (False, True)
    """
    return casters >= MIN_CASTERS


def _batched(state: ActorState) -> bool:
    return 0 < state.triangles.n_triangles <= SMALL


class CasterBatch:
    """The small casters of a snapshot in one vertex array.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    casters : list of ActorState
        The snapshot's casters, in order.

    Attributes
    ----------
    rows : numpy.ndarray
        ``(n,)`` each caster's row in the batch, -1 for one drawn on its own.
    chunk : int
        Rows per chunk of matrices (:func:`chunk_rows`).
    calls : int
        Matrix chunks and multi-draws submitted so far (a test counts them).
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, casters: list[ActorState]) -> None:
        self.chunk = chunk_rows(window)
        self.calls = 0
        batched = np.fromiter(map(_batched, casters), bool, len(casters))
        self.rows = np.where(batched, np.cumsum(batched) - 1, -1)
        self._triangles = [state.triangles for state in compress(casters, batched.tolist())]
        vertex_counts = np.array([len(t.points) for t in self._triangles], dtype=np.int64)
        index_counts = np.array([t.triangles.size for t in self._triangles], dtype=np.int64)
        self._first_vertex = np.cumsum(vertex_counts) - vertex_counts
        self._first_index = np.cumsum(index_counts) - index_counts
        #: Each batch row's index count, and where its indices start (bytes), for the draws.
        self._counts = index_counts.astype(np.int32)
        self._offsets = (4 * self._first_index).astype(np.uintp)
        starts = self._first_vertex.tolist()
        points = [t.points for t in self._triangles]
        indices = [
            t.triangles.ravel() + first for t, first in zip(self._triangles, starts, strict=True)
        ]
        owners = np.repeat(np.arange(len(self._triangles), dtype=np.int32), vertex_counts)
        self._buffers = IndexedBuffers.of_parts(window, points, indices, owners)

    def __len__(self) -> int:
        return len(self._triangles)

    def refresh(self, casters: list[ActorState], changed: Sequence[tuple[int, ActorState]]) -> bool:
        """Take the new states of some casters; return ``False`` when the batch must be built again.

        Parameters
        ----------
        casters : list of ActorState
            The snapshot's casters (the same actors, in the same order, as
            the batch was built from).
        changed : sequence of tuple
            ``(row in casters, new state)`` of the casters replaced.

        Returns
        -------
        bool
            Whether the batch now holds every caster's triangles: a caster
            that only moved changes nothing; new points of the same size are
            written over its range; anything else cannot be patched.
        """
        if len(casters) != len(self.rows):
            return False
        for row, state in changed:
            at = int(self.rows[row])
            if (at >= 0) != _batched(state):
                return False
            if at < 0:
                continue
            old, new = self._triangles[at], state.triangles
            if new is old:
                continue
            if len(new.points) != len(old.points) or new.triangles.size != old.triangles.size:
                return False
            first = int(self._first_vertex[at])
            same = np.array_equal(new.triangles, old.triangles)
            indices = None if same else new.triangles.ravel() + first
            self._buffers.write(first, new.points, int(self._first_index[at]), indices)
            self._triangles[at] = new
        return True

    def draw(
        self,
        program: vtk.vtkShaderProgram,
        rows: np.ndarray,
        columns: np.ndarray,
        culls: Sequence[str | None],
        cull: Callable[[str | None], None],
        vectors: Sequence[tuple[str, np.ndarray]] = (),
        chunk: int = 0,
    ) -> None:
        """Draw some of the batch's casters with a bound program built with ``BATCHED`` rows.

        Parameters
        ----------
        program : vtk.vtkShaderProgram
            The bound program: ``in vec3 position``, ``in int casterRow``,
            ``uniform mat4 modelToLights[chunk]`` and ``uniform int rowBase``
            (``BATCHED`` in the depth passes' vertex stages).
        rows : numpy.ndarray
            ``(k,)`` the batch rows to draw.
        columns : numpy.ndarray
            ``(k, 4, 4)`` float32: their buffer coordinates to the light's
            space, by columns (:attr:`~pvshadows.gl.caster_draws.CasterDraws.columns`).
        culls : sequence of {"front", "back", None}
            Their sides not to draw.
        cull : callable
            Sets the side to cull.
        vectors : sequence of tuple, optional
            ``(name, values)``: more ``vec4`` per caster, ``values`` ``(k, 4)``
            float32, set as the uniform array ``name + "s"`` with the matrices.
        chunk : int, optional
            Rows per chunk of uniforms, at most :attr:`chunk` (the program's
            ``BATCHED``); :attr:`chunk` by default.
        """
        if not len(rows):
            return
        gl = raw_calls()
        chunk = chunk or self.chunk
        in_order = len(rows) < 2 or not bool((rows[1:] < rows[:-1]).any())
        if in_order and len(rows) == len(self):  # every row: no gaps to fill
            every = columns
            assert every.dtype == np.float32 and every.flags.c_contiguous  # read by address
            extras = [v for _, v in vectors]
            assert all(v.dtype == np.float32 and v.flags.c_contiguous for v in extras)
        else:
            every = np.zeros((len(self), 4, 4), dtype=np.float32)
            every[rows] = columns
            extras = [np.zeros((len(self), 4), dtype=np.float32) for _ in vectors]
            for extra, (_, values) in zip(extras, vectors, strict=True):
                extra[rows] = values
        if any(culls):
            sides = np.array([_SIDE_NAMES.index(c) for c in culls], dtype=np.int8)
        else:
            sides = np.zeros(len(rows), dtype=np.int8)
        if not in_order:
            order = np.argsort(rows, kind="stable")
            rows, sides = rows[order], sides[order]
        matrices = program.FindUniform("modelToLights")
        base_location = program.FindUniform("rowBase")
        extra_locations = [program.FindUniform(name + "s") for name, _ in vectors]
        position, row = (program.FindAttributeArray(n) for n in ("position", "casterRow"))
        gl.bind(self._buffers.vertex_array(position, row))
        starts = np.searchsorted(rows, np.arange(0, len(self), chunk))
        ends = np.append(starts[1:], len(rows))
        counts, offsets = self._counts, self._offsets
        for first, (start, end) in enumerate(zip(starts.tolist(), ends.tolist(), strict=True)):
            if start == end:
                continue
            base = first * chunk
            size = min(chunk, len(self) - base)
            gl.matrix(matrices, size, 0, every[base:].ctypes.data)
            for location, extra in zip(extra_locations, extras, strict=True):
                gl.vector(location, size, extra[base:].ctypes.data)
            gl.uniform_int(base_location, base)
            in_chunk, chunk_sides = rows[start:end], sides[start:end]
            one_side = not chunk_sides.any()
            for side in [0] if one_side else np.unique(chunk_sides).tolist():
                drawn = in_chunk if one_side else in_chunk[chunk_sides == side]
                cull(_SIDE_NAMES[side])
                drawn_counts = np.ascontiguousarray(counts[drawn])
                drawn_offsets = np.ascontiguousarray(offsets[drawn])
                gl.multi_draw(
                    _TRIANGLES,
                    drawn_counts.ctypes.data,
                    _UNSIGNED_INT,
                    drawn_offsets.ctypes.data,
                    len(drawn),
                )
                self.calls += 1
            self.calls += 1
        gl.bind(0)

    def release(self) -> None:
        """Delete the buffers and vertex arrays (the context must be current)."""
        self._buffers.release()


class BatchKeeper:
    """Keeps the batch of the last snapshot's casters, patched or built again as they change.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the batch.

    Attributes
    ----------
    builds : int
        Times a batch was built (a test counts them).
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._kept: tuple[Snapshot, CasterBatch] | None = None
        self.builds = 0

    def of(self, snapshot: Snapshot) -> CasterBatch:
        """Return the batch of a snapshot's casters.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        CasterBatch
            Its small casters in one vertex array: the last batch when the
            snapshot follows the last one asked about and its replaced
            casters could be patched in, else a new one.
        """
        kept = self._kept
        if kept is not None and kept[0] is snapshot:
            return kept[1]
        if kept is not None and snapshot.parent is kept[0]:
            batch = kept[1]
            if batch.refresh(snapshot.casters, snapshot.patches(CASTERS)):
                self._kept = (snapshot, batch)
                return batch
        self.release()
        batch = CasterBatch(self._window, snapshot.casters)
        self.builds += 1
        self._kept = (snapshot, batch)
        return batch

    def release(self) -> None:
        """Delete the batch, if any."""
        if self._kept is not None:
            self._kept[1].release()
            self._kept = None
