"""Translucent casters: drawn as full shadows, traced physically by the reference."""

import warnings

import numpy as np
import pytest
from test_reference import camera_view, ground, point_light, rectangle, sphere

from conftest import spot_box_scene
from pvshadows.verify.reference import SceneMesh, trace_reference


def test_reference_lets_one_minus_opacity_through_every_surface_crossed():
    meshes = [
        ground(),
        rectangle(-2.0, 0.5, -1.0, 1.0, 1.0, receiver=False, opacity=0.3),
        rectangle(-0.5, 2.0, -1.0, 1.0, 1.5, receiver=False, opacity=0.6),
        rectangle(2.5, 3.5, -1.0, 1.0, 1.0, receiver=False),
    ]
    ball = sphere((-3.5, 0.0, 1.0), 0.5)
    meshes.append(SceneMesh(ball.points, ball.triangles, receiver=False, opacity=0.3))
    result = trace_reference(meshes, camera_view((0.0, -7.0, 9.0)), point_light((0.0, 0.0, 30.0)))
    seen = result.visibility[result.lit_side & np.isfinite(result.visibility)]
    # Lit, the opaque square, each translucent square alone, both, the sphere's two sides.
    expected = np.array([1.0, 0.0, 0.7, 0.4, 0.28, 0.49])
    nearest = np.abs(seen[:, None] - expected[None, :]).argmin(axis=1)
    np.testing.assert_allclose(seen, expected[nearest], atol=1e-6)
    assert np.bincount(nearest, minlength=expected.size).min() > 50


def test_opacity_of_a_scene_mesh_is_checked():
    with pytest.raises(ValueError, match=r"SceneMesh opacity must be from 0 to 1, got 1\.5"):
        rectangle(0, 1, 0, 1, 0, opacity=1.5)


@pytest.mark.parametrize(("opacity", "through"), [(0.3, 0.49), (0.2, 0.64)])
def test_a_translucent_caster_casts_a_full_shadow_from_maps_that_measure_judges(opacity, through):
    pl, spot = spot_box_scene()
    pl.actors["box"].prop.opacity = opacity
    pl.shadows.set_receiver(pl.actors["box"], False)  # only the ground's pixels
    with pytest.warns(UserWarning, match=f"actor 'box' has opacity {opacity} but casts a full"):
        pl.shadows.enable(technique="map", filter="hard")
    shown = pl.shadows.visibility(spot)
    exact = pl.shadows.reference(spot)
    shadow = np.isfinite(shown) & (shown == 0.0) & (exact < 1.0)
    assert shadow.sum() > 1000
    inner = np.abs(exact[shadow] - through) < 1e-6  # the box's two sides
    assert inner.mean() > 0.98
    error = pl.shadows.measure(spot)
    assert error.shadow_pixels >= shadow.sum()
    share = shadow.sum() / error.lit_pixels
    assert error.rmse == pytest.approx(through * np.sqrt(share), rel=0.05)
    if through > 0.5:  # shown dark, lit in truth
        assert error.false_shadow == pytest.approx(share, rel=0.05)
    pl.shadows.set_caster(pl.actors["box"], False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pl.shadows.enable(technique="map", filter="hard")
    assert pl.shadows.measure(spot).shadow_pixels == 0


@pytest.mark.parametrize(
    ("technique", "opacity"), [("planar", 0.3), ("planar", 0.6), ("volume", 0.3)]
)
def test_planar_and_volume_shadows_let_the_casters_transmittance_through(technique, opacity):
    pl, spot = spot_box_scene()
    pl.actors["box"].prop.opacity = opacity
    pl.shadows.set_receiver(pl.actors["box"], False)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # they honour opacity: no warning
        pl.shadows.enable(technique=technique)
    shown = pl.shadows.visibility(spot)
    exact = pl.shadows.reference(spot)
    through = (1.0 - opacity) ** 2  # the box's top and bottom
    shadow = np.isfinite(shown) & (np.abs(exact - through) < 1e-6)
    assert shadow.sum() > 1000
    inner = shadow & (np.abs(shown - through) < 0.01)
    assert inner.sum() > 0.98 * shadow.sum()  # 8-bit masks: within 0.01 but at the outline
    error = pl.shadows.measure(spot)
    assert error.rmse < 0.02 and error.misclassified < 0.002
    pl.actors["box"].prop.opacity = 1.0
    pl.render()
    assert np.nanmin(pl.shadows.visibility(spot)[shadow]) == 0.0  # the mask follows opacity
