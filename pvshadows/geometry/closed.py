"""Closed, consistently wound casters for shadow volumes.

A shadow volume is only right when its caster is a closed 2-manifold surface
whose triangles are all wound the same way (outward). This module welds a
triangle mesh, checks every edge, repairs what can be repaired without
changing the shape (winding, inverted bodies, holes of three or four edges,
pinched edges through manifold3d) and raises :class:`OpenMeshError` for
everything else, so that an open caster is never silently drawn wrong.
"""

from __future__ import annotations

from dataclasses import dataclass

import manifold3d
import numpy as np

_RELATIVE_TOLERANCE = 1e-9
_ULPS = 8.0


class OpenMeshError(ValueError):
    """A mesh cannot be made closed and consistently wound.

    The message names the mesh and says what is wrong with it, for example
    how many boundary edges it has.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.closed import OpenMeshError, make_closed
    >>> points = np.eye(3)
    >>> try:
    ...     make_closed(points, [[0, 1, 2]], name="leaf")
    ... except OpenMeshError as err:
    ...     print(err)
    mesh 'leaf' cannot be made closed: 3 boundary edges (the mesh has holes or is a sheet)
    """


@dataclass(frozen=True)
class ClosedMesh:
    """A welded, closed, consistently and outward wound triangle mesh.

    Attributes
    ----------
    points : numpy.ndarray
        ``(n, 3)`` float64 points, welded and all used by a triangle. After a
        manifold3d repair, the points of a pinched edge are duplicated so that
        every edge has exactly two faces.
    triangles : numpy.ndarray
        ``(m, 3)`` int64 triangles, wound counter-clockwise seen from outside,
        with no zero-area (repeated vertex) or duplicate faces. Every edge
        is shared by exactly two triangles that use it in opposite directions.
    repaired : bool
        ``True`` when more than welding and dropping degenerate or duplicate
        faces was needed: rewinding, flipping an inside-out body, filling
        small holes or a manifold3d repair.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.geometry.closed import make_closed
    >>> cube = pv.Cube(clean=False).triangulate()
    >>> closed = make_closed(cube.points, cube.regular_faces, name="cube")
    >>> closed.points.shape, closed.triangles.shape, closed.repaired
    ((8, 3), (12, 3), False)
    """

    points: np.ndarray
    triangles: np.ndarray
    repaired: bool


@dataclass(frozen=True)
class EdgeDefects:
    """What keeps a triangle mesh from being closed and consistently wound.

    Attributes
    ----------
    boundary : int
        Edges used by one triangle only (holes, sheets).
    non_manifold : int
        Edges used by more than two triangles.
    max_faces : int
        The largest number of triangles sharing one edge.
    inconsistent : int
        Edges whose two triangles use them in the same direction (flipped
        faces, or a non-orientable surface).

    Examples
    --------
    >>> from pvshadows.geometry.closed import edge_defects
    >>> edge_defects([[0, 1, 2], [0, 2, 3]]).boundary
    4
    """

    boundary: int
    non_manifold: int
    max_faces: int
    inconsistent: int

    @property
    def is_closed(self) -> bool:
        """Whether every edge has two triangles using it in opposite directions.

        Examples
        --------
        >>> from pvshadows.geometry.closed import edge_defects
        >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
        >>> edge_defects(tetra).is_closed
        True
        """
        return self.boundary == 0 and self.non_manifold == 0 and self.inconsistent == 0

    def describe(self) -> str:
        """Say in words what is wrong, or ``"closed"``.

        Returns
        -------
        str
            A comma-separated list of the defects.

        Examples
        --------
        >>> from pvshadows.geometry.closed import edge_defects
        >>> edge_defects([[0, 1, 2], [0, 1, 3], [0, 1, 4]]).describe()
        '6 boundary edges (the mesh has holes or is a sheet), 1 non-manifold edge shared by 3 faces'
        """
        parts = []
        if self.boundary:
            parts.append(
                f"{_count(self.boundary, 'boundary edge')} (the mesh has holes or is a sheet)"
            )
        if self.non_manifold:
            parts.append(
                f"{_count(self.non_manifold, 'non-manifold edge')} shared by "
                f"{'up to ' if self.non_manifold > 1 else ''}{self.max_faces} faces"
            )
        if self.inconsistent:
            parts.append(
                f"{_count(self.inconsistent, 'edge')} whose two faces are wound the same way"
            )
        return ", ".join(parts) if parts else "closed"


def _count(number: int, noun: str) -> str:
    """Format ``number noun`` with a plural ``s`` when needed."""
    return f"{number} {noun}{'' if number == 1 else 's'}"


def _as_points(points) -> np.ndarray:
    """Validate points as a finite ``(n, 3)`` float64 array."""
    array = np.asarray(points, dtype=np.float64)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {array.shape}")
    bad = np.count_nonzero(~np.isfinite(array))
    if bad:
        raise ValueError(f"points contains {bad} non-finite values (NaN or inf)")
    return array


def _as_triangles(triangles, n_points: int) -> np.ndarray:
    """Validate triangles as an ``(m, 3)`` int64 array indexing ``n_points`` points."""
    array = np.asarray(triangles)
    if array.size == 0:
        return np.empty((0, 3), dtype=np.int64)
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"triangles must have shape (m, 3), got {array.shape}")
    if not np.issubdtype(array.dtype, np.integer):
        raise ValueError(f"triangles must hold integer point ids, got dtype {array.dtype}")
    if array.min() < 0 or array.max() >= n_points:
        raise ValueError(
            f"triangles index points 0..{n_points - 1}, got ids from {array.min()} to {array.max()}"
        )
    return array.astype(np.int64)


def _grid_spacing(points: np.ndarray, tolerance: float | None) -> float:
    """Return the welding grid spacing: ``tolerance`` or 1e-9 of the bounding-box diagonal.

    Never below a few units in the last place of the largest coordinate, so
    that the grid cell numbers fit in int64 at any scale and offset.
    """
    if tolerance is not None and not (np.isfinite(tolerance) and tolerance >= 0):
        raise ValueError(f"tolerance must be a finite number >= 0, got {tolerance!r}")
    if len(points) == 0:
        return 1.0
    floor = max(
        _ULPS * np.finfo(np.float64).eps * float(np.abs(points).max()), np.finfo(np.float64).tiny
    )
    if tolerance is None:
        tolerance = _RELATIVE_TOLERANCE * float(np.linalg.norm(np.ptp(points, axis=0)))
    return max(float(tolerance), floor)


def _group_rows(rows: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Group equal rows of an integer array.

    Returns the group id of every row, groups numbered in order of their first
    row, and the index of each group's first row (ascending).
    """
    if len(rows) == 0:
        return np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
    low = rows.min(axis=0)
    spans = [int(span) + 1 for span in rows.max(axis=0) - low]
    if np.prod(spans, dtype=object) < 2**63:
        key = (rows[:, 0] - low[0]) * (spans[1] * spans[2]) + (rows[:, 1] - low[1]) * spans[2]
        order = np.argsort(key + (rows[:, 2] - low[2]), kind="stable")
    else:
        order = np.lexsort(rows.T[::-1])
    ordered = rows[order]
    starts = np.ones(len(rows), dtype=bool)
    starts[1:] = np.any(ordered[1:] != ordered[:-1], axis=1)
    first = order[starts]
    rank = np.empty(len(first), dtype=np.int64)
    rank[np.argsort(first)] = np.arange(len(first))
    groups = np.empty(len(rows), dtype=np.int64)
    groups[order] = rank[np.cumsum(starts) - 1]
    return groups, np.sort(first)


def _merge_points(points: np.ndarray, spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """Group points that share a cell of a grid, or of the grid shifted by half a cell.

    Rounding to one grid alone splits near-equal points that straddle a cell
    boundary; with the shifted grid joined in, that needs them to straddle a
    boundary of both grids. Returns each point's group, numbered in order of
    first appearance, and each group's first point.
    """
    if len(points) == 0:
        return np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
    scaled = (points - points.min(axis=0)) / spacing
    groups, first = _group_rows(np.rint(scaled).astype(np.int64))
    shifted, shifted_first = _group_rows(np.floor(scaled).astype(np.int64))
    linked = groups[shifted_first][shifted]
    root, _ = _union_parity(len(first), groups, linked, np.zeros(len(points), dtype=bool))
    roots, merged = np.unique(root[groups], return_inverse=True)
    return merged, first[roots]


def weld(points, triangles, tolerance: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Merge duplicate points and drop degenerate and repeated triangles.

    Points are snapped to a grid of spacing ``tolerance`` (relative to the
    bounding box by default, so it works at any scale and offset); points in
    the same grid cell, or in the same cell of the grid shifted by half a
    cell, become one point, the first of them. Triangles that then repeat a
    point (zero area) are dropped, and so are triangles with the same three
    points as an earlier one, whatever their order. Points no triangle uses
    are dropped.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` finite coordinates.
    triangles : array_like
        ``(m, 3)`` integer point ids.
    tolerance : float, optional
        Grid spacing for merging, in the units of ``points``. Defaults to
        ``1e-9`` times the bounding-box diagonal. Never smaller than a few
        units in the last place of the largest coordinate.

    Returns
    -------
    points : numpy.ndarray
        ``(k, 3)`` float64 welded points, in order of first appearance.
    triangles : numpy.ndarray
        ``(j, 3)`` int64 triangles into the welded points, in input order.

    Raises
    ------
    ValueError
        If the shapes are wrong, a point is not finite, an id is out of range
        or ``tolerance`` is negative.

    Examples
    --------
    A cube with 24 points (each corner repeated for each face) welds to 8:

    >>> import pyvista as pv
    >>> from pvshadows.geometry.closed import weld
    >>> cube = pv.Cube(clean=False).triangulate()
    >>> points, triangles = weld(cube.points, cube.regular_faces)
    >>> len(cube.points), len(points), len(triangles)
    (24, 8, 12)
    """
    points = _as_points(points)
    triangles = _as_triangles(triangles, len(points))
    groups, first = _merge_points(points, _grid_spacing(points, tolerance))
    triangles = groups[triangles]
    corners = np.sort(triangles, axis=1)
    proper = (corners[:, 0] != corners[:, 1]) & (corners[:, 1] != corners[:, 2])
    triangles = triangles[proper][_group_rows(corners[proper])[1]]
    used = np.flatnonzero(np.bincount(triangles.ravel(), minlength=len(first)))
    compact = np.zeros(len(first), dtype=np.int64)
    compact[used] = np.arange(len(used))
    return points[first[used]], compact[triangles]


def _edge_groups(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Sort the half-edges of a mesh by undirected edge.

    Returns the ``(3m, 2)`` half-edges (half-edge ``3 f + k`` runs from corner
    ``k`` of face ``f`` to the next corner), the order that groups them by
    edge, and the start and size of each group in that order.
    """
    half_edges = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    low = np.minimum(half_edges[:, 0], half_edges[:, 1])
    high = np.maximum(half_edges[:, 0], half_edges[:, 1])
    key = low * (int(high.max()) + 1) + high
    order = np.argsort(key, kind="stable")
    ordered = key[order]
    starts = np.flatnonzero(np.concatenate([[True], ordered[1:] != ordered[:-1]]))
    return half_edges, order, starts, np.diff(starts, append=len(order))


def edge_defects(triangles) -> EdgeDefects:
    """Count the edges that keep a mesh from being closed and consistently wound.

    Parameters
    ----------
    triangles : array_like
        ``(m, 3)`` integer point ids, without repeated ids in a triangle.

    Returns
    -------
    EdgeDefects
        Boundary, non-manifold and inconsistently wound edges.

    Examples
    --------
    >>> from pvshadows.geometry.closed import edge_defects
    >>> tetra = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    >>> edge_defects(tetra).is_closed
    True
    >>> edge_defects(tetra[:3]).describe()
    '3 boundary edges (the mesh has holes or is a sheet)'
    """
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if len(triangles) == 0:
        return EdgeDefects(0, 0, 0, 0)
    half_edges, order, starts, sizes = _edge_groups(triangles)
    forward = (half_edges[order, 0] < half_edges[order, 1]).astype(np.int64)
    n_forward = np.add.reduceat(forward, starts)
    return EdgeDefects(
        boundary=int(np.count_nonzero(sizes == 1)),
        non_manifold=int(np.count_nonzero(sizes > 2)),
        max_faces=int(sizes.max()),
        inconsistent=int(np.count_nonzero((sizes == 2) & (n_forward != 1))),
    )


def _face_pairs(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the two half-edges of every edge shared by exactly two faces."""
    _, order, starts, sizes = _edge_groups(triangles)
    pairs = starts[sizes == 2]
    return order[pairs], order[pairs + 1]


def _union_parity(
    n_faces: int, first: np.ndarray, second: np.ndarray, odd: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Join faces into bodies and solve ``flip[first] ^ flip[second] == odd`` on a spanning forest.

    A vectorised union-find: in each round every root that shares an edge
    with a smaller root is hooked under it, then paths are compressed by
    pointer jumping, carrying the parity of the path to the root. Returns the
    root (body label) of every face and its flip relative to that root. Edges
    closing a cycle are not checked: an odd cycle (a non-orientable surface)
    shows up later as inconsistent edges.
    """
    parent = np.arange(n_faces)
    parity = np.zeros(n_faces, dtype=bool)
    while True:
        root_first, root_second = parent[first], parent[second]
        joins = root_first != root_second
        if not joins.any():
            return parent, parity
        relative = (parity[first] ^ parity[second] ^ odd)[joins]
        low = np.minimum(root_first, root_second)[joins]
        high = np.maximum(root_first, root_second)[joins]
        order = np.argsort(high, kind="stable")
        ordered = high[order]
        hook = order[np.concatenate([[True], ordered[1:] != ordered[:-1]])]
        parent[high[hook]] = low[hook]
        parity[high[hook]] = relative[hook]
        while not np.array_equal(parent[parent], parent):
            parity = parity ^ parity[parent]
            parent = parent[parent]


def _orient_consistently(points: np.ndarray, triangles: np.ndarray) -> tuple:
    """Flip faces so that faces sharing an edge use it in opposite directions."""
    if edge_defects(triangles).inconsistent == 0:
        return points, triangles
    half_edges, twins = _face_pairs(triangles)
    same_direction = triangles.ravel()[half_edges] == triangles.ravel()[twins]
    _, flip = _union_parity(len(triangles), half_edges // 3, twins // 3, same_direction)
    return points, np.where(flip[:, None], triangles[:, ::-1], triangles)


def _fill_small_holes(points: np.ndarray, triangles: np.ndarray) -> tuple:
    """Close holes bounded by three or four edges with one or two triangles."""
    half_edges, order, starts, sizes = _edge_groups(triangles)
    boundary = half_edges[order[starts[sizes == 1]]]
    if len(boundary) == 0:
        return points, triangles
    start, end = boundary[:, 0], boundary[:, 1]
    n_out = np.bincount(start, minlength=len(points))
    leaving = np.full(len(points), -1, dtype=np.int64)
    leaving[start] = np.arange(len(boundary))
    successor = np.append(np.where(n_out[end] == 1, leaving[end], -1), -1)
    steps = [np.arange(len(boundary))]
    for _ in range(4):
        steps.append(successor[steps[-1]])
    loop = np.stack(steps[:4])
    own = np.arange(len(boundary))
    is_first = np.all((loop == -1) | (loop >= own), axis=0)
    corner = start[np.clip(loop, 0, None)]
    tri_hole = is_first & (steps[3] == own) & (steps[1] != own)
    quad_hole = is_first & (steps[4] == own) & (steps[2] != own)
    new = np.concatenate(
        [
            corner[[0, 2, 1]][:, tri_hole].T,
            corner[[0, 3, 2]][:, quad_hole].T,
            corner[[0, 2, 1]][:, quad_hole].T,
        ]
    )
    every = np.concatenate([triangles, new])
    unseen = _group_rows(np.sort(every, axis=1))[1]
    return points, every[unseen]


def _close_with_manifold(points: np.ndarray, triangles: np.ndarray) -> tuple:
    """Let manifold3d merge open edges and split pinched (non-manifold) edges."""
    if edge_defects(triangles).is_closed:
        return points, triangles
    mesh = manifold3d.Mesh64(
        vert_properties=np.ascontiguousarray(points),
        tri_verts=np.ascontiguousarray(triangles, dtype=np.uint64),
    )
    mesh.merge()
    solid = manifold3d.Manifold(mesh)
    if solid.status() != manifold3d.Error.NoError or solid.is_empty():
        return points, triangles
    result = solid.to_mesh64()
    return (
        np.array(result.vert_properties[:, :3], dtype=np.float64),
        np.array(result.tri_verts, dtype=np.int64),
    )


def _orient_outward(points: np.ndarray, triangles: np.ndarray) -> tuple:
    """Flip every closed body whose signed volume is negative (inside out)."""
    first, second = _face_pairs(triangles)
    body, _ = _union_parity(len(triangles), first // 3, second // 3, np.zeros(len(first), bool))
    corners = points[triangles] - (points.min(axis=0) + points.max(axis=0)) / 2
    six_volumes = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2]))
    inside_out = np.bincount(body, weights=six_volumes, minlength=len(triangles)) < 0
    flip = inside_out[body]
    return points, np.where(flip[:, None], triangles[:, ::-1], triangles)


def _reason(found: EdgeDefects, remaining: EdgeDefects) -> str:
    """Explain why a welded mesh with defects ``found`` stayed open after every repair."""
    if remaining.boundary == remaining.non_manifold == 0:
        return (
            f"it is not orientable: {found.describe()}, and no rewinding makes "
            "every two neighbouring faces agree"
        )
    if remaining == found:
        return found.describe()
    return f"{found.describe()}; after repair still {remaining.describe()}"


def make_closed(points, triangles, name: str = "mesh") -> ClosedMesh:
    """Weld a triangle mesh and make it closed and outward wound, or raise.

    The steps, each only when needed: weld (:func:`weld`); rewind faces so
    that neighbours agree; fill holes of three or four edges; let manifold3d
    merge open edges and split pinched (non-manifold) edges; flip bodies that
    are inside out. Larger holes are never filled and the mesh is never
    replaced by its convex hull: a mesh that is still not closed raises.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` finite coordinates.
    triangles : array_like
        ``(m, 3)`` integer point ids. An empty array (a mesh of points or lines
        only) raises :class:`OpenMeshError`.
    name : str, default: "mesh"
        The name used in error messages.

    Returns
    -------
    ClosedMesh
        The closed, consistently and outward wound mesh.

    Raises
    ------
    OpenMeshError
        If the mesh has no triangles or cannot be made closed; the message
        names the mesh and its defects.
    ValueError
        If the arrays have the wrong shape, hold NaN/inf or bad ids.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.geometry.closed import make_closed
    >>> sphere = pv.Sphere()
    >>> closed = make_closed(sphere.points, sphere.regular_faces, name="sphere")
    >>> closed.triangles.shape, closed.repaired
    ((1680, 3), False)
    """
    original = np.asarray(triangles)
    welded_points, welded = weld(points, triangles)
    if len(welded) == 0:
        reason = (
            "it has no triangles (only points or lines?)"
            if original.size == 0
            else f"all its triangles have zero area ({_count(len(original), 'triangle')} given)"
        )
        raise OpenMeshError(f"mesh {name!r} cannot be made closed: {reason}")
    defects = edge_defects(welded)
    fixed_points, fixed = welded_points, welded
    if not defects.is_closed:
        for repair in (_orient_consistently, _fill_small_holes, _close_with_manifold):
            fixed_points, fixed = repair(fixed_points, fixed)
        remaining = edge_defects(fixed)
        if not remaining.is_closed:
            reason = _reason(defects, remaining)
            raise OpenMeshError(f"mesh {name!r} cannot be made closed: {reason}")
    fixed_points, fixed = _orient_outward(fixed_points, fixed)
    fixed_points.flags.writeable = False
    fixed.flags.writeable = False
    repaired = fixed_points is not welded_points or not np.array_equal(fixed, welded)
    return ClosedMesh(points=fixed_points, triangles=fixed, repaired=bool(repaired))


def is_closed_outward(points, triangles) -> bool:
    """Return whether a mesh, once welded, is closed and wound with its fronts outward.

    Only such a mesh can have its front faces culled from a shadow map: every
    ray from the light then meets one of its back faces behind the front.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` points.
    triangles : array_like
        ``(m, 3)`` point ids.

    Returns
    -------
    bool
        ``True`` for a closed, consistently and outward wound surface.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.geometry.closed import is_closed_outward
    >>> sphere = pv.Sphere()
    >>> is_closed_outward(sphere.points, sphere.regular_faces)
    True
    >>> plane = pv.Plane().triangulate()
    >>> is_closed_outward(plane.points, plane.regular_faces)
    False
    """
    welded_points, welded = weld(points, triangles)
    if len(welded) == 0 or not edge_defects(welded).is_closed:
        return False
    corners = welded_points[welded] - welded_points.mean(axis=0)
    six_volume = np.einsum("ij,ij->i", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])).sum()
    return bool(six_volume > 0.0)
