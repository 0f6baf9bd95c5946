"""The planner: only what the scene calls for costs a pass. Asserted by counting passes."""

import numpy as np
import pytest
import pyvista as pv

from conftest import draw, point_light
from pvshadows.pipeline.cube_passes import SIX_PASSES_FROM
from pvshadows.tools.scenes import (
    crowd_scene,
    eight_spots_scene,
    spot_light,
    standard_scene,
    three_lights_scene,
)


def test_eight_lights_of_which_six_reach_no_visible_receiver_run_the_passes_of_two():
    pl, lights = eight_spots_scene()
    pl.shadows.enable(filter="hard")
    draw(pl)
    frame = pl.shadows.last_frame
    assert frame.passes_run == 2
    casting = [r for r in frame.lights if r.technique is not None]
    assert len(casting) == 2
    idle = [r for r in frame.lights[1:] if r.technique is None]
    assert len(idle) == 6
    assert all(
        "no receiver the camera sees is in the light's reach" in " ".join(r.notes) for r in idle
    )
    for light in lights[:2]:
        assert pl.shadows.measure(light).misclassified <= 0.01


def test_static_scene_from_a_new_camera_runs_no_depth_pass():
    pl, lights = three_lights_scene()
    pl.shadows.enable(filter="hard")
    draw(pl)
    assert pl.shadows.last_frame.passes_run == 3
    for azimuth in (20, 20, -50):
        pl.camera.azimuth = azimuth
        pl.camera.elevation = 5
        draw(pl)
        frame = pl.shadows.last_frame
        assert frame.passes_run == 0
        assert all(p.status == "reused" for r in frame.lights for p in r.passes)
    for light in lights:
        assert pl.shadows.measure(light).misclassified <= 0.01


def test_spot_over_two_hundred_actors_draws_only_those_in_its_cone():
    pl, light, centres = crowd_scene()
    pl.shadows.enable(filter="hard")
    draw(pl)
    report = pl.shadows.last_frame.lights[0]
    drawn = int(report.passes[0].detail.split()[0])
    inside = np.degrees(np.arctan2(np.hypot(centres[:, 0], centres[:, 1]), 20 - 0.6))
    assert drawn <= (inside < 24).sum() + 1  # the ground and the spheres near the cone
    assert drawn >= (inside < 18).sum() + 1
    assert drawn < 40
    assert pl.shadows.measure(light).misclassified <= 0.01


@pytest.mark.parametrize(
    ("quality", "technique", "bound"),
    [("draft", "cubemap", 0.01), ("balanced", "cubemap", 0.01), ("exact", "volume", 0.003)],
)
def test_quality_presets_choose_their_point_on_the_frontier(quality, technique, bound):
    scene = standard_scene(window_size=(400, 300))
    pl = scene.plotter
    pl.shadows.enable(quality=quality)
    draw(pl)
    report = pl.shadows.last_frame.lights[0]
    assert report.technique == technique
    assert f"quality={quality!r}" in " ".join(report.notes) or quality == "exact"
    assert pl.shadows.measure(scene.light).misclassified <= bound


def test_explicit_settings_win_over_the_preset():
    scene = standard_scene(window_size=(200, 150))
    pl = scene.plotter
    pl.shadows.enable(quality="draft", resolution=256)
    settings = pl.shadows.settings(scene.light)
    assert (settings.quality, settings.resolution, settings.filter) == ("draft", 256, "hard")
    pl.shadows.configure(scene.light, quality="balanced")
    assert pl.shadows.settings(scene.light).filter == "pcf"
    with pytest.raises(ValueError, match="quality='perfect' is not allowed"):
        pl.shadows.enable(quality="perfect")


def test_a_light_with_no_caster_in_reach_costs_nothing():
    pl = pv.Plotter(off_screen=True, window_size=[300, 200], lighting="none")
    pl.add_mesh(pv.Plane(i_size=10, j_size=10))
    pl.add_mesh(pv.Sphere(center=(4, 4, 1)))
    light = spot_light((-3, -3, 4), (-3, -3, 0), cone_angle=10, intensity=1.0)
    pl.add_light(light)
    pl.shadows.enable()
    draw(pl)
    report = pl.shadows.last_frame.lights[0]
    assert report.technique == "map"  # the ground itself is a caster in the cone
    pl.shadows.set_caster(pl.renderer.actors[next(iter(pl.renderer.actors))], False)
    draw(pl)
    report = pl.shadows.last_frame.lights[0]
    assert report.technique is None and report.passes == []
    assert "no caster is in the light's reach" in " ".join(report.notes)


def test_point_light_faces_without_casters_are_explained():
    pl = pv.Plotter(off_screen=True, window_size=[300, 200], lighting="none")
    pl.add_mesh(pv.Plane(center=(0, 0, -1), i_size=10, j_size=10))
    light = point_light((0, 0, 0))
    pl.add_light(light)
    pl.shadows.enable(technique="cubemap")
    draw(pl)
    detail = pl.shadows.last_frame.lights[0].passes[0].detail
    assert "skipped (no caster in frustum)" in detail


@pytest.mark.parametrize("light", ["point", "spot", "directional"])
def test_auto_picks_planar_only_when_the_only_receiver_is_one_plane(light):
    scene = standard_scene(light=light, window_size=(400, 300))
    pl = scene.plotter
    pl.shadows.enable()
    draw(pl)
    assert pl.shadows.last_frame.lights[0].technique != "planar"  # objects shadow each other
    for actor in (scene.box, scene.sphere, scene.cylinder):
        pl.shadows.set_receiver(actor, False)
    draw(pl)
    report = pl.shadows.last_frame.lights[0]
    assert report.technique == "planar"
    assert "the only receiver is one plane" in " ".join(report.notes)
    assert pl.shadows.measure(scene.light).misclassified <= 0.005


def test_the_planner_decides_what_a_volume_light_casts_before_it_draws():
    """Closed casters, open casters' fallback and z-pass or z-fail, from the plan alone."""
    from pvshadows.pipeline.planner import plan_frame

    def volume_plan(pl, light, gpu=True):
        pl.shadows.enable(technique="volume")
        snapshot = pl.shadows._reader.read(pl.renderer)
        settings = pl.shadows.settings(light)
        (plan,) = plan_frame(pl.renderer, snapshot, lambda _: settings, extrude_on_gpu=lambda: gpu)
        assert plan.technique == "volume"
        return plan.cast

    scene = standard_scene()
    bowl = pv.Sphere(center=(3, -3, 1)).clip(normal="z", origin=(3, -3, 1))
    bowl_actor = scene.plotter.add_mesh(bowl, name="bowl")
    with pytest.warns(UserWarning, match="'bowl'.*cubemap shadow map instead"):
        plan = volume_plan(scene.plotter, scene.light)
    closed = [caster.actor for caster, _ in plan.volume.closed]
    assert bowl_actor not in closed and len(closed) == 4
    name, subplan = plan.volume.fallback
    assert name == "cubemap" and [c.actor for c in subplan.casters] == [bowl_actor]
    assert plan.volume.zmode == "zpass" and plan.volume.enclosing is None
    assert plan.volume.extrude == "gpu"

    in_the_box_shadow = [(-2.9, -0.35, 0.9), (-4.5, -0.5, 0.0), (0.0, 0.0, 1.0)]
    inside = standard_scene(camera=in_the_box_shadow)
    plan = volume_plan(inside.plotter, inside.light, gpu=False)
    assert plan.volume.zmode == "zfail"
    assert any(note.startswith("zfail: the camera may be inside") for note in plan.notes)
    # a window that does not compile the extruding geometry shader: the planner says cpu
    assert plan.volume.extrude == "cpu"
    assert "the extruding geometry shader does not compile here: cpu extrusion" in plan.notes


def test_the_planner_chooses_the_receiving_plane_of_planar_lights():
    from pvshadows.pipeline.planner import plan_frame

    scene = standard_scene()
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    settings = pl.shadows.settings(scene.light)

    def planned():
        snapshot = pl.shadows._reader.read(pl.renderer)
        (plan,) = plan_frame(pl.renderer, snapshot, lambda _: settings)
        assert plan.technique == "planar" and plan.cast.plane.actor.actor is pl.actors["ground"]
        assert plan.cast.plane.reason in plan.notes
        return plan.cast.plane.reason

    assert planned() == "receiving plane: actor 'ground' (found on its own)"
    pl.shadows.set_receiver(pl.actors["ground"], plane=True)
    assert planned().endswith("(named with set_receiver(plane=True))")


def test_auto_passes_fill_a_cube_of_many_triangles_face_by_face():
    pl = pv.Plotter(off_screen=True, window_size=(200, 150), lighting="none")
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white")
    big = pv.Sphere(radius=1.0, center=(0, 0, 1.5), theta_resolution=260, phi_resolution=260)
    assert big.n_cells >= SIX_PASSES_FROM
    pl.add_mesh(big)
    light = pv.Light(position=(0.5, 0.0, 6.0), positional=True, cone_angle=180)
    pl.add_light(light)
    pl.shadows.enable(filter="hard")
    draw(pl)
    (report,) = pl.shadows.last_frame.lights
    assert report.technique == "cubemap"
    assert all(p.name.startswith("cube face") for p in report.passes)
    assert any("filled one face at a time" in note for note in report.notes)
    # The same scene with a small sphere keeps the one layered draw.
    big.copy_from(pv.Sphere(radius=1.0, center=(0, 0, 1.5)))
    draw(pl)
    (report,) = pl.shadows.last_frame.lights
    assert [p.name for p in report.passes] == ["cube depth (six faces, one draw)"]
    assert pl.shadows.measure(light).misclassified <= 0.05
