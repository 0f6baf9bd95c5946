"""Triangles of the actors in a renderer, as the shadow passes and the reference see them.

Each actor's surface is read once per change of its data (VTK modification
time) and kept in its own model coordinates, shifted to the centre of its
bounds so that float32 copies stay precise for scenes far from the origin.
The actor's matrix is applied separately, in double precision.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pyvista as pv
from vtkmodules.util.numpy_support import vtk_to_numpy

from pvshadows import _vtk as vtk
from pvshadows.geometry.closed import is_closed_outward
from pvshadows.geometry.transforms import AFFINE_LAST_ROW, from_vtk_matrix


@dataclass
class ActorTriangles:
    """The triangles of one actor in its own model coordinates.

    Attributes
    ----------
    center : numpy.ndarray
        Centre of the model-space bounds, float64 ``(3,)``.
    points : numpy.ndarray
        Points minus ``center``, float64 ``(n, 3)``.
    triangles : numpy.ndarray
        Point indices, uint32 ``(m, 3)``.
    data_mtime : int
        Modification time of the data the triangles were read from.
    """

    center: np.ndarray
    points: np.ndarray
    triangles: np.ndarray
    data_mtime: int
    version: int = field(default=0)
    _closed_outward: bool | None = field(default=None, repr=False)
    _model_bounds: np.ndarray | None = field(default=None, repr=False)
    _model_plane: tuple | None = field(default=None, repr=False)

    @property
    def n_triangles(self) -> int:
        """Number of triangles."""
        return int(self.triangles.shape[0])

    def closed_outward(self) -> bool:
        """Return whether the surface is closed and wound outward (computed once).

        Returns
        -------
        bool
            See :func:`pvshadows.geometry.closed.is_closed_outward`.
        """
        if self._closed_outward is None:
            self._closed_outward = is_closed_outward(self.points, self.triangles)
        return self._closed_outward

    def model_bounds(self) -> np.ndarray:
        """Return the ``(2, 3)`` min/max corners in model coordinates (computed once, read-only).

        An actor that moves keeps its triangles, so its world bounds cost
        eight corners, not a pass over its points.
        """
        if self._model_bounds is None:
            if self.points.shape[0] == 0:
                bounds = np.zeros((2, 3))
            else:
                bounds = np.stack([self.points.min(0), self.points.max(0)]) + self.center
            bounds.setflags(write=False)
            self._model_bounds = bounds
        return self._model_bounds

    def model_plane(self) -> tuple[np.ndarray, np.ndarray, float] | None:
        """Return the model-space plane the triangles lie in, if flat (computed once).

        Flat means every point within ``1e-6`` of the points' size of the
        plane of the first triangle. An actor that moves keeps its
        triangles, so its world plane costs a matrix, not a pass over its
        points.

        Returns
        -------
        tuple or None
            ``(point, unit normal, size)`` in model coordinates (the point
            relative to :attr:`center`); ``(zeros, zeros, 0)`` for fewer than
            three points; ``None`` when not flat.
        """
        if self._model_plane is None:
            lo, hi = self.model_bounds()
            size = float((hi - lo).max())
            self._model_plane = (_plane_of(self.points, self.triangles, size),)
        return self._model_plane[0]


#: How many evenly spaced points are tested first, so that a surface that
#: is not flat is told in a few operations, not a pass over all its points.
_PLANE_PROBES = 64


def _plane_of(
    points: np.ndarray, triangles: np.ndarray, size: float
) -> tuple[np.ndarray, np.ndarray, float] | None:
    if points.shape[0] < 3:
        return np.zeros(3), np.zeros(3), 0.0
    tri = triangles[0]
    normal = np.cross(points[tri[1]] - points[tri[0]], points[tri[2]] - points[tri[0]])
    length = float(np.linalg.norm(normal))
    if not length > 0.0 or size == 0.0:
        return None
    normal /= length
    step = max(1, points.shape[0] // _PLANE_PROBES)
    for tested in (points[::step], points):
        if np.abs((tested - points[tri[0]]) @ normal).max() > 1e-6 * size:
            return None
    return points[tri[0]], normal, size


def vtk_id(obj: vtk.vtkObjectBase) -> str:
    """Return a key for a VTK object that stays the same for its whole life.

    Python wrappers of a VTK object can be recreated between calls, so
    ``id()`` is not stable; the C++ address is.

    Parameters
    ----------
    obj : vtk.vtkObjectBase
        Any VTK object.

    Returns
    -------
    str
        Its address, as VTK's Python wrapping spells it.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.scene.triangles import vtk_id
    >>> light = vtk.vtkLight()
    >>> vtk_id(light) == vtk_id(light)
    True
    """
    # read past PyVista's wrappers, which check each attribute they are asked for
    return _ATTRIBUTE(obj, "__this__")


#: Python's own attribute lookup, without a subclass's ``__getattribute__``.
_ATTRIBUTE = object.__getattribute__


def actor_matrix(actor: vtk.vtkProp3D) -> np.ndarray:
    """Return the actor's model-to-world matrix as float64 ``(4, 4)``.

    Parameters
    ----------
    actor : vtk.vtkProp3D
        The actor.

    Returns
    -------
    numpy.ndarray
        Its matrix, including position, orientation, scale and user matrix.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.triangles import actor_matrix
    >>> actor = pv.Actor()
    >>> actor.position = (1, 2, 3)
    >>> actor_matrix(actor)[:3, 3].tolist()
    [1.0, 2.0, 3.0]
    """
    return from_vtk_matrix(actor.GetMatrix())


def _surface_of(data: vtk.vtkDataObject) -> pv.PolyData | None:
    if data is None:
        return None
    if isinstance(data, vtk.vtkCompositeDataSet):
        blocks = pv.wrap(data)
        surfaces = [
            surface
            for block in blocks.recursive_iterator(skip_none=True)
            if (surface := _surface_of(block)) is not None
        ]
        if not surfaces:
            return None
        return pv.merge(surfaces) if len(surfaces) > 1 else surfaces[0]
    mesh = pv.wrap(data)
    if not isinstance(mesh, pv.DataSet) or mesh.n_points == 0:
        return None
    if not isinstance(mesh, pv.PolyData):
        mesh = mesh.extract_surface(algorithm="dataset_surface")
    return mesh


def _triangles_as_they_are(surface: pv.PolyData) -> np.ndarray | None:
    """Return the polygons of a surface made only of triangles, without copying through a filter.

    ``None`` when it also has strips or polygons of other sizes (they need
    VTK's triangulation).
    """
    if surface.GetNumberOfStrips() > 0:
        return None
    polygons = surface.GetPolys()
    if polygons.GetNumberOfCells() == 0 or polygons.IsHomogeneous() != 3:
        return None
    connectivity = vtk_to_numpy(polygons.GetConnectivityArray())
    return connectivity.astype(np.int64, copy=False).reshape(-1, 3)


def read_triangles(actor: vtk.vtkActor, name: str = "actor") -> ActorTriangles | None:
    """Read an actor's surface as triangles.

    Parameters
    ----------
    actor : vtk.vtkActor
        An actor whose mapper holds a dataset (any kind: polygons, cells of
        a grid, blocks of a composite dataset).
    name : str, default: "actor"
        How error messages name the actor.

    Returns
    -------
    ActorTriangles or None
        ``None`` when the actor has no triangles (no data, or only lines and
        points): such an actor neither casts nor receives a shadow.

    Raises
    ------
    ValueError
        If the surface has points that are not finite (NaN or infinity).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.triangles import read_triangles
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Cube())
    >>> read_triangles(actor).n_triangles
    12
    """
    mapper = actor.GetMapper()
    if mapper is None:
        return None
    mapper.Update()
    data = mapper.GetInputDataObject(0, 0)
    surface = _surface_of(data)
    mtime = int(data.GetMTime()) if data is not None else 0
    if surface is None or surface.n_cells == 0:
        return None
    has_polygons = surface.GetNumberOfPolys() + surface.GetNumberOfStrips() > 0
    if not has_polygons:
        return None
    triangles = _triangles_as_they_are(surface)
    if triangles is None:
        surface = surface.triangulate(pass_lines=False, pass_verts=False)
        triangles = np.asarray(surface.regular_faces, dtype=np.int64).reshape(-1, 3)
    points = np.asarray(surface.points)
    if not np.isfinite(points).all():
        bad = int((~np.isfinite(points).all(axis=1)).sum())
        msg = (
            f"{name} has {bad} points that are NaN or infinite; shadows need finite points. "
            "Remove them first, for example with mesh.remove_points(~np.isfinite(mesh.points)"
            ".all(axis=1))"
        )
        raise ValueError(msg)
    if triangles.size == 0:
        return None
    marked = np.zeros(points.shape[0], dtype=bool)
    marked[triangles.ravel()] = True
    if marked.all():
        # VTK's bounds, kept with the data, are those of the same points
        bounds = np.array(surface.GetBounds(), dtype=np.float64).reshape(3, 2).T
    else:
        used = np.flatnonzero(marked)
        remap = np.full(points.shape[0], -1, dtype=np.int64)
        remap[used] = np.arange(used.size)
        points = points[used]
        triangles = remap[triangles]
        bounds = np.stack([points.min(0), points.max(0)]).astype(np.float64)
    center = 0.5 * (bounds[0] + bounds[1])
    bounds.setflags(write=False)
    return ActorTriangles(
        center,
        np.subtract(points, center, dtype=np.float64),
        triangles.astype(np.uint32),
        mtime,
        _model_bounds=bounds,
    )


def world_bounds(triangles: ActorTriangles, matrix: np.ndarray) -> np.ndarray:
    """Return the ``(2, 3)`` world-space bounds of transformed model bounds.

    Parameters
    ----------
    triangles : ActorTriangles
        The actor's triangles.
    matrix : numpy.ndarray
        Its model-to-world matrix.

    Returns
    -------
    numpy.ndarray
        Min and max corners of the box around the eight transformed corners.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.triangles import read_triangles, world_bounds
    >>> pl = pv.Plotter(off_screen=True)
    >>> tris = read_triangles(pl.add_mesh(pv.Cube()))
    >>> world_bounds(tris, np.eye(4)).tolist()
    [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]
    """
    lo, hi = triangles.model_bounds()
    rows = matrix.tolist()
    if tuple(rows[3]) == AFFINE_LAST_ROW:
        # Affine: each world coordinate takes, term by term, the smaller or larger of
        # the two corners' products, as the eight corners would; in plain floats, as
        # numpy's cost per call outweighs its speed on nine products.
        low, high = [], []
        pairs = list(zip(lo.tolist(), hi.tolist(), strict=True))
        for row in rows[:3]:
            terms = [(m * a, m * b) for m, (a, b) in zip(row[:3], pairs, strict=True)]
            low.append(sum(min(t) for t in terms) + row[3])
            high.append(sum(max(t) for t in terms) + row[3])
        return np.array([low, high])
    corners = np.array(
        [[x, y, z, 1.0] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    world = corners @ matrix.T
    world = world[:, :3] / world[:, 3:4]
    return np.stack([world.min(0), world.max(0)])


def world_points(triangles: ActorTriangles, matrix: np.ndarray) -> np.ndarray:
    """Return the actor's points in world coordinates, float64 ``(n, 3)``.

    Parameters
    ----------
    triangles : ActorTriangles
        The actor's triangles.
    matrix : numpy.ndarray
        Its model-to-world matrix.

    Returns
    -------
    numpy.ndarray
        World positions of ``triangles.points``.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.triangles import read_triangles, world_points
    >>> pl = pv.Plotter(off_screen=True)
    >>> tris = read_triangles(pl.add_mesh(pv.Cube(center=(5, 0, 0))))
    >>> float(world_points(tris, np.eye(4))[:, 0].min())
    4.5
    """
    model = triangles.points + triangles.center
    homogeneous = np.hstack([model, np.ones((model.shape[0], 1))]) @ matrix.T
    return homogeneous[:, :3] / homogeneous[:, 3:4]
