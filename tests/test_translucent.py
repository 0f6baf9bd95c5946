"""Translucent casters: each surface lets ``1 - opacity`` through, in every technique."""

import re
import warnings

import numpy as np
import pytest
import pyvista as pv
from test_reference import camera_view, ground, point_light, rectangle, sphere

from conftest import draw, spot_box_scene
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.library import MapLookup, group_uniforms, shadow_functions
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


def translucent_scene(kind):
    """A 400x300 plotter: a box under a spot light, or a sphere under a sun or a bulb.

    Returns the plotter, the light and the caster (named ``"glass"``), which
    receives no shadow, so only the ground's pixels are judged.
    """
    pl = pv.Plotter(off_screen=True, lighting="none", window_size=(400, 300))
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white", name="ground")
    if kind == "spot":
        shape = pv.Cube(center=(0, 0, 1), x_length=1.5, y_length=1.5, z_length=1.5)
        light = pv.Light(position=(0.5, 0.3, 5), focal_point=(0, 0, 0), cone_angle=60)
        light.positional = True
    else:
        shape = pv.Sphere(radius=0.8, center=(0, 0, 1.2))
        light = pv.Light(position=(0.6, 0.4, 5), focal_point=(0, 0, 0))
        light.positional = kind == "point"
        light.cone_angle = 180
    glass = pl.add_mesh(shape, name="glass")
    pl.add_light(light)
    pl.camera_position = [(7, -7, 7), (0, 0, 0.5), (0, 0, 1)]
    pl.shadows.set_receiver(glass, False)
    return pl, light, glass


def inside_the_shadow(pl, light, through):
    """Share of the pixels the reference sees at ``through`` shown within 0.01 of it."""
    shown = pl.shadows.visibility(light)
    exact = pl.shadows.reference(light)
    shadow = np.isfinite(shown) & (np.abs(exact - through) < 1e-6)
    assert shadow.sum() > 1000
    return (np.abs(shown[shadow] - through) < 0.01).mean(), shadow


@pytest.mark.parametrize("filter_name", ["hard", None])
@pytest.mark.parametrize(
    ("kind", "technique"), [("spot", "map"), ("sun", "map"), ("point", "cubemap")]
)
def test_maps_let_each_surface_of_a_translucent_caster_pass_one_minus_opacity(
    kind, technique, filter_name
):
    pl, light, glass = translucent_scene(kind)
    glass.prop.opacity = 0.3
    options = {} if filter_name is None else {"filter": filter_name}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # maps honour opacity: no warning
        pl.shadows.enable(technique=technique, **options)
    for opacity in (0.3, 0.6):
        glass.prop.opacity = opacity
        draw(pl)
        assert pl.shadows.last_frame.lights[0].technique == technique
        passes = {p.name.split(" (")[0]: p.status for p in pl.shadows.last_frame.lights[0].passes}
        assert passes["transmittance"] == "run"  # a change of opacity draws the companion again
        share, shadow = inside_the_shadow(pl, light, (1.0 - opacity) ** 2)  # both sides
        assert share > 0.98
        error = pl.shadows.measure(light)
        assert error.misclassified <= 0.01
        assert error.shadow_pixels >= shadow.sum()
    pl.render()
    passes = {p.name.split(" (")[0]: p.status for p in pl.shadows.last_frame.lights[0].passes}
    assert passes["transmittance"] == "reused"
    glass.prop.opacity = 1.0
    pl.render()
    assert (pl.shadows.visibility(light)[shadow] < 0.5).mean() > 0.98  # opaque: full shadow
    assert pl.shadows._renderers[0].technique(technique).companion_of(light) is None


@pytest.mark.parametrize(("kind", "technique"), [("spot", "map"), ("point", "cubemap")])
def test_a_light_without_translucent_casters_gets_no_companion_pass_texture_or_sampler(
    kind, technique
):
    pl, light, glass = translucent_scene(kind)
    pl.shadows.enable(technique=technique, filter="hard")
    ground = pl.actors["ground"]

    def companion():
        return pl.shadows._renderers[0].technique(technique).companion_of(light)

    def transmit_uniforms():
        edits = pl.shadows._renderers[0]._edits.of(vtk_id(ground))
        texts = "".join(new for _, new in edits.replacements)
        return re.findall(r"uniform sampler\w* (pvs\w*Transmit)", texts)

    def passes():
        return [p.name for p in pl.shadows.last_frame.lights[0].passes]

    draw(pl)
    opaque_passes = passes()
    assert not any("transmittance" in name for name in opaque_passes)
    assert companion() is None and transmit_uniforms() == []
    glass.prop.opacity = 0.5
    pl.render()
    assert len(passes()) == len(opaque_passes) + 1
    assert companion() is not None and len(transmit_uniforms()) == 1
    glass.prop.opacity = 1.0
    pl.render()
    assert passes() == opaque_passes
    assert companion() is None and transmit_uniforms() == []


@pytest.mark.parametrize(
    ("technique", "options"),
    [("map", {}), ("cubemap", {"passes": "six"}), ("planar", {}), ("volume", {})],
)  # the cube drawn face by face here, in one layered draw above
def test_set_caster_transmittance_overrides_opacity_for_every_technique_and_the_reference(
    technique, options
):
    pl, spot = spot_box_scene()
    box = pl.actors["box"]
    pl.shadows.set_receiver(box, False)
    pl.shadows.set_caster(box, transmittance=0.5)  # an opaque box passing half through each side
    pl.shadows.enable(technique=technique, filter="hard", **options)
    assert inside_the_shadow(pl, spot, 0.25)[0] > 0.98
    assert pl.shadows.measure(spot).misclassified <= 0.01
    box.prop.opacity = 0.3  # the override wins over opacity
    pl.render()
    assert inside_the_shadow(pl, spot, 0.25)[0] > 0.98
    pl.shadows.set_caster(box, transmittance=None)  # back to 1 - opacity
    pl.render()
    assert inside_the_shadow(pl, spot, 0.49)[0] > 0.98
    pl.shadows.set_caster(box, False)
    pl.render()
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


def test_lights_with_and_without_translucent_casters_are_looked_up_in_their_own_groups():
    lookups = [MapLookup("spot", "hard", 0, 2, translucent=True), MapLookup("spot", "hard", 1, 2)]
    code = shadow_functions(lookups)
    assert code.count("#define PVS_WITH_TRANSMIT") == 1
    assert code.count("#define PVS_GROUP_TRANSLUCENT") == 1
    assert code.count("#define PVS_GROUP_LOOKUP pvsSpotHard") == 2
    own = {"pvsDepth0": 3, "pvsTransmit0": 4, "pvsDepth1": 5}
    packed = group_uniforms(lookups, own)
    assert packed["pvsSpotHardTranslucentTransmit"] == [4]
    assert packed["pvsSpotHardTranslucentDepth"] == [3] and packed["pvsSpotHardDepth"] == [5]
    assert "pvsSpotHardTransmit" not in packed

    pl = pv.Plotter(off_screen=True, lighting="none", window_size=(400, 300))
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white", name="ground")
    pl.add_mesh(pv.Cube(center=(0, 0, 1)), opacity=0.5, name="glass")
    pl.add_mesh(pv.Sphere(center=(3, 3, 0.5), radius=0.4), name="stone")
    over_glass = pv.Light(position=(0.2, 0.1, 5), focal_point=(0, 0, 0), cone_angle=30)
    over_stone = pv.Light(position=(3, 3, 4), focal_point=(3, 3, 0), cone_angle=20)
    for light in (over_glass, over_stone):
        light.positional = True
        pl.add_light(light)
    pl.camera_position = [(8, -8, 8), (1, 1, 0.5), (0, 0, 1)]
    pl.shadows.enable(technique="map", filter="pcf")
    draw(pl)
    frame = pl.shadows.last_frame
    assert frame.failure is None and frame.receivers == []
    names = [[p.name for p in light.passes] for light in frame.lights]
    assert names == [["map depth", "transmittance"], ["map depth"]]
    for light in (over_glass, over_stone):
        error = pl.shadows.measure(light)
        assert error.shadow_pixels > 400 and error.misclassified <= 0.01
