"""Which actors each light reaches, kept between frames.

A spot light reaches only the actors whose bounds touch its cone. The answer
for an actor stays right while neither the light's pose nor the actor's
state changed (the scene reader keeps an unchanged actor's
:class:`~pvshadows.scene.snapshot.ActorState` object), so each frame tests only the
actors that are new or changed, or all of them when the light moved, in one
vectorised call.
"""

from __future__ import annotations

import numpy as np

from pvshadows.scene.culling import boxes_in_spot
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.snapshot import ActorState


class ReachCache:
    """Remembers, per light, which actor states its reach was tested on and the answers.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.pipeline.reach import ReachCache
    >>> from pvshadows.scene.snapshot import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Cube(center=(0, 0, -3)))
    >>> _ = pl.add_mesh(pv.Cube(center=(9, 0, -3)))
    >>> actors = SceneReader(lambda actor: "an actor").read(pl.renderer).actors
    >>> spot = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 20.0)
    >>> cache = ReachCache()
    >>> cache.reaches("spot", spot, actors).tolist(), cache.tests
    ([True, False], 2)
    >>> cache.reaches("spot", spot, actors).tolist(), cache.tests
    ([True, False], 2)
    """

    def __init__(self) -> None:
        self._lights: dict[str, _Answers] = {}
        #: Cone tests run since the cache was made (one per actor tested).
        self.tests = 0

    def reaches(
        self,
        light: str,
        pose: LightPose,
        states: list[ActorState],
        bounds: np.ndarray | None = None,
    ) -> np.ndarray:
        """Return, for each state, whether the light can reach it (conservative).

        Parameters
        ----------
        light : str
            The light's key (:func:`pvshadows.scene.triangles.vtk_id`).
        pose : LightPose
            Its pose this frame.
        states : list of ActorState
            The actors to answer for.
        bounds : numpy.ndarray, optional
            Their world bounds ``(n, 2, 3)`` already stacked (a snapshot
            keeps them), so a moved light tests them in one call without
            gathering them again.

        Returns
        -------
        numpy.ndarray
            One bool per state; always ``True`` for point and directional
            lights.
        """
        if pose.kind is not LightKind.SPOT:
            return np.ones(len(states), dtype=bool)
        pose_key = pose.key()
        answers = self._lights.get(light)
        if answers is None or answers.pose_key != pose_key:
            answers = self._lights[light] = _Answers(pose_key)
        hits = answers.recall(states)
        if hits is not None:
            return hits
        known = answers.known()
        if not known:
            untested = list(range(len(states)))
            hits = np.zeros(len(states), dtype=bool)
        else:
            found = [known.get(id(s), (None, False)) for s in states]
            hits = np.fromiter((hit for _, hit in found), dtype=bool, count=len(states))
            untested = [i for i, (kept, _) in enumerate(found) if kept is not states[i]]
        if untested:
            self.tests += len(untested)
            if bounds is None:
                boxes = np.array([states[i].bounds for i in untested]).reshape(-1, 2, 3)
            else:
                boxes = bounds if len(untested) == len(states) else bounds[untested]
            hits[untested] = boxes_in_spot(boxes, pose)
        hits.setflags(write=False)  # handed out again for the same list
        answers.keep(states, hits)
        return hits

    def keep_only(self, lights: set[str]) -> None:
        """Forget the lights not in ``lights``.

        Parameters
        ----------
        lights : set of str
            Keys of the lights still planned.
        """
        for key in set(self._lights) - lights:
            del self._lights[key]


class _Answers:
    """One light's answers at one pose: the last few lists of states asked about."""

    #: Lists kept: a light is asked about its receivers and its casters each frame.
    KEPT = 4

    def __init__(self, pose_key: tuple) -> None:
        self.pose_key = pose_key
        self._recent: list[tuple[list[ActorState], np.ndarray]] = []
        self._known: dict[int, tuple[ActorState, bool]] | None = None

    def recall(self, states: list[ActorState]) -> np.ndarray | None:
        """Return the answers for this very list of states, if asked before."""
        for kept, hits in self._recent:
            if kept is states:
                return hits
        return None

    def known(self) -> dict[int, tuple[ActorState, bool]]:
        """Return every state answered for, by ``id``, with its answer."""
        if self._known is None:
            self._known = {
                id(state): (state, bool(hit))
                for kept, hits in reversed(self._recent)
                for state, hit in zip(kept, hits.tolist(), strict=True)
            }
        return self._known

    def keep(self, states: list[ActorState], hits: np.ndarray) -> None:
        """Remember the answers for a list of states."""
        self._recent = [(states, hits), *self._recent[: self.KEPT - 1]]
        self._known = None
