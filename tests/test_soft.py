"""Soft shadows (PCF, random sampling, PCSS) against a many-sample area-light reference."""

import numpy as np
import pytest
import pyvista as pv

from conftest import point_light
from pvshadows.tools.scenes import standard_scene
from pvshadows.verify.measure import compare

SIZE = {"point": 0.3, "spot": 0.3, "directional": 2.5}


@pytest.mark.parametrize("light", ["point", "spot", "directional"])
def test_pcss_follows_the_area_light_and_beats_fixed_pcf(light):
    scene = standard_scene(light=light, window_size=(400, 300))
    shadows = scene.plotter.shadows
    shadows.enable(filter="pcf", pcf_taps=16)
    reference = shadows._trace(scene.light, light_size=SIZE[light], samples=128)
    pcf = compare(shadows.visibility(scene.light), reference)
    shadows.configure(scene.light, filter="pcss", samples=32, light_size=SIZE[light])
    pcss = compare(shadows.visibility(scene.light), reference)
    # A penumbra one can see: many pixels are neither fully lit nor fully dark.
    soft = reference.visibility[reference.lit_side]
    assert np.mean((soft > 0.05) & (soft < 0.95)) > 0.02
    assert pcss.rmse <= 0.08
    assert pcss.rmse < pcf.rmse


@pytest.mark.parametrize("light", ["point", "spot"])
def test_random_sampling_noise_is_bounded(light):
    scene = standard_scene(light=light, window_size=(400, 300))
    shadows = scene.plotter.shadows
    shadows.enable(filter="random", samples=64, filter_radius=3.0)
    few = shadows.visibility(scene.light)
    shadows.configure(scene.light, samples=256)
    many = shadows.visibility(scene.light)
    both = np.isfinite(few) & np.isfinite(many)
    assert np.sqrt(np.mean((few[both] - many[both]) ** 2)) <= 0.02
    assert np.mean((many[both] > 0.05) & (many[both] < 0.95)) > 0.005  # it does blur


def test_pcss_hardens_at_contact():
    """A tall thin post on the ground: its shadow is sharp at the foot and soft at the tip."""
    pl = pv.Plotter(off_screen=True, window_size=[500, 400], lighting="none")
    pl.add_mesh(pv.Plane(i_size=12, j_size=12), color="white")
    pl.add_mesh(pv.Box(bounds=(-0.15, 0.15, -0.15, 0.15, 0.0, 3.0)), color="white")
    light = point_light((0.0, -2.0, 4.0))
    pl.add_light(light)
    pl.camera_position = [(0, 0, 16), (0, 2.5, 0), (0, 1, 0)]
    pl.shadows.enable(filter="pcss", light_size=0.4, samples=64)
    shown = pl.shadows.visibility(light)
    reference = pl.shadows._trace(light, light_size=0.4, samples=128)
    assert compare(shown, reference).rmse <= 0.08
    partial = (shown > 0.1) & (shown < 0.9)
    rows = np.nonzero(partial.any(axis=1))[0]
    widths = partial.sum(axis=1)
    foot, tip = widths[rows[-20:]].mean(), widths[rows[:20]].mean()
    assert tip > 2 * foot


@pytest.mark.parametrize(
    ("settings", "words"),
    [
        ({"filter": "pcss"}, "filter='pcss' sizes penumbrae by the light's physical size"),
        ({"filter": "pcss", "light_size": 0.0}, "give light_size > 0"),
        ({"light_size": -1.0}, "light_size=-1.0 is not allowed"),
        ({"samples": 4}, "samples=4 is not allowed; it must be a multiple of 8 from 8 to 256"),
        ({"samples": 1000}, "samples=1000 is not allowed"),
        ({"pcf_taps": 9}, "pcf_taps=9 is not allowed; choose one of 4, 16, 36, 64"),
        ({"filter": "gaussian"}, "filter='gaussian' is not allowed"),
    ],
)
def test_bad_soft_shadow_settings(settings, words):
    scene = standard_scene(window_size=(200, 150))
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        scene.plotter.shadows.configure(scene.light, **settings)


def test_spot_cone_of_zero_is_refused():
    pl = pv.Plotter(off_screen=True)
    spot = pv.Light(position=(0, 0, 3), focal_point=(0, 0, 0), positional=True, cone_angle=0)
    pl.add_light(spot)
    with pytest.raises(ValueError, match=r"cone_angle=0\.0 is not allowed for a spot light"):
        pl.shadows.enable()
