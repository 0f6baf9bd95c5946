"""The actors of a renderer in one frame: casters, receivers and what is derived from them.

A :class:`Snapshot` lists the frame's :class:`~pvshadows.scene.actor_state.ActorState`
objects and stacks what the passes and the planner read of them all (bounds,
model matrices, role rows, the boxes round them). A snapshot in which only
some actors changed follows the last one and patches those rows only
(:meth:`Snapshot.successor`), so a frame costs the actors that changed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.scene.actor_state import ActorState, Sheet
from pvshadows.scene.culling import box_around

#: Roles of :meth:`Snapshot.patches`: the casters, the receivers, every actor.
CASTERS, RECEIVERS, ALL_ACTORS = 0, 1, 2
#: Lists made by :meth:`Snapshot.casters_at` whose rows a snapshot remembers (the latest).
KEPT_SUBSETS = 16


@dataclass(eq=False)
class Snapshot:
    """The actors of a renderer in one frame.

    A snapshot in which only some actors' states changed, their roles kept,
    follows the last one (:meth:`successor`): what it derives from its
    actors (role lists, stacked bounds and matrices) is last frame's,
    patched in the changed rows, so it costs the actors that changed rather
    than every actor. The role lists are copied (plans keep them); the
    stacked arrays, per-caster lists and row maps are taken over from the
    parent and patched in place (the parent derives them afresh if it is
    asked again).

    Attributes
    ----------
    actors : list of ActorState
        Visible actors with triangles.
    bystanders : list of vtk.vtkActor
        Visible actors that show no shadow (not receivers, unlit, or without
        triangles); they still need the probe edit to report "no surface".
    """

    actors: list[ActorState]
    bystanders: list[vtk.vtkActor]
    #: Keys (:func:`pvshadows.scene.triangles.vtk_id`) of the actors read again for this frame.
    changed: frozenset[str] = field(default_factory=frozenset)
    #: The snapshot this one follows (:meth:`successor`), else ``None``: read afresh.
    parent: Snapshot | None = field(default=None, repr=False)
    #: Rows of :attr:`actors` whose state is new since :attr:`parent`.
    replaced: tuple[int, ...] = ()

    def successor(self, states: dict[int, ActorState], changed: frozenset[str]) -> Snapshot:
        """Return the snapshot that follows this one with some actors' states replaced.

        Parameters
        ----------
        states : dict of int to ActorState
            New states by row of :attr:`actors`; each keeps its actor's roles
            (caster, receiver, plane).
        changed : frozenset of str
            Keys of the actors read again.

        Returns
        -------
        Snapshot
            The next snapshot; it derives its arrays from this one's.
        """
        actors = list(self.actors)
        for row, state in states.items():
            actors[row] = state
        # Only one generation back is kept: this snapshot no longer needs its own parent.
        self.parent = None
        return Snapshot(actors, self.bystanders, changed, self, tuple(sorted(states)))

    def _inherited(self, name: str) -> object | None:
        """Return what the parent derived as ``name``, if it has (else ``None``)."""
        parent = self.parent
        return None if parent is None else parent.__dict__.get(name)

    def _taken(self, name: str) -> Any:
        """Take over what the parent derived as ``name``, to patch it in place (else ``None``).

        The parent lets it go: asked again, it derives it afresh from its
        own actors, so what it answers stays right.
        """
        parent = self.parent
        return None if parent is None else parent.__dict__.pop(name, None)

    @cached
    def _role_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """Each actor's row in :attr:`casters` and in :attr:`receivers` (-1 when not one)."""
        kept = self._inherited("_role_rows")
        if kept is not None:
            return kept  # type: ignore[return-value]  # roles are the parent's
        casting = np.array([a.caster for a in self.actors], dtype=bool)
        receiving = np.array([a.receiver for a in self.actors], dtype=bool)
        return _rows_within(casting), _rows_within(receiving)

    @cached
    def caster_index(self) -> np.ndarray:
        """Rows of :attr:`actors` that are :attr:`casters`, in order (read-only)."""
        return self._role_index("caster_index", CASTERS)

    def _role_index(self, name: str, role: int) -> np.ndarray:
        kept = self._inherited(name)
        if kept is not None:
            return kept  # type: ignore[return-value]  # roles are the parent's
        index = np.flatnonzero(self._role_rows[role] >= 0)
        index.setflags(write=False)
        return index

    @cached
    def every_receiver(self) -> np.ndarray:
        """``(n,)`` read-only, true for each of :attr:`receivers`.

        What a light that reaches every actor reaches of them: one array per
        snapshot and those that follow it (their roles are its), so that
        what the camera saw of it last frame answers first
        (:class:`pvshadows.pipeline.sight.ViewSight`).
        """
        kept = self._inherited("every_receiver")
        if kept is not None:
            return kept  # type: ignore[return-value]
        every = np.ones(len(self.receivers), dtype=bool)
        every.setflags(write=False)
        return every

    @cached
    def receiver_index(self) -> np.ndarray:
        """Rows of :attr:`actors` that are :attr:`receivers`, in order (read-only)."""
        return self._role_index("receiver_index", RECEIVERS)

    def patches(self, role: int) -> list[tuple[int, ActorState]]:
        """Return the actors of a role replaced since :attr:`parent`.

        Parameters
        ----------
        role : int
            :data:`CASTERS`, :data:`RECEIVERS` or :data:`ALL_ACTORS`.

        Returns
        -------
        list of tuple
            ``(row in the role's list, new state)`` for each.
        """
        if role == ALL_ACTORS:
            return [(r, self.actors[r]) for r in self.replaced]
        rows = self._role_rows[role]
        return [(int(rows[r]), self.actors[r]) for r in self.replaced if rows[r] >= 0]

    @cached
    def casters(self) -> list[ActorState]:
        """Actors that cast shadows."""
        return self._role_list("casters", CASTERS, lambda a: a.caster)

    @cached
    def receivers(self) -> list[ActorState]:
        """Actors that show shadows."""
        return self._role_list("receivers", RECEIVERS, lambda a: a.receiver)

    def _role_list(self, name: str, role: int, member) -> list[ActorState]:
        kept = self._inherited(name)
        if kept is None:
            return [a for a in self.actors if member(a)]
        states = list(kept)  # type: ignore[call-overload]
        for row, state in self.patches(role):
            states[row] = state
        return states

    @cached
    def caster_sides(self) -> list[str | None]:
        """:attr:`ActorState.cull_side` of :attr:`casters`."""
        return self._caster_values("caster_sides", lambda c: c.cull_side)

    @cached
    def caster_keys(self) -> list[tuple]:
        """:meth:`ActorState.key` of :attr:`casters`."""
        return self._caster_values("caster_keys", ActorState.key)

    def _caster_values(self, name: str, value) -> list:
        """List ``value`` of the casters, or take the parent's list and patch the changed rows."""
        values = self._taken(name)
        if values is None:
            return [value(c) for c in self.casters]
        for row, state in self.patches(CASTERS):
            values[row] = value(state)
        return values

    @cached
    def caster_flat(self) -> np.ndarray:
        """Whether each of :attr:`casters` is flat (:attr:`ActorState.sheet`), ``(n,)``."""
        return self._stacked("caster_flat", CASTERS, lambda s: s.sheet is not None, ())

    @cached
    def flat_caster_rows(self) -> list[int]:
        """The rows of :attr:`casters` that are flat (:attr:`caster_flat`), in plain ints."""
        return np.flatnonzero(self.caster_flat).tolist()

    @cached
    def solid_caster_rows(self) -> np.ndarray:
        """The rows of :attr:`casters` that are not flat, ``(n,)`` (read-only)."""
        rows = np.flatnonzero(~self.caster_flat)
        rows.setflags(write=False)
        return rows

    @cached
    def caster_transmittance(self) -> np.ndarray:
        """:attr:`ActorState.transmittance` of :attr:`casters`, ``(n,)``."""
        return self._stacked("caster_transmittance", CASTERS, lambda s: s.transmittance, ())

    @cached
    def some_caster_translucent(self) -> bool:
        """Whether some caster lets light through (:attr:`ActorState.transmittance` above 0)."""
        return bool(self.caster_transmittance.any())

    @cached
    def caster_serials(self) -> np.ndarray:
        """:attr:`ActorState.serial` of :attr:`casters`, ``(n,)`` int64."""
        return self._stacked("caster_serials", CASTERS, lambda s: s.serial, ()).astype(
            np.int64, copy=False
        )

    @cached
    def caster_triangles(self) -> np.ndarray:
        """Triangle counts of :attr:`casters`, ``(n,)``."""
        return self._stacked("caster_triangles", CASTERS, lambda s: s.triangles.n_triangles, ())

    def sheet_span(self, state: ActorState) -> tuple[float, float]:
        """Return how far the other receivers reach on either side of a flat actor's plane.

        Found once per snapshot and flat actor, and shared by every light
        that asks whether the actor shadows anything; a snapshot that
        follows another measures again only the receivers replaced since.

        Parameters
        ----------
        state : ActorState
            An actor of this snapshot with a :attr:`ActorState.sheet`.

        Returns
        -------
        tuple of float
            The least and greatest signed distance along the sheet's normal
            of the corners of every other receiver's bounds;
            ``(inf, -inf)`` when there is no other receiver.
        """
        span = self._sheet_spans.get(id(state))
        if span is None:
            sheet = state.sheet
            assert sheet is not None  # asked of flat actors only
            low, high = self._sheet_heights(state, sheet)
            offset = float(sheet.anchor @ sheet.normal)
            span = (float(low.min()) - offset, float(high.max()) - offset) if low.size else _NO_SPAN
            self._sheet_spans[id(state)] = span
        return span

    @cached
    def _sheet_spans(self) -> dict[int, tuple[float, float]]:
        return {}

    @cached
    def _heights_by_sheet(self) -> dict[int, tuple[np.ndarray, np.ndarray]]:
        return {}

    def _sheet_heights(self, state: ActorState, sheet: Sheet) -> tuple[np.ndarray, np.ndarray]:
        """Each receiver's lowest and highest corner along a flat actor's normal.

        The flat actor's own row, when it receives, is left out (``inf`` and
        ``-inf``). An unchanged flat actor takes the parent's heights,
        measured again in the rows of the receivers replaced since.
        """
        heights = self._heights_by_sheet.get(id(state))
        if heights is not None:
            return heights
        kept = self._inherited("_heights_by_sheet")
        kept_heights = kept.pop(id(state), None) if isinstance(kept, dict) else None
        if kept_heights is None:
            low, high = _extents_along(self.receiver_bounds, sheet.normal)
            row = self._receiver_rows.get(id(state))
            if row is not None:
                low[row], high[row] = np.inf, -np.inf
        else:  # taken over from the parent, patched in place
            rows = [row for row, _ in self.patches(RECEIVERS)]
            low, high = kept_heights
            low[rows], high[rows] = _extents_along(self.receiver_bounds[rows], sheet.normal)
        heights = self._heights_by_sheet[id(state)] = (low, high)
        return heights

    def keys_of(self, casters: list[ActorState]) -> tuple:
        """Return :meth:`ActorState.key` of some of this snapshot's casters, as one tuple.

        Parameters
        ----------
        casters : list of ActorState
            Casters of this snapshot.

        Returns
        -------
        tuple
            Their keys, in order: equal for the same casters in the same shapes.
        """
        if casters is self.casters:
            return self._every_caster_key
        keys = self.caster_keys
        return tuple(map(keys.__getitem__, self.caster_rows(casters).tolist()))

    @cached
    def _every_caster_key(self) -> tuple:
        """:attr:`caster_keys` as a tuple, made once (asked for by every map drawn)."""
        return tuple(self.caster_keys)

    @cached
    def actor_bounds(self) -> np.ndarray:
        """World bounds of :attr:`actors`, ``(n, 2, 3)``."""
        return self._stacked("actor_bounds", ALL_ACTORS, lambda s: s.bounds, (2, 3))

    @cached
    def caster_bounds(self) -> np.ndarray:
        """World bounds of :attr:`casters`, ``(n, 2, 3)``."""
        return self._stacked("caster_bounds", CASTERS, lambda s: s.bounds, (2, 3))

    @cached
    def receiver_bounds(self) -> np.ndarray:
        """World bounds of :attr:`receivers`, ``(n, 2, 3)``."""
        return self._stacked("receiver_bounds", RECEIVERS, lambda s: s.bounds, (2, 3))

    @cached
    def receivers_box(self) -> np.ndarray:
        """World bounds of all :attr:`receivers` together, ``(2, 3)`` (NaN when there are none)."""
        return self._box_round("receivers_box", "receiver_bounds", RECEIVERS)

    @cached
    def casters_box(self) -> np.ndarray:
        """World bounds of all :attr:`casters` together, ``(2, 3)`` (NaN when there are none)."""
        return self._box_round("casters_box", "caster_bounds", CASTERS)

    @cached
    def scene_box(self) -> np.ndarray:
        """World bounds of every caster and receiver together, ``(2, 3)`` (NaN when none is).

        Worked out from :attr:`casters_box` and :attr:`receivers_box`, which a
        snapshot that follows patches: no pass over the actors.
        """
        boxes = [box for box in (self.casters_box, self.receivers_box) if np.isfinite(box).all()]
        if not boxes:
            return np.full((2, 3), np.nan)
        if len(boxes) == 1:
            return boxes[0]
        return np.array(
            [np.minimum(boxes[0][0], boxes[1][0]), np.maximum(boxes[0][1], boxes[1][1])]
        )

    @cached
    def scene_size(self) -> float:
        """The diagonal of :attr:`scene_box` (0 when there is no caster or receiver)."""
        low, high = self.scene_box.tolist()
        return math.dist(low, high) if math.isfinite(sum(low) + sum(high)) else 0.0

    def _box_round(self, name: str, bounds_name: str, role: int) -> np.ndarray:
        """Return the box round a role's bounds, widening the parent's where it can.

        The parent's box stays exact unless a replaced actor's old bounds
        held one of its faces and its new bounds no longer reach it: then the
        box is found afresh. Otherwise it only widens to take in the new
        bounds (min and max are exact: the box found afresh, bit for bit), a
        few plain floats per moved actor instead of a pass over every actor.
        """
        bounds = getattr(self, bounds_name)
        kept, parent = self._inherited(name), self.parent
        rows = [row for row, _ in self.patches(role)]
        if not (isinstance(kept, np.ndarray) and parent is not None and rows):
            return box_around(bounds)
        before = (parent.casters, parent.receivers, parent.actors)[role]
        olds = [before[row].bounds.tolist() for row in rows]
        (low, high), news = kept.tolist(), bounds[rows].tolist()
        for (old_low, old_high), (new_low, new_high) in zip(olds, news, strict=True):
            for axis in range(3):
                if old_low[axis] <= low[axis] < new_low[axis]:
                    return box_around(bounds)  # it held a face it has left
                if new_high[axis] < high[axis] <= old_high[axis]:
                    return box_around(bounds)
        for new_low, new_high in news:
            low = [min(a, b) for a, b in zip(low, new_low, strict=True)]
            high = [max(a, b) for a, b in zip(high, new_high, strict=True)]
        return np.array([low, high])

    @cached
    def caster_model_columns(self) -> np.ndarray:
        """Model matrices of :attr:`casters` (:meth:`ActorState.model_matrix`), transposed.

        ``(n, 4, 4)``: row ``i`` holds caster ``i``'s matrix transposed, so that
        ``caster_model_columns.reshape(-1, 4) @ matrix.T`` is ``matrix`` times
        every caster's matrix (transposed) in one product of two 2-D arrays,
        several times cheaper than numpy's stacked ``matrix @ models`` for
        many casters.
        """
        return self._stacked("caster_model_columns", CASTERS, _model_columns, (4, 4))

    def _stacked(self, name: str, role: int, value, shape: tuple[int, ...]) -> np.ndarray:
        """Stack ``value`` of a role's states, or patch the parent's stack (taken over)."""
        stacked = self._taken(name)
        if stacked is None:
            states = (self.casters, self.receivers, self.actors)[role]
            return np.array([value(s) for s in states]).reshape(-1, *shape)
        for row, state in self.patches(role):
            stacked[row] = value(state)
        return stacked

    @cached
    def _caster_rows(self) -> dict[int, int]:
        return self._rows_by_id("_caster_rows", CASTERS)

    @cached
    def _receiver_rows(self) -> dict[int, int]:
        return self._rows_by_id("_receiver_rows", RECEIVERS)

    def _rows_by_id(self, name: str, role: int) -> dict[int, int]:
        """Map ``id(state)`` to its row in a role's list, or take the parent's map and patch it."""
        states = (self.casters, self.receivers)[role]
        rows = self._taken(name)
        if rows is None:
            return {id(state): row for row, state in enumerate(states)}
        parent = self.parent
        assert parent is not None  # kept comes from it
        before = (parent.casters, parent.receivers)[role]
        for row, state in self.patches(role):
            del rows[id(before[row])]
            rows[id(state)] = row
        return rows

    @cached
    def _subsets(self) -> dict[int, tuple[list[ActorState], np.ndarray]]:
        return {}

    def casters_at(self, rows: np.ndarray) -> list[ActorState]:
        """Return the casters in some rows of :attr:`casters`, remembering where they sit.

        A list made here knows its rows: :meth:`caster_rows`, and through it
        every stacked array gathered for it, costs no lookup per caster. The
        snapshot remembers the latest :data:`KEPT_SUBSETS` such lists; an
        older one is looked up caster by caster.

        Parameters
        ----------
        rows : numpy.ndarray
            ``(n,)`` increasing rows of :attr:`casters`.

        Returns
        -------
        list of ActorState
            Those casters, in order (:attr:`casters` itself when ``rows``
            holds every row).

        Examples
        --------
        >>> import numpy as np
        >>> import pyvista as pv
        >>> from pvshadows.scene.reader import SceneReader
        >>> pl = pv.Plotter(off_screen=True)
        >>> for x in range(3):
        ...     _ = pl.add_mesh(pv.Cube(center=(2 * x, 0, 0)))
        >>> snapshot = SceneReader(lambda actor: "a cube").read(pl.renderer)
        >>> pair = snapshot.casters_at(np.array([0, 2]))
        >>> snapshot.caster_rows(pair).tolist()
        [0, 2]
        """
        casters = self.casters
        if len(rows) == len(casters):
            return casters
        subset = [casters[row] for row in rows.tolist()]
        rows = rows.copy()
        rows.setflags(write=False)
        subsets = self._subsets
        if len(subsets) >= KEPT_SUBSETS:  # a light moving over a still scene makes one a frame
            del subsets[next(iter(subsets))]
        subsets[id(subset)] = (subset, rows)
        return subset

    def caster_rows(self, casters: list[ActorState]) -> np.ndarray:
        """Return where each of some of this snapshot's casters sits in :attr:`casters`.

        Parameters
        ----------
        casters : list of ActorState
            Casters of this snapshot.

        Returns
        -------
        numpy.ndarray
            ``(n,)`` rows of :attr:`caster_bounds` and :attr:`caster_model_columns`.
        """
        if casters is self.casters:
            return np.arange(len(casters))
        known = self._subsets.get(id(casters))
        if known is not None and known[0] is casters:
            return known[1]
        rows = self._caster_rows
        return np.fromiter(map(rows.__getitem__, map(id, casters)), np.intp, len(casters))

    def caster_rows_among(self, actors: list[ActorState]) -> np.ndarray:
        """Return where each of some of this snapshot's actors sits in :attr:`casters`.

        Parameters
        ----------
        actors : list of ActorState
            Actors of this snapshot, casters or not.

        Returns
        -------
        numpy.ndarray
            ``(n,)`` rows of :attr:`casters`, -1 for an actor that casts nothing.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows.scene.reader import SceneReader
        >>> from pvshadows.scene.triangles import vtk_id
        >>> pl = pv.Plotter(off_screen=True)
        >>> ground = pl.add_mesh(pv.Plane())
        >>> _ = pl.add_mesh(pv.Sphere())
        >>> reader = SceneReader(vtk_id)
        >>> reader.set_casting(vtk_id(ground), False, None)
        >>> snapshot = reader.read(pl.renderer)
        >>> snapshot.caster_rows_among(snapshot.actors).tolist()
        [-1, 0]
        """
        rows = self._caster_rows
        return np.fromiter((rows.get(id(a), -1) for a in actors), np.intp, len(actors))

    def bounds_of(self, casters: list[ActorState]) -> np.ndarray:
        """Return the world bounds of some of this snapshot's casters, ``(n, 2, 3)``.

        Parameters
        ----------
        casters : list of ActorState
            Casters of this snapshot.

        Returns
        -------
        numpy.ndarray
            Their rows of :attr:`caster_bounds`, gathered without stacking again.
        """
        return self.for_casters(self.caster_bounds, casters)

    def for_casters(self, values: np.ndarray, casters: list[ActorState]) -> np.ndarray:
        """Return the rows of a per-caster array that belong to some of this snapshot's casters.

        Parameters
        ----------
        values : numpy.ndarray
            One row per caster of :attr:`casters`.
        casters : list of ActorState
            Casters of this snapshot.

        Returns
        -------
        numpy.ndarray
            ``values`` itself for every caster, else their rows gathered.

        Examples
        --------
        >>> import numpy as np
        >>> import pyvista as pv
        >>> from pvshadows.scene.reader import SceneReader
        >>> pl = pv.Plotter(off_screen=True)
        >>> for x in range(2):
        ...     _ = pl.add_mesh(pv.Cube(center=(2 * x, 0, 0)))
        >>> snapshot = SceneReader(lambda actor: "a cube").read(pl.renderer)
        >>> values = np.array([10, 20])
        >>> snapshot.for_casters(values, snapshot.casters) is values
        True
        >>> snapshot.for_casters(values, snapshot.casters_at(np.array([1]))).tolist()
        [20]
        """
        if casters is self.casters:
            return values
        return values[self.caster_rows(casters)]


_NO_SPAN = (math.inf, -math.inf)


def _model_columns(state: ActorState) -> np.ndarray:
    """Return a state's model matrix transposed (:attr:`Snapshot.caster_model_columns`)."""
    return state.model_matrix().T


def _rows_within(members: np.ndarray) -> np.ndarray:
    """Return each item's row among the members (``-1`` for a non-member)."""
    rows = np.full(len(members), -1, dtype=np.intp)
    rows[members] = np.arange(int(members.sum()))
    return rows


def _extents_along(bounds: np.ndarray, normal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the lowest and highest corner of each ``(n, 2, 3)`` box along ``normal``.

    A box's lowest corner takes its minimum where the normal is positive
    and its maximum where it is negative. Summed per box in the same order
    for any number of boxes, so that rows measured again alone match rows
    measured among all.
    """
    up, down = np.maximum(normal, 0.0), np.minimum(normal, 0.0)
    low, high = bounds[:, 0], bounds[:, 1]
    return (low * up + high * down).sum(axis=1), (high * up + low * down).sum(axis=1)
