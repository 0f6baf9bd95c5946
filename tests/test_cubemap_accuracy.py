"""Cube-map shadows of point lights against exact ray-cast visibility, on the same frame."""

import numpy as np
import pytest
import pyvista as pv

from conftest import point_light
from pvshadows.tools.scenes import standard_scene

HARD = {"filter": "hard", "resolution": 1024}


def measured(scene, **settings):
    scene.plotter.shadows.enable(**{**HARD, **settings})
    return scene.plotter.shadows.measure(scene.light)


@pytest.fixture(scope="module")
def unit_error():
    return measured(standard_scene()).misclassified


@pytest.mark.parametrize("passes", ["single", "six"])
def test_standard_scene_within_one_percent(scene, passes):
    error = measured(scene, passes=passes)
    assert error.lit_pixels > 100_000
    assert error.misclassified <= 0.01
    assert scene.plotter.shadows.last_frame.lights[0].technique == "cubemap"


def test_single_and_six_passes_fill_the_same_cube(scene):
    shadows = scene.plotter.shadows
    shadows.enable(**HARD, passes="single")
    single = shadows.visibility(scene.light)
    shadows.configure(scene.light, passes="six")
    six = shadows.visibility(scene.light)
    same = np.isfinite(single) & np.isfinite(six)
    assert np.mean(single[same] != six[same]) < 1e-4


def test_pcf_within_one_percent(scene):
    error = measured(scene, filter="pcf", pcf_taps=16)
    assert error.misclassified <= 0.01


def test_sphere_straight_under_the_light_casts_the_analytic_disk():
    height, radius, center_z = 4.0, 0.8, 1.5
    pl = pv.Plotter(off_screen=True, window_size=[400, 400], lighting="none")
    pl.add_mesh(pv.Plane(i_size=12, j_size=12), color="white")
    pl.add_mesh(
        pv.Sphere(radius=radius, center=(0, 0, center_z), theta_resolution=96, phi_resolution=96),
        color="white",
    )
    light = point_light((0, 0, height))
    pl.add_light(light)
    pl.camera_position = [(0, 0, 20), (0, 0, 0), (0, 1, 0)]
    pl.enable_parallel_projection()
    pl.camera.parallel_scale = 6.0
    pl.shadows.enable(**HARD)
    shown = pl.shadows.visibility(light)
    # Pixel centres of a parallel top view map linearly onto the ground.
    n = shown.shape[0]
    coords = (np.arange(n) + 0.5) / n * 12.0 - 6.0
    x, y = np.meshgrid(coords, coords[::-1])
    r = np.hypot(x, y)
    # Tangent cone from the light: half angle asin(radius / distance), cut by the ground.
    disk = height * np.tan(np.arcsin(radius / (height - center_z)))
    ground = r > radius * 1.05
    inside = ground & (r < disk * 0.97)
    outside = ground & (r > disk * 1.03) & (r < 5.5)
    assert inside.sum() > 1000
    assert np.all(shown[inside] < 0.5)
    assert np.all(shown[outside] > 0.5)


def test_light_two_hundredths_above_the_ground():
    error = measured(standard_scene(light_position=(0.3, -0.2, 0.02)))
    assert error.misclassified <= 0.005


@pytest.mark.parametrize(
    ("scale", "offset"),
    [(1e-4, (0, 0, 0)), (1e6, (0, 0, 0)), (1.0, (1e6, 1e6, 1e6))],
    ids=["scaled 1e-4", "scaled 1e6", "translated 1e6"],
)
def test_error_independent_of_scale_and_position(scale, offset, unit_error):
    error = measured(standard_scene(scale=scale, offset=offset))
    assert error.misclassified <= 2 * unit_error
    assert error.misclassified <= 0.01


def test_camera_between_the_light_and_an_object():
    camera = ((0.6, -1.2, 2.8), (0.9, -2.1, 0.6), (0.0, 0.0, 1.0))
    error = measured(standard_scene(camera=camera))
    assert error.lit_pixels > 100_000
    assert error.misclassified <= 0.01


def test_no_acne_on_a_receiver_at_grazing_incidence():
    pl = pv.Plotter(off_screen=True, window_size=[800, 600], lighting="none")
    pl.add_mesh(pv.Plane(i_size=20, j_size=20, i_resolution=40, j_resolution=40), color="white")
    light = point_light((0, 0, 0.1))
    pl.add_light(light)
    pl.camera_position = [(0, -12, 8), (0, 2, 0), (0, 0, 1)]
    for filter_name in ("hard", "pcf"):
        pl.shadows.enable(filter=filter_name, resolution=1024)
        error = pl.shadows.measure(light)
        # Light reaches the plane at 0.3 to 6 degrees over most of the view.
        assert error.lit_pixels > 200_000
        assert error.false_shadow <= 0.001


def test_shadows_near_grazing_stay_attached():
    error = measured(standard_scene(light_position=(0.3, -0.2, 0.25)))
    assert error.false_shadow <= 0.001
    assert error.misclassified <= 0.005


def test_resolution_extremes_work_and_error_falls_with_resolution():
    scene = standard_scene(window_size=(400, 300))
    shadows = scene.plotter.shadows
    errors = {}
    for resolution in (64, 1024, 4096):
        shadows.enable(filter="hard", resolution=resolution)
        errors[resolution] = shadows.measure(scene.light).misclassified
    assert errors[64] > errors[1024] >= errors[4096]
    assert errors[64] <= 0.05
    assert errors[4096] <= 0.005


def test_front_face_culling_stores_the_far_side_of_closed_casters():
    pl = pv.Plotter(off_screen=True, window_size=[300, 200], lighting="none")
    pl.add_mesh(pv.Plane(i_size=10, j_size=10))
    pl.add_mesh(pv.Sphere(radius=1.0, center=(0, 0, 2)))
    light = point_light((0, 0, 5))
    pl.add_light(light)
    depths = {}
    for cull in (False, True):
        pl.shadows.enable(filter="hard", cull_front=cull)
        pl.shadows.measure(light)
        cube = pl.shadows._renderers[0].technique("cubemap").cube_of(light)
        down = cube.read_faces()[5]  # -Z face, looking at the sphere and the ground
        centre = down.shape[0] // 2
        depths[cull] = down[centre, centre]
        assert pl.shadows.measure(light).misclassified <= 0.01
    far = depths[False] / 2.0 * 4.0  # distance 2 -> 4: the sphere's far side, below its near side
    assert depths[True] == pytest.approx(far, rel=0.01)
