"""Casters made ready for shadow volumes, and the z-pass/z-fail decision, on the CPU."""

import numpy as np
import pytest
import pyvista as pv

from pvshadows.geometry.boxes import CasterBoxes
from pvshadows.geometry.closed import OpenMeshError, edge_defects
from pvshadows.geometry.silhouette import volume_geometry
from pvshadows.geometry.volume_casters import batches, prepare_volume_mesh, winding_number
from pvshadows.pipeline.volume_zmode import (
    choose_zmode,
    hull_touches_box,
    light_region,
    near_region,
    zpass_clearance,
)
from pvshadows.scene.view import FrameView


def faces(mesh):
    mesh = mesh.triangulate()
    return mesh.points, mesh.regular_faces


def signed_crossings(mesh, light, point):
    """Winding number of the volume's closed surface around ``point``, by its solid angle."""
    volume = volume_geometry(mesh.points, mesh.triangles, mesh.adjacency, light)
    positions = volume.positions.astype(np.float64)
    # Put the points at infinity far away: 1e6 times the scene size is enough here.
    finite = positions[:, 3:] != 0
    coords = np.where(finite, positions[:, :3], positions[:, :3] * 1e6)
    triangles = np.concatenate([volume.sides, volume.light_cap, volume.dark_cap])
    return winding_number(coords, triangles, np.asarray(point, float))


def test_a_flat_sheet_becomes_a_closed_two_sided_slab():
    points, triangles = faces(pv.Plane(i_resolution=4, j_resolution=3))
    triangles[::2] = triangles[::2, ::-1]  # winding need not agree on a sheet
    mesh = prepare_volume_mesh(points, triangles, "ground")
    assert mesh.how == "two-sided sheet"
    assert edge_defects(mesh.triangles).is_closed
    assert mesh.n_bodies == 1
    light = [0.1, 0.2, 2.0, 1.0]
    # A point under the sheet is inside the volume exactly once; above it, outside.
    assert round(signed_crossings(mesh, light, (0.05, 0.05, -1.0))) == 1
    assert round(signed_crossings(mesh, light, (0.05, 0.05, 1.0))) == 0
    assert round(signed_crossings(mesh, [0.1, 0.2, -2.0, 1.0], (0.05, 0.05, 1.0))) == 1


def test_open_meshes_that_are_not_flat_sheets_raise():
    bowl = pv.Sphere().clip(normal="z")
    with pytest.raises(OpenMeshError, match=r"'bowl' cannot be made closed: .*boundary edges"):
        prepare_volume_mesh(*faces(bowl), "bowl")
    pinched = pv.merge([pv.Plane(center=(0.5, 0.5, 0)), pv.Plane(center=(-0.5, -0.5, 0))])
    with pytest.raises(OpenMeshError):  # two squares touching at one corner
        prepare_volume_mesh(*faces(pinched.clean()), "pinched")
    with pytest.raises(OpenMeshError, match="no triangles"):
        prepare_volume_mesh(np.zeros((2, 3)), np.zeros((0, 3), int), "lines")


def test_bodies_sorted_and_batched():
    spheres = pv.merge([pv.Sphere(center=(3 * k, 0, 0), radius=1) for k in range(5)])
    mesh = prepare_volume_mesh(*faces(spheres), "spheres")
    assert mesh.n_bodies == 5
    body_of_triangle = mesh.point_body[mesh.triangles[:, 0]]
    assert np.all(np.diff(body_of_triangle) >= 0)
    assert np.all(mesh.point_body[mesh.triangles] == body_of_triangle[:, None])
    assert mesh.adjacency_rows.shape == (len(mesh.triangles), 6)
    assert batches([300, 1, 254], limit=255) == [
        [(0, 0, 255)],
        [(0, 255, 300), (1, 0, 1), (2, 0, 209)],
        [(2, 209, 254)],
    ]
    assert all(sum(e - s for _, s, e in b) <= 255 for b in batches([200] * 7))


def test_winding_number_tells_inside_from_outside():
    points, triangles = faces(pv.Cylinder(resolution=24))
    mesh = prepare_volume_mesh(points, triangles, "cylinder")
    assert winding_number(mesh.points, mesh.triangles, np.zeros(3)) == pytest.approx(1.0)
    assert winding_number(mesh.points, mesh.triangles, np.array([0, 3.0, 0])) == pytest.approx(0.0)


def test_hull_box_test_agrees_with_sampling():
    rng = np.random.default_rng(5)
    box = np.array([[-1.0, -1, -1], [1, 1, 1]])
    for _ in range(200):
        points = rng.uniform(-3, 3, (5, 3))
        touches = hull_touches_box(points, box)
        # Random convex combinations inside the box prove contact.
        weights = rng.dirichlet(np.ones(5), 4000)
        inside = np.all(np.abs(weights @ points) <= 1.0, axis=1).any()
        if inside:
            assert touches
        if not touches:
            assert not inside


def test_directional_light_region_reaches_past_the_box():
    region = np.array([[0.0, 0, 5], [0.1, 0, 5], [0, 0.1, 5]])
    box = np.array([[-1.0, -1, 0], [1, 1, 1]])
    # Light from below the box's far side: the sweep towards it crosses the box.
    swept = light_region(np.array([0, 0, -1.0, 0]), region, box)
    assert hull_touches_box(swept, box)
    swept = light_region(np.array([0, 0, 1.0, 0]), region, box)
    assert not hull_touches_box(swept, box)


@pytest.mark.parametrize("light", [(0.5, -0.3, 6.0, 1.0), (0.4, 0.2, 1.0, 0.0)])
def test_the_zmode_of_many_casters_is_the_first_whose_hull_test_meets_it(light):
    # choose_zmode tests every box at once before testing one by one: the answer and
    # the caster it names must be those of testing each caster in turn.
    light = np.array(light)
    pl = pv.Plotter(off_screen=True, window_size=(200, 150))
    pl.add_mesh(pv.Sphere())
    rng = np.random.default_rng(3)
    named = 0
    for trial in range(40):
        pl.camera_position = [tuple(rng.uniform(-4, 4, 3)), (0, 0, 0), (0, 0, 1)]
        casters = []
        for i in range(int(rng.integers(2, 7))):
            low = rng.uniform(-4, 3, 3)
            casters.append((f"box {i}", np.array([low, low + rng.uniform(0.2, 2.0, 3)])))
        region = near_region(pl.renderer)
        touched = [
            n for n, box in casters if hull_touches_box(light_region(light, region, box), box)
        ]
        expected = touched[0] if touched else None
        zmode, why = choose_zmode("auto", light, pl.renderer, casters, FrameView.of(pl.renderer))
        assert zmode == ("zpass" if expected is None else "zfail"), trial
        if expected is not None:
            assert f"shadow volume of {expected} " in why
            named += 1
    assert 5 <= named <= 35  # both answers were tested


@pytest.mark.parametrize("seed", range(3))
def test_within_its_zpass_clearance_the_near_region_meets_no_caster(seed):
    # A kept z-pass holds while every point of the near region moves less than the
    # clearance: then the full test must find every box apart from the light's region.
    rng = np.random.default_rng(seed)
    kept = 0
    for _ in range(60):
        light = np.append(rng.uniform(-3, 3, 3), 1.0)
        lows = rng.uniform(-4, 3, (int(rng.integers(1, 5)), 3))
        casters = [
            (f"box {i}", np.array([low, low + rng.uniform(0.2, 2, 3)]))
            for i, low in enumerate(lows)
        ]
        region = rng.uniform(-6, 6, 3) + rng.uniform(-0.3, 0.3, (5, 3))
        room = zpass_clearance(light, region, CasterBoxes.of(casters))
        touching = any(hull_touches_box(light_region(light, region, b), b) for _, b in casters)
        assert not (touching and room > 0)
        if room == 0.0:
            continue
        kept += 1
        for _ in range(5):
            moved = region + rng.uniform(-1, 1, (5, 3)) * 0.999 * room
            assert not any(hull_touches_box(light_region(light, moved, b), b) for _, b in casters)
    assert kept >= 5
    box = CasterBoxes.of([("box", np.array([[-1.0, -1, 0], [1, 1, 2]]))])
    far = np.full((5, 3), 9.0)
    assert zpass_clearance(np.array([0, 0, 1.0, 0]), far, box) == 0.0  # directional: never
    assert zpass_clearance(np.array([9, 9, 9, 1.0]), None, box) == 0.0  # parallel projection
    assert zpass_clearance(np.array([9, 9, 9, 1.0]), far, CasterBoxes.of([])) == np.inf
