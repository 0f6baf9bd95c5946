"""Tests for pvshadows.geometry.closed: welding, checking and repairing casters."""

import numpy as np
import pytest
import pyvista as pv
from pyvista import examples

from pvshadows.geometry.closed import ClosedMesh, OpenMeshError, edge_defects, make_closed, weld


def surface(mesh: pv.PolyData) -> tuple[np.ndarray, np.ndarray]:
    """Float64 points and triangles of a PyVista surface."""
    mesh = mesh.triangulate()
    return np.asarray(mesh.points, dtype=np.float64), mesh.regular_faces


def signed_volume(points: np.ndarray, triangles: np.ndarray) -> float:
    corners = points[triangles]
    return float(np.einsum("ij,ij->", corners[:, 0], np.cross(corners[:, 1], corners[:, 2])) / 6)


def assert_closed(mesh: ClosedMesh) -> None:
    """Every directed edge once, its reverse once, outward, no degenerate or repeated face."""
    triangles = mesh.triangles
    directed = triangles[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    assert len(np.unique(directed, axis=0)) == len(directed)
    reverse = {tuple(edge) for edge in directed[:, ::-1].tolist()}
    assert reverse == {tuple(edge) for edge in directed.tolist()}
    corners = np.sort(triangles, axis=1)
    assert np.all((corners[:, 0] < corners[:, 1]) & (corners[:, 1] < corners[:, 2]))
    assert len(np.unique(corners, axis=0)) == len(corners)
    assert signed_volume(mesh.points, triangles) > 0
    assert mesh.points.dtype == np.float64 and triangles.dtype == np.int64


@pytest.fixture(scope="module")
def sphere() -> tuple[np.ndarray, np.ndarray]:
    return surface(pv.Sphere())


def test_sphere_and_cube_are_closed_after_welding(sphere):
    mesh = make_closed(*sphere, name="sphere")
    assert_closed(mesh)
    assert not mesh.repaired
    cube = make_closed(*surface(pv.Cube(clean=False)), name="cube")
    assert_closed(cube)
    assert (len(cube.points), len(cube.triangles), cube.repaired) == (8, 12, False)
    assert signed_volume(cube.points, cube.triangles) == pytest.approx(1.0)


def test_triangle_soup_welds_closed_despite_noise(sphere):
    points, triangles = sphere
    soup = points[triangles].reshape(-1, 3)
    noise = np.random.default_rng(0).uniform(-1e-12, 1e-12, soup.shape)
    mesh = make_closed(soup + noise, np.arange(soup.shape[0]).reshape(-1, 3))
    assert_closed(mesh)
    assert len(mesh.points) == len(points)
    assert not mesh.repaired


@pytest.mark.parametrize(
    ("scale", "offset"), [(1e-6, 0.0), (1e9, 0.0), (1.0, 1e6), (1e-6, 1e6), (1e-3, 1e9)]
)
def test_weld_is_scale_and_offset_invariant(scale, offset):
    cube = pv.Cube(clean=False).triangulate()
    points = np.asarray(cube.points, dtype=np.float64)
    reference_points, reference = weld(points, cube.regular_faces)
    welded_points, welded = weld(points * scale + offset, cube.regular_faces)
    np.testing.assert_array_equal(welded, reference)
    np.testing.assert_allclose(welded_points, reference_points * scale + offset, rtol=1e-15)
    assert make_closed(points * scale + offset, cube.regular_faces).triangles.tolist() == (
        make_closed(points, cube.regular_faces).triangles.tolist()
    )


def test_weld_keeps_fine_detail():
    fine = pv.Sphere(theta_resolution=200, phi_resolution=200)
    points, triangles = surface(fine)
    welded_points, welded = weld(points * 1e-6, triangles)
    assert len(welded_points) == fine.n_points
    assert len(welded) == len(triangles)


def test_weld_explicit_tolerance_merges_a_crack():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1e-4, 1e-4, 0]], dtype=float)
    triangles = [[0, 1, 2], [3, 2, 1]]
    assert len(weld(points, triangles)[0]) == 4
    welded_points, welded = weld(points, triangles, tolerance=1e-3)
    assert len(welded_points) == 3
    assert len(welded) == 1


def test_one_missing_triangle_is_filled(sphere):
    points, triangles = sphere
    mesh = make_closed(points, np.delete(triangles, 100, axis=0), name="holey")
    assert_closed(mesh)
    assert mesh.repaired
    assert len(mesh.triangles) == len(triangles)


def test_quad_hole_is_filled(sphere):
    points, triangles = sphere
    adjacent = [100, 101]
    assert len(set(triangles[100]) & set(triangles[101])) == 2
    mesh = make_closed(points, np.delete(triangles, adjacent, axis=0))
    assert_closed(mesh)
    assert mesh.repaired


def test_big_cut_raises():
    """A sphere clipped at z = 0.3 has a 60-edge hole: it is never capped, it raises."""
    bowl = pv.Sphere().clip(normal="z", value=0.3)
    with pytest.raises(OpenMeshError, match=r"'bowl'.*60 boundary edges"):
        make_closed(*surface(bowl), name="bowl")


def test_ant_is_closed():
    ant = examples.load_ant()
    mesh = make_closed(*surface(ant), name="ant")
    assert_closed(mesh)
    assert not mesh.repaired


def test_airplane_is_open_and_raises():
    """The airplane has 223 boundary edges and one edge with 3 faces: it raises."""
    airplane = examples.load_airplane()
    with pytest.raises(OpenMeshError) as info:
        make_closed(*surface(airplane), name="airplane")
    message = str(info.value)
    assert "'airplane'" in message
    assert "223 boundary edges" in message
    assert "non-manifold edge shared by 3 faces" in message


def test_flipped_faces_are_rewound(sphere):
    points, triangles = sphere
    flipped = triangles.copy()
    chosen = np.random.default_rng(1).choice(len(triangles), 300, replace=False)
    flipped[chosen] = flipped[chosen, ::-1]
    assert edge_defects(flipped).inconsistent > 0
    mesh = make_closed(points, flipped)
    assert_closed(mesh)
    assert mesh.repaired
    assert signed_volume(mesh.points, mesh.triangles) == pytest.approx(
        signed_volume(points, triangles)
    )


def test_inside_out_bodies_are_flipped_one_by_one(sphere):
    points, triangles = sphere
    two = np.vstack([points, points + 3.0])
    mesh = make_closed(two, np.vstack([triangles, triangles[:, ::-1] + len(points)]))
    assert_closed(mesh)
    assert mesh.repaired
    bodies = np.split(mesh.triangles, [len(triangles)])
    assert all(signed_volume(mesh.points, body) > 0 for body in bodies)


def test_inside_out_vtk_ellipsoid_is_flipped():
    mesh = make_closed(*surface(pv.ParametricEllipsoid()))
    assert_closed(mesh)
    assert mesh.repaired


def test_zero_area_and_duplicate_faces_are_dropped(sphere):
    points, triangles = sphere
    extra_points = np.vstack([points, points[:1]])
    degenerate = [[0, 0, 1], [5, 6, 5], [0, len(points), 1]]
    duplicates = np.vstack([triangles[:5], np.roll(triangles[5:10], 1, axis=1)])
    mesh = make_closed(extra_points, np.vstack([triangles, degenerate, duplicates]))
    assert_closed(mesh)
    assert not mesh.repaired
    assert len(mesh.triangles) == len(triangles)
    assert len(mesh.points) == len(points)


def test_pinched_edge_is_split_by_manifold3d():
    """Two cubes sharing one edge: manifold3d duplicates the edge's points."""
    cube = pv.Cube(clean=False).triangulate()
    points = np.asarray(cube.points, dtype=np.float64)
    both = np.vstack([points, points + np.array([1.0, 1.0, 0.0])])
    triangles = np.vstack([cube.regular_faces, cube.regular_faces + len(points)])
    assert edge_defects(weld(both, triangles)[1]).non_manifold == 1
    mesh = make_closed(both, triangles, name="pinched")
    assert_closed(mesh)
    assert mesh.repaired
    assert (len(mesh.points), len(mesh.triangles)) == (16, 24)
    assert signed_volume(mesh.points, mesh.triangles) == pytest.approx(2.0)


def test_non_orientable_surface_raises():
    with pytest.raises(OpenMeshError, match=r"'boy'.*not orientable"):
        make_closed(*surface(pv.ParametricBoy()), name="boy")


@pytest.mark.parametrize(
    "mesh",
    [pv.Line(), pv.PolyData(np.random.default_rng(2).random((5, 3)))],
    ids=["line", "points"],
)
def test_no_triangles_raises(mesh):
    with pytest.raises(OpenMeshError, match="'wire' cannot be made closed: it has no triangles"):
        make_closed(mesh.points, mesh.regular_faces, name="wire")


def test_only_degenerate_triangles_raise():
    with pytest.raises(OpenMeshError, match="zero area"):
        make_closed(np.zeros((3, 3)), [[0, 1, 2]], name="dot")


def test_single_triangle_is_not_closed_into_a_double_sided_sheet():
    with pytest.raises(OpenMeshError, match="3 boundary edges"):
        make_closed(np.eye(3), [[0, 1, 2]])


@pytest.mark.parametrize(
    ("points", "triangles", "match"),
    [
        (np.full((3, 3), np.nan), [[0, 1, 2]], "non-finite"),
        (np.eye(3)[:, :2], [[0, 1, 2]], r"points must have shape \(n, 3\)"),
        (np.eye(3), [[0, 1, 3]], "triangles index points 0..2"),
        (np.eye(3), [[0.0, 1.0, 2.0]], "integer"),
        (np.eye(3), [[0, 1, 2, 0]], r"triangles must have shape \(m, 3\)"),
    ],
)
def test_bad_input_raises_value_error(points, triangles, match):
    with pytest.raises(ValueError, match=match):
        make_closed(points, triangles)


def test_bad_tolerance_raises():
    with pytest.raises(ValueError, match="tolerance"):
        weld(np.eye(3), [[0, 1, 2]], tolerance=-1.0)


def test_result_is_read_only(sphere):
    mesh = make_closed(*sphere)
    with pytest.raises(ValueError, match="read-only"):
        mesh.points[0, 0] = 1.0
