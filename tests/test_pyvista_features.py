"""Shadows stay right with the PyVista features users turn on, over frames that move.

Each case turns one feature on in the standard scene (small window), enables
a technique, then orbits the camera and moves the light for a few frames,
judging every frame against the exact reference on the image actually
produced, with the plain scene's bounds. ``disable()`` must then give the
same pixels as the scene drawn without shadows.
"""

import numpy as np
import pytest
import pyvista as pv

from conftest import draw
from pvshadows.scene.light_kit import key_light
from pvshadows.scene.render_target import SSAA_FACTOR, render_target
from pvshadows.tools.scenes import standard_scene

#: The plain scene's bounds (tests/test_volume.py, test_planar.py, test_maps.py).
BOUNDS = {"volume": 0.003, "planar": 0.005, "cubemap": 0.01, "map": 0.01}

#: Techniques that serve the standard scene's point light.
POINT_TECHNIQUES = ["cubemap", "volume", "planar"]

WINDOW = (320, 240)

#: Frames after the first: camera orbit (degrees) and light move each.
FRAMES = 2


def _ssaa(pl):
    pl.enable_anti_aliasing("ssaa")


def _edl(pl):
    pl.enable_eye_dome_lighting()


def _ssao(pl):
    pl.enable_ssao()


def _depth_peeling(pl):
    pl.enable_depth_peeling()


def _parallel(pl):
    pl.enable_parallel_projection()


def _wireframe_hidden_lines(pl):
    pl.actors["ground"].prop.style = "wireframe"
    pl.actors["ground"].prop.line_width = 2
    pl.enable_hidden_line_removal()


def _wireframe_caster(pl):
    pl.actors["box"].prop.style = "wireframe"


def _edges(pl):
    for name in ("ground", "box", "sphere", "cylinder"):
        pl.actors[name].prop.show_edges = True


FEATURES = {
    "ssaa": _ssaa,
    "eye_dome_lighting": _edl,
    "ssao": _ssao,
    "depth_peeling": _depth_peeling,
    "parallel_projection": _parallel,
    "wireframe_hidden_lines": _wireframe_hidden_lines,
    "wireframe_caster": _wireframe_caster,
    "show_edges": _edges,
}


def _move(scene, step):
    scene.plotter.camera.Azimuth(12.0)
    scene.plotter.camera.Elevation(3.0)
    position = np.asarray(scene.light.position) + np.array([0.25, -0.15, 0.1]) * step
    scene.light.position = tuple(position)
    scene.light.focal_point = tuple(position - np.array([0.0, 0.0, 1.0]))


def _frames(scene):
    """Yield after each frame: the first, then FRAMES frames with camera and light moved."""
    draw(scene.plotter)
    yield
    for step in range(1, FRAMES + 1):
        _move(scene, step)
        draw(scene.plotter)
        yield


def _plain_images(scene, steps):
    """The scene without shadows at each frame's camera and light: (plain, light off)."""
    images = []
    for step in range(steps):
        if step:
            _move(scene, step)
        plain = draw(scene.plotter).astype(np.float64)
        scene.light.intensity = 0.0
        dark = draw(scene.plotter).astype(np.float64)
        scene.light.intensity = 1.0
        images.append((plain, dark))
    return images


def _image_misclassified(shadowed, plain, dark, reference):
    """Share of directly lit pixels whose shadow class in the colour image disagrees.

    The light's own contribution to a pixel is ``plain - dark`` (the frame
    with the light, without it); where it is clearly visible, the shadowed
    frame is dark when less than half of it is left. Image passes that
    recolour by depth (eye-dome lighting, SSAO) shade the three frames alike.
    """
    direct = (plain - dark).mean(axis=-1)
    left = (shadowed.astype(np.float64) - dark).mean(axis=-1)
    judged = (direct > 40.0) & np.isfinite(reference)
    shown_dark = left < 0.5 * direct
    exact_dark = reference < 0.5
    return float((shown_dark != exact_dark)[judged].mean()), int(judged.sum())


@pytest.mark.parametrize("technique", POINT_TECHNIQUES)
@pytest.mark.parametrize("feature", list(FEATURES))
def test_feature_keeps_shadows_right_over_moving_frames(feature, technique):
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    FEATURES[feature](pl)
    camera, light = pl.camera_position, scene.light.position
    plain = draw(pl)
    pl.shadows.enable(technique=technique)
    for _ in _frames(scene):
        error = pl.shadows.measure(scene.light)
        assert error.lit_pixels > 5_000, error
        assert error.misclassified <= BOUNDS[technique], error
        assert pl.shadows.last_frame.lights[0].technique == technique
    pl.camera_position, scene.light.position = camera, light
    scene.light.focal_point = tuple(np.asarray(light) - [0.0, 0.0, 1.0])
    pl.shadows.disable()
    assert np.array_equal(draw(pl), plain)


@pytest.mark.parametrize(
    "feature", ["ssaa", "eye_dome_lighting", "ssao", "parallel_projection", "show_edges"]
)
def test_spot_light_maps_stay_right_with_features(feature):
    scene = standard_scene(window_size=WINDOW, light="spot", cone_angle=50.0)
    pl = scene.plotter
    FEATURES[feature](pl)
    camera, light = pl.camera_position, (scene.light.position, scene.light.focal_point)
    plain = draw(pl)
    pl.shadows.enable(technique="map")
    for _ in _frames(scene):
        error = pl.shadows.measure(scene.light)
        assert error.lit_pixels > 5_000, error
        assert error.misclassified <= BOUNDS["map"], error
        assert pl.shadows.last_frame.lights[0].technique == "map"
    pl.camera_position = camera
    scene.light.position, scene.light.focal_point = light
    pl.shadows.disable()
    assert np.array_equal(draw(pl), plain)


@pytest.mark.parametrize("technique", ["volume", "planar"])
@pytest.mark.parametrize("feature", ["eye_dome_lighting", "ssao"])
def test_image_passes_show_the_shadows_in_the_picture(feature, technique):
    """The probe frame leaves image passes out, so judge the picture itself too."""
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    FEATURES[feature](pl)
    plains = _plain_images(scene, FRAMES + 1)
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    FEATURES[feature](pl)
    pl.shadows.enable(technique=technique)
    for (plain, dark), _ in zip(plains, _frames(scene), strict=True):
        shadowed = pl.screenshot(return_img=True)
        wrong, judged = _image_misclassified(shadowed, plain, dark, pl.shadows.reference())
        assert judged > 5_000
        assert wrong <= 0.01, f"{100 * wrong:.2f} % of {judged} lit pixels"


@pytest.mark.parametrize(
    ("scale", "technique"), [(2, "cubemap"), (2, "volume"), (2, "planar"), (3, "volume")]
)
def test_scaled_screenshots_are_right_in_every_tile(scale, technique):
    scene = standard_scene(window_size=(200, 150))
    pl = scene.plotter
    pl.shadows.enable(technique=technique)
    for _ in _frames(scene):
        error = pl.shadows.measure(scene.light, scale=scale)
        assert error.lit_pixels > 5_000 * scale, error
        assert error.misclassified <= BOUNDS[technique], error
    image = pl.screenshot(return_img=True, scale=scale)
    assert image.shape[:2] == (150 * scale, 200 * scale)
    assert pl.shadows.visibility(scene.light, scale=scale).shape == image.shape[:2]


def test_ssaa_masks_are_built_in_the_larger_framebuffer():
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    pl.enable_anti_aliasing("ssaa")
    pl.shadows.enable(technique="volume")
    draw(pl)
    target = render_target(pl.renderer)
    assert target.size == (int(WINDOW[0] * SSAA_FACTOR), int(WINDOW[1] * SSAA_FACTOR))
    mask = pl.shadows._renderers[0].technique("volume").mask_of(scene.light)
    assert mask.size == target.size


def test_subplots_and_a_resized_window_stay_right():
    pl = pv.Plotter(shape=(1, 2), off_screen=True, window_size=[480, 240], lighting="none")
    lights = []
    for column in range(2):
        pl.subplot(0, column)
        pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white")
        pl.add_mesh(pv.Sphere(center=(0.5 * column, 0, 1.2)), color="white")
        pl.add_mesh(pv.Cube(center=(-1.5, 1.0, 0.6)), color="white")
        light = pv.Light(position=(0.5, -0.5, 3.5), positional=True, cone_angle=180)
        pl.add_light(light)
        lights.append(light)
        pl.camera_position = [(7, -8, 6), (0, 0, 0.3), (0, 0, 1)]
    pl.shadows.enable()
    for light, technique in zip(lights, ["volume", "cubemap"], strict=True):
        pl.shadows.configure(light, technique=technique)
    for size, frames in (([480, 240], 2), ([360, 300], 1)):
        pl.window_size = size
        for _ in range(frames):
            for renderer in pl.renderers:
                renderer.GetActiveCamera().Azimuth(15.0)
            draw(pl)
            for light, technique in zip(lights, ["volume", "cubemap"], strict=True):
                error = pl.shadows.measure(light)
                assert error.lit_pixels > 3_000, error
                assert error.misclassified <= BOUNDS[technique], (technique, size, error)


@pytest.mark.parametrize("technique", ["map", "volume", "planar"])
def test_light_kit_key_light_casts_as_the_camera_orbits(technique):
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    pl.remove_all_lights()
    pl.enable_lightkit()
    camera = pl.camera_position
    plain = draw(pl)
    pl.shadows.enable(technique=technique)
    key = key_light(pl.renderer)
    for step in range(3):
        pl.camera.Azimuth(20.0 * step)
        draw(pl)
        casting = [r.index for r in pl.shadows.last_frame.lights if r.technique]
        assert casting == [1]  # the key light; head, fill and back lights cast nothing
        error = pl.shadows.measure(key)
        assert error.misclassified <= BOUNDS[technique], error
    pl.camera_position = camera
    pl.shadows.disable()
    assert np.array_equal(draw(pl), plain)


@pytest.mark.parametrize("scale", [0, -2])
def test_measure_refuses_a_scale_below_one(scene, scale):
    scene.plotter.shadows.enable()
    with pytest.raises(ValueError, match="scale must be 1 or more"):
        scene.plotter.shadows.measure(scene.light, scale=scale)


@pytest.mark.parametrize("scale", [1.5, "2", True])
def test_visibility_refuses_a_scale_that_is_not_an_int(scene, scale):
    scene.plotter.shadows.enable()
    with pytest.raises(TypeError, match="scale must be an int"):
        scene.plotter.shadows.visibility(scene.light, scale=scale)


def _grid_on_ground(spacing=0.8, height=0.12):
    xs = np.arange(-4.0, 4.01, spacing)
    return np.array([[x, y, height] for x in xs for y in xs])


def _pixels_of(pl, points):
    """Pixel (row from the top, column) of each world point."""
    renderer = pl.renderer
    height = renderer.GetSize()[1]
    out = []
    for point in points:
        renderer.SetWorldPoint(*point, 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        out.append((height - 1 - round(y), round(x)))
    return np.array(out)


@pytest.mark.parametrize("style", ["spheres", "tubes"])
def test_point_clouds_and_tubes_receive_from_a_cube_map_and_cast_nothing(style):
    scene = standard_scene(window_size=WINDOW)
    pl = scene.plotter
    points = _grid_on_ground()
    if style == "spheres":
        cloud = pl.add_points(points, render_points_as_spheres=True, point_size=9, name="cloud")
    else:
        rows = round(np.sqrt(len(points)))
        cells = np.hstack([[rows, *range(r * rows, (r + 1) * rows)] for r in range(rows)])
        cloud = pl.add_mesh(
            pv.PolyData(points, lines=cells), render_lines_as_tubes=True, line_width=7, name="cloud"
        )
    pl.shadows.enable(technique="cubemap")
    draw(pl)
    exact = pl.shadows.reference(scene.light)  # the ground and objects: the cloud casts nothing
    pl.shadows.set_caster(cloud, False)
    assert np.array_equal(pl.shadows.reference(scene.light), exact, equal_nan=True)
    shadowed = draw(pl).astype(np.float64).mean(axis=-1)
    notes = [note for note in pl.shadows.last_frame.lights[0].notes if "without triangles" in note]
    assert notes == ["points or lines without triangles receive, cast nothing: actor 'cloud'"]
    pl.shadows.disable()
    plain = draw(pl).astype(np.float64).mean(axis=-1)
    agree = judged = dark = 0
    for row, col in _pixels_of(pl, points):
        if not (2 <= row < WINDOW[1] - 2 and 2 <= col < WINDOW[0] - 2):
            continue
        around = exact[row - 2 : row + 3, col - 2 : col + 3] < 0.5
        if plain[row, col] < 90 or around.min() != around.max():
            continue  # not lit enough by the light to tell, or at a shadow's edge
        judged += 1
        dark += int(around[0, 0])
        agree += (shadowed[row, col] < 0.7 * plain[row, col]) == around[0, 0]
    assert judged >= 20
    assert dark >= 3
    assert agree == judged
