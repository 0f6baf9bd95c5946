"""Shadow volumes at the edges: a light on a caster's face, a caster around the whole scene."""

import numpy as np
import pytest
import pyvista as pv

from pvshadows.scenes import standard_scene

SMALL = (400, 300)


@pytest.mark.parametrize(
    "position",
    [(-2.0, -0.3, 2.1), (0.9, -2.1, 1.8), (0.3, -0.2, 0.0)],
    ids=["box top", "cylinder cap centre", "ground"],
)
def test_a_light_on_a_casters_face(position):
    scene = standard_scene(window_size=SMALL, light_position=position)
    scene.plotter.shadows.enable(technique="volume")
    error = scene.plotter.shadows.measure(scene.light)
    assert error.misclassified <= 0.002


def _enclosed(radius):
    scene = standard_scene(window_size=SMALL)
    scene.plotter.add_mesh(
        pv.Sphere(radius=radius, theta_resolution=16, phi_resolution=16), name="sky"
    )
    scene.plotter.shadows.enable(technique="volume")
    return scene


def test_a_caster_around_the_scene_and_the_light_shadows_nothing_inside_it():
    scene = _enclosed(100.0)
    error = scene.plotter.shadows.measure(scene.light)
    notes = " ".join(scene.plotter.shadows.last_frame.lights[0].notes)
    assert "every other receiver are inside actor 'sky'" in notes
    assert error.misclassified <= 0.002
    assert error.lit_pixels > 40000


def test_a_caster_beyond_float32_resolution_draws_right_and_the_reference_refuses():
    near = _enclosed(100.0).plotter.shadows.visibility()
    scene = _enclosed(1e30)
    far = scene.plotter.shadows.visibility()
    assert np.mean(np.isnan(near) == np.isnan(far)) == 1.0
    assert np.nanmean(np.abs(near - far) > 0.5) <= 0.001
    with pytest.raises(ValueError, match=r"reference\(\): actor 'box' is 1\.88 across .*'sky'"):
        scene.plotter.shadows.measure(scene.light)
