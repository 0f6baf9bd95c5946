"""One actor as a frame sees it: its triangles, matrix, bounds and roles.

An :class:`ActorState` is made when an actor changed (the
:class:`~pvshadows.scene.reader.SceneReader` reads it again) and is kept
unchanged while it does not, so what it derives (its model matrix, its key,
the side a depth pass culls, the plane a flat actor lies in) is worked out
once per state.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import count

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.geometry.transforms import translation
from pvshadows.scene.triangles import (
    ActorTriangles,
    vtk_id,
)


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

    @cached
    def name(self) -> str:
        """How messages name it: asked once, when first needed (naming reads PyVista's wrappers)."""
        return self.namer(self.actor)

    def model_matrix(self) -> np.ndarray:
        """Return the model-to-world matrix of :attr:`triangles`' centred points (float64).

        Computed once per state and read-only: every pass of every light
        reads the same matrix.
        """
        return self._model_matrix

    @cached
    def _model_matrix(self) -> np.ndarray:
        matrix = self.matrix @ translation(self.triangles.center)
        matrix.setflags(write=False)
        return matrix

    def key(self) -> tuple:
        """Return a value that changes when the actor's shadow-casting shape changes."""
        return self._key

    @cached
    def _key(self) -> tuple:
        return (vtk_id(self.actor), self.triangles.version, self.matrix.tobytes())

    @cached
    def bounds_center(self) -> tuple[float, float, float]:
        """The centre of its world bounds, in plain floats."""
        (x0, y0, z0), (x1, y1, z1) = self.bounds.tolist()
        return 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)

    @cached
    def model_inverse(self) -> np.ndarray:
        """The inverse of :meth:`model_matrix`, worked out once per state and read-only.

        A light that moves is taken into each caster's frame through it, so
        a state that stays pays for the inverse once.
        """
        inverse = np.linalg.inv(self.model_matrix())
        inverse.setflags(write=False)
        return inverse

    @cached
    def determinant(self) -> float:
        """The determinant of its matrix's linear part: 0 flattens it, below 0 mirrors it."""
        return float(np.linalg.det(self.matrix[:3, :3]))

    @cached
    def mirrored(self) -> bool:
        """Whether its matrix mirrors it (turns outward-wound triangles inward)."""
        return self.determinant < 0.0

    @cached
    def box(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """Its world bounds in plain floats, and so read at no numpy call's cost."""
        low, high = self.bounds.tolist()
        return (low[0], low[1], low[2]), (high[0], high[1], high[2])

    @cached
    def diagonal(self) -> float:
        """The length of its world bounds' diagonal."""
        (x0, y0, z0), (x1, y1, z1) = self.box
        return math.sqrt((x1 - x0) ** 2 + (y1 - y0) ** 2 + (z1 - z0) ** 2)

    @cached
    def cull_side(self) -> str | None:
        """The side of its triangles a depth pass that culls front faces leaves out.

        ``"front"`` for a closed, outward-wound caster (``"back"`` if its
        matrix mirrors it), ``None`` when it is open or inward-wound.
        """
        if not self.triangles.closed_outward():
            return None
        return "back" if self.mirrored else "front"

    @cached
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
    >>> from pvshadows.scene.actor_state import hides_what_is_behind
    >>> from pvshadows.scene.reader import SceneReader
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
