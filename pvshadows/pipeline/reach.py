"""Which actors each light reaches, kept between frames.

A spot light reaches only the actors whose bounds touch its cone. The answer
for an actor stays right while neither the light's pose nor the actor's
state changed, so a frame whose snapshot follows the last one
(:meth:`pvshadows.scene.snapshot.Snapshot.successor`) tests only the actors
replaced in it, and a moved light tests every actor in one vectorised call.
"""

from __future__ import annotations

import numpy as np

from pvshadows.scene.culling import boxes_in_spot
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.snapshot import Snapshot


class ReachCache:
    """Remembers, per light, its pose, the snapshot its reach was tested on and the answers.

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
    >>> snapshot = SceneReader(lambda actor: "an actor").read(pl.renderer)
    >>> spot = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 20.0)
    >>> cache = ReachCache()
    >>> cache.reaches("spot", spot, snapshot).tolist(), cache.tests
    ([True, False], 2)
    >>> cache.reaches("spot", spot, snapshot).tolist(), cache.tests
    ([True, False], 2)
    """

    def __init__(self) -> None:
        self._lights: dict[str, tuple[tuple, Snapshot, np.ndarray]] = {}
        #: Cone tests run since the cache was made (one per actor tested).
        self.tests = 0

    def reaches(self, light: str, pose: LightPose, snapshot: Snapshot) -> np.ndarray:
        """Return, for each of a snapshot's actors, whether the light can reach it (conservative).

        Parameters
        ----------
        light : str
            The light's key (:func:`pvshadows.scene.triangles.vtk_id`).
        pose : LightPose
            Its pose this frame.
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        numpy.ndarray
            One read-only bool per actor of :attr:`Snapshot.actors`; always
            ``True`` for point and directional lights.
        """
        if pose.kind is not LightKind.SPOT:
            return np.ones(len(snapshot.actors), dtype=bool)
        pose_key = pose.key()
        kept = self._lights.get(light)
        if kept is not None and kept[0] == pose_key:
            if kept[1] is snapshot:
                return kept[2]
            if snapshot.parent is kept[1]:
                rows = list(snapshot.replaced)
                hits = kept[2].copy()
                hits[rows] = boxes_in_spot(snapshot.actor_bounds[rows], pose)
                return self._keep(light, pose_key, snapshot, hits, len(rows))
        hits = boxes_in_spot(snapshot.actor_bounds, pose)
        return self._keep(light, pose_key, snapshot, hits, len(hits))

    def touches(self, light: str, pose: LightPose, snapshot: Snapshot) -> bool:
        """Whether the light reaches some actor replaced since the snapshot's parent.

        Reached before the change or after it, either counts. Brings the
        light's answers up to this snapshot as :meth:`reaches` does.

        Parameters
        ----------
        light : str
            The light's key.
        pose : LightPose
            Its pose this frame.
        snapshot : Snapshot
            This frame's actors, following (:attr:`Snapshot.parent`) the
            last snapshot planned.

        Returns
        -------
        bool
            ``True`` also when the light reaches every actor (point and
            directional lights) and some actor changed, or when last
            frame's answers are not at hand.
        """
        rows = list(snapshot.replaced)
        if pose.kind is not LightKind.SPOT:
            return bool(rows)
        kept = self._lights.get(light)
        known = kept is not None and kept[0] == pose.key() and kept[1] is snapshot.parent
        before = kept[2][rows].any() if kept is not None and known else True
        return bool(before or self.reaches(light, pose, snapshot)[rows].any())

    def _keep(
        self, light: str, pose_key: tuple, snapshot: Snapshot, hits: np.ndarray, tested: int
    ) -> np.ndarray:
        self.tests += tested
        hits.setflags(write=False)  # handed out again while nothing changes
        self._lights[light] = (pose_key, snapshot, hits)
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
