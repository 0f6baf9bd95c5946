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
        self._lights: dict[str, tuple[tuple, dict[int, tuple[ActorState, bool]]]] = {}
        self._kept: tuple[frozenset[str], list[ActorState]] | None = None
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
        kept_key, kept = self._lights.get(light, (None, {}))
        if kept_key != pose_key:
            kept = {}
        untested = [i for i, s in enumerate(states) if id(s) not in kept or kept[id(s)][0] is not s]
        if untested:
            self.tests += len(untested)
            if bounds is None:
                boxes = np.array([states[i].bounds for i in untested]).reshape(-1, 2, 3)
            else:
                boxes = bounds if len(untested) == len(states) else bounds[untested]
            inside = boxes_in_spot(boxes, pose).tolist()
            tested = zip(untested, inside, strict=True)
            kept = {**kept, **{id(states[i]): (states[i], hit) for i, hit in tested}}
        self._lights[light] = (pose_key, kept)
        return np.fromiter((kept[id(s)][1] for s in states), dtype=bool, count=len(states))

    def keep_only(self, lights: set[str], states: list[ActorState]) -> None:
        """Forget lights not in ``lights`` and actor states not in ``states``.

        Parameters
        ----------
        lights : set of str
            Keys of the lights still planned.
        states : list of ActorState
            This frame's actor states.
        """
        if self._kept is not None and self._kept[0] == lights and self._kept[1] is states:
            return
        self._kept = (frozenset(lights), states)
        alive = {id(s) for s in states}
        self._lights = {
            key: (pose, {i: v for i, v in kept.items() if i in alive})
            for key, (pose, kept) in self._lights.items()
            if key in lights
        }
