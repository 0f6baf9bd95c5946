"""Tests of the ray-traced reference against shadows computed by hand."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
import pyvista as pv
import trimesh
import vtk

from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.verify.reference import SceneMesh, ViewSpec, trace_reference

WIDTH, HEIGHT = 160, 120
DOWN = np.array([0.0, 0.0, -1.0])


def camera_view(
    position,
    focal_point=(0.0, 0.0, 0.0),
    *,
    up=(0.0, 0.0, 1.0),
    clipping=(1.0, 60.0),
    parallel_scale=None,
    width=WIDTH,
    height=HEIGHT,
) -> ViewSpec:
    camera = vtk.vtkCamera()
    camera.SetPosition(*position)
    camera.SetFocalPoint(*focal_point)
    camera.SetViewUp(*up)
    camera.SetViewAngle(30.0)
    camera.SetClippingRange(*clipping)
    if parallel_scale is not None:
        camera.SetParallelProjection(True)
        camera.SetParallelScale(parallel_scale)
    matrix = camera.GetCompositeProjectionTransformMatrix(width / height, -1, 1)
    return ViewSpec(pv.array_from_vtkmatrix(matrix), width, height)


def rectangle(x0, x1, y0, y1, z, **flags) -> SceneMesh:
    points = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], dtype=float)
    return SceneMesh(points, np.array([[0, 1, 2], [0, 2, 3]]), **flags)


def ground(half=20.0) -> SceneMesh:
    return rectangle(-half, half, -half, half, 0.0)


def sphere(center, radius, subdivisions=4) -> SceneMesh:
    mesh = trimesh.creation.icosphere(subdivisions=subdivisions, radius=radius)
    return SceneMesh(mesh.vertices + np.asarray(center), mesh.faces)


def point_light(position) -> LightPose:
    return LightPose(LightKind.POINT, np.asarray(position, dtype=float), DOWN, 180.0)


def directional_light(direction) -> LightPose:
    direction = np.asarray(direction, dtype=float)
    return LightPose(LightKind.DIRECTIONAL, np.zeros(3), direction / np.linalg.norm(direction), 90)


def hit_points(view: ViewSpec, depth: np.ndarray) -> np.ndarray:
    """World positions of what each pixel centre sees, recomputed from the NDC depth."""
    x = 2.0 * (np.arange(view.width) + 0.5) / view.width - 1.0
    y = 1.0 - 2.0 * (np.arange(view.height) + 0.5) / view.height
    ndc_x, ndc_y = np.meshgrid(x, y)
    ndc = np.stack([ndc_x, ndc_y, depth, np.ones_like(depth)], axis=-1)
    world = ndc @ np.linalg.inv(view.world_to_ndc).T
    return world[..., :3] / world[..., 3:]


def disk_fraction(offset):
    """Fraction of a unit disk on the far side of a line at ``offset`` from its centre."""
    c = np.clip(offset, -1.0, 1.0)
    return (np.arccos(c) - c * np.sqrt(1.0 - c * c)) / np.pi


def assert_classes(visibility, shadowed, lit):
    assert shadowed.sum() > 50 and lit.sum() > 50
    np.testing.assert_array_equal(visibility[shadowed], 0.0)
    np.testing.assert_array_equal(visibility[lit], 1.0)


@pytest.mark.parametrize("parallel_scale", [None, 3.5], ids=["perspective", "parallel"])
def test_square_blocker_under_point_light(parallel_scale):
    view = camera_view((5.0, -7.0, 8.0), parallel_scale=parallel_scale)
    meshes = [ground(), rectangle(-0.5, 0.5, -0.5, 0.5, 1.0)]
    result = trace_reference(meshes, view, point_light((0.0, 0.0, 3.0)))
    on_ground = result.mesh_index == 0
    points = hit_points(view, result.depth)
    np.testing.assert_allclose(points[on_ground, 2], 0.0, atol=1e-9)
    extent = np.abs(points[..., :2]).max(axis=-1)
    margin = 1e-3
    assert_classes(
        result.visibility,
        on_ground & (extent < 0.75 - margin),
        on_ground & (extent > 0.75 + margin),
    )
    on_blocker = result.mesh_index == 1
    assert on_blocker.any()
    np.testing.assert_array_equal(result.visibility[on_blocker], 1.0)
    np.testing.assert_array_equal(result.surface, np.isfinite(result.visibility))


def test_sphere_casts_tangent_cone_disk():
    radius, center_height, light_height = 0.5, 1.5, 4.0
    view = camera_view((4.0, -6.0, 7.0))
    meshes = [ground(), sphere((0.0, 0.0, center_height), radius)]
    result = trace_reference(meshes, view, point_light((0.0, 0.0, light_height)))
    sine = radius / (light_height - center_height)
    shadow_radius = light_height * sine / math.sqrt(1.0 - sine**2)
    points = hit_points(view, result.depth)
    distance = np.hypot(points[..., 0], points[..., 1])
    on_ground = result.mesh_index == 0
    assert_classes(
        result.visibility,
        on_ground & (distance < 0.97 * shadow_radius),
        on_ground & (distance > 1.03 * shadow_radius),
    )
    on_sphere = result.mesh_index == 1
    assert (on_sphere & ~result.lit_side).any()
    np.testing.assert_array_equal(result.visibility[on_sphere], result.lit_side[on_sphere])


@pytest.mark.parametrize("height", [1.0, 2.5])
def test_directional_light_at_45_degrees_shifts_shadow_by_height(height):
    view = camera_view((7.0, -6.0, 7.0), clipping=(1.0, 60.0))
    meshes = [ground(), rectangle(-0.5, 0.5, -0.5, 0.5, height)]
    result = trace_reference(meshes, view, directional_light((1.0, 0.0, -1.0)))
    points = hit_points(view, result.depth)
    on_ground = result.mesh_index == 0
    extent = np.maximum(np.abs(points[..., 0] - height), np.abs(points[..., 1]))
    margin = 1e-3
    assert_classes(
        result.visibility,
        on_ground & (extent < 0.5 - margin),
        on_ground & (extent > 0.5 + margin),
    )


def test_spot_light_lights_only_inside_its_cone():
    view = camera_view((0.0, -8.0, 9.0))
    cone = 20.0
    spot = LightPose(LightKind.SPOT, np.array([0.0, 0.0, 3.0]), DOWN, cone)
    result = trace_reference([ground()], view, spot)
    points = hit_points(view, result.depth)
    distance = np.hypot(points[..., 0], points[..., 1])
    edge = 3.0 * math.tan(math.radians(cone))
    inside, outside = distance < edge - 1e-3, distance > edge + 1e-3
    assert inside.sum() > 50 and outside.sum() > 50
    assert result.surface.all()
    assert result.lit_side[inside].all() and not result.lit_side[outside].any()
    assert_classes(result.visibility, outside, inside)


def test_surface_seen_from_below_is_not_lit_side():
    light = point_light((0.0, 0.0, 3.0))
    below = trace_reference([ground()], camera_view((0.0, -6.0, -7.0)), light)
    assert below.surface.all()
    assert not below.lit_side.any()
    np.testing.assert_array_equal(below.visibility, 0.0)
    flipped = SceneMesh(ground().points, ground().triangles[:, ::-1])
    above = trace_reference([flipped], camera_view((0.0, -6.0, 7.0)), light)
    assert above.lit_side.all()
    np.testing.assert_array_equal(above.visibility, 1.0)


def test_non_receiver_in_front_gives_nan_pixels():
    view = camera_view((0.0, 0.0, 10.0), up=(0.0, 1.0, 0.0))
    card = rectangle(-0.5, 0.5, -0.5, 0.5, 2.0, receiver=False)
    result = trace_reference([ground(), card], view, point_light((0.0, 0.0, 3.0)))
    on_card = result.mesh_index == 1
    assert on_card.sum() > 50
    assert np.isnan(result.visibility[on_card]).all()
    assert not result.surface[on_card].any() and not result.lit_side[on_card].any()
    assert np.isfinite(result.depth[on_card]).all()
    assert result.surface[~on_card].all()
    np.testing.assert_array_equal(np.isnan(result.visibility), on_card)


def test_faces_not_drawn_are_seen_through_and_still_cast():
    view = camera_view((0.0, 0.0, 10.0), up=(0.0, 1.0, 0.0))
    frame = rectangle(-0.5, 0.5, -0.5, 0.5, 2.0)
    frame = SceneMesh(frame.points, frame.triangles, faces_seen=False)
    result = trace_reference([ground(), frame], view, point_light((0.0, 0.0, 3.0)))
    assert (result.mesh_index == 0).all()  # the ground shows where the card's faces are
    solid = trace_reference(
        [ground(), rectangle(-0.5, 0.5, -0.5, 0.5, 2.0)], view, point_light((0.0, 0.0, 3.0))
    )
    behind = solid.mesh_index == 1
    # under the card, seen straight down through it: the card's shadow (1.5 wide), all dark
    assert behind.sum() > 50
    np.testing.assert_array_equal(result.visibility[behind], 0.0)
    lit = result.visibility == 1.0
    assert lit.sum() + (result.visibility == 0.0).sum() == lit.size


def test_non_caster_casts_no_shadow():
    view = camera_view((5.0, -7.0, 8.0))
    card = rectangle(-0.5, 0.5, -0.5, 0.5, 1.0, caster=False)
    result = trace_reference([ground(), card], view, point_light((0.0, 0.0, 3.0)))
    assert (result.mesh_index == 1).any()
    np.testing.assert_array_equal(result.visibility, 1.0)


def test_point_light_penumbra_matches_disk_segments():
    light_radius = 0.3
    view = camera_view((6.0, 0.0, 4.0), (0.0, 0.0, 0.0), width=128, height=97)
    meshes = [ground(), rectangle(-5.0, 0.0, -5.0, 5.0, 1.0)]
    result = trace_reference(
        meshes, view, point_light((0.0, 0.0, 3.0)), light_size=light_radius, samples=128
    )
    points = hit_points(view, result.depth)
    near_axis = (result.mesh_index == 0) & (np.abs(points[..., 1]) < 0.3)
    x = points[near_axis, 0]
    visibility = result.visibility[near_axis]
    # Seen from a ground point at x, the blocker's edge crosses the light's plane at -2x.
    expected = disk_fraction(-2.0 * x / light_radius)
    assert (np.abs(x) < 0.02).sum() >= 3
    np.testing.assert_allclose(visibility, expected, atol=0.04)
    np.testing.assert_array_equal(visibility[x < -0.16], 0.0)
    np.testing.assert_array_equal(visibility[x > 0.16], 1.0)
    order = np.argsort(x)
    bins = np.array_split(visibility[order][(np.abs(x[order]) < 0.2)], 8)
    means = np.array([b.mean() for b in bins])
    assert (np.diff(means) > -0.02).all()


def test_sun_penumbra_at_edge_is_half():
    angle = 10.0
    view = camera_view((6.0, 0.0, 4.0), (0.0, 0.0, 0.0), width=128, height=97)
    meshes = [ground(), rectangle(-5.0, 0.0, -5.0, 5.0, 1.0)]
    result = trace_reference(meshes, view, directional_light(DOWN), light_size=angle, samples=128)
    points = hit_points(view, result.depth)
    on_ground = result.mesh_index == 0
    x = points[on_ground, 0]
    visibility = result.visibility[on_ground]
    half_width = math.tan(math.radians(angle))
    np.testing.assert_allclose(visibility, disk_fraction(-x / half_width), atol=0.05)
    at_edge = np.abs(x) < 0.01
    assert at_edge.sum() >= 3
    np.testing.assert_allclose(visibility[at_edge], 0.5, atol=0.1)


def test_sun_below_the_horizon_is_blocked():
    radius, elevation = 10.0, 5.0
    sun = directional_light((1.0, 0.0, -math.tan(math.radians(elevation))))
    view = camera_view((0.0, -6.0, 7.0))
    result = trace_reference([ground()], view, sun, light_size=radius, samples=256)
    assert result.lit_side.all()
    # Directions uniform over the cap; the tangent plane cuts it at elevation/radius.
    expected = cap_fraction_above(math.radians(radius), math.radians(elevation))
    assert abs(result.visibility.mean() - expected) < 0.01
    assert result.visibility.max() < 1.0


def cap_fraction_above(radius, elevation, n=400_000):
    """Fraction of a cap of angular ``radius`` above a plane ``elevation`` below its axis."""
    rng = np.random.default_rng(1)
    cos_theta = 1.0 - rng.random(n) * (1.0 - math.cos(radius))
    theta, phi = np.arccos(cos_theta), rng.random(n) * 2.0 * math.pi
    # Height above the plane of a direction at (theta, phi) around an axis at ``elevation``.
    height = cos_theta * math.sin(elevation) + np.sin(theta) * np.cos(phi) * math.cos(elevation)
    return float(np.mean(height > 0.0))


def test_tiny_light_matches_hard_shadows_and_seed_is_deterministic():
    view = camera_view((5.0, -7.0, 8.0))
    meshes = [ground(), sphere((0.0, 0.0, 1.5), 0.5, subdivisions=3)]
    light = point_light((0.5, 0.0, 4.0))
    hard = trace_reference(meshes, view, light)
    explicit = trace_reference(meshes, view, light, light_size=0.0, samples=1, seed=7)
    np.testing.assert_array_equal(hard.visibility, explicit.visibility)
    tiny = trace_reference(meshes, view, light, light_size=1e-9, samples=16)
    assert np.mean(tiny.visibility != hard.visibility) <= 5e-4
    soft = trace_reference(meshes, view, light, light_size=0.2, samples=16, seed=3)
    again = trace_reference(meshes, view, light, light_size=0.2, samples=16, seed=3)
    other = trace_reference(meshes, view, light, light_size=0.2, samples=16, seed=4)
    np.testing.assert_array_equal(soft.visibility, again.visibility)
    penumbra = (soft.visibility > 0) & (soft.visibility < 1)
    assert (soft.visibility != other.visibility)[penumbra].any()
    np.testing.assert_array_equal(soft.lit_side, hard.lit_side)


def test_grazing_light_leaves_no_acne():
    view = camera_view((0.0, -8.0, 9.0))
    meshes = [ground(), sphere((0.0, 0.0, 1.0), 0.5, subdivisions=3)]
    sun = directional_light((1.0, 0.3, -math.tan(math.radians(0.5))))
    result = trace_reference(meshes, view, sun)
    on_ground = result.mesh_index == 0
    points = hit_points(view, result.depth)
    away = on_ground & (points[..., 0] < -1.0)
    assert away.sum() > 1000
    np.testing.assert_array_equal(result.visibility[away], 1.0)
    on_sphere = result.mesh_index == 1
    np.testing.assert_array_equal(result.visibility[on_sphere], result.lit_side[on_sphere])


def brute_force_first_hit(origins, directions, corners, limit):
    """Nearest triangle hit by each ray before ``limit``, by Moller-Trumbore over all pairs."""
    v0 = corners[:, 0]
    e1, e2 = corners[:, 1] - v0, corners[:, 2] - v0
    p = np.cross(directions[:, None], e2)
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse = 1.0 / np.sum(e1 * p, axis=-1)
        s = origins[:, None] - v0
        u = np.sum(s * p, axis=-1) * inverse
        q = np.cross(s, e1)
        v = np.sum(directions[:, None] * q, axis=-1) * inverse
        t = np.sum(e2 * q, axis=-1) * inverse
    valid = (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & (t < limit[:, None])
    t = np.where(valid, t, np.inf)
    nearest = np.argmin(t, axis=1)
    distance = t[np.arange(t.shape[0]), nearest]
    return np.where(np.isfinite(distance), nearest, -1), distance


def brute_force_hard_shadows(meshes, view, light_position, epsilon):
    """Mesh index and hard point-light visibility of every pixel, in plain float64 numpy."""
    corners = np.concatenate([m.points[m.triangles] for m in meshes])
    owner = np.concatenate([np.full(m.triangles.shape[0], i) for i, m in enumerate(meshes)])
    x = 2.0 * (np.arange(view.width) + 0.5) / view.width - 1.0
    y = 1.0 - 2.0 * (np.arange(view.height) + 0.5) / view.height
    ndc_x, ndc_y = (a.ravel() for a in np.meshgrid(x, y))
    inverse = np.linalg.inv(view.world_to_ndc)
    ends = [
        np.stack([ndc_x, ndc_y, np.full_like(ndc_x, z), np.ones_like(ndc_x)], -1) @ inverse.T
        for z in (-1.0, 1.0)
    ]
    near, far = (e[:, :3] / e[:, 3:] for e in ends)
    length = np.linalg.norm(far - near, axis=1)
    direction = (far - near) / length[:, None]
    triangle, distance = brute_force_first_hit(near, direction, corners, length)
    mesh_index = np.where(triangle >= 0, owner[triangle], -1)
    visibility = np.full(triangle.shape, np.nan)
    hit = triangle >= 0
    point = near[hit] + distance[hit, None] * direction[hit]
    normal = np.cross(*(corners[triangle[hit], i] - corners[triangle[hit], 0] for i in (1, 2)))
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    normal *= -np.sign(np.sum(normal * direction[hit], axis=1))[:, None]
    to_light = light_position - point
    facing = np.sum(normal * to_light, axis=1) > 0
    origin = point + epsilon * normal
    to_light = light_position - origin
    blocked, _ = brute_force_first_hit(
        origin,
        to_light / np.linalg.norm(to_light, axis=1)[:, None],
        corners,
        np.linalg.norm(to_light, axis=1),
    )
    visibility[hit] = facing & (blocked < 0)
    shape = (view.height, view.width)
    return mesh_index.reshape(shape), visibility.reshape(shape)


def random_scene(scale, shift):
    rng = np.random.default_rng(5)
    centers = rng.uniform([-2.0, -2.0, 0.3], [2.0, 2.0, 2.0], size=(150, 1, 3))
    soup = centers + rng.normal(scale=0.35, size=(150, 3, 3))
    meshes = [
        rectangle(-6.0, 6.0, -6.0, 6.0, 0.0),
        SceneMesh(soup.reshape(-1, 3), np.arange(450).reshape(-1, 3)),
    ]
    return [SceneMesh(scale * m.points + np.asarray(shift), m.triangles) for m in meshes]


@pytest.mark.parametrize(("scale", "shift"), [(1.0, 0.0), (1e-3, (1e6, -1e6, 2e6))])
def test_matches_brute_force_float64_ray_casting(scale, shift):
    shift = np.broadcast_to(np.asarray(shift, dtype=float), (3,))
    meshes = random_scene(scale, shift)
    view = camera_view(
        scale * np.array([6.0, -8.0, 9.0]) + shift,
        shift,
        clipping=(scale, 40 * scale),
        width=64,
        height=48,
    )
    light = scale * np.array([0.7, 0.4, 5.0]) + shift
    result = trace_reference(meshes, view, point_light(light))
    diagonal = np.linalg.norm(np.ptp(np.concatenate([m.points for m in meshes]), axis=0))
    mesh_index, visibility = brute_force_hard_shadows(meshes, view, light, 1e-6 * diagonal)
    assert (visibility == 0).sum() > 300 and (visibility == 1).sum() > 300
    assert np.sum(result.mesh_index != mesh_index) <= 1
    same = (result.visibility == visibility) | (np.isnan(result.visibility) & np.isnan(visibility))
    assert np.sum(~same) <= 1


def scaled_scene(scale, shift):
    shift = np.asarray(shift, dtype=float)

    def move(point):
        return scale * np.asarray(point, dtype=float) + shift

    meshes = [
        ground(),
        rectangle(-0.5, 0.5, -0.5, 0.5, 1.0),
        sphere((1.5, 1.0, 0.8), 0.6, subdivisions=3),
    ]
    meshes = [SceneMesh(move(m.points), m.triangles) for m in meshes]
    view = camera_view(move((5.0, -7.0, 8.0)), move((0.0, 0.0, 0.0)), clipping=(scale, 50 * scale))
    return meshes, view, point_light(move((0.3, -0.2, 3.0)))


@pytest.mark.parametrize(
    ("scale", "shift"),
    [(1e-4, 0.0), (1e6, 0.0), (1.0, (1e6, -2e6, 1e6)), (1e-3, (1e6, 1e6, -1e6))],
)
def test_scale_and_translation_invariance(scale, shift):
    base = trace_reference(*scaled_scene(1.0, 0.0))
    moved = trace_reference(*scaled_scene(scale, shift))
    assert (base.visibility == 0).sum() > 500
    n_pixels = base.visibility.size
    for name in ("surface", "lit_side", "mesh_index"):
        assert np.sum(getattr(base, name) != getattr(moved, name)) <= 5e-4 * n_pixels, name
    same = (base.visibility == moved.visibility) | (
        np.isnan(base.visibility) & np.isnan(moved.visibility)
    )
    assert np.sum(~same) <= 5e-4 * n_pixels
    hit = np.isfinite(base.depth) & np.isfinite(moved.depth)
    np.testing.assert_allclose(moved.depth[hit], base.depth[hit], atol=1e-5)


def test_soft_shadows_are_scale_invariant():
    base_meshes, base_view, base_light = scaled_scene(1.0, 0.0)
    base = trace_reference(base_meshes, base_view, base_light, light_size=0.2, samples=16)
    meshes, view, light = scaled_scene(1e-4, (1e6, 0.0, 0.0))
    moved = trace_reference(meshes, view, light, light_size=0.2e-4, samples=16)
    assert np.mean(np.abs(base.visibility - moved.visibility) > 1e-6) <= 5e-4


def test_depth_is_ndc_z():
    view = ViewSpec(np.diag([0.25, 0.25, -0.2, 1.0]), 8, 8)
    meshes = [ground(), rectangle(-2.0, 2.0, -2.0, 2.0, 1.0)]
    result = trace_reference(meshes, view, directional_light(DOWN))
    np.testing.assert_allclose(result.depth[result.mesh_index == 0], 0.0, atol=1e-12)
    np.testing.assert_allclose(result.depth[result.mesh_index == 1], -0.2, atol=1e-12)
    assert (result.mesh_index == 1).sum() == 16


def test_row_zero_is_top_of_image():
    view = ViewSpec(np.diag([0.25, 0.25, -0.2, 1.0]), 8, 8)
    top_half = rectangle(-4.0, 4.0, 0.0, 4.0, 1.0)
    result = trace_reference([ground(), top_half], view, directional_light(DOWN))
    assert (result.mesh_index[:4] == 1).all() and (result.mesh_index[4:] == 0).all()
    right_half = rectangle(0.0, 4.0, -4.0, 4.0, 1.0)
    result = trace_reference([ground(), right_half], view, directional_light(DOWN))
    assert (result.mesh_index[:, 4:] == 1).all() and (result.mesh_index[:, :4] == 0).all()


def test_geometry_outside_the_clipping_range_is_not_seen():
    card = rectangle(-0.5, 0.5, -0.5, 0.5, 2.0)
    between = camera_view((0.0, 0.0, 10.0), up=(0.0, 1.0, 0.0), clipping=(7.5, 9.5))
    result = trace_reference([ground(), card], between, directional_light(DOWN))
    assert (result.mesh_index == 1).any()
    assert set(np.unique(result.mesh_index)) == {-1, 1}
    beyond = camera_view((0.0, 0.0, 10.0), up=(0.0, 1.0, 0.0), clipping=(8.5, 10.5))
    result = trace_reference([ground(), card], beyond, directional_light(DOWN))
    assert (result.mesh_index == 0).all()
    assert (result.visibility[result.mesh_index == 0] == 0).any()


def test_empty_scene_and_meshes_without_triangles():
    view = camera_view((5.0, -7.0, 8.0))
    light = point_light((0.0, 0.0, 3.0))
    empty = trace_reference([], view, light)
    assert empty.visibility.shape == (HEIGHT, WIDTH)
    assert empty.visibility.dtype == np.float32 and empty.mesh_index.dtype == np.int32
    assert np.isnan(empty.visibility).all() and np.isnan(empty.depth).all()
    assert (empty.mesh_index == -1).all() and not empty.surface.any()
    nothing = SceneMesh(np.zeros((0, 3)), np.zeros((0, 3), dtype=int))
    result = trace_reference([nothing, ground()], view, light)
    assert set(np.unique(result.mesh_index)) == {1}
    np.testing.assert_array_equal(result.visibility, 1.0)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"samples": 0}, "samples"),
        ({"samples": 4097, "light_size": 0.1}, "samples"),
        ({"samples": 2.0, "light_size": 0.1}, "samples"),
        ({"samples": True}, "samples"),
        ({"light_size": -0.1, "samples": 4}, "light_size"),
        ({"light_size": math.nan, "samples": 4}, "light_size"),
        ({"light_size": math.inf, "samples": 4}, "light_size"),
        ({"light_size": 0.1}, "samples > 1"),
        ({"samples": 8}, "light_size > 0"),
    ],
)
def test_bad_options_raise(kwargs, name):
    with pytest.raises(ValueError, match=re.escape(name)):
        trace_reference([ground()], camera_view((0, -6, 7)), point_light((0, 0, 3)), **kwargs)


def test_bad_inputs_raise():
    view = camera_view((0, -6, 7))
    with pytest.raises(ValueError, match="light_size"):
        trace_reference([ground()], view, directional_light(DOWN), light_size=90.0, samples=4)
    with pytest.raises(ValueError, match="invertible"):
        trace_reference([ground()], ViewSpec(np.zeros((4, 4)), 4, 4), point_light((0, 0, 3)))
    with pytest.raises(ValueError, match="width"):
        ViewSpec(np.eye(4), 0, 4)
    with pytest.raises(ValueError, match="triangles"):
        SceneMesh(np.zeros((3, 3)), np.array([[0, 1, 3]]))
    with pytest.raises(ValueError, match="points"):
        SceneMesh(np.zeros((3, 2)), np.array([[0, 1, 2]]))
    with pytest.raises(TypeError, match="SceneMesh"):
        trace_reference([pv.Plane()], view, point_light((0, 0, 3)))


def test_missing_embree_names_the_extra(monkeypatch):
    monkeypatch.setattr(trimesh.ray, "has_embree", False)
    with pytest.raises(ImportError, match=r'pvshadows\[reference\]".*embreex'):
        trace_reference([ground()], camera_view((0, -6, 7)), point_light((0, 0, 3)))
