"""GPU copies of the actors' triangles, shared by every light and technique."""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.gl.buffers import TriangleBuffers
from pvshadows.scene.snapshot import ActorState


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

    def get_all(self, states: list[ActorState]) -> list[TriangleBuffers]:
        """Return the buffers of several actors (see :meth:`get`).

        Parameters
        ----------
        states : list of ActorState
            The actors this frame.

        Returns
        -------
        list of TriangleBuffers
            Their triangles on the GPU, in the same order.
        """
        return [self.get(state) for state in states]

    def keep_only(self, states: list[ActorState]) -> None:
        """Release the buffers of actors that are gone.

        Parameters
        ----------
        states : list of ActorState
            The actors of this frame.
        """
        alive = {s.key()[0] for s in states}
        for key in set(self._buffers) - alive:
            self._buffers.pop(key)[1].release()

    def release(self) -> None:
        """Release every buffer."""
        self.keep_only([])
