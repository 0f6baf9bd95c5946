"""What a renderer holds in one frame: casters, receivers and their geometry.

VTK tells which actors changed: observers on each object an actor's shadow
depends on (:mod:`pvshadows.scene.watch`) mark it a suspect when VTK modifies
it, and a frame compares the stamps (modification times and roles) of the
suspects alone, or of every actor when the actors' roles (a version the role
setters raise) changed. An actor whose stamp did not change keeps last
frame's state (matrix, bounds, name, triangles) untouched. The renderer's
actor list is walked again only when its props changed. Triangles are re-read
only when the actor's data changed. When no actor changed, the frame reads
no actor at all and gets last frame's :class:`Snapshot` itself, so what is
derived from it can be kept too.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from itertools import count
from typing import Any

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import translation
from pvshadows.scene.culling import box_around
from pvshadows.scene.translucency import transmittance
from pvshadows.scene.triangles import (
    ActorTriangles,
    actor_matrix,
    read_triangles,
    vtk_id,
    world_bounds,
)
from pvshadows.scene.watch import ModificationWatch, watched_objects


@dataclass
class ActorState:
    """One actor in one frame.

    Attributes
    ----------
    actor : vtk.vtkActor
        The actor.
    namer : callable
        Names an actor for messages (the plotter's
        :class:`pvshadows.scene.naming.ActorNames`): :attr:`name` asks it
        only when a message needs the name.
    triangles : ActorTriangles
        Its surface.
    matrix : numpy.ndarray
        Model-to-world matrix (float64, 4x4).
    bounds : numpy.ndarray
        World bounds ``(2, 3)``.
    caster, receiver : bool
        Its roles this frame.
    plane : bool
        Named the receiving plane of planar shadows
        (``pl.shadows.set_receiver(actor, plane=True)``).
    transmittance : float
        Share of light each of its surfaces lets through as a caster:
        ``1 - opacity``, or what ``pl.shadows.set_caster(actor,
        transmittance=...)`` set.
    faces_drawn : bool
        Whether VTK draws its faces: ``False`` for the wireframe and points
        styles, between whose lines or points the camera sees what lies
        behind (unless the renderer's hidden-line removal hides it). Its
        triangles cast all the same.
    serial : int
        A number no other state of the process has: equal serials, the same
        state (compared in bulk where comparing states one by one would
        cost a call each).
    """

    actor: vtk.vtkActor
    namer: Callable[[vtk.vtkActor], str] = field(repr=False)
    triangles: ActorTriangles
    matrix: np.ndarray
    bounds: np.ndarray
    caster: bool
    receiver: bool
    plane: bool = False
    transmittance: float = 0.0
    faces_drawn: bool = True
    serial: int = field(default_factory=count().__next__, init=False, repr=False, compare=False)

    @cached_property
    def name(self) -> str:
        """How messages name it: asked once, when first needed (naming reads PyVista's wrappers)."""
        return self.namer(self.actor)

    def model_matrix(self) -> np.ndarray:
        """Return the model-to-world matrix of :attr:`triangles`' centred points (float64).

        Computed once per state and read-only: every pass of every light
        reads the same matrix.
        """
        return self._model_matrix

    @cached_property
    def _model_matrix(self) -> np.ndarray:
        matrix = self.matrix @ translation(self.triangles.center)
        matrix.setflags(write=False)
        return matrix

    def key(self) -> tuple:
        """Return a value that changes when the actor's shadow-casting shape changes."""
        return self._key

    @cached_property
    def _key(self) -> tuple:
        return (vtk_id(self.actor), self.triangles.version, self.matrix.tobytes())

    @cached_property
    def mirrored(self) -> bool:
        """Whether its matrix mirrors it (turns outward-wound triangles inward)."""
        return bool(np.linalg.det(self.matrix[:3, :3]) < 0.0)

    @cached_property
    def cull_side(self) -> str | None:
        """The side of its triangles a depth pass that culls front faces leaves out.

        ``"front"`` for a closed, outward-wound caster (``"back"`` if its
        matrix mirrors it), ``None`` when it is open or inward-wound.
        """
        if not self.triangles.closed_outward():
            return None
        return "back" if self.mirrored else "front"

    @cached_property
    def sheet(self) -> Sheet | None:
        """The plane the actor lies in when it is flat (a ground, a wall), else ``None``.

        Flat means every point within ``1e-6`` of the actor's size of the
        plane of its first triangle
        (:meth:`pvshadows.scene.triangles.ActorTriangles.model_plane`, found
        once per triangles); placed in the world once per state.
        """
        plane = self.triangles.model_plane()
        if plane is None:
            return None
        point, normal, size = plane
        if size == 0.0:
            return Sheet(np.zeros(3), np.zeros(3), 0.0)
        world_normal = np.linalg.inv(self.matrix[:3, :3]).T @ normal
        world_normal /= np.linalg.norm(world_normal)
        anchor = (self.matrix @ np.append(point + self.triangles.center, 1.0))[:3]
        return Sheet(anchor, world_normal, size)


@dataclass(frozen=True)
class Sheet:
    """The world plane of a flat actor.

    Attributes
    ----------
    anchor : numpy.ndarray
        A world point of the plane.
    normal : numpy.ndarray
        Its unit normal (either side); zero for an actor with fewer than
        three points, which has no surface at all.
    size : float
        The actor's largest extent, the scale of the flatness tolerance.
    """

    anchor: np.ndarray
    normal: np.ndarray
    size: float


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

    @cached_property
    def _role_rows(self) -> tuple[np.ndarray, np.ndarray]:
        """Each actor's row in :attr:`casters` and in :attr:`receivers` (-1 when not one)."""
        kept = self._inherited("_role_rows")
        if kept is not None:
            return kept  # type: ignore[return-value]  # roles are the parent's
        casting = np.array([a.caster for a in self.actors], dtype=bool)
        receiving = np.array([a.receiver for a in self.actors], dtype=bool)
        return _rows_within(casting), _rows_within(receiving)

    @cached_property
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

    @cached_property
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

    @cached_property
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

    @cached_property
    def casters(self) -> list[ActorState]:
        """Actors that cast shadows."""
        return self._role_list("casters", CASTERS, lambda a: a.caster)

    @cached_property
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

    @cached_property
    def caster_sides(self) -> list[str | None]:
        """:attr:`ActorState.cull_side` of :attr:`casters`."""
        return self._caster_values("caster_sides", lambda c: c.cull_side)

    @cached_property
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

    @cached_property
    def caster_flat(self) -> np.ndarray:
        """Whether each of :attr:`casters` is flat (:attr:`ActorState.sheet`), ``(n,)``."""
        return self._stacked("caster_flat", CASTERS, lambda s: s.sheet is not None, ())

    @cached_property
    def caster_transmittance(self) -> np.ndarray:
        """:attr:`ActorState.transmittance` of :attr:`casters`, ``(n,)``."""
        return self._stacked("caster_transmittance", CASTERS, lambda s: s.transmittance, ())

    @cached_property
    def some_caster_translucent(self) -> bool:
        """Whether some caster lets light through (:attr:`ActorState.transmittance` above 0)."""
        return bool(self.caster_transmittance.any())

    @cached_property
    def caster_serials(self) -> np.ndarray:
        """:attr:`ActorState.serial` of :attr:`casters`, ``(n,)`` int64."""
        return self._stacked("caster_serials", CASTERS, lambda s: s.serial, ()).astype(
            np.int64, copy=False
        )

    @cached_property
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

    @cached_property
    def _sheet_spans(self) -> dict[int, tuple[float, float]]:
        return {}

    @cached_property
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
        keys = self.caster_keys
        if casters is self.casters:
            return tuple(keys)
        return tuple(map(keys.__getitem__, self.caster_rows(casters).tolist()))

    @cached_property
    def actor_bounds(self) -> np.ndarray:
        """World bounds of :attr:`actors`, ``(n, 2, 3)``."""
        return self._stacked("actor_bounds", ALL_ACTORS, lambda s: s.bounds, (2, 3))

    @cached_property
    def caster_bounds(self) -> np.ndarray:
        """World bounds of :attr:`casters`, ``(n, 2, 3)``."""
        return self._stacked("caster_bounds", CASTERS, lambda s: s.bounds, (2, 3))

    @cached_property
    def receiver_bounds(self) -> np.ndarray:
        """World bounds of :attr:`receivers`, ``(n, 2, 3)``."""
        return self._stacked("receiver_bounds", RECEIVERS, lambda s: s.bounds, (2, 3))

    @cached_property
    def receivers_box(self) -> np.ndarray:
        """World bounds of all :attr:`receivers` together, ``(2, 3)`` (NaN when there are none)."""
        return self._box_round("receivers_box", "receiver_bounds", RECEIVERS)

    @cached_property
    def casters_box(self) -> np.ndarray:
        """World bounds of all :attr:`casters` together, ``(2, 3)`` (NaN when there are none)."""
        return self._box_round("casters_box", "caster_bounds", CASTERS)

    @cached_property
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

    @cached_property
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

    @cached_property
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

    @cached_property
    def _caster_rows(self) -> dict[int, int]:
        return self._rows_by_id("_caster_rows", CASTERS)

    @cached_property
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

    @cached_property
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
        >>> from pvshadows.scene.snapshot import SceneReader
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
        >>> from pvshadows.scene.snapshot import SceneReader
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


class SceneReader:
    """Reads a renderer's actors each frame, keeping what did not change.

    Parameters
    ----------
    names : callable
        Returns the display name of an actor (for messages).
    """

    def __init__(self, names) -> None:
        self._names = names
        self._cache: dict[str, tuple[vtk.vtkActor, tuple | None, ActorTriangles | None]] = {}
        self._versions = 0
        self._frames: dict[str, _RendererCache] = {}
        self.casting: dict[str, bool] = {}
        #: Transmittances set in place of ``1 - opacity``, by actor key.
        self.transmitting: dict[str, float] = {}
        self.receiving: dict[str, bool] = {}
        #: Actors named receiving planes of planar shadows.
        self.planes: set[str] = set()
        #: Raised by every change of the roles above, so a frame compares them only then.
        self.roles = 0
        self.problems: dict[str, str] = {}
        #: How many actors were read again (stamp changed) since the reader was made.
        self.reread = 0
        #: How many actors' stamps were compared (VTK modified them, or every actor's
        #: when the actor list or the roles changed).
        self.compared = 0

    def set_casting(self, key: str, cast: bool, transmittance: float | None) -> None:
        """Set whether the actor ``key`` casts, and the share of light it lets through.

        Parameters
        ----------
        key : str
            The actor's :func:`pvshadows.scene.triangles.vtk_id`.
        cast : bool
            Whether it casts shadows.
        transmittance : float or None
            The share of light it lets through as a caster; ``None`` for
            ``1 - opacity``.
        """
        self.casting[key] = cast
        if transmittance is None:
            self.transmitting.pop(key, None)
        else:
            self.transmitting[key] = transmittance
        self.roles += 1

    def set_receiving(self, key: str, receive: bool, plane: bool) -> None:
        """Set whether the actor ``key`` receives, and whether it is the planar receiving plane.

        Parameters
        ----------
        key : str
            The actor's :func:`pvshadows.scene.triangles.vtk_id`.
        receive : bool
            Whether it shows shadows.
        plane : bool
            Whether planar shadows flatten onto it.
        """
        self.receiving[key] = receive
        if plane:
            self.planes.add(key)
        else:
            self.planes.discard(key)
        self.roles += 1

    def name_of(self, actor: vtk.vtkActor) -> str:
        """Return how messages name an actor, e.g. ``"actor 'ground'"``."""
        return self._names(actor)

    def triangles_of(self, actor: vtk.vtkActor) -> ActorTriangles | None:
        """Return the actor's triangles, re-reading them only when its data changed.

        Parameters
        ----------
        actor : vtk.vtkActor
            The actor.

        Returns
        -------
        ActorTriangles or None
            ``None`` for an actor without triangles.

        Raises
        ------
        ValueError
            If the actor's points are not finite.
        """
        mapper = actor.GetMapper()
        data = mapper.GetInputDataObject(0, 0) if mapper is not None else None
        stamp = (vtk_id(data), int(data.GetMTime())) if data is not None else None
        cached = self._cache.get(vtk_id(actor))
        if cached is not None and cached[1] == stamp:
            return cached[2]
        triangles = read_triangles(actor, self._names(actor))
        if triangles is not None:
            self._versions += 1
            triangles.version = self._versions
        self._cache[vtk_id(actor)] = (actor, stamp, triangles)
        return triangles

    def read(self, renderer: vtk.vtkRenderer) -> Snapshot:
        """Return the renderer's actors as this frame sees them.

        An actor whose geometry cannot be used (non-finite points) is left out
        of the shadows with a warning naming it, once, and the frame goes on.

        Parameters
        ----------
        renderer : vtk.vtkRenderer
            The renderer.

        Returns
        -------
        Snapshot
            Casters, receivers and bystanders; last frame's own object when
            no actor changed.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows.scene.snapshot import SceneReader
        >>> pl = pv.Plotter(off_screen=True)
        >>> box = pl.add_mesh(pv.Cube())
        >>> reader = SceneReader(lambda actor: "an actor")
        >>> first = reader.read(pl.renderer)
        >>> reader.read(pl.renderer) is first
        True
        >>> box.position = (1, 0, 0)
        >>> sorted(reader.read(pl.renderer).changed) == [box.__this__]
        True
        """
        cache = self._frames.setdefault(vtk_id(renderer), _RendererCache())
        # VTK's own methods, called on the class: PyVista's wrappers check every attribute
        camera = vtk.vtkCamera.GetMTime(vtk.vtkRenderer.GetActiveCamera(renderer))
        props = vtk.vtkRenderer.GetViewProps(renderer).GetMTime()
        if cache.props != props:
            collection = renderer.GetActors()
            collection.InitTraversal()
            cache.actors = [collection.GetNextActor() for _ in range(collection.GetNumberOfItems())]
            cache.props = props
            cache.snapshot = None
        same_roles = cache.roles == self.roles and (cache.camera == camera or not cache.followers)
        if not same_roles or cache.snapshot is None:
            return self._read_changed(cache, camera, None)
        suspects = cache.watch.take()
        if not suspects:
            cache.camera = camera
            return cache.snapshot
        return self._read_changed(cache, camera, suspects)

    def release(self, renderer: vtk.vtkRenderer) -> None:
        """Stop watching a renderer's actors and forget what was read of them.

        Parameters
        ----------
        renderer : vtk.vtkRenderer
            The renderer.
        """
        cache = self._frames.pop(vtk_id(renderer), None)
        if cache is not None:
            cache.watch.clear()

    def _read_changed(
        self, cache: _RendererCache, camera: int, suspects: set[int] | None
    ) -> Snapshot:
        """Read again the actors that changed, among ``suspects`` (indices; ``None``: all).

        A read that raises leaves no snapshot behind: the suspects' entries
        are replaced in place and VTK will not name them again, so the next
        read compares every actor and builds its snapshot from the entries.
        """
        try:
            return self._read_entries(cache, camera, suspects)
        except Exception:
            cache.snapshot = None
            raise

    def _read_entries(
        self, cache: _RendererCache, camera: int, suspects: set[int] | None
    ) -> Snapshot:
        renewed: list[tuple[_Entry, _Entry]] = []
        if suspects is None:
            entries, changed = self._compare_all(cache, camera)
        else:
            entries, changed = self._compare_suspects(cache, camera, suspects, renewed)
        cache.camera, cache.roles = camera, self.roles
        # The suspects' entries are patched in place, under the same keys.
        same_actors = suspects is not None or entries.keys() == cache.entries.keys()
        if not changed and same_actors and cache.snapshot:
            return cache.snapshot
        self.reread += len(changed)
        following = self._successor(cache, renewed, frozenset(changed)) if renewed else None
        if following is not None:
            cache.entries, cache.snapshot = entries, following
            return following
        ordered = [entries[id(actor)] for actor in cache.actors]
        if suspects is None:
            kept = {e.key for e in ordered}
            for gone in cache.entries.values():
                if gone.key not in kept:
                    self._cache.pop(gone.key, None)
        actors = [e.state for e in ordered if e.state is not None]
        bystanders = [e.actor for e in ordered if e.bystander]
        cache.entries = entries
        cache.rows = {id(e.actor): row for row, e in enumerate(e for e in ordered if e.state)}
        cache.snapshot = Snapshot(actors, bystanders, frozenset(changed))
        return cache.snapshot

    @staticmethod
    def _successor(
        cache: _RendererCache, renewed: list[tuple[_Entry, _Entry]], changed: frozenset[str]
    ) -> Snapshot | None:
        """Return last frame's snapshot with the renewed actors' states replaced.

        ``None`` when some renewed actor changed roles, appeared or left (the
        snapshot is then built afresh).
        """
        if cache.snapshot is None:
            return None
        states = {}
        for old, new in renewed:
            if old.state is None or new.state is None:
                if old.state is not new.state or old.bystander != new.bystander:
                    return None
                continue
            if _roles(old.state) != _roles(new.state):
                return None
            states[cache.rows[id(new.actor)]] = new.state
        return cache.snapshot.successor(states, changed)

    def _compare_all(
        self, cache: _RendererCache, camera: int
    ) -> tuple[dict[int, _Entry], list[str]]:
        """Compare every actor's stamp, keep the unchanged entries, watch every actor afresh."""
        entries: dict[int, _Entry] = {}
        changed = []
        self.compared += len(cache.actors)
        cache.watch.clear()
        for index, actor in enumerate(cache.actors):
            entry = cache.entries.get(id(actor))
            if (
                entry is None
                or entry.actor is not actor
                or entry.stamp != self._stamp(entry, camera)
            ):
                entry = self._entry(actor, camera)
                changed.append(entry.key)
            cache.watch.watch(index, watched_objects(actor, entry.mapper, entry.data))
            entries[id(actor)] = entry
        cache.followers = any(e.follower for e in entries.values())
        return entries, changed

    def _compare_suspects(
        self,
        cache: _RendererCache,
        camera: int,
        suspects: set[int],
        renewed: list[tuple[_Entry, _Entry]],
    ) -> tuple[dict[int, _Entry], list[str]]:
        """Compare the stamps of the actors VTK modified; read and watch again those that changed.

        The actor list is last frame's, so every other entry stays as it is:
        the work is in the suspects alone, and the entries are replaced in
        place. Each changed actor's old and new entries are added to
        ``renewed``.
        """
        entries = cache.entries
        changed = []
        self.compared += len(suspects)
        for index in sorted(suspects):
            actor = cache.actors[index]
            entry = entries[id(actor)]
            if entry.stamp == self._stamp(entry, camera):
                continue
            renewed.append((entry, self._entry(actor, camera)))
            entry = renewed[-1][1]
            changed.append(entry.key)
            cache.watch.watch(index, watched_objects(actor, entry.mapper, entry.data))
            entries[id(actor)] = entry
        return entries, changed

    def _stamp(self, entry: _Entry, camera: int) -> tuple:
        """Return the modification times and roles that decide whether an actor is read again."""
        key = entry.key
        return (
            vtk.vtkActor.GetMTime(entry.actor),
            0 if entry.mapper is None else vtk.vtkObject.GetMTime(entry.mapper),
            # The data's own time and its points', cells' and arrays' (a virtual call).
            0 if entry.data is None else entry.data.GetMTime(),
            # A follower turns to face the camera: its matrix changes with the camera's.
            camera if entry.follower else 0,
            self.casting.get(key, True),
            self.transmitting.get(key),
            self.receiving.get(key, True),
            key in self.planes,
        )

    def _entry(self, actor: vtk.vtkActor, camera: int) -> _Entry:
        entry = _Entry(actor, vtk_id(actor), isinstance(actor, vtk.vtkFollower))
        entry.state, entry.bystander = self._state_of(actor, entry.key)
        entry.mapper = actor.GetMapper()
        entry.data = None if entry.mapper is None else entry.mapper.GetInputDataObject(0, 0)
        entry.stamp = self._stamp(entry, camera)
        return entry

    def _state_of(self, actor: vtk.vtkActor, key: str) -> tuple[ActorState | None, bool]:
        if not actor.GetVisibility() or actor.GetMapper() is None:
            return None, False
        try:
            triangles = self.triangles_of(actor)
        except ValueError as error:
            if self.problems.get(key) != str(error):
                warnings.warn(f"pvshadows leaves it out: {error}", stacklevel=4)
            self.problems[key] = str(error)
            return None, True
        self.problems.pop(key, None)
        if triangles is None:
            return None, True
        matrix = actor_matrix(actor)
        caster = self.casting.get(key, True)
        receiver = self.receiving.get(key, True) and bool(actor.GetProperty().GetLighting())
        state = ActorState(
            actor,
            self._names,
            triangles,
            matrix,
            world_bounds(triangles, matrix),
            caster,
            receiver,
            receiver and key in self.planes,
            self.transmitting.get(key, transmittance(actor)),
            actor.GetProperty().GetRepresentation() == vtk.VTK_SURFACE,
        )
        return state, not receiver


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


def hides_what_is_behind(state: ActorState, renderer: vtk.vtkRenderer) -> bool:
    """Return whether an actor hides what lies behind it from the renderer's camera.

    Its faces do when VTK draws them (:attr:`ActorState.faces_drawn`), or
    when the renderer's hidden-line removal draws them into depth.

    Parameters
    ----------
    state : ActorState
        The actor this frame.
    renderer : vtk.vtkRenderer
        The renderer drawing it.

    Returns
    -------
    bool
        ``False`` for a wireframe or points actor without hidden-line removal.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.snapshot import SceneReader, hides_what_is_behind
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Cube(), style="wireframe")
    >>> state = SceneReader(lambda actor: "a cube").read(pl.renderer).actors[0]
    >>> hides_what_is_behind(state, pl.renderer)
    False
    >>> pl.enable_hidden_line_removal()
    >>> hides_what_is_behind(state, pl.renderer)
    True
    """
    return state.faces_drawn or bool(vtk.vtkRenderer.GetUseHiddenLineRemoval(renderer))


def _roles(state: ActorState) -> tuple[bool, bool, bool]:
    return state.caster, state.receiver, state.plane


@dataclass
class _Entry:
    """What one actor was at its last change, and the VTK objects whose times say it changed."""

    actor: vtk.vtkActor
    key: str
    follower: bool
    state: ActorState | None = None
    bystander: bool = False
    mapper: vtk.vtkMapper | None = None
    data: vtk.vtkDataObject | None = None
    stamp: tuple = ()


@dataclass
class _RendererCache:
    """The actors one renderer showed in its last frame, and the watch on them.

    The watch marks an actor by its place in ``actors``; the places change
    only when the list is walked again, and then every actor is watched
    afresh.
    """

    props: int = -1
    actors: list[vtk.vtkActor] = field(default_factory=list)
    entries: dict[int, _Entry] = field(default_factory=dict)
    #: Each shadowed actor's row in the snapshot's actors, by ``id`` of the actor.
    rows: dict[int, int] = field(default_factory=dict)
    snapshot: Snapshot | None = None
    watch: ModificationWatch = field(default_factory=ModificationWatch)
    camera: int = -1
    roles: int = -1
    followers: bool = False
