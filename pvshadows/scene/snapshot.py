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

import warnings
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import translation
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
    name : str
        How messages name it.
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
    """

    actor: vtk.vtkActor
    name: str
    triangles: ActorTriangles
    matrix: np.ndarray
    bounds: np.ndarray
    caster: bool
    receiver: bool
    plane: bool = False
    transmittance: float = 0.0

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


@dataclass(eq=False)
class Snapshot:
    """The actors of a renderer in one frame.

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

    @cached_property
    def casters(self) -> list[ActorState]:
        """Actors that cast shadows."""
        return [a for a in self.actors if a.caster]

    @cached_property
    def receivers(self) -> list[ActorState]:
        """Actors that show shadows."""
        return [a for a in self.actors if a.receiver]

    @cached_property
    def caster_bounds(self) -> np.ndarray:
        """World bounds of :attr:`casters`, ``(n, 2, 3)``."""
        return _stacked(self.casters)

    @cached_property
    def receiver_bounds(self) -> np.ndarray:
        """World bounds of :attr:`receivers`, ``(n, 2, 3)``."""
        return _stacked(self.receivers)

    @cached_property
    def caster_models(self) -> np.ndarray:
        """Model matrices of :attr:`casters` (:meth:`ActorState.model_matrix`), ``(n, 4, 4)``."""
        return np.array([c.model_matrix() for c in self.casters]).reshape(-1, 4, 4)

    @cached_property
    def _caster_rows(self) -> dict[int, int]:
        return {id(state): row for row, state in enumerate(self.casters)}

    def caster_rows(self, casters: list[ActorState]) -> np.ndarray:
        """Return where each of some of this snapshot's casters sits in :attr:`casters`.

        Parameters
        ----------
        casters : list of ActorState
            Casters of this snapshot.

        Returns
        -------
        numpy.ndarray
            ``(n,)`` rows of :attr:`caster_bounds` and :attr:`caster_models`.
        """
        rows = self._caster_rows
        return np.fromiter((rows[id(c)] for c in casters), dtype=np.intp, count=len(casters))

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
        if casters is self.casters:
            return self.caster_bounds
        return self.caster_bounds[self.caster_rows(casters)]


def _stacked(states: list[ActorState]) -> np.ndarray:
    return np.array([s.bounds for s in states]).reshape(-1, 2, 3)


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
        camera = renderer.GetActiveCamera().GetMTime()
        props = renderer.GetViewProps().GetMTime()
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
        """Read again the actors that changed, among ``suspects`` (indices; ``None``: all)."""
        if suspects is None:
            entries, changed = self._compare_all(cache, camera)
        else:
            entries, changed = self._compare_suspects(cache, camera, suspects)
        cache.camera, cache.roles = camera, self.roles
        if not changed and entries.keys() == cache.entries.keys() and cache.snapshot:
            return cache.snapshot
        self.reread += len(changed)
        ordered = [entries[id(actor)] for actor in cache.actors]
        if suspects is None:
            kept = {e.key for e in ordered}
            for gone in cache.entries.values():
                if gone.key not in kept:
                    self._cache.pop(gone.key, None)
        actors = [e.state for e in ordered if e.state is not None]
        bystanders = [e.actor for e in ordered if e.bystander]
        cache.entries = entries
        cache.snapshot = Snapshot(actors, bystanders, frozenset(changed))
        return cache.snapshot

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
        self, cache: _RendererCache, camera: int, suspects: set[int]
    ) -> tuple[dict[int, _Entry], list[str]]:
        """Compare the stamps of the actors VTK modified; read and watch again those that changed.

        The actor list is last frame's, so every other entry stays as it is:
        the work is in the suspects alone.
        """
        entries = dict(cache.entries)
        changed = []
        self.compared += len(suspects)
        for index in sorted(suspects):
            actor = cache.actors[index]
            entry = entries[id(actor)]
            if entry.stamp == self._stamp(entry, camera):
                continue
            entry = self._entry(actor, camera)
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
            self._names(actor),
            triangles,
            matrix,
            world_bounds(triangles, matrix),
            caster,
            receiver,
            receiver and key in self.planes,
            self.transmitting.get(key, transmittance(actor)),
        )
        return state, not receiver


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
    snapshot: Snapshot | None = None
    watch: ModificationWatch = field(default_factory=ModificationWatch)
    camera: int = -1
    roles: int = -1
    followers: bool = False
