"""GPU copies of the actors' triangles, shared by every light and technique."""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.gl.buffers import TriangleBuffers
from pvshadows.gl.caster_batch import BatchKeeper, CasterBatch, worth_batching
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import CASTERS, Snapshot


class ActorBuffers:
    """Uploads each actor's triangles once per change of its data.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffers.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._buffers: dict[str, tuple[int, TriangleBuffers]] = {}
        self._casters: tuple[Snapshot, list[TriangleBuffers]] | None = None
        #: The small casters of the last snapshot in one vertex array.
        self.batches = BatchKeeper(window)

    def get(self, state: ActorState) -> TriangleBuffers:
        """Return the buffers of an actor, uploading them if its data changed.

        Parameters
        ----------
        state : ActorState
            The actor this frame.

        Returns
        -------
        TriangleBuffers
            Its triangles on the GPU.
        """
        key = state.key()[0]
        version = state.triangles.version
        cached = self._buffers.get(key)
        if cached is not None and cached[0] == version:
            return cached[1]
        if cached is not None:
            cached[1].release()
        buffers = TriangleBuffers(self._window, state.triangles.points, state.triangles.triangles)
        self._buffers[key] = (version, buffers)
        return buffers

    def of_casters(self, snapshot: Snapshot) -> list[TriangleBuffers]:
        """Return the buffers of a snapshot's casters (see :meth:`get`).

        A snapshot that follows the last one asked about
        (:meth:`~pvshadows.scene.snapshot.Snapshot.successor`) looks up its
        replaced casters only.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        list of TriangleBuffers
            The triangles of :attr:`Snapshot.casters` on the GPU, in order.
        """
        kept = self._casters
        if kept is not None and kept[0] is snapshot:
            return kept[1]
        if kept is not None and snapshot.parent is kept[0]:
            listed = list(kept[1])
            for row, state in snapshot.patches(CASTERS):
                listed[row] = self.get(state)
        else:
            listed = [self.get(state) for state in snapshot.casters]
        self._casters = (snapshot, listed)
        return listed

    def batch_of(self, snapshot: Snapshot) -> CasterBatch | None:
        """Return the batch of a snapshot's small casters, or ``None`` for a scene of few casters.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        CasterBatch or None
            See :class:`~pvshadows.gl.caster_batch.BatchKeeper`; ``None``
            below :data:`~pvshadows.gl.caster_batch.MIN_CASTERS` casters.
        """
        if not worth_batching(len(snapshot.casters)):
            self.batches.release()
            return None
        return self.batches.of(snapshot)

    def keep_only(self, states: list[ActorState]) -> None:
        """Release the buffers of actors that are gone.

        Parameters
        ----------
        states : list of ActorState
            The actors of this frame.
        """
        self._casters = None
        alive = {s.key()[0] for s in states}
        for key in set(self._buffers) - alive:
            self._buffers.pop(key)[1].release()

    def release(self) -> None:
        """Release every buffer."""
        self.keep_only([])
        self.batches.release()
