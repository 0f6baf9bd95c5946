"""What a depth pass draws of its casters, and the drawing: batched, or one caster at a time."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.caster_batch import CasterBatch, worth_batching
from pvshadows.gl.raw_calls import raw_calls

#: ``GL_UNSIGNED_INT``, the type of every index buffer.
_UNSIGNED_INT = 0x1405


@dataclass(slots=True)
class CasterDraws:
    """The casters one pass draws, side by side: one object per pass, not one per caster.

    Attributes
    ----------
    buffers : sequence of IndexedBuffers
        Each caster's triangles on the GPU.
    columns : numpy.ndarray
        ``(n, 4, 4)`` float32, C-contiguous: each caster's buffer coordinates
        to the light's space, by columns (transposed, as GL reads a ``mat4``).
    culls : sequence of {"front", "back", None}
        Each caster's side of its triangles not to draw.
    batch : CasterBatch or None
        The snapshot's small casters in one vertex array, when there is one.
    rows : numpy.ndarray or None
        ``(n,)`` each caster's row in ``batch``, -1 for one drawn on its own.
    vectors : tuple of tuple
        ``(name, values)``: more ``vec4`` per caster, ``values`` ``(n, 4)``
        float32 C-contiguous, set as ``uniform vec4 name`` for a caster drawn
        on its own and as the array ``name + "s"`` for the batch.
    chunk : int
        Rows per chunk of the batch's uniforms where the pass's program holds
        fewer than the batch's (0: the batch's).
    """

    buffers: Sequence[IndexedBuffers]
    columns: np.ndarray
    culls: Sequence[str | None]
    batch: CasterBatch | None = None
    rows: np.ndarray | None = None
    vectors: tuple[tuple[str, np.ndarray], ...] = ()
    chunk: int = 0

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
            self.columns[chosen],
            [self.culls[i] for i in chosen],
            self.batch,
            None if self.rows is None else self.rows[chosen],
            tuple((name, values[chosen]) for name, values in self.vectors),
            self.chunk,
        )

    def batched(self) -> np.ndarray | None:
        """Return which casters a pass draws through :attr:`batch`.

        Returns
        -------
        numpy.ndarray or None
            ``(n,)`` bool: the batch's casters, when the pass draws at least
            :data:`~pvshadows.gl.caster_batch.MIN_CASTERS` of them; ``None``
            when it draws none through the batch.
        """
        if self.batch is None or self.rows is None:
            return None
        inside = self.rows >= 0
        return inside if worth_batching(int(inside.sum())) else None


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
    if batched is None:
        draw_one_by_one(programs(False), casters, cull)
        return
    every = bool(batched.all())
    if not every:
        draw_one_by_one(programs(False), casters.subset(~batched), cull)
    part = casters if every else casters.subset(batched)
    assert part.batch is not None and part.rows is not None  # batched() said so
    program = programs(True)
    part.batch.draw(program, part.rows, part.columns, part.culls, cull, part.vectors, part.chunk)


def draw_one_by_one(
    program: vtk.vtkShaderProgram,
    casters: CasterDraws,
    cull: Callable[[str | None], None],
) -> None:
    """Draw casters' triangles, each with its own ``mat4`` uniform, in few Python calls.

    Every caster's float32 columns (:attr:`CasterDraws.columns`, read in
    place by address) are set by location with the raw
    ``glUniformMatrix4fv``; each caster then costs that call, its vertex
    array's binding, its draw and a culling call when its side differs from
    the last caster's. Drawing casters one
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
    columns = casters.columns
    assert columns.dtype == np.float32 and columns.flags.c_contiguous  # read by address
    base = columns.ctypes.data
    extras = [(program.FindUniform(name), values.ctypes.data) for name, values in casters.vectors]
    set_matrix, set_vector, bind, draw = gl.matrix, gl.vector, gl.bind, gl.draw
    triangles = 0x0004  # GL_TRIANGLES
    side: str | bool | None = False  # not a side: the first caster sets culling
    for i, (buffers, culled) in enumerate(zip(casters.buffers, casters.culls, strict=True)):
        if not buffers.n_indices:
            continue
        set_matrix(location, 1, 0, base + 64 * i)
        for extra, at in extras:
            set_vector(extra, 1, at + 16 * i)
        if culled != side:
            cull(culled)
            side = culled
        bind(buffers.vertex_array(position))
        draw(triangles, buffers.n_indices, _UNSIGNED_INT, None)
    bind(0)
