"""Tests for pvshadows.geometry.silhouette: adjacency, silhouettes and shadow-volume geometry."""

import numpy as np
import pytest
import pyvista as pv
from pyvista import examples

from pvshadows.geometry.closed import make_closed
from pvshadows.geometry.silhouette import (
    EdgeAdjacency,
    VolumeGeometry,
    adjacency_indices,
    edge_adjacency,
    facing,
    silhouette_edges,
    time_silhouette,
    volume_geometry,
)

# A unit cube by hand, wound counter-clockwise seen from outside.
CUBE_POINTS = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=np.float64,
)
CUBE_TRIANGLES = np.array(
    [
        [0, 2, 1], [0, 3, 2],  # bottom, z = 0
        [4, 5, 6], [4, 6, 7],  # top, z = 1
        [0, 1, 5], [0, 5, 4],  # front, y = 0
        [3, 7, 6], [3, 6, 2],  # back, y = 1
        [0, 4, 7], [0, 7, 3],  # left, x = 0
        [1, 2, 6], [1, 6, 5],  # right, x = 1
    ]
)  # fmt: skip


def closed(mesh: pv.PolyData):
    mesh = mesh.triangulate()
    return make_closed(np.asarray(mesh.points, dtype=np.float64), mesh.regular_faces)


def all_triangles(volume: VolumeGeometry) -> np.ndarray:
    return np.vstack([volume.sides, volume.light_cap, volume.dark_cap]).astype(np.int64)


def assert_closed_surface(triangles: np.ndarray, n_points: int, silhouette: np.ndarray) -> None:
    """Every directed edge is used as often as its reverse: a closed, consistently wound surface.

    Each edge is used once in each direction, except the edge from a silhouette point
    to its point at infinity, used once per silhouette edge leaving (and arriving at)
    that point: twice where the silhouette crosses itself.
    """
    directed = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    edges, counts = np.unique(directed, axis=0, return_counts=True)
    reverse, reverse_counts = np.unique(directed[:, ::-1], axis=0, return_counts=True)
    np.testing.assert_array_equal(edges, reverse)
    np.testing.assert_array_equal(counts, reverse_counts)
    leaving = np.bincount(silhouette[:, 0], minlength=n_points)
    vertical = np.abs(edges[:, 1] - edges[:, 0]) == n_points
    np.testing.assert_array_equal(counts[vertical], leaving[edges[vertical].min(axis=1)])
    assert np.all(counts[~vertical] == 1)


def finite(volume: VolumeGeometry, stretch: float) -> np.ndarray:
    """Replace each point at infinity by a finite point ``stretch`` times its direction away."""
    n = len(volume.positions) // 2
    near = volume.positions[:n, :3].astype(np.float64)
    return np.vstack([near, near + stretch * volume.positions[n:, :3].astype(np.float64)])


def winding_numbers(vertices: np.ndarray, triangles: np.ndarray, queries: np.ndarray):
    """Generalised winding number: the stencil count a ray from the point to infinity sees."""
    corners = vertices[triangles][None] - queries[:, None, None, :]
    a, b, c = corners[:, :, 0], corners[:, :, 1], corners[:, :, 2]
    la, lb, lc = (np.linalg.norm(v, axis=-1) for v in (a, b, c))
    numerator = np.einsum("qtk,qtk->qt", a, np.cross(b, c))
    denominator = (
        la * lb * lc
        + np.einsum("qtk,qtk->qt", a, b) * lc
        + np.einsum("qtk,qtk->qt", b, c) * la
        + np.einsum("qtk,qtk->qt", c, a) * lb
    )
    return np.arctan2(numerator, denominator).sum(axis=1) / (2 * np.pi)


def random_lights(rng: np.random.Generator, bounds: np.ndarray, count: int) -> list:
    centre, size = bounds.mean(axis=0), np.ptp(bounds, axis=0).max()
    lights = []
    for _ in range(count):
        lights.append([*(centre + rng.uniform(-2, 2, 3) * size), 1.0])
        lights.append([*rng.normal(size=3), 0.0])
    return lights


@pytest.fixture(scope="module")
def torus():
    return closed(pv.ParametricTorus(u_res=40, v_res=30))


@pytest.fixture(scope="module")
def ant():
    return closed(examples.load_ant())


@pytest.fixture(scope="module")
def ball():
    return closed(pv.Sphere(radius=0.5, theta_resolution=48, phi_resolution=48))


def test_edge_adjacency_pairs_opposite_half_edges(ant):
    adjacency = edge_adjacency(ant.triangles)
    assert isinstance(adjacency, EdgeAdjacency)
    assert adjacency.edges.shape == adjacency.faces.shape == (len(ant.triangles) * 3 // 2, 2)
    assert adjacency.edges.dtype == adjacency.faces.dtype == np.int64
    for side, direction in ((0, slice(None)), (1, slice(None, None, -1))):
        faces = ant.triangles[adjacency.faces[:, side]]
        edge = adjacency.edges[:, direction]
        rolled = np.stack([faces, np.roll(faces, -1, axis=1)], axis=2)
        assert np.all(np.any(np.all(rolled == edge[:, None, :], axis=2), axis=1))


@pytest.mark.parametrize(
    ("triangles", "message"),
    [
        (CUBE_TRIANGLES[1:], "3 boundary edges"),
        (np.vstack([CUBE_TRIANGLES[:1, ::-1], CUBE_TRIANGLES[1:]]), "3 edges whose two faces"),
        (np.vstack([CUBE_TRIANGLES, [[4, 5, 8], [5, 4, 9]]]), "non-manifold edge shared by 4"),
        (np.array([[0, 0, 1]]), "must not repeat a point"),
        (np.array([[0.0, 1.0, 2.0]]), "integer"),
    ],
)
def test_edge_adjacency_rejects_open_or_inconsistent_meshes(triangles, message):
    with pytest.raises(ValueError, match=message):
        edge_adjacency(triangles)


def test_adjacency_indices_for_a_cube_by_hand():
    indices = adjacency_indices(CUBE_TRIANGLES, edge_adjacency(CUBE_TRIANGLES))
    assert indices.dtype == np.uint32
    assert indices.shape == (12, 6)
    # Top triangle 4-5-6: across 4-5 is the front face (0, 5, 4), across 5-6 the right
    # face (1, 6, 5), across 6-4 the other top triangle (4, 6, 7).
    assert indices[2].tolist() == [4, 0, 5, 1, 6, 7]
    # Bottom triangle 0-2-1: across 0-2 is (0, 3, 2), across 2-1 (1, 2, 6), across 1-0 (0, 1, 5).
    assert indices[0].tolist() == [0, 3, 2, 6, 1, 5]


def test_adjacency_indices_name_the_neighbour_across_each_edge(ant):
    triangles = ant.triangles
    indices = adjacency_indices(triangles, edge_adjacency(triangles)).astype(np.int64)
    np.testing.assert_array_equal(indices[:, 0::2], triangles)
    rotations = {tuple(np.roll(face, k)) for face in triangles.tolist() for k in range(3)}
    for corner in range(3):
        start, end = indices[:, 2 * corner], indices[:, (2 * corner + 2) % 6]
        across = indices[:, 2 * corner + 1]
        assert all(tuple(face) in rotations for face in np.stack([end, start, across], 1).tolist())


def test_cube_lit_from_above_the_top_face():
    light = [0.5, 0.5, 2.0, 1.0]
    lit = facing(CUBE_POINTS, CUBE_TRIANGLES, light)
    assert lit.tolist() == [False, False, True, True] + [False] * 8
    edges = silhouette_edges(CUBE_POINTS, CUBE_TRIANGLES, edge_adjacency(CUBE_TRIANGLES), light)
    assert sorted(map(sorted, edges.tolist())) == [[4, 5], [4, 7], [5, 6], [6, 7]]
    # oriented as in the top face: counter-clockwise seen from above
    assert sorted(map(tuple, edges.tolist())) == [(4, 5), (5, 6), (6, 7), (7, 4)]


def test_pyvista_cube_under_a_bulb_and_the_sun():
    cube = closed(pv.Cube())
    adjacency = edge_adjacency(cube.triangles)
    for light in ([0.0, 0.0, 2.0, 1.0], [0.0, 0.0, -1.0, 0.0]):
        edges = silhouette_edges(cube.points, cube.triangles, adjacency, light)
        ends = cube.points[edges]
        assert len(edges) == 4
        assert np.all(ends[:, :, 2] == 0.5)
        assert np.all(np.count_nonzero(ends[:, 0] != ends[:, 1], axis=1) == 1)  # no diagonal
        start, end = ends[:, 0], ends[:, 1]
        twice_area = np.sum(start[:, 0] * end[:, 1] - start[:, 1] * end[:, 0])
        assert twice_area == pytest.approx(2.0)  # a counter-clockwise unit square
    oblique = silhouette_edges(cube.points, cube.triangles, adjacency, [-1.0, -2.0, -3.0, 0.0])
    assert len(oblique) == 6  # top, +x and +y faces lit: a hexagon


def test_sphere_silhouette_is_one_closed_loop():
    sphere = closed(pv.Sphere(theta_resolution=40, phi_resolution=40))
    adjacency = edge_adjacency(sphere.triangles)
    for light in ([2.0, 1.0, 1.5, 1.0], [0.3, -1.0, 0.2, 0.0]):
        edges = silhouette_edges(sphere.points, sphere.triangles, adjacency, light)
        n = len(sphere.points)
        leaving = np.bincount(edges[:, 0], minlength=n)
        arriving = np.bincount(edges[:, 1], minlength=n)
        np.testing.assert_array_equal(leaving, arriving)
        assert np.all((leaving + arriving) % 2 == 0)
        assert set(leaving) <= {0, 1}  # a simple loop on a convex mesh
        successor = dict(edges.tolist())
        start = int(edges[0, 0])
        vertex, steps = successor[start], 1
        while vertex != start:
            vertex, steps = successor[vertex], steps + 1
        assert steps == len(edges)


@pytest.mark.parametrize("caster", ["torus", "ant"])
def test_volume_is_a_closed_consistently_wound_surface(caster, request):
    mesh = request.getfixturevalue(caster)
    adjacency = edge_adjacency(mesh.triangles)
    bounds = np.array([mesh.points.min(axis=0), mesh.points.max(axis=0)])
    for light in random_lights(np.random.default_rng(7), bounds, 4):
        volume = volume_geometry(mesh.points, mesh.triangles, adjacency, light)
        edges = silhouette_edges(mesh.points, mesh.triangles, adjacency, light)
        assert_closed_surface(all_triangles(volume), len(mesh.points), edges)
        assert len(volume.sides) == 2 * len(edges)
        assert len(volume.light_cap) + len(volume.dark_cap) == len(mesh.triangles)


def test_volume_layout_point_light(ball):
    light = np.array([0.3, 0.2, 2.0, 1.0])
    adjacency = edge_adjacency(ball.triangles)
    volume = volume_geometry(ball.points, ball.triangles, adjacency, light)
    n = len(ball.points)
    assert volume.positions.dtype == np.float32 and volume.positions.shape == (2 * n, 4)
    assert all(a.dtype == np.uint32 for a in (volume.sides, volume.light_cap, volume.dark_cap))
    np.testing.assert_array_equal(volume.positions[:n, 3], 1.0)
    np.testing.assert_array_equal(volume.positions[n:, 3], 0.0)
    np.testing.assert_allclose(volume.positions[n:, :3], ball.points - light[:3], rtol=1e-6)
    assert volume.light_cap.max() < n <= volume.dark_cap.min()
    lit = facing(ball.points, ball.triangles, light)
    np.testing.assert_array_equal(volume.light_cap, ball.triangles[lit])


def test_volume_layout_directional_light(ball):
    volume = volume_geometry(
        ball.points, ball.triangles, edge_adjacency(ball.triangles), [0.0, 0.0, -2.0, 0.0]
    )
    n = len(ball.points)
    np.testing.assert_array_equal(volume.positions[n:], np.tile([0.0, 0.0, -2.0, 0.0], (n, 1)))


@pytest.mark.parametrize("light", [[0.3, 0.2, 2.0, 1.0], [-0.2, 0.3, -1.0, 0.0]])
def test_volume_counts_one_exactly_in_the_shadow(ball, light):
    """Winding number of the volume (the stencil count) is 1 in the shadow, 0 elsewhere."""
    volume = volume_geometry(ball.points, ball.triangles, edge_adjacency(ball.triangles), light)
    vertices = finite(volume, stretch=1e3)
    triangles = all_triangles(volume)
    queries = np.random.default_rng(3).uniform([-1.5, -1.5, -2.0], [1.5, 1.5, 1.0], (300, 3))
    source, directional = np.asarray(light[:3], dtype=float), light[3] == 0
    towards = np.broadcast_to(-source, queries.shape) if directional else source - queries
    reach = np.inf if directional else 1.0
    along = np.einsum("ij,ij->i", -queries, towards) / np.einsum("ij,ij->i", towards, towards)
    closest = queries + np.clip(along, 0.0, reach)[:, None] * towards
    distance = np.linalg.norm(closest, axis=1)
    clear = (np.abs(distance - 0.5) > 0.02) & (np.abs(np.linalg.norm(queries, axis=1) - 0.5) > 0.02)
    count = winding_numbers(vertices, triangles, queries[clear])
    np.testing.assert_allclose(count, np.round(count), atol=1e-6)
    np.testing.assert_array_equal(np.round(count), distance[clear] < 0.5)
    assert 20 < np.count_nonzero(distance[clear] < 0.5) < np.count_nonzero(clear) - 20
    corners = vertices[triangles]
    six_volume = np.einsum("ij,ij->", corners[:, 0], np.cross(corners[:, 1], corners[:, 2]))
    assert six_volume > 0


def test_light_inside_the_caster_has_no_silhouette(ball):
    volume = volume_geometry(
        ball.points, ball.triangles, edge_adjacency(ball.triangles), [0, 0, 0, 1]
    )
    assert len(volume.sides) == len(volume.light_cap) == 0
    assert len(volume.dark_cap) == len(ball.triangles)


@pytest.mark.parametrize(
    ("scale", "offset"), [(1.0, 0.0), (1e-6, 0.0), (1e9, 0.0), (1.0, 1e6), (1e-6, 1e6)]
)
def test_topology_is_scale_and_offset_invariant(scale, offset):
    cube = pv.Cube(clean=False).triangulate()
    points = np.asarray(cube.points, dtype=np.float64) * scale + offset
    mesh = make_closed(points, cube.regular_faces)
    reference = make_closed(np.asarray(cube.points, dtype=np.float64), cube.regular_faces)
    np.testing.assert_array_equal(mesh.triangles, reference.triangles)
    adjacency = edge_adjacency(mesh.triangles)
    np.testing.assert_array_equal(adjacency.edges, edge_adjacency(reference.triangles).edges)
    np.testing.assert_array_equal(adjacency.faces, edge_adjacency(reference.triangles).faces)
    origin = mesh.points.mean(axis=0)
    local = mesh.points - origin
    light = [*(np.array([0.1, 0.2, 2.0]) * scale), 1.0]
    volume = volume_geometry(local, mesh.triangles, adjacency, light)
    expected = volume_geometry(
        reference.points - reference.points.mean(axis=0),
        reference.triangles,
        edge_adjacency(reference.triangles),
        [0.1, 0.2, 2.0, 1.0],
    )
    for name in ("sides", "light_cap", "dark_cap"):
        np.testing.assert_array_equal(getattr(volume, name), getattr(expected, name))
    atol = 1e-6 + 4 * np.spacing(offset + 1.0) / scale
    np.testing.assert_allclose(
        volume.positions[:, :3] / scale, expected.positions[:, :3], rtol=1e-6, atol=atol
    )
    np.testing.assert_array_equal(volume.positions[:, 3], expected.positions[:, 3])


@pytest.mark.parametrize(
    ("light", "match"),
    [
        ([0, 0, 1], "homogeneous"),
        ([0, 0, np.nan, 1], "homogeneous"),
        ([0, 0, 0, 0], "non-zero direction"),
    ],
)
def test_bad_light_raises(light, match):
    with pytest.raises(ValueError, match=match):
        facing(CUBE_POINTS, CUBE_TRIANGLES, light)


def test_non_finite_points_raise():
    points = CUBE_POINTS.copy()
    points[3, 1] = np.inf
    with pytest.raises(ValueError, match="non-finite"):
        facing(points, CUBE_TRIANGLES, [0, 0, 2, 1])


def test_homogeneous_point_light_is_normalised():
    adjacency = edge_adjacency(CUBE_TRIANGLES)
    a = volume_geometry(CUBE_POINTS, CUBE_TRIANGLES, adjacency, [0.5, 0.5, 2.0, 1.0])
    b = volume_geometry(CUBE_POINTS, CUBE_TRIANGLES, adjacency, [1.0, 1.0, 4.0, 2.0])
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.sides, b.sides)


def test_time_silhouette_reports_medians():
    timing = time_silhouette(3000, repeats=2)
    assert 2500 < timing["n_triangles"] < 3500
    assert timing["n_silhouette_edges"] > 0
    for key in ("make_closed_s", "edge_adjacency_s", "silhouette_point_s", "volume_point_s"):
        assert 0 < timing[key] < 5
