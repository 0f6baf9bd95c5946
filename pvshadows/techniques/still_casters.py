"""A map redrawn for a few moving casters: those drawn over the kept depth of the still ones.

When a light's map must be drawn again but its light, its projection and its
casters are the ones it was last drawn with, save a few casters whose shape
or place changed again since the redraw before (an actor moving, its points
edited frame after frame), those few are *moving*. The other casters' depth
is drawn once into a second map of the same size, the *still* map; each
later redraw copies it into the light's map and draws only the moving
casters over it. A depth test keeps the nearest depth whatever order casters
are drawn in, so the map is the one a full redraw makes, texel for texel,
and the redraw costs the moving casters, not the scene. A caster that changes
once (an actor moved by hand) is drawn with all the others, as is every
caster of a redraw where the light or the projection changed, a caster came
or went, or more than :data:`MOST_MOVING` of the casters are moving, and every caster
of a map whose still casters are too few to be worth a still map
(:data:`STILL_CASTERS`, :data:`STILL_TRIANGLES`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Generic, TypeVar

import numpy as np

from pvshadows.model.report import PassReport
from pvshadows.scene.actor_state import ActorState
from pvshadows.techniques.base import Releasable

#: The largest share of a light's casters drawn over the still map; more and
#: every caster is drawn (the still map would save little).
MOST_MOVING = 0.5
#: The still casters worth a still map: this many, or this many triangles. Fewer
#: are drawn again at each redraw: a few draws of little cost less than the copy
#: of a whole map (a 2048-texel cube is 96 MiB of depth).
STILL_CASTERS, STILL_TRIANGLES = 16, 100_000


MapT = TypeVar("MapT", bound=Releasable)
#: The light's own map: a texture like the still map, or a cube's slot of an array.
TargetT = TypeVar("TargetT")


@dataclass(frozen=True)
class DepthStep(Generic[TargetT, MapT]):
    """One depth pass of a redraw: casters drawn into a map, cleared or over another's depth.

    Attributes
    ----------
    target : texture
        The map drawn.
    casters : list of ActorState
        The casters drawn into it.
    under : texture or None
        The map whose depth ``target`` starts with (copied in); ``None``:
        it starts cleared.
    still : bool
        Whether ``target`` is a still map (its passes' reports say so).
    """

    target: TargetT | MapT
    casters: list[ActorState]
    under: MapT | None = None
    still: bool = False

    def named(self, reports: list[PassReport]) -> list[PassReport]:
        """Return the step's pass reports, a still map's named as such ("... (still casters)").

        Parameters
        ----------
        reports : list of PassReport
            The reports of the passes that drew this step, changed in place.

        Returns
        -------
        list of PassReport
            The same reports.
        """
        if self.still:
            for report in reports:
                report.name = f"{report.name} (still casters)"
        return reports


class StillCasters(Generic[MapT]):
    """Tells, at each redraw of one light's map, which casters to draw into which map.

    Parameters
    ----------
    make_map : callable
        Makes the still map (a texture like the light's map) when first needed.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import numpy as np
    >>> from pvshadows.techniques.still_casters import StillCasters
    >>> mesh = SimpleNamespace(n_triangles=50_000)  # 3 still: worth a still map
    >>> casters = [SimpleNamespace(name=n, triangles=mesh) for n in "abcd"]
    >>> still = StillCasters(lambda: SimpleNamespace(name="still", release=lambda: None))
    >>> keys = [(n, 0) for n in "abcd"]
    >>> def redraw(view="light"):
    ...     serials = np.array([hash(key) for key in keys])  # a new one for each new key
    ...     steps = still.steps(view, casters, tuple(keys), serials, SimpleNamespace(name="map"))
    ...     return [(s.target.name, "".join(c.name for c in s.casters)) for s in steps]
    >>> redraw()  # a first draw: every caster
    [('map', 'abcd')]
    >>> keys[0] = ("a", 1)  # a moved once: drawn with every other caster
    >>> redraw()
    [('map', 'abcd')]
    >>> keys[0] = ("a", 2)  # again: the still map is drawn, and a over it
    >>> redraw()
    [('still', 'bcd'), ('map', 'a')]
    >>> keys[0] = ("a", 3)  # again: a alone, over the still map
    >>> redraw()
    [('map', 'a')]
    >>> redraw("the light moved")
    [('map', 'abcd')]
    """

    def __init__(self, make_map: Callable[[], MapT]) -> None:
        self._make_map = make_map
        self._map: MapT | None = None
        self._view: object = None
        self._keys: tuple = ()
        self._serials = np.zeros(0, dtype=np.int64)
        #: Rows of the casters drawn over the still map (the others are in it).
        self._moving: set[int] = set()
        #: Rows that changed at the last redraw without being moving yet.
        self._changed: set[int] = set()
        #: Whether the still map holds the casters not in ``_moving``.
        self._still_drawn = False
        #: Whether those casters are too few for a still map (fewer as ``_moving`` grows).
        self._too_few = False

    def steps(
        self,
        view: object,
        casters: list[ActorState],
        keys: tuple,
        serials: np.ndarray,
        target: TargetT,
    ) -> list[DepthStep[TargetT, MapT]]:
        """Say how this redraw draws ``casters`` into the light's map ``target``.

        Parameters
        ----------
        view : object
            What the map is drawn with besides its casters (the light, the
            projection, the settings): compared by equality.
        casters : list of ActorState
            The casters this redraw draws.
        keys : tuple
            Their :meth:`~pvshadows.scene.actor_state.ActorState.key`, in order
            (the actor's id first).
        serials : numpy.ndarray
            ``(n,)`` their :attr:`~pvshadows.scene.actor_state.ActorState.serial`:
            the rows where it differs from the last redraw's are the only
            ones whose keys are compared.
        target : texture
            The light's map.

        Returns
        -------
        list of DepthStep
            Every caster into ``target``; or the still casters into the still
            map when it does not hold them yet, and the moving ones into
            ``target`` over it.
        """
        every: list[DepthStep[TargetT, MapT]] = [DepthStep(target, casters)]
        last_view, last_keys, last_serials = self._view, self._keys, self._serials
        # A copy: the snapshot patches its own array in place at later frames.
        self._view, self._keys, self._serials = view, keys, serials.copy()
        if view != last_view or len(keys) != len(last_keys):
            self._start_afresh()
            return every
        # A caster's state is the same while its serial is: compare the others' keys only.
        differ = np.flatnonzero(serials != last_serials).tolist()
        if any(last_keys[row][0] != keys[row][0] for row in differ):  # another caster there
            self._start_afresh()
            return every
        fresh = {row for row in differ if last_keys[row] != keys[row]} - self._moving
        repeated, self._changed = fresh <= self._changed, fresh
        if fresh and not repeated:  # changed once (so far): the still map no longer holds it
            self._still_drawn = False
            return every
        self._moving |= fresh
        if not self._moving or len(self._moving) > MOST_MOVING * len(keys):
            self._start_afresh()
            return every
        rows = self._moving
        if self._still_drawn and not fresh:
            assert self._map is not None  # drawn
            return [DepthStep(target, [casters[row] for row in sorted(rows)], self._map)]
        if self._too_few:
            return every
        still = [caster for row, caster in enumerate(casters) if row not in rows]
        if not worth_a_still_map(still):
            self._too_few = True
            return every
        if self._map is None:
            self._map = self._make_map()
        self._still_drawn = True
        moving = [casters[row] for row in sorted(rows)]
        return [DepthStep(self._map, still, still=True), DepthStep(target, moving, self._map)]

    def _start_afresh(self) -> None:
        self._moving, self._changed = set(), set()
        self._still_drawn = self._too_few = False

    def release(self) -> None:
        """Release the still map, if one was made."""
        if self._map is not None:
            self._map.release()
            self._map = None
        self._start_afresh()


def worth_a_still_map(still: list[ActorState]) -> bool:
    """Tell whether casters are many enough to be kept in a still map rather than drawn again.

    Parameters
    ----------
    still : list of ActorState
        The casters that stay still.

    Returns
    -------
    bool
        ``True`` for at least :data:`STILL_CASTERS` casters or
        :data:`STILL_TRIANGLES` triangles.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pvshadows.techniques.still_casters import worth_a_still_map
    >>> mesh = SimpleNamespace(triangles=SimpleNamespace(n_triangles=60_000))
    >>> worth_a_still_map([mesh]), worth_a_still_map([mesh, mesh])
    (False, True)
    """
    if len(still) >= STILL_CASTERS:
        return True
    return sum(caster.triangles.n_triangles for caster in still) >= STILL_TRIANGLES


def depth_steps(
    still: StillCasters[MapT] | None,
    view: object,
    casters: list[ActorState],
    keys: tuple,
    serials: np.ndarray,
    target: TargetT,
) -> list[DepthStep[TargetT, MapT]]:
    """Return :meth:`StillCasters.steps`, or every caster into ``target`` without a still map.

    Parameters
    ----------
    still : StillCasters or None
        The light's, ``None`` where maps cannot be copied.
    view, casters, keys, serials, target
        As for :meth:`StillCasters.steps`.

    Returns
    -------
    list of DepthStep
        The redraw's passes.
    """
    if still is None:
        return [DepthStep(target, casters)]
    return still.steps(view, casters, keys, serials, target)
