"""A point light far from a small scene keeps every shadow, and the reference stays exact."""

import numpy as np
import pytest
import pyvista as pv

from pvshadows.tools.scenes import standard_scene

SMALL = (400, 300)


@pytest.mark.parametrize(
    ("distance", "map_kind"),
    [
        (1e2, "a perspective map"),
        (1e3, "a perspective map"),
        (1e4, "an orthographic map"),  # a perspective map rounded depths: 0.57 % wrong
        (2e4, "an orthographic map"),  # 7.3 %
        (1e6, "an orthographic map"),
    ],
)
def test_a_far_point_light_keeps_its_shadows(distance, map_kind):
    scene = standard_scene(window_size=SMALL, light_position=(distance, distance / 2, distance))
    scene.plotter.shadows.enable(filter="hard")
    error = scene.plotter.shadows.measure(scene.light)
    report = scene.plotter.shadows.last_frame.lights[0]
    assert report.technique == "map"
    assert map_kind in " ".join(report.notes)
    assert error.misclassified <= 0.002
    assert error.missed_shadow <= 0.02
    assert np.nansum(scene.plotter.shadows.reference(scene.light) < 0.5) > 4000


@pytest.mark.parametrize("distance", [1e3, 1e4, 1e5])
def test_a_far_spot_light_keeps_its_shadows(distance):
    # Before: 0.02 %, 0.44 % and 26 % wrong (float32 depths of a perspective map so far away).
    scene = standard_scene(
        window_size=SMALL, light="spot", light_position=(distance, distance / 2, distance)
    )
    scene.light.cone_angle = 60.0
    scene.light.focal_point = (0.0, 0.0, 0.0)
    scene.plotter.shadows.enable(filter="hard")
    error = scene.plotter.shadows.measure(scene.light)
    notes = " ".join(scene.plotter.shadows.last_frame.lights[0].notes)
    assert ("an orthographic map" in notes) == (distance > 1e3)
    assert error.misclassified <= 0.001
    assert np.nansum(scene.plotter.shadows.reference(scene.light) < 0.5) > 4000


def test_the_reference_of_a_point_light_at_any_distance_matches_a_parallel_light():
    """Past 1e4 scene sizes a bulb casts a sun's shadows, to a pixel; so does the reference."""
    scene = standard_scene(window_size=SMALL)
    sun = pv.Light(position=(1, 0.5, 1), focal_point=(0, 0, 0), positional=False)
    scene.plotter.add_light(sun)
    parallel = scene.plotter.shadows.reference(sun) < 0.5
    for distance in (1e5, 1e9, 1e30):
        scene.light.position = (distance, distance / 2, distance)
        scene.light.focal_point = (0, 0, 0)
        traced = scene.plotter.shadows.reference(scene.light) < 0.5
        assert parallel.sum() > 4000
        assert np.sum(traced != parallel) <= 2, distance


def test_a_point_light_among_its_casters_keeps_the_cube():
    scene = standard_scene(window_size=SMALL)
    scene.plotter.shadows.enable(filter="hard")
    scene.plotter.shadows.visibility(scene.light)
    assert scene.plotter.shadows.last_frame.lights[0].technique == "cubemap"


def test_receivers_outside_the_casters_cone_stay_lit():
    scene = standard_scene(window_size=SMALL, light_position=(60.0, 30.0, 60.0))
    scene.plotter.shadows.set_caster(scene.ground, False)
    scene.plotter.shadows.enable(filter="pcf")
    error = scene.plotter.shadows.measure(scene.light)
    assert "a perspective map" in " ".join(scene.plotter.shadows.last_frame.lights[0].notes)
    assert error.misclassified <= 0.002
    assert error.lit_pixels > 40000
