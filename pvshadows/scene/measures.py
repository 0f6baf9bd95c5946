"""Values measured from a light for each caster, kept and patched where actors changed.

A light's map is fitted to its casters (their distances, their spread
around a spot's axis, the cube faces each touches). Measured afresh, that is
a pass over every caster each time anything changes; kept per light while
the light stays where it is, a frame whose snapshot follows the last
(:meth:`pvshadows.scene.snapshot.Snapshot.successor`) measures only the
casters replaced in it: an actor that moved costs its own box, not the scene's.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Generic, NamedTuple, TypeVar

import numpy as np

from pvshadows.scene.lights import LightPose
from pvshadows.scene.snapshot import CASTERS, Snapshot

MeasuresT = TypeVar("MeasuresT", bound=NamedTuple)


class CasterMeasureCache(Generic[MeasuresT]):
    """One light's measures of every caster, kept while the light stays where it is.

    Parameters
    ----------
    measure : callable
        ``measure(pose, boxes)`` returns a named tuple of ``(n,)`` arrays, one
        row per ``(n, 2, 3)`` box (for example
        :func:`pvshadows.scene.fitting.cone_measures`).

    Attributes
    ----------
    measured : int
        Casters measured so far (for tests).

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.fitting import cone_measures
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.scene.measures import CasterMeasureCache
    >>> from pvshadows.scene.snapshot import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> boxes = [pl.add_mesh(pv.Cube(center=(x, 0, -5))) for x in (-1, 1)]
    >>> reader = SceneReader(lambda actor: "a cube")
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 45.0)
    >>> cache = CasterMeasureCache(cone_measures)
    >>> cache.of(pose, reader.read(pl.renderer)).near.round(2).tolist()
    [20.5, 20.5]
    >>> boxes[1].position = (0, 0, 1)
    >>> cache.of(pose, reader.read(pl.renderer)).near.round(2).tolist(), cache.measured
    ([20.5, 12.5], 3)
    """

    def __init__(self, measure: Callable[[LightPose, np.ndarray], MeasuresT]) -> None:
        self._measure = measure
        self._key: tuple | None = None
        self._snapshot: Snapshot | None = None
        self._measures: MeasuresT | None = None
        self.measured = 0

    def of(self, pose: LightPose, snapshot: Snapshot) -> MeasuresT:
        """Return the measures of every caster of ``snapshot`` from the light ``pose``.

        Parameters
        ----------
        pose : LightPose
            The light.
        snapshot : Snapshot
            This frame's actors.

        Returns
        -------
        named tuple
            What ``measure`` returns, one row per caster of ``snapshot``.
        """
        key = pose.key()
        kept = self._measures
        if kept is not None and key == self._key:
            if snapshot is self._snapshot:
                return kept
            if self._snapshot is not None and snapshot.parent is self._snapshot:
                patches = snapshot.patches(CASTERS)
                self.measured += len(patches)
                self._snapshot = snapshot
                if patches:
                    rows = [row for row, _ in patches]
                    fresh = self._measure(pose, np.array([state.bounds for _, state in patches]))
                    pairs = zip(kept, fresh, strict=True)
                    kept = kept._make(_patched(old, rows, new) for old, new in pairs)
                    self._measures = kept
                return kept
        self._key, self._snapshot = key, snapshot
        boxes = snapshot.caster_bounds
        self.measured += len(boxes)
        self._measures = self._measure(pose, boxes)
        return self._measures


def _patched(values: np.ndarray, rows: list[int], fresh: np.ndarray) -> np.ndarray:
    """Return a copy of ``values`` with ``fresh`` in ``rows`` (the kept array stays as it was)."""
    patched = values.copy()
    patched[rows] = fresh
    return patched
