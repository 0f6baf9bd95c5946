"""Shadow volumes at the edges: a light on a caster's face, a caster around the whole scene."""

import numpy as np
import pytest
import pyvista as pv

from pvshadows.tools.scenes import standard_scene

SMALL = (400, 300)


@pytest.mark.parametrize(
    ("position", "technique"),
    [
        ((-2.0, -0.3, 2.1), "volume"),
        ((-2.0, -0.9, 1.7), "volume"),
        ((-2.6, -0.9, 1.7), "volume"),
        ((-2.0, -0.9, 1.7), "cubemap"),
        ((0.9, -2.1, 1.8), "volume"),
        ((0.3, -0.2, 0.0), "volume"),
    ],
    ids=["box top", "box side", "box edge", "box side cubemap", "cylinder cap", "ground"],
)
def test_a_light_on_a_casters_face(position, technique):
    """The light's own face does not block it: only what lies behind that face is dark."""
    scene = standard_scene(window_size=SMALL, light_position=position)
    scene.plotter.shadows.enable(technique=technique, filter="hard")
    error = scene.plotter.shadows.measure(scene.light)
    assert error.misclassified <= 0.002
    assert error.lit_pixels > 900


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
