"""Reading an actor's triangles: bounds and flatness taken without extra passes, still exact."""

import numpy as np
import pyvista as pv

from pvshadows.scene.triangles import _PLANE_PROBES, read_triangles


def test_model_bounds_are_the_data_bounds_far_from_the_origin():
    pl = pv.Plotter(off_screen=True)
    mesh = pv.Sphere(center=(1e6, -3e5, 7.0))
    read = read_triangles(pl.add_mesh(mesh))
    expected = np.array(mesh.bounds).reshape(3, 2).T
    assert np.array_equal(read.model_bounds(), expected)
    assert np.array_equal(read.center, expected.mean(axis=0))
    lo, hi = read.points.min(0), read.points.max(0)
    assert np.allclose(lo, expected[0] - read.center, rtol=0, atol=1e-9)
    assert np.allclose(hi, expected[1] - read.center, rtol=0, atol=1e-9)


def test_model_bounds_leave_out_points_no_triangle_uses():
    mesh = pv.Cube()
    far = np.vstack([mesh.points, [[50.0, 50.0, 50.0]]])
    mesh = pv.PolyData(far, mesh.faces)
    pl = pv.Plotter(off_screen=True)
    read = read_triangles(pl.add_mesh(mesh))
    assert read.points.shape[0] == 8
    assert read.model_bounds().tolist() == [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]


def test_a_sheet_is_flat_until_one_point_between_the_probes_leaves_it():
    grid = pv.Plane(i_resolution=99, j_resolution=99).triangulate()
    pl = pv.Plotter(off_screen=True)
    assert read_triangles(pl.add_mesh(grid)).model_plane() is not None
    step = grid.n_points // _PLANE_PROBES
    lifted = grid.copy()
    points = lifted.points.copy()
    points[step + 1, 2] = 1e-3  # not one of the evenly spaced points tested first
    lifted.points = points
    assert read_triangles(pl.add_mesh(lifted)).model_plane() is None
    assert read_triangles(pl.add_mesh(pv.Sphere())).model_plane() is None
