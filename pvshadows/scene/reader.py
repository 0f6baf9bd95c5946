"""Reading what a renderer holds each frame: its actors, re-read only where VTK changed them.

VTK tells which actors changed: observers on each object an actor's shadow
depends on (:mod:`pvshadows.scene.watch`) mark it a suspect when VTK modifies
it, and a frame compares the stamps (modification times and roles) of the
suspects alone, or of every actor when the actors' roles (a version the role
setters raise) changed. An actor whose stamp did not change keeps last
frame's state (matrix, bounds, name, triangles) untouched. The renderer's
actor list is walked again only when its props changed. Triangles are re-read
only when the actor's data changed. When no actor changed, the frame reads
no actor at all and gets last frame's :class:`~pvshadows.scene.snapshot.Snapshot` itself, so what is
derived from it can be kept too.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

from pvshadows import _vtk as vtk
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.translucency import transmittance
from pvshadows.scene.triangles import (
    ActorTriangles,
    actor_matrix,
    read_triangles,
    vtk_id,
    world_bounds,
)
from pvshadows.scene.watch import ModificationWatch, watched_objects


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
        >>> from pvshadows.scene.reader import SceneReader
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
        key = vtk_id(renderer)
        cache = self._frames.get(key)
        if cache is None:
            cache = self._frames[key] = _RendererCache()
        # VTK's own methods, called on the class: PyVista's wrappers check every attribute
        camera = vtk.vtkCamera.GetMTime(vtk.vtkRenderer.GetActiveCamera(renderer))
        if cache.view_props is None:  # a renderer's props are one collection for its life
            cache.view_props = vtk.vtkRenderer.GetViewProps(renderer)
        props = vtk.vtkObject.GetMTime(cache.view_props)
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
    #: The renderer's props, held so that their Python wrapper lives on: VTK makes a
    #: wrapper afresh, looking its class up by name, for an object Python no longer holds.
    view_props: vtk.vtkPropCollection | None = None
    actors: list[vtk.vtkActor] = field(default_factory=list)
    entries: dict[int, _Entry] = field(default_factory=dict)
    #: Each shadowed actor's row in the snapshot's actors, by ``id`` of the actor.
    rows: dict[int, int] = field(default_factory=dict)
    snapshot: Snapshot | None = None
    watch: ModificationWatch = field(default_factory=ModificationWatch)
    camera: int = -1
    roles: int = -1
    followers: bool = False
