"""The pl.shadows component: registration, lifecycle, what each frame runs, lighting kept."""

import subprocess
import sys
import textwrap

import numpy as np
import pyvista as pv

from conftest import draw, point_light
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.timing import MAX_FRAMES_IN_FLIGHT
from pvshadows.tools.scenes import standard_scene


def run_python(code):
    result = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=120
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_entry_point_gives_every_plotter_shadows_without_import():
    out = run_python(
        """
        import sys
        import pyvista as pv
        assert "pvshadows" not in sys.modules
        pl = pv.Plotter(off_screen=True)
        print(type(pl.shadows).__name__, "pvshadows" in sys.modules)
        """
    )
    assert out.split() == ["ShadowsComponent", "True"]


def test_import_registers_the_component():
    out = run_python(
        """
        import pyvista as pv
        import pvshadows
        names = [r.name for r in pv.registered_plotter_components()]
        print(names.count("shadows"))
        """
    )
    assert out.strip() == "1"


def test_disable_gives_pixel_identical_frames_and_releases_everything(scene):
    pl = scene.plotter
    plain = pl.screenshot(return_img=True)
    pl.shadows.enable(filter="pcf")
    shadowed = pl.screenshot(return_img=True)
    assert np.abs(plain.astype(int) - shadowed).max() > 100  # shadows did change the frame
    cube = pl.shadows._renderers[0].technique("cubemap").cube_of(scene.light)
    texture = cube.texture.GetHandle()
    gl = opengl_for(pl.ren_win)
    assert gl.glIsTexture(texture)
    pl.shadows.disable()
    pl.ren_win.MakeCurrent()
    assert not gl.glIsTexture(texture)
    assert np.array_equal(pl.screenshot(return_img=True), plain)
    for actor in (scene.ground, scene.box, scene.sphere, scene.cylinder):
        prop = actor.GetShaderProperty()
        assert prop.GetNumberOfShaderReplacements() == 0
        assert prop.GetFragmentCustomUniforms().GetNumberOfUniforms() == 0
    assert not pl.renderer.HasObserver("StartEvent")
    assert not pl.shadows.enabled


def test_shadow_removes_only_that_lights_diffuse_and_specular():
    """In the shadow of light A, a pixel looks as if A were off; other lights and ambient stay."""

    def build(with_a=True):
        scene = standard_scene(window_size=(400, 300))
        pl = scene.plotter
        sun = pv.Light(position=(-3, 2, 6), focal_point=(0, 0, 0), intensity=0.5)
        pl.add_light(sun)
        scene.light.switch = with_a
        return scene, pl

    scene, pl = build()
    plain = pl.screenshot(return_img=True).astype(int)
    pl.shadows.enable(filter="hard", lights=[scene.light])
    shadowed = pl.screenshot(return_img=True).astype(int)
    vis = pl.shadows.visibility(scene.light)
    _, without_a = build(with_a=False)
    off = without_a.screenshot(return_img=True).astype(int)
    # Away from edges: erode the shadow and lit masks by 2 pixels.
    dark = np.isfinite(vis) & (vis == 0)
    lit = np.isfinite(vis) & (vis == 1)
    for _ in range(2):
        dark[1:-1, 1:-1] &= dark[:-2, 1:-1] & dark[2:, 1:-1] & dark[1:-1, :-2] & dark[1:-1, 2:]
        lit[1:-1, 1:-1] &= lit[:-2, 1:-1] & lit[2:, 1:-1] & lit[1:-1, :-2] & lit[1:-1, 2:]
    assert dark.sum() > 1000 and lit.sum() > 10000
    assert np.abs(shadowed[dark] - off[dark]).max() <= 2
    assert np.abs(shadowed[lit] - plain[lit]).max() <= 2
    assert off[dark].mean() > 20  # ambient and the other light still light the shadow


def test_receivers_keep_their_scalars_textures_and_pbr():
    pl = pv.Plotter(off_screen=True, window_size=[400, 300], lighting="none")
    plane = pv.Plane(i_size=6, j_size=6).texture_map_to_plane()
    plane["height"] = plane.points[:, 0]
    textured = pl.add_mesh(
        plane,
        texture=pv.Texture(np.random.default_rng(0).integers(0, 255, (8, 8, 3), dtype=np.uint8)),
        ambient=0.2,
    )
    sphere = pl.add_mesh(pv.Sphere(center=(1, 1, 1)), scalars=pv.Sphere().points[:, 2], ambient=0.2)
    metal = pl.add_mesh(
        pv.Cube(center=(-1.5, -1, 0.6)), pbr=True, metallic=0.3, roughness=0.4, color="orange"
    )
    light = point_light((0.2, 0.1, 4))
    pl.add_light(light)
    pl.camera_position = [(6, -7, 6), (0, 0, 0), (0, 0, 1)]
    plain = pl.screenshot(return_img=True).astype(int)
    pl.shadows.enable(filter="hard")
    shadowed = pl.screenshot(return_img=True).astype(int)
    vis = pl.shadows.visibility(light)
    lit = np.isfinite(vis) & (vis == 1)
    lit[1:-1, 1:-1] &= lit[:-2, 1:-1] & lit[2:, 1:-1] & lit[1:-1, :-2] & lit[1:-1, 2:]
    assert np.abs(shadowed[lit] - plain[lit]).max() <= 2
    error = pl.shadows.measure(light)
    assert error.misclassified <= 0.01
    assert all(
        a.GetShaderProperty().GetNumberOfShaderReplacements() > 0 for a in (textured, sphere, metal)
    )


def test_four_point_lights_each_cast_their_own_shadows():
    scene = standard_scene(window_size=(400, 300))
    pl = scene.plotter
    scene.light.intensity = 0.4
    extra = [point_light(p, intensity=0.4) for p in [(-3, -3, 3), (3, 3, 2.5), (-2, 3, 4)]]
    for light in extra:
        pl.add_light(light)
    pl.shadows.enable(filter="hard")
    draw(pl)
    frame = pl.shadows.last_frame
    assert [light.technique for light in frame.lights] == ["cubemap"] * 4
    for light in [scene.light, *extra]:
        assert pl.shadows.measure(light).misclassified <= 0.01


def test_static_scene_reuses_the_map_and_a_moved_light_is_followed(scene):
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    assert pl.shadows.last_frame.passes_run == 1
    pl.camera.azimuth = 30
    pl.render()
    frame = pl.shadows.last_frame
    assert frame.passes_run == 0
    assert frame.lights[0].passes[0].status == "reused"
    assert pl.shadows.measure(scene.light).misclassified <= 0.01
    before = pl.shadows.visibility(scene.light)
    scene.light.position = (-1.5, 1.0, 3.0)
    pl.render()
    assert pl.shadows.last_frame.passes_run == 1
    after = pl.shadows.visibility(scene.light)
    assert np.nanmean(before != after) > 0.01
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_a_mesh_added_after_enable_casts_and_receives(scene):
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    before = pl.shadows.visibility(scene.light)
    cone = pv.Cone(center=(-1.5, -2.5, 0.6), direction=(0, 0, 1), height=1.2, radius=0.5)
    pl.add_mesh(cone, name="cone")
    draw(pl)
    after = pl.shadows.visibility(scene.light)
    newly_dark = np.isfinite(before) & (before == 1) & (after == 0)
    assert newly_dark.sum() > 2000  # the cone's shadow on the ground
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_a_light_that_is_off_or_dark_costs_nothing(scene):
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    for change in ({"switch": False}, {"intensity": 0.0}):
        scene.light.switch, scene.light.intensity = True, 1.0
        for name, value in change.items():
            setattr(scene.light, name, value)
        pl.render()
        report = pl.shadows.last_frame.lights[0]
        assert report.technique is None
        assert report.passes == []
        assert "costs nothing" in " ".join(report.notes)


def test_cube_faces_without_casters_are_not_rendered():
    pl = pv.Plotter(off_screen=True, window_size=[300, 200], lighting="none")
    pl.add_mesh(pv.Box(bounds=(2, 3, -0.5, 0.5, -0.5, 0.5)))
    pl.add_mesh(pv.Plane(center=(5, 0, 0), direction=(-1, 0, 0), i_size=6, j_size=6))
    light = point_light((0, 0, 0))
    pl.add_light(light)
    pl.camera_position = [(-4, -6, 3), (3, 0, 0), (0, 0, 1)]
    pl.shadows.enable(filter="hard", passes="six")
    draw(pl)
    passes = pl.shadows.last_frame.lights[0].passes
    assert [p.status for p in passes] == ["run"] + ["skipped"] * 5
    pl.shadows.configure(light, passes="single")
    detail = pl.shadows.last_frame.lights[0].passes[0].detail
    assert detail.startswith("faces drawn: +X;")
    assert pl.shadows.measure(light).misclassified <= 0.01


def test_set_caster_and_set_receiver(scene):
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    pl.shadows.set_caster(scene.box, False)
    pl.render()
    without_box = pl.shadows.visibility(scene.light)
    assert pl.shadows.measure(scene.light).misclassified <= 0.01
    pl.shadows.set_caster(scene.box, True)
    pl.shadows.set_receiver(scene.ground, False)
    pl.render()
    no_ground = pl.shadows.visibility(scene.light)
    assert np.isnan(no_ground).sum() > np.isnan(without_box).sum() + 100_000
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_last_frame_prints_what_ran(scene):
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    report = pl.shadows.last_frame
    for _ in range(MAX_FRAMES_IN_FLIGHT):  # GPU times arrive without stalling, frames later
        draw(pl)
    assert pl.shadows.last_frame.frame == report.frame + MAX_FRAMES_IN_FLIGHT
    assert report.gpu_ready
    text = str(report)
    assert "light 0 (point): cubemap" in text
    assert " ms " in text
    ms = report.lights[0].passes[0].ms
    assert ms is not None and 0 < ms < 10_000


def test_close_releases_the_component(scene):
    pl = scene.plotter
    pl.shadows.enable()
    pl.screenshot(return_img=True)
    pl.close()
    assert not pl.shadows.enabled


def test_subplots_each_with_its_own_light_and_technique():
    """Each subplot is a renderer with its own lights: each measures like a plotter of its own."""

    def build(pl, light):
        pl.add_mesh(pv.Plane(i_size=9, j_size=9), color="white")
        pl.add_mesh(pv.Sphere(radius=0.55, center=(-1.2, 0.3, 1.5)), color="white")
        pl.add_light(light, only_active=True)
        pl.camera_position = [(0.0, -8.0, 8.0), (-0.6, 1.0, 0.3), (0, 0, 1)]

    def lights():
        sun = pv.Light(position=(3, -2, 5), focal_point=(0, 0, 0))
        return [point_light((2.2, -1.2, 4.0)), sun]

    techniques = ["cubemap", "map"]
    pl = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(640, 300), lighting="none")
    for column, light in enumerate(lights_in_subplots := lights()):
        pl.subplot(0, column)
        build(pl, light)
    pl.shadows.enable(filter="hard")
    for light, technique in zip(lights_in_subplots, techniques, strict=True):
        pl.shadows.configure(light, technique=technique)
    draw(pl)
    text = str(pl.shadows.last_frame)
    assert "subplot (0, 0), light 0 (point): cubemap" in text
    assert "subplot (0, 1), light 0 (directional): map" in text
    for column, technique in enumerate(techniques):
        alone = pv.Plotter(off_screen=True, window_size=(320, 300), lighting="none")
        light = lights()[column]
        build(alone, light)
        alone.shadows.enable(filter="hard", technique=technique)
        expected = alone.shadows.measure(light)
        measured = pl.shadows.measure(lights_in_subplots[column])
        assert measured.lit_pixels == expected.lit_pixels
        assert abs(measured.misclassified - expected.misclassified) <= 1e-3
        assert expected.misclassified <= 0.01
        alone.close()
