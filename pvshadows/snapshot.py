"""What a renderer holds in one frame: casters, receivers and their geometry.

Triangles are re-read only when an actor's data changed (VTK modification
time); transforms and bounds are refreshed every frame, which is cheap.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import vtk

from pvshadows.scene import ActorTriangles, actor_matrix, read_triangles, vtk_id, world_bounds
from pvshadows.transforms import translation


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
    """

    actor: vtk.vtkActor
    name: str
    triangles: ActorTriangles
    matrix: np.ndarray
    bounds: np.ndarray
    caster: bool
    receiver: bool
    plane: bool = False

    def model_matrix(self) -> np.ndarray:
        """Return the model-to-world matrix of :attr:`triangles`' centred points (float64)."""
        return self.matrix @ translation(self.triangles.center)

    def key(self) -> tuple:
        """Return a value that changes when the actor's shadow-casting shape changes."""
        return (vtk_id(self.actor), self.triangles.version, self.matrix.tobytes())


@dataclass
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

    @property
    def casters(self) -> list[ActorState]:
        """Actors that cast shadows."""
        return [a for a in self.actors if a.caster]

    @property
    def receivers(self) -> list[ActorState]:
        """Actors that show shadows."""
        return [a for a in self.actors if a.receiver]


class SceneReader:
    """Reads a renderer's actors each frame, keeping triangles between frames.

    Parameters
    ----------
    names : callable
        Returns the display name of an actor (for messages).
    """

    def __init__(self, names) -> None:
        self._names = names
        self._cache: dict[str, tuple[vtk.vtkActor, tuple | None, ActorTriangles | None]] = {}
        self._versions = 0
        self.casting: dict[str, bool] = {}
        self.receiving: dict[str, bool] = {}
        #: Actors named receiving planes of planar shadows.
        self.planes: set[str] = set()
        self.problems: dict[str, str] = {}

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
            Casters, receivers and bystanders.
        """
        actors: list[ActorState] = []
        bystanders: list[vtk.vtkActor] = []
        seen = set()
        collection = renderer.GetActors()
        collection.InitTraversal()
        for _ in range(collection.GetNumberOfItems()):
            actor = collection.GetNextActor()
            if not actor.GetVisibility() or actor.GetMapper() is None:
                continue
            seen.add(vtk_id(actor))
            try:
                triangles = self.triangles_of(actor)
            except ValueError as error:
                if self.problems.get(vtk_id(actor)) != str(error):
                    warnings.warn(f"pvshadows leaves it out: {error}", stacklevel=2)
                self.problems[vtk_id(actor)] = str(error)
                bystanders.append(actor)
                continue
            self.problems.pop(vtk_id(actor), None)
            if triangles is None:
                bystanders.append(actor)
                continue
            matrix = actor_matrix(actor)
            caster = self.casting.get(vtk_id(actor), True)
            receiver = self.receiving.get(vtk_id(actor), True) and bool(
                actor.GetProperty().GetLighting()
            )
            if not receiver:
                bystanders.append(actor)
            actors.append(
                ActorState(
                    actor,
                    self._names(actor),
                    triangles,
                    matrix,
                    world_bounds(triangles, matrix),
                    caster,
                    receiver,
                    receiver and vtk_id(actor) in self.planes,
                )
            )
        for key in set(self._cache) - seen:
            del self._cache[key]
        return Snapshot(actors, bystanders)
