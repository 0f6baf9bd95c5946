"""Stencil shadow volumes against exact ray-cast visibility, on the same frame."""

import warnings

import numpy as np
import pytest
import pyvista as pv
from pyvista import examples

from conftest import draw, point_light
from pvshadows.geometry import volume_casters
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.timing import MAX_FRAMES_IN_FLIGHT
from pvshadows.shaders.shading import LightShading
from pvshadows.tools.scenes import standard_scene

#: The issue's bound for pixel-exact hard shadows.
EXACT = 0.003

#: A camera standing in the box's shadow, looking at the ground behind it.
IN_THE_BOX_SHADOW = ((-2.9, -0.35, 0.9), (-4.5, -0.5, 0.0), (0.0, 0.0, 1.0))


def volume_light_report(plotter):
    return next(light for light in plotter.shadows.last_frame.lights if light.technique)


def enable(plotter, **settings):
    """Turn volumes on and draw a frame (a plotter never shown draws only on screenshot)."""
    plotter.shadows.enable(technique="volume", **settings)
    draw(plotter)


def measured(scene, light=None, **settings):
    scene.plotter.shadows.enable(technique="volume", **settings)
    return scene.plotter.shadows.measure(light or scene.light)


def assert_no_gl_error(plotter):
    plotter.ren_win.MakeCurrent()
    gl = opengl_for(plotter.ren_win)
    assert gl.glGetError() == gl.GL_NO_ERROR


@pytest.mark.parametrize("zmode", ["zpass", "zfail"])
@pytest.mark.parametrize("extrude", ["gpu", "cpu"])
def test_standard_scene_is_pixel_exact(scene, extrude, zmode):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        error = measured(scene, extrude=extrude, zmode=zmode)
    assert not caught  # a forced z-pass is right here: no warning
    assert error.lit_pixels > 100_000
    assert error.misclassified <= EXACT
    assert scene.plotter.ren_win.GetMultiSamples() > 1  # PyVista's multisampled window
    assert_no_gl_error(scene.plotter)


def test_last_frame_reports_the_passes_and_the_counting(scene):
    pl = scene.plotter
    enable(pl)
    report = volume_light_report(pl)
    assert report.technique == "volume"
    names = [p.name for p in report.passes if p.status == "run"]
    assert names == ["volume depth pre-pass", "stencil count (zpass, gpu extrusion)"]
    for _ in range(MAX_FRAMES_IN_FLIGHT):  # GPU times arrive without stalling, frames later
        draw(pl)
    assert all(p.ms is not None and p.ms >= 0 for p in report.passes)
    assert "zpass: the camera is outside every shadow volume" in report.notes
    assert any("'ground' counted as a two-sided slab" in note for note in report.notes)
    assert pl.shadows._renderers[0].technique("volume").zmode_of(scene.light) == "zpass"
    draw(pl)  # nothing moved: the mask is reused
    assert [p.status for p in volume_light_report(pl).passes] == ["reused"]


def test_camera_inside_a_volume_needs_zfail_and_auto_chooses_it():
    auto = standard_scene(camera=IN_THE_BOX_SHADOW)
    error = measured(auto)
    report = volume_light_report(auto.plotter)
    assert error.lit_pixels > 100_000
    assert error.misclassified <= EXACT
    assert any(note.startswith("zfail: the camera may be inside") for note in report.notes)
    assert "stencil count (zfail, gpu extrusion)" in [p.name for p in report.passes]
    forced = standard_scene(camera=IN_THE_BOX_SHADOW)
    with pytest.warns(UserWarning, match="zmode='zpass', which may miscount here: the camera"):
        wrong = measured(forced, zmode="zpass")
    assert wrong.misclassified > 0.5  # z-pass from inside a volume inverts the count
    assert any(
        note.startswith("zpass: zpass forced by zmode='zpass', although z-pass may miscount")
        for note in volume_light_report(forced.plotter).notes
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        draw(forced.plotter)
    assert not caught  # said once


def test_a_wireframe_caster_is_counted_with_zfail_as_the_camera_sees_into_its_volume():
    scene = standard_scene()
    scene.box.prop.style = "wireframe"  # the ground below the box shows through its faces
    error = measured(scene)
    report = volume_light_report(scene.plotter)
    assert error.lit_pixels > 100_000
    assert error.misclassified <= EXACT
    assert any(
        note.startswith("zfail: actor 'box' is drawn without faces") for note in report.notes
    )
    forced = standard_scene()
    forced.box.prop.style = "wireframe"
    with pytest.warns(UserWarning, match="may miscount here: actor 'box' is drawn without faces"):
        wrong = measured(forced, zmode="zpass")
    assert wrong.misclassified > 0.002  # entering the volume through its light cap is not counted
    forced.plotter.enable_hidden_line_removal()  # the faces hide the inside again
    draw(forced.plotter)
    assert forced.plotter.shadows.measure(forced.light).misclassified <= EXACT


def test_a_caster_turned_to_wireframe_after_enable_is_counted_again():
    scene = standard_scene()
    assert measured(scene).misclassified <= EXACT
    assert "zpass: the camera is outside every shadow volume" in (
        volume_light_report(scene.plotter).notes
    )
    scene.box.prop.style = "wireframe"
    draw(scene.plotter)
    assert scene.plotter.shadows.measure(scene.light).misclassified <= EXACT
    scene.box.prop.style = "surface"
    draw(scene.plotter)
    assert scene.plotter.shadows.measure(scene.light).misclassified <= EXACT


@pytest.mark.parametrize(
    ("scale", "offset", "extrude"),
    [(1e6, (1e6, 1e6, 1e6), "gpu"), (1e6, (1e6, 1e6, 1e6), "cpu"), (1e-4, (0, 0, 0), "gpu")],
    ids=["scaled and translated 1e6 gpu", "scaled and translated 1e6 cpu", "scaled 1e-4"],
)
def test_error_independent_of_scale_and_position(scale, offset, extrude):
    error = measured(standard_scene(scale=scale, offset=offset), extrude=extrude)
    assert error.misclassified <= EXACT


@pytest.mark.parametrize("extrude", ["gpu", "cpu"])
def test_light_a_hundredth_from_a_caster_leaves_no_cracks(extrude):
    # 0.01 above the sphere's surface: its silhouette is a small loop right by the
    # light and its shadow a wide cone over most of the ground. A crack between
    # two side quads would show as a lit ray inside that shadow.
    centre, radius = np.array([1.6, 1.4, 0.7]), 0.7
    direction = np.array([0.6, 0.0, 0.8])
    scene = standard_scene(light_position=centre + (radius + 0.01) * direction)
    error = measured(scene, extrude=extrude)
    shadowed = scene.plotter.shadows.reference(scene.light) < 0.5
    assert shadowed.sum() > 100_000
    assert error.missed_shadow <= 0.0005
    assert error.misclassified <= EXACT


def test_spot_and_directional_lights():
    spot = standard_scene()
    spot.light.cone_angle = 40.0
    spot.light.focal_point = (0.0, 0.0, 0.0)
    assert measured(spot).misclassified <= EXACT
    sun = standard_scene()
    sun.light.positional = False
    sun.light.position, sun.light.focal_point = (3.0, -2.0, 6.0), (0.0, 0.0, 0.0)
    error = measured(sun, extrude="cpu")
    assert error.lit_pixels > 100_000
    assert error.misclassified <= EXACT
    assert volume_light_report(sun.plotter).kind == "directional"


def test_several_lights_each_counted_separately():
    scene = standard_scene(window_size=(480, 360))
    pl = scene.plotter
    second = point_light((-2.5, 2.0, 3.0), intensity=0.6)
    sun = pv.Light(position=(-3, -4, 6), focal_point=(0, 0, 0), intensity=0.4)
    pl.add_light(second)
    pl.add_light(sun)
    enable(pl)
    technique = pl.shadows._renderers[0].technique("volume")
    masks = [technique.mask_of(light) for light in (scene.light, second, sun)]
    assert len({mask.handle for mask in masks}) == 3
    for light in (scene.light, second, sun):
        assert pl.shadows.measure(light).misclassified <= EXACT
    pictures = [mask.read() for mask in masks]
    assert not np.array_equal(pictures[0], pictures[1])


def stacked_plates(count):
    """One actor of ``count`` separate thin boxes under a light: ``count`` nested volumes."""
    pl = pv.Plotter(off_screen=True, window_size=[400, 300], lighting="none")
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white", name="ground")
    plates = [
        pv.Box(bounds=(-0.5, 0.5, -0.5, 0.5, 1.0 + 0.01 * k, 1.005 + 0.01 * k))
        for k in range(count)
    ]
    pl.add_mesh(pv.merge(plates), color="gray", name="stack")
    light = point_light((0.0, 0.0, 6.0))
    pl.add_light(light)
    pl.camera_position = [(0, -7, 3), (0, 0, 0), (0, 0, 1)]
    return pl, light


def test_more_than_255_overlapping_volumes(monkeypatch):
    # Under the stack a light ray crosses 256 plates: an 8-bit count wraps to 0.
    pl, light = stacked_plates(256)
    enable(pl)
    report = volume_light_report(pl)
    assert "257 bodies in 2 batch(es)" in report.passes[-1].detail
    assert pl.shadows.measure(light).misclassified <= EXACT
    # The same frame counted in one batch shows the wrap: the test can fail.
    monkeypatch.setattr(volume_casters, "MAX_BODIES_PER_BATCH", 1000)
    # new points batch them again: the camera, the light or the stack moving keeps the batches
    stack = pl.actors["stack"].mapper.dataset
    stack.points = stack.points + np.array([0.0, 0.0, 1e-4])
    assert pl.shadows.measure(light).missed_shadow > 0.05


def test_airplane_is_open_and_casts_from_a_cube_map_with_a_warning():
    plane = examples.load_airplane()
    pl = pv.Plotter(off_screen=True, window_size=[480, 360], lighting="none")
    pl.add_mesh(pv.Plane(center=(900, 700, -300), i_size=5000, j_size=5000), name="ground")
    pl.add_mesh(plane, color="tan", name="airplane")
    light = point_light((1050, 800, 1800))
    pl.add_light(light)
    pl.camera_position = [(2700, -1500, 2000), (900, 700, -100), (0, 0, 1)]
    with pytest.warns(UserWarning, match="actor 'airplane' is not a closed surface") as caught:
        enable(pl)
    assert "cubemap shadow map instead" in str(caught[0].message)
    report = volume_light_report(pl)
    assert any(p.name.startswith("fallback cube depth") for p in report.passes)
    assert pl.shadows.measure(light).misclassified <= 0.01  # the cube map's accuracy
    with pytest.raises(ValueError, match="actor 'airplane' is not a closed surface"):
        pl.shadows.enable(technique="volume", on_open="raise")


def test_ant_is_closed_and_exact():
    pl = pv.Plotter(off_screen=True, window_size=[480, 360], lighting="none")
    pl.add_mesh(pv.Plane(center=(0, 0, -20), i_size=120, j_size=120), name="ground")
    pl.add_mesh(examples.load_ant(), color="tan", name="ant")
    light = point_light((5, 3, 40))
    pl.add_light(light)
    pl.camera_position = [(60, -70, 60), (0, 0, -10), (0, 0, 1)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        enable(pl, on_open="raise")
    assert not any(p.name.startswith("fallback") for p in volume_light_report(pl).passes)
    assert pl.shadows.measure(light).misclassified <= EXACT


def test_a_hole_cut_in_a_sphere_falls_back_or_raises():
    sphere = pv.Sphere(radius=1.0, center=(0, 0, 1.5), theta_resolution=40, phi_resolution=40)
    holed = sphere.remove_cells(np.flatnonzero(sphere.cell_centers().points[:, 0] > 0.7))
    pl = pv.Plotter(off_screen=True, window_size=[400, 300], lighting="none")
    pl.add_mesh(pv.Plane(i_size=12, j_size=12), name="ground")
    pl.add_mesh(holed, name="holed sphere")
    light = point_light((0.5, 0.3, 4.0))
    pl.add_light(light)
    pl.camera_position = [(5, -6, 5), (0, 0, 0.5), (0, 0, 1)]
    with pytest.raises(ValueError, match=r"actor 'holed sphere' .*boundary edges"):
        pl.shadows.enable(technique="volume", on_open="raise")
    with pytest.warns(UserWarning, match="actor 'holed sphere'"):
        enable(pl, on_open="fallback")
    assert pl.shadows.measure(light).misclassified <= 0.01


def test_directional_fallback_hook(monkeypatch):
    """Open casters under a directional light: no shadow until a map technique is registered."""
    import pvshadows.techniques as techniques
    from pvshadows.pipeline import planner
    from pvshadows.scene.lights import LightKind

    def scene():
        pl = pv.Plotter(off_screen=True, window_size=[320, 240], lighting="none")
        pl.add_mesh(pv.Plane(i_size=10, j_size=10), name="ground")
        bowl = pv.Sphere(center=(0, 0, 1.5)).clip(normal="z", origin=(0, 0, 1.5))
        pl.add_mesh(bowl, name="bowl")
        pl.add_light(pv.Light(position=(1, 1, 5), focal_point=(0, 0, 0)))
        return pl

    monkeypatch.delitem(techniques.TECHNIQUE_CLASSES, "map", raising=False)
    pl = scene()
    with pytest.warns(UserWarning, match="actor 'bowl'.*casts no shadow from directional"):
        enable(pl)
    assert any("no shadow-map fallback" in n for n in volume_light_report(pl).notes)

    class StubMap:
        name = "map"

        def __init__(self, window):
            self.updated = []

        def update(self, plan, context):
            self.updated.append([c.name for c in plan.casters])
            return []

        def shading(self, plan):
            return LightShading(plan.vtk_index, "pvsStub", sources=("shadow_mask.glsl",))

        def activate(self, plan, context, entry):
            return {}

        def end_frame(self):
            pass

        def keep_only(self, plans):
            pass

        def release(self):
            pass

    monkeypatch.setitem(techniques.TECHNIQUE_CLASSES, "map", StubMap)
    monkeypatch.setitem(planner.SERVES, "map", (LightKind.SPOT, LightKind.DIRECTIONAL))
    pl = scene()
    with pytest.warns(UserWarning, match="actor 'bowl'.*from a map shadow map instead"):
        enable(pl)
    technique = pl.shadows._renderers[0].technique("volume")
    assert technique._fallbacks.technique("map").updated[0] == ["actor 'bowl'"]
    plan = pl.shadows._renderers[0].plans[0]
    assert technique.shading(plan).visibility.endswith("* (pvsStub)")


def test_bad_casters_give_the_right_shadow():
    """Zero-area and duplicated triangles, flipped winding: welded and repaired, still exact."""
    box = pv.Box(bounds=(-0.8, 0.8, -0.6, 0.6, 1.0, 2.0)).triangulate()
    faces = box.regular_faces.copy()
    faces[::3] = faces[::3, ::-1]  # inconsistent winding
    faces = np.vstack([faces, faces[:4], [[0, 0, 1], [2, 2, 2]]])  # duplicates, zero area
    bad = pv.PolyData.from_regular_faces(box.points, faces)
    lines = pv.Line((2, 2, 0.5), (3, 3, 2.5))
    pl = pv.Plotter(off_screen=True, window_size=[400, 300], lighting="none")
    pl.add_mesh(pv.Plane(i_size=10, j_size=10), name="ground")
    pl.add_mesh(bad, name="bad box")
    pl.add_mesh(lines, name="lines", show_scalar_bar=False)
    pl.add_mesh(pv.PolyData(np.array([[1.0, -2, 1]])), name="points")
    light = point_light((0.4, 0.2, 4.0))
    pl.add_light(light)
    pl.camera_position = [(6, -8, 7), (0, 0, 0.5), (0, 0, 1)]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        enable(pl)
    report = volume_light_report(pl)
    assert any("'bad box' counted as a closed surface after repair" in n for n in report.notes)
    assert pl.shadows.measure(light).misclassified <= EXACT
    assert_no_gl_error(pl)


def test_light_inside_a_closed_caster_shadows_everything_outside():
    pl = pv.Plotter(off_screen=True, window_size=[320, 240], lighting="none")
    pl.add_mesh(pv.Plane(i_size=10, j_size=10), name="ground")
    pl.add_mesh(pv.Box(bounds=(-1, 1, -1, 1, 0.5, 2.5)), name="room")
    light = point_light((0.1, 0.2, 1.5))
    pl.add_light(light)
    pl.camera_position = [(6, -8, 7), (0, 0, 0.5), (0, 0, 1)]
    enable(pl)
    assert any("inside actor 'room'" in n for n in volume_light_report(pl).notes)
    error = pl.shadows.measure(light)
    assert error.misclassified <= EXACT


def test_stencil_buffer_requested_before_the_first_render_and_not_needed_after():
    fresh = standard_scene(window_size=(320, 240))
    fresh.plotter.shadows.enable(technique="volume")
    assert fresh.plotter.ren_win.GetStencilCapable()
    rendered = standard_scene(window_size=(320, 240))
    rendered.plotter.screenshot(return_img=True)  # the window exists, without stencil
    assert not rendered.plotter.ren_win.GetStencilCapable()
    error = measured(rendered)
    assert error.misclassified <= EXACT


def test_subplots_read_their_own_viewport():
    pl = pv.Plotter(off_screen=True, shape=(1, 2), window_size=[800, 300], lighting="none")
    lights = []
    for col in range(2):
        pl.subplot(0, col)
        pl.add_mesh(pv.Plane(i_size=10, j_size=10))
        pl.add_mesh(pv.Cube(center=(col * 1.0, 0, 1.5)))
        lights.append(point_light((0.3 - col, 0.2, 4.0)))
        pl.add_light(lights[-1], only_active=True)
        pl.camera_position = [(6, -8, 7), (0, 0, 0), (0, 0, 1)]
    pl.shadows.enable(technique="volume")
    for light in lights:
        assert pl.shadows.measure(light).misclassified <= EXACT


def test_show_volumes_draws_over_the_frame_and_goes_away(scene):
    pl = scene.plotter
    enable(pl)
    plain = draw(pl)
    pl.shadows.show_volumes(True)
    shown = draw(pl)
    changed = np.abs(shown.astype(int) - plain).max(axis=2) > 10
    assert 0.05 < changed.mean() < 0.9
    assert_no_gl_error(pl)
    pl.shadows.show_volumes(False)
    assert np.array_equal(draw(pl), plain)
    with pytest.raises(TypeError, match="show must be True or False"):
        pl.shadows.show_volumes("yes")


def test_silhouettes_rebuilt_only_when_the_light_or_a_caster_moves(scene):
    pl = scene.plotter
    enable(pl, extrude="cpu")
    statuses = lambda: {p.name: p.status for p in volume_light_report(pl).passes}  # noqa: E731
    assert statuses()["silhouettes and volumes (cpu)"] == "run"
    pl.camera.azimuth = 5.0
    draw(pl)
    assert statuses()["silhouettes and volumes (cpu)"] == "reused"
    assert statuses()["stencil count (zpass, cpu extrusion)"] == "run"
    scene.sphere.position = (0.2, 0.0, 0.0)
    draw(pl)
    detail = next(p.detail for p in volume_light_report(pl).passes if "cpu)" in p.name)
    assert detail.startswith("1 rebuilt, 3 reused")
    scene.light.position = (0.4, -0.2, 3.5)
    draw(pl)
    detail = next(p.detail for p in volume_light_report(pl).passes if "cpu)" in p.name)
    assert detail.startswith("4 rebuilt")


def test_disable_releases_the_masks(scene):
    pl = scene.plotter
    plain = pl.screenshot(return_img=True)
    enable(pl)
    handle = pl.shadows._renderers[0].technique("volume").mask_of(scene.light).handle
    gl = opengl_for(pl.ren_win)
    assert gl.glIsTexture(handle)
    pl.shadows.disable()
    pl.ren_win.MakeCurrent()
    assert not gl.glIsTexture(handle)
    assert np.array_equal(pl.screenshot(return_img=True), plain)


@pytest.mark.parametrize(
    ("setting", "value", "kind"),
    [
        ("zmode", "zsomething", ValueError),
        ("extrude", "gpu2", ValueError),
        ("on_open", None, TypeError),
    ],
)
def test_settings_are_validated(scene, setting, value, kind):
    with pytest.raises(kind, match=setting):
        scene.plotter.shadows.enable(technique="volume", **{setting: value})


@pytest.mark.parametrize("extrude", ["gpu", "cpu"])
def test_parallel_projection_casts_the_analytic_disk(extrude):
    # A parallel projection cannot draw points at infinity: volumes end beyond the scene.
    height, radius, center_z = 4.0, 0.8, 1.5
    pl = pv.Plotter(off_screen=True, window_size=[300, 300], lighting="none")
    pl.add_mesh(pv.Plane(i_size=12, j_size=12), color="white")
    sphere = pv.Sphere(
        radius=radius, center=(0, 0, center_z), theta_resolution=96, phi_resolution=96
    )
    pl.add_mesh(sphere, color="white")
    light = point_light((0, 0, height))
    pl.add_light(light)
    pl.camera_position = [(0, 0, 20), (0, 0, 0), (0, 1, 0)]
    pl.enable_parallel_projection()
    pl.camera.parallel_scale = 6.0
    enable(pl, extrude=extrude)
    assert any(n.startswith("zpass: parallel projection") for n in volume_light_report(pl).notes)
    shown = pl.shadows.visibility(light)
    n = shown.shape[0]
    coords = (np.arange(n) + 0.5) / n * 12.0 - 6.0
    x, y = np.meshgrid(coords, coords[::-1])
    r = np.hypot(x, y)
    disk = height * np.tan(np.arcsin(radius / (height - center_z)))
    ground = r > radius * 1.02
    inside = ground & (r < disk - 0.05)  # 0.05: a bit more than one pixel (0.04)
    outside = ground & (r > disk + 0.05) & (r < 5.5)
    assert inside.sum() > 1000
    assert np.all(shown[inside] < 0.5)
    assert np.all(shown[outside] > 0.5)


def test_resizing_the_window_resizes_the_masks():
    scene = standard_scene(window_size=(320, 240))
    pl = scene.plotter
    enable(pl)
    pl.window_size = [400, 260]
    draw(pl)
    assert pl.shadows._renderers[0].technique("volume").mask_of(scene.light).size == (400, 260)
    assert pl.shadows.measure(scene.light).misclassified <= EXACT


def test_airplane_under_a_sun_falls_back_to_a_fitted_map():
    pl = pv.Plotter(off_screen=True, window_size=[480, 360], lighting="none")
    pl.add_mesh(pv.Plane(center=(900, 700, -300), i_size=5000, j_size=5000), name="ground")
    pl.add_mesh(examples.load_airplane(), color="tan", name="airplane")
    sun = pv.Light(position=(2900, -300, 2700), focal_point=(900, 700, -300))
    pl.add_light(sun)
    pl.camera_position = [(2700, -1500, 2000), (900, 700, -100), (0, 0, 1)]
    with pytest.warns(UserWarning, match="actor 'airplane' is not a closed surface") as caught:
        enable(pl)
    assert "map shadow map instead" in str(caught[0].message)
    report = volume_light_report(pl)
    assert any(p.name.startswith("fallback map depth") for p in report.passes)
    error = pl.shadows.measure(sun)
    assert error.misclassified <= 0.01
    assert np.nansum(pl.shadows.visibility(sun) < 0.5) > 3_000  # the airplane's shadow
