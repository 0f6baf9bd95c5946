"""Casters made ready for shadow volumes: closed, split into bodies, with adjacency.

A shadow volume is right only for a closed, consistently wound caster
(:mod:`pvshadows.geometry.closed`). :func:`prepare_volume_mesh` welds, checks and
repairs a caster with :func:`pvshadows.geometry.closed.make_closed`, and treats one
more case itself: a **flat open sheet** (a plane, a disc, a rectangle of
triangles) becomes a *two-sided slab of zero thickness* — the sheet, the
same sheet wound the other way, and zero-area walls joining them along the
border. That surface is closed and consistently wound, so the usual
counting applies; exactly one side of every triangle faces a light, so a
light ray crossing the sheet once enters the volume once, as the ray caster
(:mod:`pvshadows.verify.reference`) sees it. Every other open mesh raises
:class:`~pvshadows.geometry.closed.OpenMeshError` and is left to the caller
(``on_open="fallback"`` or ``"raise"``).

The mesh's triangles are sorted by *body* (connected piece), so that the
stencil pass can draw them in batches of at most 255 bodies: an 8-bit count
then wraps only for a ray that enters the bodies of one batch a multiple of
256 times.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pvshadows.geometry.closed import OpenMeshError, _union_parity, edge_defects, make_closed, weld
from pvshadows.geometry.silhouette import EdgeAdjacency, adjacency_indices, edge_adjacency

#: Largest distance from its plane, over its diagonal, for a sheet to count as flat.
FLAT_TOLERANCE = 1e-7

#: Most bodies counted together in one 8-bit stencil pass.
MAX_BODIES_PER_BATCH = 255


@dataclass(frozen=True)
class VolumeMesh:
    """A caster ready for shadow volumes.

    Attributes
    ----------
    points : numpy.ndarray
        ``(n, 3)`` float64 points in the caster's own (shifted) model frame.
    triangles : numpy.ndarray
        ``(m, 3)`` int64 closed, outward wound triangles, sorted by body.
    adjacency : EdgeAdjacency
        Every edge with its two faces.
    adjacency_rows : numpy.ndarray
        ``(m, 6)`` uint32 ``GL_TRIANGLES_ADJACENCY`` rows, in triangle order.
    point_body : numpy.ndarray
        ``(n,)`` int64 body of every point.
    body_starts : numpy.ndarray
        ``(b + 1,)`` int64: the triangles of body ``k`` are
        ``triangles[body_starts[k]:body_starts[k + 1]]``.
    how : str
        ``"closed"``, ``"repaired"`` (closed after rewinding, hole filling or
        a manifold3d repair) or ``"two-sided sheet"``.
    """

    points: np.ndarray
    triangles: np.ndarray
    adjacency: EdgeAdjacency
    adjacency_rows: np.ndarray
    point_body: np.ndarray
    body_starts: np.ndarray
    how: str

    @property
    def n_bodies(self) -> int:
        """Number of connected bodies."""
        return len(self.body_starts) - 1


def _flat_sheet(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Return a flat, open, manifold sheet as a two-sided slab, or ``None``."""
    points, triangles = weld(points, triangles)
    if len(triangles) == 0:
        return None
    centre = points.mean(axis=0)
    _, singular, axes = np.linalg.svd(points - centre, full_matrices=False)
    normal = axes[-1]
    diagonal = float(np.linalg.norm(np.ptp(points, axis=0)))
    if diagonal == 0.0 or singular[1] <= 0.0:
        return None
    if np.abs((points - centre) @ normal).max() > FLAT_TOLERANCE * diagonal:
        return None
    corner = points[triangles[:, 0]]
    normals = np.cross(points[triangles[:, 1]] - corner, points[triangles[:, 2]] - corner)
    triangles = np.where((normals @ normal < 0)[:, None], triangles[:, ::-1], triangles)
    defects = edge_defects(triangles)
    if defects.non_manifold or defects.inconsistent or not defects.boundary:
        return None
    half = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    key = np.minimum(half[:, 0], half[:, 1]) * len(points) + np.maximum(half[:, 0], half[:, 1])
    _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    border = half[counts[inverse] == 1]
    if np.bincount(border[:, 0], minlength=len(points)).max() > 1:
        return None  # two border loops touch at a point: not a manifold border
    n = len(points)
    a, b = border[:, 0], border[:, 1]
    walls = np.concatenate([np.stack([b, a, a + n], 1), np.stack([b, a + n, b + n], 1)])
    slab = np.concatenate([triangles, triangles[:, ::-1] + n, walls])
    return np.concatenate([points, points]), slab


def _bodies(n_points: int, triangles: np.ndarray, adjacency: EdgeAdjacency) -> np.ndarray:
    """Return the body of every triangle, numbered 0.. in order of first triangle."""
    faces = adjacency.faces
    root, _ = _union_parity(
        len(triangles), faces[:, 0], faces[:, 1], np.zeros(len(faces), dtype=bool)
    )
    _, first, labels = np.unique(root, return_index=True, return_inverse=True)
    order = np.argsort(first)
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    return rank[labels]


def prepare_volume_mesh(points, triangles, name: str = "mesh") -> VolumeMesh:
    """Make a caster ready for shadow volumes, or say why it cannot be.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` finite coordinates (best relative to a point near the mesh).
    triangles : array_like
        ``(m, 3)`` integer point ids.
    name : str, default: "mesh"
        How error messages name the caster.

    Returns
    -------
    VolumeMesh
        Closed, outward wound, sorted by body, with its adjacency.

    Raises
    ------
    OpenMeshError
        When the mesh has no triangles or cannot be made closed and is not a
        flat sheet; the message names it and says what is wrong.

    Examples
    --------
    A plane becomes a two-sided slab; a cube stays a cube:

    >>> import pyvista as pv
    >>> from pvshadows.geometry.volume_casters import prepare_volume_mesh
    >>> plane = pv.Plane(i_resolution=2, j_resolution=2).triangulate()
    >>> prepare_volume_mesh(plane.points, plane.regular_faces, "ground").how
    'two-sided sheet'
    >>> cube = pv.Cube().triangulate()
    >>> mesh = prepare_volume_mesh(cube.points, cube.regular_faces, "box")
    >>> mesh.how, mesh.triangles.shape, mesh.n_bodies
    ('closed', (12, 3), 1)
    """
    try:
        closed = make_closed(points, triangles, name=name)
        how = "repaired" if closed.repaired else "closed"
        points, triangles = closed.points, closed.triangles
    except OpenMeshError:
        array = np.asarray(triangles)
        sheet = _flat_sheet(np.asarray(points, float), array) if array.size else None
        if sheet is None:
            raise
        (points, triangles), how = sheet, "two-sided sheet"
    adjacency = edge_adjacency(triangles)
    body = _bodies(len(points), triangles, adjacency)
    order = np.argsort(body, kind="stable")
    triangles = triangles[order]
    new_index = np.empty_like(order)
    new_index[order] = np.arange(len(order))
    adjacency = EdgeAdjacency(edges=adjacency.edges, faces=new_index[adjacency.faces])
    point_body = np.zeros(len(points), dtype=np.int64)
    point_body[triangles.ravel()] = np.repeat(body[order], 3)
    counts = np.bincount(body, minlength=int(body.max()) + 1)
    points = np.asarray(points, dtype=np.float64)
    return VolumeMesh(
        points=points,
        triangles=triangles,
        adjacency=adjacency,
        adjacency_rows=adjacency_indices(triangles, adjacency),
        point_body=point_body,
        body_starts=np.concatenate([[0], np.cumsum(counts)]),
        how=how,
    )


def winding_number(points: np.ndarray, triangles: np.ndarray, query: np.ndarray) -> float:
    """Return the generalized winding number of a closed mesh around a point.

    About 1 inside an outward wound closed mesh, 0 outside, whatever its
    shape (Jacobson et al. 2013: the sum of the solid angles of its triangles
    seen from the point, over 4 pi).

    Parameters
    ----------
    points : numpy.ndarray
        ``(n, 3)`` coordinates.
    triangles : numpy.ndarray
        ``(m, 3)`` point ids, wound outward.
    query : numpy.ndarray
        ``(3,)`` the point.

    Returns
    -------
    float
        The winding number.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.geometry.volume_casters import winding_number
    >>> cube = pv.Cube().triangulate()
    >>> round(winding_number(cube.points, cube.regular_faces, np.zeros(3)), 6)
    1.0
    >>> round(winding_number(cube.points, cube.regular_faces, np.array([2.0, 0, 0])), 6)
    0.0
    """
    corners = np.asarray(points, dtype=np.float64)[np.asarray(triangles)] - query
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
    la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
    numerator = np.einsum("ij,ij->i", a, np.cross(b, c))
    denominator = (
        la * lb * lc
        + np.einsum("ij,ij->i", a, b) * lc
        + np.einsum("ij,ij->i", b, c) * la
        + np.einsum("ij,ij->i", c, a) * lb
    )
    return float(np.arctan2(numerator, denominator).sum() / (2.0 * np.pi))


def batches(body_counts: list[int], limit: int | None = None) -> list[list[tuple]]:
    """Split casters' bodies into batches of at most ``limit`` bodies.

    Parameters
    ----------
    body_counts : list of int
        Bodies of each caster, in drawing order.
    limit : int, optional
        Most bodies per batch; by default :data:`MAX_BODIES_PER_BATCH` (255,
        the largest count an 8-bit stencil holds).

    Returns
    -------
    list of list of tuple
        Per batch, ``(caster, first_body, end_body)`` ranges.

    Examples
    --------
    >>> from pvshadows.geometry.volume_casters import batches
    >>> batches([1, 1])
    [[(0, 0, 1), (1, 0, 1)]]
    >>> [len(b) for b in batches([300, 2], limit=255)]
    [1, 2]
    """
    limit = MAX_BODIES_PER_BATCH if limit is None else int(limit)
    result: list[list[tuple]] = [[]]
    room = limit
    for caster, count in enumerate(body_counts):
        start = 0
        while start < count:
            if room == 0:
                result.append([])
                room = limit
            end = min(count, start + room)
            result[-1].append((caster, start, end))
            room -= end - start
            start = end
    return [batch for batch in result if batch]
