"""Which actors each light reaches, kept between frames.

A spot light reaches only the actors whose bounds touch its cone. The actors
are tested against a wider cone than the light's (its *cover*: a degree
wider, its apex a little behind the light), so the answers stay right
(conservative) while the light moves and turns a little: a light dragged or
animated across frames tests its actors again only when its cone leaves the
cover, not at every frame. The answer for an actor stays right while the
cover holds the light's cone and the actor's state did not change, so a
frame whose snapshot follows the last
(:meth:`pvshadows.scene.snapshot.Snapshot.successor`) tests only the actors
replaced in it, and a light that left its cover tests every actor in one
vectorised call.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.scene.culling import MANY_LIGHTS, SpotCones, boxes_in_spot, boxes_in_spots
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.triangles import vtk_id

#: Degrees a spot light's cover is wider than its cone (never past 89.9).
COVER_DEGREES = 1.0
#: How far behind a spot light its cover's apex sits, as a fraction of the
#: diagonal of the box round the actors.
COVER_BACK = 0.01
#: The widest cone :func:`pvshadows.scene.culling.boxes_in_spot` tests as it is.
_WIDEST_DEGREES = 89.9


@dataclass
class _Reached:
    """A spot light's answers: the cover they were tested against, on which snapshot."""

    cover: LightPose
    snapshot: Snapshot
    hits: np.ndarray
    #: The last pose the cover was found to hold (the test is skipped for it).
    pose_key: tuple
    #: The answers on the snapshot's parent, when these were patched from them.
    before: np.ndarray | None = None


def light_cover(pose: LightPose, snapshot: Snapshot) -> LightPose:
    """Return the cone the actors are tested against for a spot light: its cover.

    :data:`COVER_DEGREES` wider than the light's cone and its apex
    :data:`COVER_BACK` of the actors' size behind the light, so that it holds
    the light's cone also after the light moved or turned a little
    (:func:`cover_holds`).

    Parameters
    ----------
    pose : LightPose
        The spot light.
    snapshot : Snapshot
        This frame's actors: their size sets how far back the apex goes.

    Returns
    -------
    LightPose
        The cover, a spot pose.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.pipeline.reach import light_cover
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.scene.reader import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Cube(x_length=10, y_length=10, z_length=10))
    >>> snapshot = SceneReader(lambda actor: "a cube").read(pl.renderer)
    >>> spot = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 30.0)
    >>> cover = light_cover(spot, snapshot)
    >>> cover.position.round(3).tolist(), cover.cone_angle
    ([0.0, 0.0, 0.173], 31.0)
    """
    angle = max(pose.cone_angle, min(pose.cone_angle + COVER_DEGREES, _WIDEST_DEGREES))
    position = pose.position - (COVER_BACK * snapshot.scene_size) * pose.direction
    return replace(pose, position=position, cone_angle=angle)


def cover_holds(cover: LightPose, pose: LightPose) -> bool:
    """Tell whether a spot light's cone lies inside a cover, so that what the cover reaches holds.

    It does when the light is inside the cover and its cone's edge is no
    farther from the cover's axis than the cover's: every ray of the light
    then stays in the cover (a cone holds each ray that starts inside it and
    points within its angle).

    Parameters
    ----------
    cover : LightPose
        The cover (:func:`light_cover`).
    pose : LightPose
        The spot light this frame.

    Returns
    -------
    bool
        Whether the cover's answers hold for the light.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.pipeline.reach import cover_holds
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> cover = LightPose(LightKind.SPOT, np.array([0, 0, 1.0]), np.array([0, 0, -1.0]), 32.0)
    >>> beside = np.array([0.1, 0, 0])
    >>> spot = LightPose(LightKind.SPOT, beside, np.array([0, 0, -1.0]), 30.0)
    >>> tilt = np.array([0, 0.1, -1.0]) / np.hypot(0.1, 1)
    >>> turned = LightPose(LightKind.SPOT, beside, tilt, 30.0)
    >>> cover_holds(cover, spot), cover_holds(cover, turned)
    (True, False)
    """
    if cover.degrees_from(pose) + pose.cone_angle > cover.cone_angle:
        return False
    # Plain floats, written out: numpy's calls, and a generator's, cost more than the sums.
    (ax, ay, az), (px, py, pz) = cover.direction.tolist(), pose.position.tolist()
    cx, cy, cz = cover.position.tolist()
    ox, oy, oz = px - cx, py - cy, pz - cz
    along = ox * ax + oy * ay + oz * az
    return along >= math.hypot(ox, oy, oz) * math.cos(math.radians(cover.cone_angle))


def same_objects(first: Sequence, second: Sequence) -> bool:
    """Tell whether two sequences hold the very same objects in the same order.

    Compared by identity: a :class:`pyvista.Light` equals another with the
    same settings.

    Parameters
    ----------
    first, second : sequence
        The lists or tuples.

    Returns
    -------
    bool
        Whether each item of one is the other's item at the same place.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.pipeline.reach import same_objects
    >>> light = pv.Light()
    >>> same_objects([light], [light]), same_objects([light], [pv.Light()])
    (True, False)
    """
    if first is second:
        return True
    if len(first) != len(second):
        return False
    for one, other in zip(first, second, strict=True):
        if one is not other:
            return False
    return True


class ReachCache:
    """Remembers, per light, its pose, the snapshot its reach was tested on and the answers.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.pipeline.reach import ReachCache
    >>> from pvshadows.scene.reader import SceneReader
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
        self._lights: dict[str, _Reached] = {}
        #: The lights of the last :meth:`keep_only`.
        self._kept_for: tuple[vtk.vtkLight, ...] = ()
        #: The covers last stacked for a test of many lights at once, and their stack.
        self._cones: tuple[list[LightPose], SpotCones] | None = None
        #: Cone tests run since the cache was made (one per actor and light tested).
        self.tests = 0
        #: Times the actors replaced in a snapshot were tested against several lights at once.
        self.batches = 0

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
            ``True`` for point and directional lights. ``False`` only for
            actors outside the light's cover (:func:`light_cover`), which
            holds its cone.
        """
        if pose.kind is not LightKind.SPOT:
            return np.ones(len(snapshot.actors), dtype=bool)
        kept = self._held(light, pose)
        if kept is not None:
            if kept.snapshot is not snapshot and snapshot.parent is kept.snapshot:
                self._bring_to(snapshot)
                kept = self._lights[light]
            if kept.snapshot is snapshot:
                return kept.hits
        cover = light_cover(pose, snapshot)
        hits = boxes_in_spot(snapshot.actor_bounds, cover)
        return self._keep(light, cover, pose, snapshot, hits, len(hits))

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
        kept = self._held(light, pose)
        before: np.ndarray | None
        if kept is not None and kept.snapshot is snapshot.parent:
            before = kept.hits
        elif kept is not None and kept.snapshot is snapshot:
            before = kept.before  # brought here from the parent along with another light
        else:
            before = None
        if before is None or before[rows].any():
            return True
        return bool(self.reaches(light, pose, snapshot)[rows].any())

    def _bring_to(self, snapshot: Snapshot) -> None:
        """Test the actors replaced in ``snapshot`` for every light whose answers are its parent's.

        One batched test for all those lights (:func:`boxes_in_spots`,
        from :data:`~pvshadows.scene.culling.MANY_LIGHTS` lights on), each
        against its cover; a light whose cover no longer holds its
        cone is tested afresh when asked, as before.
        """
        parent = snapshot.parent
        followers = [key for key, kept in self._lights.items() if kept.snapshot is parent]
        rows = list(snapshot.replaced)
        boxes = snapshot.actor_bounds[rows]
        covers = [self._lights[key].cover for key in followers]
        if len(covers) < MANY_LIGHTS:
            answers = np.array([boxes_in_spot(boxes, cover) for cover in covers])
        else:
            answers = boxes_in_spots(boxes, self._stacked(covers))
            self.batches += 1
        for key, answer in zip(followers, answers, strict=True):
            kept = self._lights[key]
            hits = kept.hits.copy()
            hits[rows] = answer
            hits.setflags(write=False)
            self._lights[key] = _Reached(kept.cover, snapshot, hits, kept.pose_key, kept.hits)
            self.tests += len(rows)

    def _stacked(self, covers: list[LightPose]) -> SpotCones:
        """Return the covers stacked for :func:`boxes_in_spots` (again only when one changed)."""
        kept = self._cones
        if kept is None or not same_objects(kept[0], covers):
            kept = self._cones = (covers, SpotCones(covers))
        return kept[1]

    def _held(self, light: str, pose: LightPose) -> _Reached | None:
        """Return the light's kept answers if their cover holds its cone this frame."""
        kept = self._lights.get(light)
        if kept is None:
            return None
        pose_key = pose.key()
        if kept.pose_key == pose_key:
            return kept
        if not cover_holds(kept.cover, pose):
            return None
        kept.pose_key = pose_key
        return kept

    def _keep(
        self,
        light: str,
        cover: LightPose,
        pose: LightPose,
        snapshot: Snapshot,
        hits: np.ndarray,
        tested: int,
    ) -> np.ndarray:
        self.tests += tested
        hits.setflags(write=False)  # handed out again while nothing changes
        self._lights[light] = _Reached(cover, snapshot, hits, pose.key())
        return hits

    def keep_only(self, lights: Sequence[vtk.vtkLight]) -> None:
        """Forget the lights not in ``lights``; nothing to look at when they are the last call's.

        Parameters
        ----------
        lights : sequence of vtk.vtkLight
            The lights still planned.
        """
        if same_objects(lights, self._kept_for):
            return  # answers are kept only for these lights, and none was forgotten since
        self._kept_for = tuple(lights)
        alive = {vtk_id(light) for light in lights}
        gone = set(self._lights) - alive
        for key in gone:
            del self._lights[key]
        if gone:
            self._cones = None
