"""Receiving planes: which actors are flat, their plane, and the matrix that flattens onto it.

An actor is a *plane* when every one of its points lies within
:data:`PLANE_TOLERANCE` of its size (the diagonal of its bounds) from the
plane that fits them best, plus the rounding of its coordinates' own
precision (a float32 mesh far from the origin is as flat as float32 can
say). The fit is made once per version of an actor's triangles, in its own
model coordinates, and carried to world coordinates by its matrix each
frame.

A plane is a float64 4-vector ``(n, d)``: unit normal ``n`` and offset
``d``, the points ``p`` of the plane being those with ``n . p + d = 0``. A
light is a homogeneous 4-vector too: ``(position, 1)`` for point and spot
lights, ``(direction towards the light, 0)`` for directional ones. Then the
matrix ``(plane . light) I - light plane^T`` (:func:`flattening`) takes any
point to where the line through it and the light meets the plane.

The planner's question, "is the only receiver one plane?", is
:func:`sole_plane`; :func:`choose_plane` picks the plane that receives
planar shadows among several receivers.
"""

from __future__ import annotations

import weakref
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.triangles import ActorTriangles

#: Largest distance of a plane's points from their best-fitting plane, as a
#: share of the diagonal of its bounds (besides the rounding of its coordinates).
PLANE_TOLERANCE = 1e-5

_FITS: dict[int, tuple[weakref.ref, PlaneFit]] = {}


@dataclass(frozen=True)
class PlaneFit:
    """The plane that fits a set of points best, and how far they are from it.

    Attributes
    ----------
    plane : numpy.ndarray
        ``(4,)`` float64 ``(n, d)`` with ``|n| = 1``, in the points' coordinates.
    off_plane : float
        Largest distance of a point from the plane.
    size : float
        Diagonal of the points' bounds.
    width : float
        Extent of the points across their longest direction, in the plane
        (0 for points along a line).
    tolerance : float
        Largest ``off_plane`` of a plane.
    """

    plane: np.ndarray
    off_plane: float
    size: float
    width: float
    tolerance: float

    @property
    def planar(self) -> bool:
        """Whether the points are a plane: flat within tolerance, and not a line or a point."""
        return self.width > self.tolerance and self.off_plane <= self.tolerance

    def describe(self) -> str:
        """Say how far the points are from their plane, in words."""
        share = 100.0 * self.off_plane / self.size if self.size else 0.0
        return (
            f"its points lie up to {self.off_plane:.3g} from the plane that fits them best, "
            f"{share:.3g} % of its size {self.size:.3g} (a plane may be off by "
            f"{self.tolerance:.3g}, {100.0 * PLANE_TOLERANCE:.3g} % of its size plus the "
            "rounding of its coordinates)"
        )


def fit_plane(points: np.ndarray, rounding: float = 0.0) -> PlaneFit:
    """Fit a plane to points and measure how far they are from it.

    Parameters
    ----------
    points : numpy.ndarray
        ``(n, 3)`` coordinates.
    rounding : float, default: 0.0
        How far the coordinates may be off through their storage precision
        (added to the tolerance).

    Returns
    -------
    PlaneFit
        The plane through the points' mid-range along the least-spread
        direction, with the largest distance of a point from it. Points
        along a line (or one point) fit no plane: their ``width`` is 0.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.planes import fit_plane
    >>> square = np.array([[0, 0, 2], [1, 0, 2], [1, 1, 2], [0, 1, 2.0]])
    >>> fit = fit_plane(square)
    >>> fit.planar, np.abs(fit.plane).round(6).tolist()
    (True, [0.0, 0.0, 1.0, 2.0])
    >>> fit_plane(square + [[0, 0, 0], [0, 0, 0.1], [0, 0, 0], [0, 0, 0]]).planar
    False
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 3)
    if points.shape[0] == 0:
        return PlaneFit(np.array([0.0, 0.0, 1.0, 0.0]), 0.0, 0.0, 0.0, 0.0)
    lo, hi = points.min(0), points.max(0)
    size = float(np.linalg.norm(hi - lo))
    middle = 0.5 * (lo + hi)
    centred = points - middle
    # The least-spread direction: the eigenvector of the smallest eigenvalue.
    axes = np.linalg.eigh(centred.T @ centred)[1]
    normal = axes[:, 0]
    heights = centred @ normal
    low, high = float(heights.min()), float(heights.max())
    offset = 0.5 * (low + high)
    plane = np.append(normal, -(normal @ middle) - offset)
    width = float(np.ptp(centred @ axes[:, 1]))
    return PlaneFit(plane, 0.5 * (high - low), size, width, PLANE_TOLERANCE * size + rounding)


def coordinate_rounding(actor: vtk.vtkActor, triangles: ActorTriangles) -> float:
    """Return how far an actor's stored coordinates may be from what they stand for.

    Parameters
    ----------
    actor : vtk.vtkActor
        The actor (its data's point type is read).
    triangles : ActorTriangles
        Its triangles.

    Returns
    -------
    float
        The machine epsilon of the points' type (float32 unless they are
        stored as float64) times the largest coordinate.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.planes import coordinate_rounding
    >>> from pvshadows.scene.triangles import read_triangles
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Plane(center=(1e6, 0, 0)))
    >>> round(coordinate_rounding(actor, read_triangles(actor)), 3)  # float32 points
    0.119
    """
    mapper = actor.GetMapper()
    data = mapper.GetInputDataObject(0, 0) if mapper is not None else None
    points = data.GetPoints() if isinstance(data, vtk.vtkPointSet) else None
    double = points is not None and points.GetDataType() == vtk.VTK_DOUBLE
    epsilon = np.finfo(np.float64 if double else np.float32).eps
    largest = np.abs(triangles.model_bounds()).max() if triangles.points.size else 0.0
    return float(epsilon * largest)


def model_fit(actor: vtk.vtkActor, triangles: ActorTriangles) -> PlaneFit:
    """Return the plane fit of an actor's triangles, once per version of them.

    Parameters
    ----------
    actor : vtk.vtkActor
        The actor.
    triangles : ActorTriangles
        Its triangles (the fit is kept as long as they live).

    Returns
    -------
    PlaneFit
        In the triangles' own coordinates (``triangles.points``, centred).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.planes import model_fit
    >>> from pvshadows.scene.triangles import read_triangles
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Sphere())
    >>> model_fit(actor, read_triangles(actor)).planar
    False
    """
    key = id(triangles)
    cached = _FITS.get(key)
    if cached is not None and cached[0]() is triangles:
        return cached[1]
    fit = fit_plane(triangles.points, coordinate_rounding(actor, triangles))
    _FITS[key] = (weakref.ref(triangles), fit)
    weakref.finalize(triangles, _FITS.pop, key, None)
    return fit


def world_plane(plane: np.ndarray, matrix: np.ndarray) -> np.ndarray:
    """Carry a plane from model to world coordinates.

    Parameters
    ----------
    plane : numpy.ndarray
        ``(4,)`` ``(n, d)`` in model coordinates.
    matrix : numpy.ndarray
        ``(4, 4)`` model-to-world matrix.

    Returns
    -------
    numpy.ndarray
        ``(4,)`` float64 ``(n, d)`` in world coordinates, ``|n| = 1``.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.planes import world_plane
    >>> from pvshadows.geometry.transforms import translation
    >>> world_plane(np.array([0, 0, 1.0, 0]), translation([0, 0, 5])).tolist()
    [0.0, 0.0, 1.0, -5.0]
    """
    world = np.linalg.solve(np.asarray(matrix, np.float64).T, np.asarray(plane, np.float64))
    return world / np.linalg.norm(world[:3])


def actor_plane(state: ActorState) -> np.ndarray | None:
    """Return an actor's plane in world coordinates, or ``None`` when it is not flat.

    Parameters
    ----------
    state : ActorState
        The actor in this frame.

    Returns
    -------
    numpy.ndarray or None
        ``(4,)`` float64 ``(n, d)``, ``|n| = 1``.
    """
    fit = model_fit(state.actor, state.triangles)
    if not fit.planar:
        return None
    return world_plane(fit.plane, state.model_matrix())


def require_plane(actor: vtk.vtkActor, triangles: ActorTriangles | None, name: str) -> PlaneFit:
    """Check that an actor can be named a receiving plane.

    Parameters
    ----------
    actor : vtk.vtkActor
        The actor.
    triangles : ActorTriangles or None
        Its triangles (``None``: it has none).
    name : str
        How the message names it.

    Returns
    -------
    PlaneFit
        Its fit, planar.

    Raises
    ------
    ValueError
        Saying how far off a plane it is, or that it has no triangles.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.planes import require_plane
    >>> from pvshadows.scene.triangles import read_triangles
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Cube())
    >>> require_plane(actor, read_triangles(actor), "the cube")
    Traceback (most recent call last):
    ...
    ValueError: the cube is not a plane: its points lie up to 0.5 from the plane ...
    """
    if triangles is None:
        msg = f"{name} has no triangles, so it cannot receive planar shadows"
        raise ValueError(msg)
    fit = model_fit(actor, triangles)
    if not fit.planar:
        msg = (
            f"{name} is not a plane: {fit.describe()}; planar shadows need a flat receiver. "
            "Use another technique for it, or name a flat actor"
        )
        raise ValueError(msg)
    return fit


def receiving_planes(receivers: Iterable[ActorState]) -> list[tuple[ActorState, np.ndarray]]:
    """Return the receivers that are planes, each with its world plane.

    Parameters
    ----------
    receivers : iterable of ActorState
        Actors that show shadows this frame.

    Returns
    -------
    list of tuple
        ``(actor, plane)`` for every flat one, ``plane`` a float64 ``(n, d)``.
    """
    found = []
    for state in receivers:
        plane = actor_plane(state)
        if plane is not None:
            found.append((state, plane))
    return found


def sole_plane(receivers: Sequence[ActorState]) -> tuple[ActorState, np.ndarray] | None:
    """Return the receiver and its plane when there is exactly one receiver and it is a plane.

    This is when planar shadows show everything there is to see: with more
    receivers, objects would not shadow each other.

    Parameters
    ----------
    receivers : sequence of ActorState
        Actors that show shadows this frame (``snapshot.receivers``).

    Returns
    -------
    tuple or None
        ``(actor, plane)`` with ``plane`` a float64 ``(n, d)`` in world
        coordinates, or ``None``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.planes import sole_plane
    >>> from pvshadows.scene.reader import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> ground = pl.add_mesh(pv.Plane(center=(0, 0, -1)))
    >>> reader = SceneReader(lambda actor: "an actor")
    >>> actor, plane = sole_plane(reader.read(pl.renderer).receivers)
    >>> abs(plane).round(6).tolist()
    [0.0, 0.0, 1.0, 1.0]
    >>> _ = pl.add_mesh(pv.Sphere())
    >>> sole_plane(reader.read(pl.renderer).receivers) is None
    True
    """
    if len(receivers) != 1:
        return None
    plane = actor_plane(receivers[0])
    return None if plane is None else (receivers[0], plane)


@dataclass(frozen=True)
class PlaneChoice:
    """The plane that receives planar shadows in one frame, and why.

    Attributes
    ----------
    actor : ActorState or None
        The receiving plane, ``None`` when no receiver is flat.
    plane : numpy.ndarray or None
        Its world plane ``(n, d)``.
    reason : str
        Why it was chosen, in words.
    """

    actor: ActorState | None
    plane: np.ndarray | None
    reason: str


def _size(state: ActorState) -> float:
    return float(np.linalg.norm(np.ptp(state.bounds, axis=0)))


def choose_plane(receivers: Sequence[ActorState]) -> PlaneChoice:
    """Choose the receiver that planar shadows fall on.

    An actor named with ``pl.shadows.set_receiver(actor, plane=True)`` comes
    first (the largest, if several are named); otherwise the flat receivers
    are found on their own, and the largest of them is chosen.

    Parameters
    ----------
    receivers : sequence of ActorState
        Actors that show shadows this frame.

    Returns
    -------
    PlaneChoice
        The plane, or none with the reason.
    """
    named = [state for state in receivers if state.plane]
    lines = []
    planes = []
    for state in named:
        plane = actor_plane(state)
        if plane is None:
            fit = model_fit(state.actor, state.triangles)
            lines.append(f"{state.name} was named a plane but is no longer flat: {fit.describe()}")
        else:
            planes.append((state, plane))
    how = "named with set_receiver(plane=True)"
    if not planes:
        planes = receiving_planes(receivers)
        how = "found on its own"
    if not planes:
        lines.append("no receiver is a plane: planar shadows fall on nothing")
        return PlaneChoice(None, None, "; ".join(lines))
    planes.sort(key=lambda pair: _size(pair[0]), reverse=True)
    state, plane = planes[0]
    if len(planes) == 1:
        lines.append(f"receiving plane: {state.name} ({how})")
    else:
        lines.append(f"receiving plane: {state.name}, the largest of {len(planes)} planes ({how})")
    return PlaneChoice(state, plane, "; ".join(lines))


def facing(plane: np.ndarray, light: np.ndarray) -> np.ndarray:
    """Return the plane oriented so that the light is on its positive side.

    Parameters
    ----------
    plane : numpy.ndarray
        ``(4,)`` ``(n, d)``.
    light : numpy.ndarray
        ``(4,)`` homogeneous light: ``(position, 1)`` or ``(direction towards it, 0)``.

    Returns
    -------
    numpy.ndarray
        ``plane`` or ``-plane``: ``plane . light >= 0``.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.planes import facing
    >>> facing(np.array([0, 0, 1.0, 0]), np.array([0, 0, -3.0, 1])).tolist()
    [-0.0, -0.0, -1.0, -0.0]
    """
    plane = np.asarray(plane, np.float64)
    return -plane if plane @ np.asarray(light, np.float64) < 0.0 else plane


def flattening(plane: np.ndarray, light: np.ndarray) -> np.ndarray:
    """Return the matrix that flattens points onto a plane along the lines to a light.

    ``M = (plane . light) I - light plane^T``: a homogeneous point ``p``
    goes to ``M p``, where the line through ``p`` and the light meets the
    plane. ``M p`` is left homogeneous, so ``M`` is linear and clip-space
    images of triangles stay triangles; its ``w`` is ``plane . light - light_w
    (plane . p)``, negative for points beyond a positional light (whose line
    meets the plane on the other side of the light).

    Parameters
    ----------
    plane : numpy.ndarray
        ``(4,)`` ``(n, d)``, or ``(k, 4)`` planes.
    light : numpy.ndarray
        ``(4,)`` ``(position, 1)`` or ``(direction towards the light, 0)``,
        or ``(k, 4)`` lights, one per plane.

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` float64, or ``(k, 4, 4)``.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.planes import flattening
    >>> ground, bulb = np.array([0, 0, 1.0, 0]), np.array([0, 0, 4.0, 1])
    >>> p = flattening(ground, bulb) @ np.array([1, 0, 2.0, 1])
    >>> (p[:3] / p[3]).tolist()
    [2.0, 0.0, 0.0]
    """
    plane = np.asarray(plane, np.float64)
    light = np.asarray(light, np.float64)
    dots = np.einsum("...i,...i->...", plane, light)
    return dots[..., None, None] * np.eye(4) - light[..., :, None] * plane[..., None, :]
