"""Silhouettes and shadow-volume geometry on the CPU.

For a closed, consistently wound caster (see :mod:`pvshadows.geometry.closed`) and a
light, this module finds the faces that face the light, the silhouette edges
between lit and unlit faces, and assembles the shadow volume: the lit faces
as the light cap, the silhouette extruded to infinity (``w = 0``) as the
sides, and the unlit faces projected to infinity as the dark cap. Every
triangle of the volume is wound outward, so a stencil count (z-pass or
z-fail) increments on entering it.

Lights are homogeneous 4-vectors: ``(x, y, z, 1)`` for a point or spot light
at ``(x, y, z)``, ``(dx, dy, dz, 0)`` for a directional light shining along
``(dx, dy, dz)``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from pvshadows.geometry.closed import edge_defects, make_closed


@dataclass(frozen=True)
class EdgeAdjacency:
    """The edges of a closed mesh with the two faces on either side.

    Attributes
    ----------
    edges : numpy.ndarray
        ``(e, 2)`` int64 point ids ``(a, b)``, in the direction face ``0`` of
        the edge uses them.
    faces : numpy.ndarray
        ``(e, 2)`` int64 face ids: face ``0`` has the edge as ``a -> b``, face
        ``1`` as ``b -> a``.

    Examples
    --------
    >>> from pvshadows.geometry.silhouette import edge_adjacency
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> adjacency = edge_adjacency(tetra)
    >>> adjacency.edges.shape, adjacency.faces.shape
    ((6, 2), (6, 2))
    """

    edges: np.ndarray
    faces: np.ndarray


@dataclass(frozen=True)
class VolumeGeometry:
    """The shadow volume of one caster for one light, ready to upload.

    Point ``i`` of the caster is ``positions[i]`` (``w = 1``) and its
    extrusion to infinity is ``positions[n + i]`` (``w = 0``), where ``n`` is
    the number of caster points. All triangles are wound outward.

    Attributes
    ----------
    positions : numpy.ndarray
        ``(2 n, 4)`` float32 homogeneous positions, in the caster's frame:
        ``(p, 1)`` then ``(p - L, 0)`` for a point light at ``L`` or
        ``(d, 0)`` for a directional light shining along ``d``.
    sides : numpy.ndarray
        ``(s, 3)`` uint32 triangles: each silhouette edge extruded to
        infinity as two triangles.
    light_cap : numpy.ndarray
        ``(c, 3)`` uint32 triangles: the faces facing the light, at their
        finite positions.
    dark_cap : numpy.ndarray
        ``(d, 3)`` uint32 triangles: the faces facing away from the light,
        projected to infinity. For a directional light they collapse to a
        point and draw nothing.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.silhouette import edge_adjacency, volume_geometry
    >>> points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    >>> volume = volume_geometry(points, tetra, edge_adjacency(tetra), [0, 0, 5, 1])
    >>> volume.positions.shape, len(volume.sides), len(volume.light_cap), len(volume.dark_cap)
    ((8, 4), 6, 1, 3)
    """

    positions: np.ndarray
    sides: np.ndarray
    light_cap: np.ndarray
    dark_cap: np.ndarray


def _as_triangles(triangles) -> np.ndarray:
    """Validate triangles as ``(m, 3)`` int64 ids without repeats in a row."""
    array = np.asarray(triangles)
    if array.size == 0:
        return np.empty((0, 3), dtype=np.int64)
    if array.ndim != 2 or array.shape[1] != 3 or not np.issubdtype(array.dtype, np.integer):
        raise ValueError(
            f"triangles must be an (m, 3) integer array, got {array.shape} {array.dtype}"
        )
    array = array.astype(np.int64)
    if array.min() < 0:
        raise ValueError(f"triangles must hold point ids >= 0, got {array.min()}")
    if np.any(
        (array[:, 0] == array[:, 1]) | (array[:, 1] == array[:, 2]) | (array[:, 2] == array[:, 0])
    ):
        raise ValueError("triangles must not repeat a point (weld the mesh with make_closed)")
    return array


def _as_points(points, triangles: np.ndarray) -> np.ndarray:
    """Validate points as a finite ``(n, 3)`` float64 array covering every triangle id."""
    array = np.asarray(points, dtype=np.float64)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {array.shape}")
    if not np.isfinite(array).all():
        raise ValueError("points contains non-finite values (NaN or inf)")
    if len(triangles) and triangles.max() >= len(array):
        raise ValueError(
            f"triangles index point {triangles.max()} but there are {len(array)} points"
        )
    return array


def _as_light(light) -> tuple[np.ndarray, bool]:
    """Split a homogeneous light into its position or direction and a directional flag."""
    array = np.asarray(light, dtype=np.float64)
    if array.shape != (4,) or not np.all(np.isfinite(array)):
        raise ValueError(
            "light must be finite homogeneous (x, y, z, 1) for a point light or "
            f"(dx, dy, dz, 0) for a directional light, got {light!r}"
        )
    if array[3] != 0:
        return array[:3] / array[3], False
    if not np.any(array[:3]):
        raise ValueError("a directional light (w = 0) needs a non-zero direction, got (0, 0, 0, 0)")
    return array[:3], True


def edge_adjacency(triangles) -> EdgeAdjacency:
    """Pair every edge of a closed mesh with the two faces that share it.

    Set up once per mesh; the silhouette of every frame reads it.

    Parameters
    ----------
    triangles : array_like
        ``(m, 3)`` integer point ids of a closed, consistently wound mesh,
        such as :attr:`pvshadows.geometry.closed.ClosedMesh.triangles`.

    Returns
    -------
    EdgeAdjacency
        ``3 m / 2`` edges, each with its two faces.

    Raises
    ------
    ValueError
        If an edge does not have exactly two faces using it in opposite
        directions; the message counts the bad edges.

    Examples
    --------
    >>> from pvshadows.geometry.silhouette import edge_adjacency
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> adjacency = edge_adjacency(tetra)
    >>> adjacency.edges[0].tolist(), adjacency.faces[0].tolist()
    ([0, 1], [1, 0])
    """
    triangles = _as_triangles(triangles)
    if len(triangles) == 0:
        empty = np.empty((0, 2), dtype=np.int64)
        return EdgeAdjacency(edges=empty, faces=empty)
    half_edges = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    low, high = half_edges.min(axis=1), half_edges.max(axis=1)
    key = low * (int(high.max()) + 1) + high
    order = np.argsort(key, kind="stable")
    first, second = order[0::2], order[1::2]
    forward = half_edges[:, 0] < half_edges[:, 1]
    paired = len(order) % 2 == 0 and np.array_equal(key[first], key[second])
    if (
        not paired
        or np.any(key[second[:-1]] == key[first[1:]])
        or np.any(forward[first] == forward[second])
    ):
        raise ValueError(
            f"the mesh is not closed and consistently wound: {edge_defects(triangles).describe()}"
        )
    forward_first = np.where(forward[first], first, second)
    backward_first = np.where(forward[first], second, first)
    return EdgeAdjacency(
        edges=half_edges[forward_first],
        faces=np.stack([forward_first // 3, backward_first // 3], axis=1),
    )


def adjacency_indices(triangles, adjacency: EdgeAdjacency) -> np.ndarray:
    """Index buffer for ``GL_TRIANGLES_ADJACENCY``, for extrusion in a geometry shader.

    Parameters
    ----------
    triangles : array_like
        ``(m, 3)`` integer point ids of a closed, consistently wound mesh.
    adjacency : EdgeAdjacency
        Its edges, from :func:`edge_adjacency`.

    Returns
    -------
    numpy.ndarray
        ``(m, 6)`` uint32 rows ``v0, n01, v1, n12, v2, n20``: the triangle's
        points, each edge ``XY`` followed by the point of the neighbouring
        face across it that is not on the edge.

    Examples
    --------
    >>> from pvshadows.geometry.silhouette import adjacency_indices, edge_adjacency
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> adjacency_indices(tetra, edge_adjacency(tetra))[0].tolist()
    [0, 3, 2, 3, 1, 3]
    """
    triangles = _as_triangles(triangles)
    edges, faces = adjacency.edges, adjacency.faces
    corner_sums = triangles.sum(axis=1)
    across = corner_sums[faces] - edges.sum(axis=1)[:, None]
    indices = np.zeros((len(triangles), 6), dtype=np.int64)
    indices[:, 0::2] = triangles
    for side, start in ((0, edges[:, 0]), (1, edges[:, 1])):
        face = faces[:, side]
        corner = np.argmax(triangles[face] == start[:, None], axis=1)
        indices[face, 2 * corner + 1] = across[:, 1 - side]
    return indices.astype(np.uint32)


def facing(points, triangles, light) -> np.ndarray:
    """Tell which faces have their front (outer) side towards the light.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` coordinates, best relative to a local origin near the mesh.
    triangles : array_like
        ``(m, 3)`` integer point ids, wound outward.
    light : array_like
        ``(x, y, z, 1)`` for a point light, ``(dx, dy, dz, 0)`` for a
        directional light shining along ``(dx, dy, dz)``.

    Returns
    -------
    numpy.ndarray
        ``(m,)`` bool, ``True`` where the face's outward normal points
        towards the light. Faces seen exactly edge-on (and zero-area faces)
        count as facing away.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.silhouette import facing
    >>> points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> facing(points, tetra, [0, 0, -1, 0]).tolist()  # sun overhead; two faces edge-on
    [False, False, True, False]
    >>> facing(points, tetra, [0.2, 0.2, -3.0, 1.0]).tolist()  # bulb below
    [True, False, False, False]
    """
    triangles = _as_triangles(triangles)
    return _facing(_as_points(points, triangles), triangles, *_as_light(light))


def _facing(
    points: np.ndarray, triangles: np.ndarray, light: np.ndarray, directional: bool
) -> np.ndarray:
    """Face orientation test on validated input (see :func:`facing`)."""
    corner = points[triangles[:, 0]]
    normal = np.cross(points[triangles[:, 1]] - corner, points[triangles[:, 2]] - corner)
    if directional:
        return normal @ light < 0
    return np.einsum("ij,ij->i", normal, light - corner) > 0


def silhouette_edges(points, triangles, adjacency: EdgeAdjacency, light) -> np.ndarray:
    """Find the edges between a face that faces the light and one that does not.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` coordinates.
    triangles : array_like
        ``(m, 3)`` integer point ids of a closed mesh, wound outward.
    adjacency : EdgeAdjacency
        Its edges, from :func:`edge_adjacency`.
    light : array_like
        ``(x, y, z, 1)`` point light or ``(dx, dy, dz, 0)`` directional light.

    Returns
    -------
    numpy.ndarray
        ``(k, 2)`` int64 point ids ``(a, b)``, each edge in the direction its
        lit face uses it. The side quad ``b, a, a', b'`` (primes: extruded to
        infinity) is then wound outward, like the caps. The edges form closed
        loops: every point has as many edges leaving as arriving.

    Examples
    --------
    A tetrahedron lit from below: its bottom face is lit, the silhouette is
    that face's three edges.

    >>> import numpy as np
    >>> from pvshadows.geometry.silhouette import edge_adjacency, silhouette_edges
    >>> points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> edges = silhouette_edges(points, tetra, edge_adjacency(tetra), [0.2, 0.2, -3, 1])
    >>> sorted(map(tuple, edges.tolist()))
    [(0, 2), (1, 0), (2, 1)]
    """
    triangles = _as_triangles(triangles)
    lit = _facing(_as_points(points, triangles), triangles, *_as_light(light))
    return _silhouette(adjacency, lit)


def _silhouette(adjacency: EdgeAdjacency, lit: np.ndarray) -> np.ndarray:
    """Silhouette edges in the direction of their lit face."""
    lit_sides = lit[adjacency.faces]
    edges = adjacency.edges[lit_sides[:, 0] != lit_sides[:, 1]]
    reverse = lit_sides[lit_sides[:, 0] != lit_sides[:, 1], 1]
    return np.where(reverse[:, None], edges[:, ::-1], edges)


def volume_geometry(points, triangles, adjacency: EdgeAdjacency, light) -> VolumeGeometry:
    """Build the shadow volume of a closed caster for one light.

    The arithmetic is done in float64; the positions are returned as float32,
    so pass points relative to a local origin near the caster.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` coordinates of the caster, in its local frame.
    triangles : array_like
        ``(m, 3)`` integer point ids of a closed mesh, wound outward.
    adjacency : EdgeAdjacency
        Its edges, from :func:`edge_adjacency`.
    light : array_like
        ``(x, y, z, 1)`` point light or ``(dx, dy, dz, 0)`` directional
        light, in the same frame as ``points``.

    Returns
    -------
    VolumeGeometry
        Positions and the three index lists. Together the sides and caps are a
        closed surface: every edge is used once in each direction.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.geometry.closed import make_closed
    >>> from pvshadows.geometry.silhouette import edge_adjacency, volume_geometry
    >>> cube = pv.Cube().triangulate()
    >>> mesh = make_closed(cube.points, cube.regular_faces)
    >>> adjacency = edge_adjacency(mesh.triangles)
    >>> volume = volume_geometry(mesh.points, mesh.triangles, adjacency, [0, 0, 2, 1])
    >>> len(volume.sides), len(volume.light_cap), len(volume.dark_cap)
    (8, 2, 10)
    """
    triangles = _as_triangles(triangles)
    points = _as_points(points, triangles)
    light, directional = _as_light(light)
    if 2 * len(points) > np.iinfo(np.uint32).max:
        raise ValueError(f"too many points for uint32 indices: {len(points)}")
    lit = _facing(points, triangles, light, directional)
    n = len(points)
    positions = np.zeros((2 * n, 4), dtype=np.float32)
    positions[:n, :3] = points
    positions[:n, 3] = 1.0
    positions[n:, :3] = light if directional else points - light
    a, b = _silhouette(adjacency, lit).T
    sides = np.stack([b, a, a + n, b, a + n, b + n], axis=1).reshape(-1, 3)
    return VolumeGeometry(
        positions=positions,
        sides=sides.astype(np.uint32),
        light_cap=triangles[lit].astype(np.uint32),
        dark_cap=(triangles[~lit] + n).astype(np.uint32),
    )


def time_silhouette(n_triangles: int, repeats: int = 3) -> dict:
    """Time the shadow-volume set-up and per-frame rebuild on a sphere.

    Builds a closed UV sphere of about ``n_triangles`` triangles, times
    :func:`make_closed` and :func:`edge_adjacency` (once per mesh) and, for a
    light moving around it, :func:`silhouette_edges` and
    :func:`volume_geometry` (once per frame when the light or caster moves).

    Parameters
    ----------
    n_triangles : int
        Approximate triangle count, at least 100.
    repeats : int, default: 3
        Timed repetitions; the median is reported.

    Returns
    -------
    dict
        ``n_triangles``, ``n_points``, ``n_silhouette_edges`` (last frame)
        and median seconds ``make_closed_s``, ``edge_adjacency_s``,
        ``silhouette_point_s``, ``silhouette_directional_s``,
        ``volume_point_s``, ``volume_directional_s``.

    Examples
    --------
    >>> from pvshadows.geometry.silhouette import time_silhouette
    >>> timing = time_silhouette(2000, repeats=1)
    >>> timing["n_triangles"] > 1000
    True
    """
    import pyvista as pv

    if n_triangles < 100 or repeats < 1:
        raise ValueError(
            f"need n_triangles >= 100 and repeats >= 1, got {n_triangles} and {repeats}"
        )
    resolution = max(int(np.sqrt(n_triangles / 2.0)), 8)
    sphere = pv.Sphere(theta_resolution=resolution, phi_resolution=resolution + 2)
    timings: dict[str, list[float]] = {}

    def timed(label: str, function, *args):
        start = time.perf_counter()
        result = function(*args)
        timings.setdefault(label, []).append(time.perf_counter() - start)
        return result

    for _ in range(repeats):
        mesh = timed("make_closed_s", make_closed, sphere.points, sphere.regular_faces, "sphere")
        adjacency = timed("edge_adjacency_s", edge_adjacency, mesh.triangles)
    for angle in np.linspace(0.0, 2.0 * np.pi, repeats, endpoint=False):
        direction = np.array([np.cos(angle), np.sin(angle), -0.5])
        for kind, light in (
            ("point", [*(-3.0 * direction), 1.0]),
            ("directional", [*direction, 0.0]),
        ):
            args = (mesh.points, mesh.triangles, adjacency, light)
            edges = timed(f"silhouette_{kind}_s", silhouette_edges, *args)
            timed(f"volume_{kind}_s", volume_geometry, *args)
    return {
        "n_triangles": len(mesh.triangles),
        "n_points": len(mesh.points),
        "n_silhouette_edges": len(edges),
        **{label: float(np.median(values)) for label, values in timings.items()},
    }
