"""Many small shadow volumes in one set of buffers, counted by the stencil pass in a few calls.

Drawn one by one, a volume extruded on the GPU costs the stencil pass its
matrix, its light, its vertex array's binding and its draw: a few
microseconds of CPU each, milliseconds a frame over hundreds of casters.
Here the volume meshes of a light's small closed casters share one vertex
buffer, one index buffer of ``GL_TRIANGLES_ADJACENCY`` rows and one vertex
array; each vertex also carries its caster's row, and the extruding
geometry stage reads that caster's matrix, light and reach from uniform
arrays (``BATCHED`` in ``glsl/volume_extrude.vert`` and
``glsl/volume_extrude.geom``). A run of volumes then costs a few calls per
chunk of rows, whatever the number of casters. Positions, matrices and
lights are the float32 values the one-by-one draw uses, and every
caster's vertex indices keep their order, so the same faces face the light
and the same silhouettes are extruded.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.volume_casters import VolumeMesh
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.caster_batch import chunk_rows

#: Volume meshes of at most this many triangles go into the batch; a bigger
#: one is drawn on its own, where its draw call is a small part of its cost.
SMALL = 65_536
#: A light's casters are batched from this many small closed ones on.
MIN_VOLUMES = 16
#: ``vec4`` uniforms of each row besides its matrix: its light and its reach.
ROW_VECTORS = 2


def batchable(meshes: Sequence[VolumeMesh | None]) -> list[bool]:
    """Return which volume meshes go into a batch: the small ones, when there are enough.

    Parameters
    ----------
    meshes : sequence of VolumeMesh or None
        A light's closed casters' meshes in order, ``None`` for one whose
        volume is not extruded on the GPU.

    Returns
    -------
    list of bool
        All ``False`` below :data:`MIN_VOLUMES` small meshes.

    Examples
    --------
    >>> from pvshadows.gl.volume_batch import batchable
    >>> batchable([None, None])
    [False, False]
    """
    small = [m is not None and len(m.triangles) <= SMALL for m in meshes]
    return small if sum(small) >= MIN_VOLUMES else [False] * len(small)


@dataclass(frozen=True)
class VolumeRun:
    """Volumes of one chunk of rows drawn with one ``glMultiDrawElements``.

    Attributes
    ----------
    base : int
        The chunk's first row.
    size : int
        Rows its uniform arrays are set for.
    counts : numpy.ndarray
        ``(k,)`` int32 index counts of its draws.
    offsets : numpy.ndarray
        ``(k,)`` uintp byte offsets of their first indices.
    """

    base: int
    size: int
    counts: np.ndarray
    offsets: np.ndarray


class VolumeBatch:
    """The small closed casters' volume meshes of one light in one vertex array.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    meshes : sequence of VolumeMesh or None
        The light's closed casters' meshes in order; only those
        :func:`batchable` says are taken, at the caster's row.

    Attributes
    ----------
    meshes : tuple
        The meshes it was built from, compared by identity
        (:meth:`holds`).
    in_batch : numpy.ndarray
        ``(n,)`` bool, per row: its volume is in the batch.
    chunk : int
        Rows per chunk of uniforms
        (:func:`~pvshadows.gl.caster_batch.chunk_rows` of the geometry stage).
    calls : int
        Runs drawn so far, one multi-draw each (a test counts them).
    """

    def __init__(
        self, window: vtk.vtkOpenGLRenderWindow, meshes: Sequence[VolumeMesh | None]
    ) -> None:
        self.meshes = tuple(meshes)
        self.chunk = chunk_rows(window, ROW_VECTORS, geometry=True)
        self.calls = 0
        self.in_batch = np.array(batchable(meshes), dtype=bool)
        taken = [(row, m) for row, m in enumerate(meshes) if m is not None and self.in_batch[row]]
        vertex_counts = np.array([len(m.points) for _, m in taken], dtype=np.int64)
        first_vertex = np.cumsum(vertex_counts) - vertex_counts
        index_counts = np.array([m.adjacency_rows.size for _, m in taken], dtype=np.int64)
        #: Each row's first index in the batch's index buffer (0 where not batched).
        self._first_index = np.zeros(len(meshes), dtype=np.int64)
        self._first_index[[row for row, _ in taken]] = np.cumsum(index_counts) - index_counts
        points = [m.points for _, m in taken]
        indices = [
            m.adjacency_rows.ravel() + first
            for (_, m), first in zip(taken, first_vertex.tolist(), strict=True)
        ]
        owners = np.repeat(np.array([row for row, _ in taken], dtype=np.int32), vertex_counts)
        self.buffers = IndexedBuffers.of_parts(window, points, indices, owners)

    def holds(self, meshes: Sequence[VolumeMesh | None]) -> bool:
        """Return whether the batch was built from these very meshes, in this order.

        Parameters
        ----------
        meshes : sequence of VolumeMesh or None
            As given to the constructor.

        Returns
        -------
        bool
            A caster that moved keeps its mesh: the batch holds.
        """
        return len(meshes) == len(self.meshes) and all(
            a is b for a, b in zip(meshes, self.meshes, strict=True)
        )

    def runs(self, rows: Sequence[int], spans: Sequence[tuple[int, int]]) -> list[VolumeRun]:
        """Group batched draws into runs of one chunk of rows each.

        Parameters
        ----------
        rows : sequence of int
            Each draw's row (in the batch), in drawing order.
        spans : sequence of tuple
            Each draw's ``(first, count)`` range of its own mesh's indices.

        Returns
        -------
        list of VolumeRun
            One per chunk that holds draws, in order of rows.
        """
        if not len(rows):
            return []
        at = np.asarray(rows, dtype=np.int64)
        span = np.asarray(spans, dtype=np.int64).reshape(-1, 2)
        order = np.argsort(at, kind="stable")
        at, span = at[order], span[order]
        offsets = 4 * (self._first_index[at] + span[:, 0])
        chunks = at // self.chunk
        runs = []
        for chunk in np.unique(chunks).tolist():
            mine = chunks == chunk
            base = chunk * self.chunk
            runs.append(
                VolumeRun(
                    base,
                    min(self.chunk, len(self.meshes) - base),
                    np.ascontiguousarray(span[mine, 1], dtype=np.int32),
                    np.ascontiguousarray(offsets[mine], dtype=np.uintp),
                )
            )
        return runs

    def release(self) -> None:
        """Delete the buffers and vertex arrays (the context must be current)."""
        self.buffers.release()
