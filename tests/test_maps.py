"""2D shadow maps of spot and directional lights against exact ray-cast visibility."""

import numpy as np
import pytest
import pyvista as pv

import pvshadows.scene.light_kit as light_kit
from conftest import draw, point_light
from pvshadows.tools.scenes import standard_scene
from pvshadows.verify.builtin import builtin_visibility
from pvshadows.verify.measure import compare

HARD = {"filter": "hard", "resolution": 1024}


def sun(elevation, azimuth=0.0, distance=10.0, center=(0.0, 0.0, 0.0)):
    e, a = np.radians(elevation), np.radians(azimuth)
    towards = np.array([np.cos(e) * np.cos(a), np.cos(e) * np.sin(a), np.sin(e)])
    center = np.asarray(center, dtype=float)
    return pv.Light(
        position=tuple(center + distance * towards),
        focal_point=tuple(center),
        light_type="scene light",
    )


@pytest.mark.parametrize("light", ["spot", "directional"])
def test_standard_scene_within_one_percent(light):
    scene = standard_scene(light=light)
    scene.plotter.shadows.enable(**HARD)
    error = scene.plotter.shadows.measure(scene.light)
    assert error.lit_pixels > 100_000
    assert error.misclassified <= 0.01
    assert scene.plotter.shadows.last_frame.lights[0].technique == "map"


def test_vtk_builtin_shadows_are_far_off_on_the_same_frame():
    scene = standard_scene(light="spot", window_size=(400, 300))
    pl = scene.plotter
    pl.screenshot(return_img=True)
    builtin = builtin_visibility(pl, scene.light)
    pl.shadows.enable(**HARD)
    reference = pl.shadows._trace(scene.light)
    assert compare(builtin, reference).misclassified > 0.05
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_sun_at_grazing_incidence_has_no_acne_and_attached_shadows():
    scene = standard_scene(light="directional", sun_elevation=10.0)
    scene.plotter.shadows.enable(**HARD)
    error = scene.plotter.shadows.measure(scene.light)
    assert error.false_shadow <= 0.001
    assert error.misclassified <= 0.01


def test_box_standing_on_the_ground_touches_its_shadow():
    """Top view, sun 10 degrees above the ground from +x: the shadow starts at the box's foot."""
    pl = pv.Plotter(off_screen=True, window_size=[600, 300], lighting="none")
    ground = pl.add_mesh(pv.Plane(center=(-3, 0, 0), i_size=12, j_size=6), color="white")
    pl.add_mesh(pv.Box(bounds=(-0.5, 0.5, -0.5, 0.5, 0.0, 1.0)), color="white")
    light = sun(10.0)
    pl.add_light(light)
    pl.camera_position = [(-3, 0, 20), (-3, 0, 0), (0, 1, 0)]
    pl.enable_parallel_projection()
    pl.camera.parallel_scale = 3.0
    pl.shadows.enable(**HARD)
    shown = pl.shadows.visibility(light)
    reference = pl.shadows._trace(light)
    gaps = []
    for row in range(shown.shape[0]):
        box = np.nonzero(reference.mesh_index[row] == 1)[0]
        if box.size < 10:
            continue
        column = box.min() - 1
        while column >= 0 and reference.mesh_index[row, column] == 0 and shown[row, column] >= 0.5:
            column -= 1
        gaps.append(box.min() - 1 - column)
    assert len(gaps) >= 40
    assert max(gaps) <= 1  # pixels of lit ground between the box and its shadow
    assert ground is not None
    assert compare(shown, reference).misclassified <= 0.01


def holding_cone(scene):
    """The cone angle, from the spot towards the origin, that just holds every actor's bounds."""
    position = np.array(scene.light.position)
    axis = -position / np.linalg.norm(position)
    lo, hi = np.array(scene.plotter.bounds).reshape(3, 2).T
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    rays = (corners - position) / np.linalg.norm(corners - position, axis=1)[:, None]
    return float(np.degrees(np.arccos(np.clip(rays @ axis, -1, 1)).max()))


@pytest.mark.parametrize("narrow", [True, False], ids=["5 degrees", "just holding the scene"])
def test_spot_cones_narrow_and_just_holding_the_scene(narrow):
    scene = standard_scene(light="spot")
    cone = 5.0 if narrow else holding_cone(scene) + 0.5
    scene.light.cone_angle = cone
    scene.plotter.shadows.enable(**HARD)
    error = scene.plotter.shadows.measure(scene.light)
    assert error.lit_pixels > (500 if narrow else 150_000)
    assert error.misclassified <= 0.01


def test_sun_over_a_scene_1e5_wide_keeps_small_shadows():
    pl = pv.Plotter(off_screen=True, window_size=[600, 450], lighting="none")
    pl.add_mesh(pv.Plane(i_size=1e5, j_size=1e5), color="white")
    for x, y in [(0, 0), (3, 1), (-2, 2.5)]:
        pl.add_mesh(pv.Box(bounds=(x - 0.4, x + 0.4, y - 0.4, y + 0.4, 0.0, 1.2)), color="tan")
    light = sun(35.0, 20.0)
    pl.add_light(light)
    pl.camera_position = [(8, -8, 7), (0.5, 1, 0), (0, 0, 1)]
    pl.renderer.SetNearClippingPlaneTolerance(1e-5)
    pl.renderer.ResetCameraClippingRange()
    pl.shadows.enable(**HARD)
    draw(pl)
    detail = pl.shadows.last_frame.lights[0].passes[0].detail
    assert "fitted" in detail and float(detail.split()[1]) < 100  # not 1e5 wide
    shown = pl.shadows.visibility(light)
    error = pl.shadows.measure(light)
    assert np.nansum(shown < 0.5) > 5_000  # the boxes' shadows are there
    assert error.misclassified <= 0.01


def test_point_spot_and_directional_lights_at_once():
    scene = standard_scene(window_size=(400, 300))
    pl = scene.plotter
    scene.light.intensity = 0.5
    spot = pv.Light(
        position=(-3, 3, 4), focal_point=(0, 0, 0), positional=True, cone_angle=45, intensity=0.5
    )
    sunlight = sun(50.0, -60.0)
    sunlight.intensity = 0.5
    pl.add_light(spot)
    pl.add_light(sunlight)
    pl.shadows.enable(**HARD)
    draw(pl)
    frame = pl.shadows.last_frame
    assert [(r.kind, r.technique) for r in frame.lights] == [
        ("point", "cubemap"),
        ("spot", "map"),
        ("directional", "map"),
    ]
    for light in (scene.light, spot, sunlight):
        assert pl.shadows.measure(light).misclassified <= 0.01


def test_sun_map_stays_put_while_the_camera_orbits():
    scene = standard_scene(light="directional", window_size=(400, 300))
    pl = scene.plotter
    pl.shadows.enable(**HARD)
    draw(pl)
    for _ in range(6):
        pl.camera.azimuth = 15
        draw(pl)
        assert pl.shadows.last_frame.lights[0].passes[0].status == "reused"
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_nothing_outside_a_map_is_shadowed():
    """A ground far wider than the fitted map, lit by a sun and a spot: no false shadow."""
    pl = pv.Plotter(off_screen=True, window_size=[600, 450], lighting="none")
    pl.add_mesh(pv.Plane(i_size=60, j_size=60), color="white")
    pl.add_mesh(pv.Sphere(radius=0.5, center=(0, 0, 1)), color="white")
    sunlight = sun(45.0)
    spot = pv.Light(
        position=(0, 0, 4), focal_point=(0, 0, 0), positional=True, cone_angle=70, intensity=0.5
    )
    pl.add_light(sunlight)
    pl.add_light(spot)
    pl.camera_position = [(0, -30, 25), (0, 0, 0), (0, 0, 1)]
    pl.shadows.enable(**HARD)
    for light in (sunlight, spot):
        error = pl.shadows.measure(light)
        assert error.false_shadow <= 0.001
        assert error.misclassified <= 0.01


def test_light_kit_key_light_casts_and_the_others_opt_in():
    pl = pv.Plotter(off_screen=True, window_size=[300, 200])
    pl.add_mesh(pv.Plane(i_size=6, j_size=6))
    pl.add_mesh(pv.Sphere(center=(0, 0, 1)))
    pl.shadows.enable(**HARD)
    draw(pl)
    techniques = [r.technique for r in pl.shadows.last_frame.lights]
    # The headlight's shadows hide behind their casters; fill and back lights stay unshadowed.
    assert techniques == [None, "map", None, None, None]
    assert "fill and back lights stay unshadowed" in pl.shadows.last_frame.lights[2].notes[0]
    kit = list(pl.renderer.lights)
    pl.shadows.enable(lights=kit[1:], **HARD)
    draw(pl)
    assert [r.technique for r in pl.shadows.last_frame.lights][1:] == ["map"] * 4
    for light in kit[1:]:
        assert pl.shadows.measure(light).misclassified <= 0.02


def test_the_light_kit_light_that_casts_follows_the_brightest_camera_light(monkeypatch):
    pl = pv.Plotter(off_screen=True, window_size=[300, 200])
    pl.add_mesh(pv.Plane(i_size=6, j_size=6))
    pl.add_mesh(pv.Sphere(center=(0, 0, 1)))
    pl.shadows.enable(**HARD)
    draw(pl)
    _, key, fill, *_ = pl.renderer.lights
    searched, look = [], light_kit.key_light
    monkeypatch.setattr(light_kit, "key_light", lambda r: searched.append(r) or look(r))
    shadows = pl.shadows._renderers[0]
    frame = shadows._frame
    for _ in range(3):
        pl.camera.Azimuth(10)  # the camera lights move: the fill and back lights are planned
        draw(pl)
    assert len(searched) == shadows._frame - frame  # once a frame, not once per camera light
    fill.intensity = 2 * key.intensity
    draw(pl)
    assert [r.technique for r in pl.shadows.last_frame.lights] == [None, None, "map", None, None]
    fill.intensity = key.intensity / 4  # dimmer than the key light again, and than a back light
    key.switch_off()
    draw(pl)
    casting = [r.technique == "map" for r in pl.shadows.last_frame.lights]
    back = max(pl.renderer.lights[3:], key=lambda light: light.intensity)
    assert back.intensity > fill.intensity
    assert casting == [light is back for light in pl.renderer.lights]
    assert pl.shadows.measure(back).misclassified <= 0.02
    fill.intensity = 2 * key.intensity
    draw(pl)
    assert [r.technique for r in pl.shadows.last_frame.lights][1:3] == [None, "map"]
    assert pl.shadows.measure(fill).misclassified <= 0.02


def test_technique_map_refuses_point_lights():
    pl = pv.Plotter(off_screen=True)
    bulb = point_light((0, 0, 3))
    pl.add_light(bulb)
    with pytest.raises(ValueError, match="technique='map' cannot serve this point light"):
        pl.shadows.configure(bulb, technique="map")


@pytest.mark.parametrize("seed", range(3))
def test_a_suns_rotation_is_the_look_rotation_along_it_turned_round_bit_for_bit(seed):
    from pvshadows.geometry.transforms import look_rotation
    from pvshadows.scene.fitting import up_for
    from pvshadows.scene.lights import LightKind, LightPose
    from pvshadows.scene.sun_fitting import sun_rotation

    rng = np.random.default_rng(seed)
    for trial in range(500):
        direction = rng.normal(size=3)
        if trial % 3 == 0:  # near the vertical, where the up vector switches
            direction[:2] *= 10.0 ** rng.uniform(-9, -1)
        direction /= np.linalg.norm(direction)
        expected = look_rotation(direction, up_for(direction))
        expected[::2] *= -1.0  # x and z turned round
        pose = LightPose(LightKind.DIRECTIONAL, np.zeros(3), direction, 90.0)
        assert sun_rotation(pose).tobytes() == expected.tobytes(), trial
