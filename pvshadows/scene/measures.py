"""Values measured from a light for each caster, kept while the light stays near, patched.

A light's map is fitted to its casters (their distances, their spread
around a spot's axis, the cube faces each touches). Measured afresh, that is
a pass over every caster each time anything changes. Kept per light, a
frame whose snapshot follows the last
(:meth:`pvshadows.scene.snapshot.Snapshot.successor`) measures only the
casters replaced in it: an actor that moved costs its own box, not the
scene's. A light that moves measures its casters' boxes widened by a margin
(:data:`MARGIN_OF_NEAREST` of the nearest caster's distance): the measures
then hold, conservatively, for every position of the light within that
margin of where they were taken (and for a spot turned by at most
:data:`TURN_DEGREES` from its axis there), so a light dragged or animated
across frames measures its casters again only when it leaves the margin.
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, NamedTuple, TypeVar, cast

import numpy as np

from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.culling import MANY_LIGHTS, widened_boxes
from pvshadows.scene.lights import LightPose
from pvshadows.scene.snapshot import CASTERS, Snapshot

MeasuresT = TypeVar("MeasuresT", bound=NamedTuple)

#: A moving light's casters are measured with their boxes widened by this share of
#: the distance from the light to the nearest of them.
MARGIN_OF_NEAREST = 0.02
#: Degrees a spot light may turn from the axis its casters were measured about.
TURN_DEGREES = 1.0


@dataclass(slots=True)
class Measured(Generic[MeasuresT]):
    """A light's measures of every caster, and where they were taken from.

    Attributes
    ----------
    values : named tuple
        One row per caster of the snapshot (what the cache's ``measure``
        returns). They are the light's exact measures when ``margin`` is 0,
        and otherwise hold for every light within ``margin`` of ``base``
        (see :class:`CasterMeasureCache`).
    base : LightPose
        The pose they were measured from: a spot's map looks along its
        direction (the casters' spread is measured about it).
    margin : float
        How far the casters' boxes were widened on every side.
    """

    values: MeasuresT
    base: LightPose
    margin: float


class CasterMeasureCache(Generic[MeasuresT]):
    """One light's measures of every caster, kept while the light stays near where they were taken.

    Parameters
    ----------
    measure : callable
        ``measure(pose, boxes)`` returns a named tuple of ``(n,)`` arrays, one
        row per ``(n, 2, 3)`` box (for example
        :func:`pvshadows.scene.spot_fitting.cone_measures`). Each measure must
        bound from below (a distance to a box) or above (a distance to its
        farthest corner, a spread, the cube faces it touches) what it gives
        for any smaller box, so that measures of widened boxes hold for a
        light that moved within the widening.
    turns : bool, default: False
        Whether the measures depend on the light's direction (a spot's spread
        about its axis): then they are kept only while the light turns by at
        most :data:`TURN_DEGREES`.
    group : MeasureGroup, optional
        The caches of the other lights of the same kind: a snapshot's
        replaced casters are then measured for all of them in one call.

    Attributes
    ----------
    measured : int
        Casters measured so far (for tests).

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.spot_fitting import cone_measures
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.scene.measures import CasterMeasureCache
    >>> from pvshadows.scene.reader import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> boxes = [pl.add_mesh(pv.Cube(center=(x, 0, -5))) for x in (-1, 1)]
    >>> reader = SceneReader(lambda actor: "a cube")
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 45.0)
    >>> cache = CasterMeasureCache(cone_measures, turns=True)
    >>> cache.of(pose, reader.read(pl.renderer)).values.near.round(2).tolist()
    [20.5, 20.5]
    >>> boxes[1].position = (0, 0, 1)
    >>> cache.of(pose, reader.read(pl.renderer)).values.near.round(2).tolist(), cache.measured
    ([20.5, 12.5], 3)

    A light that moved measures boxes widened by 2 % of the nearest one's
    distance (3.5), and keeps those measures while it stays within that margin:

    >>> snapshot = reader.read(pl.renderer)
    >>> moved = LightPose(LightKind.SPOT, np.array([0.01, 0, 0]), pose.direction, 45.0)
    >>> measured = cache.of(moved, snapshot)
    >>> measured.base is moved, round(measured.margin, 4), cache.measured
    (True, 0.0705, 5)
    >>> further = LightPose(LightKind.SPOT, np.array([0.05, 0, 0]), pose.direction, 45.0)
    >>> cache.of(further, snapshot).base is moved, cache.measured
    (True, 5)
    """

    def __init__(
        self,
        measure: Callable[[LightPose, np.ndarray], MeasuresT],
        *,
        turns: bool = False,
        group: MeasureGroup[MeasuresT] | None = None,
    ) -> None:
        self._measure = measure
        self._turns = turns
        self._group = group
        if group is not None:
            group.join(self)
        self._base: LightPose | None = None
        self._margin = 0.0
        #: A lower bound of the distance from ``_base`` to the nearest caster.
        self._nearest = 0.0
        #: The key of the last pose served: the light's pose is compared with it first.
        self._served: tuple | None = None
        self._snapshot: Snapshot | None = None
        self._measures: MeasuresT | None = None
        self.measured = 0

    def of(self, pose: LightPose, snapshot: Snapshot) -> Measured[MeasuresT]:
        """Return measures of every caster of ``snapshot`` that hold for the light ``pose``.

        Parameters
        ----------
        pose : LightPose
            The light.
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        Measured
            One row per caster of ``snapshot``: exact for ``pose`` while the
            light has not moved since they were taken, else those of widened
            boxes taken from a pose near it.
        """
        key = pose.key()
        base = self._base
        if base is not None and (key == self._served or self._holds(base, pose)):
            values = self._brought_to(snapshot)
            if values is not None:
                self._served = key
                return Measured(values, base, self._margin)
        moving = base is not None and key != self._served
        margin = 0.0
        if moving:
            assert base is not None
            margin = MARGIN_OF_NEAREST * max(self._nearest - _distance(base, pose), 0.0)
        self._measure_all(pose, snapshot, margin)
        self._served = key
        assert self._measures is not None  # measured just now
        return Measured(self._measures, pose, margin)

    def _holds(self, base: LightPose, pose: LightPose) -> bool:
        """Whether measures taken from ``base`` with this margin hold for ``pose``."""
        if _distance(base, pose) > self._margin:
            return False
        if not self._turns:
            return True
        return base.degrees_from(pose) <= TURN_DEGREES

    def _brought_to(self, snapshot: Snapshot) -> MeasuresT | None:
        """Return the kept measures brought up to ``snapshot``, or ``None`` if it is not theirs."""
        if snapshot is self._snapshot:
            return self._measures
        if not self._follows(snapshot):
            return None
        patches = snapshot.patches(CASTERS)
        if patches and self._group is not None:
            self._group.bring_to(snapshot, patches)
        else:
            self._patch(snapshot, patches)
        return self._measures

    def _patch(self, snapshot: Snapshot, patches: list[tuple[int, ActorState]]) -> None:
        """Measure the replaced casters of ``snapshot`` on their own and take them in."""
        if not patches:
            self._take(snapshot, [], None)
            return
        assert self._base is not None  # measures were taken from it
        bounds = np.array([state.bounds for _, state in patches])
        fresh = self._measure(self._base, widened_boxes(bounds, self._margin))
        self._take(snapshot, [row for row, _ in patches], fresh)

    def _follows(self, snapshot: Snapshot) -> bool:
        """Whether the kept measures are of the snapshot's parent (patched, they are its)."""
        kept = self._snapshot
        return kept is not None and snapshot.parent is kept and self._measures is not None

    def _take(self, snapshot: Snapshot, rows: list[int], fresh: MeasuresT | None) -> None:
        """Hold the measures of ``snapshot``: the kept ones with ``fresh`` in ``rows``."""
        self.measured += len(rows)
        self._snapshot = snapshot
        kept = self._measures
        if fresh is None or kept is None:
            return
        pairs = zip(kept, fresh, strict=True)
        self._measures = kept._make(_patched(old, rows, new) for old, new in pairs)
        self._nearest = min(self._nearest, _nearest_of(fresh))

    def _measure_all(self, pose: LightPose, snapshot: Snapshot, margin: float) -> None:
        boxes = snapshot.caster_bounds
        self.measured += len(boxes)
        measures = self._measure(pose, widened_boxes(boxes, margin))
        self._base, self._margin, self._snapshot, self._measures = pose, margin, snapshot, measures
        # The widened boxes are no farther than the boxes themselves.
        self._nearest = _nearest_of(measures)


class MeasureGroup(Generic[MeasuresT]):
    """The caster measures of several lights, brought up to a new snapshot in one call.

    A caster that moved under many lights is measured from all of them
    together when the first of them asks, instead of once per light (from
    :data:`~pvshadows.scene.culling.MANY_LIGHTS` lights on).

    Parameters
    ----------
    measure_many : callable
        ``measure_many(poses, boxes)``, with ``(lights, n, 2, 3)`` boxes,
        returns the named tuple of ``(lights, n)`` arrays whose row ``i`` is
        what the members' ``measure`` gives for ``poses[i]`` and
        ``boxes[i]``, to the same bits (for example
        :func:`pvshadows.scene.spot_fitting.cone_measures_many`).

    Attributes
    ----------
    batches : int
        Times several members were measured in one call (for tests).

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.spot_fitting import cone_measures, cone_measures_many
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.scene.measures import CasterMeasureCache, MeasureGroup
    >>> from pvshadows.scene.reader import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> box = pl.add_mesh(pv.Cube(center=(0, 0, -5)))
    >>> reader = SceneReader(lambda actor: "a cube")
    >>> group = MeasureGroup(cone_measures_many)
    >>> down = np.array([0, 0, -1.0])
    >>> poses = [LightPose(LightKind.SPOT, np.array([x, 0, 0]), down, 45.0) for x in (-1, 0, 1)]
    >>> caches = [CasterMeasureCache(cone_measures, turns=True, group=group) for _ in poses]
    >>> snapshot = reader.read(pl.renderer)
    >>> [c.of(p, snapshot).values.near.tolist() for c, p in zip(caches, poses)]
    [[20.5], [20.25], [20.5]]
    >>> box.position = (0, 0, 1)
    >>> snapshot = reader.read(pl.renderer)
    >>> [c.of(p, snapshot).values.near.tolist() for c, p in zip(caches, poses)], group.batches
    ([[12.5], [12.25], [12.5]], 1)
    """

    def __init__(self, measure_many: Callable[[list[LightPose], np.ndarray], MeasuresT]) -> None:
        self._measure_many = measure_many
        self._members: weakref.WeakSet[CasterMeasureCache[MeasuresT]] = weakref.WeakSet()
        self.batches = 0

    def join(self, cache: CasterMeasureCache[MeasuresT]) -> None:
        """Add a light's cache (it leaves when it is let go of).

        Parameters
        ----------
        cache : CasterMeasureCache
            The cache.
        """
        self._members.add(cache)

    def bring_to(self, snapshot: Snapshot, patches: list[tuple[int, ActorState]]) -> None:
        """Measure the casters replaced in ``snapshot`` for every member whose measures follow it.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors, following the members' last snapshot.
        patches : list of tuple
            Its ``(row in casters, new state)`` of the casters replaced.
        """
        followers = [cache for cache in self._members if cache._follows(snapshot)]
        if len(followers) < MANY_LIGHTS:
            for cache in followers:
                cache._patch(snapshot, patches)
            return
        rows = [row for row, _ in patches]
        bounds = np.array([state.bounds for _, state in patches])
        boxes = np.stack([widened_boxes(bounds, cache._margin) for cache in followers])
        bases = [cache._base for cache in followers]
        assert all(base is not None for base in bases)  # measures were taken from them
        fresh = self._measure_many(cast(list[LightPose], bases), boxes)
        self.batches += 1
        for i, cache in enumerate(followers):
            cache._take(snapshot, rows, fresh._make(values[i] for values in fresh))


def _distance(a: LightPose, b: LightPose) -> float:
    return math.dist(a.position.tolist(), b.position.tolist())


def _nearest_of(measures: NamedTuple) -> float:
    """Return the distance to the nearest box, from measures whose ``near`` is squared distances."""
    near = measures.near  # type: ignore[attr-defined]
    return math.sqrt(float(near.min())) if len(near) else math.inf


def _patched(values: np.ndarray, rows: list[int], fresh: np.ndarray) -> np.ndarray:
    """Return a copy of ``values`` with ``fresh`` in ``rows`` (the kept array stays as it was)."""
    patched = values.copy()
    patched[rows] = fresh
    return patched
