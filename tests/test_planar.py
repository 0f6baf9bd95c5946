"""Planar projected shadows against exact ray-cast visibility, on the same frame."""

import dataclasses

import numpy as np
import pytest
import pyvista as pv

from conftest import draw, point_light
from pvshadows.geometry.transforms import look_rotation, perspective, translation
from pvshadows.gl.binding import opengl_for
from pvshadows.scene import planes
from pvshadows.scene.reader import SceneReader
from pvshadows.scene.triangles import read_triangles
from pvshadows.techniques import planar
from pvshadows.tools.scenes import standard_scene

#: The issue's bound: lit-side pixels of the ground misclassified.
BOUND = 0.005

#: The standard scene seen from under the ground.
FROM_BELOW = ((11.0, -12.5, -9.5), (0.0, 0.0, -0.3), (0.0, 0.0, 1.0))


def only_ground(scene):
    """The standard scene with the ground as its only receiver."""
    for actor in (scene.box, scene.sphere, scene.cylinder):
        scene.plotter.shadows.set_receiver(actor, False)
    return scene


def measured(scene, light=None):
    scene.plotter.shadows.enable(technique="planar")
    return scene.plotter.shadows.measure(light or scene.light)


def light_report(plotter):
    return next(light for light in plotter.shadows.last_frame.lights if light.technique)


def shadowed_pixels(scene):
    return int((scene.plotter.shadows.reference(scene.light) < 0.5).sum())


@pytest.mark.parametrize("light", ["point", "spot", "directional"])
def test_standard_scene_with_the_ground_as_only_receiver(light):
    scene = only_ground(standard_scene(light=light))
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    draw(pl)
    report = light_report(pl)
    assert report.technique == "planar"
    assert "receiving plane: actor 'ground' (found on its own)" in report.notes
    assert [(p.status, p.detail) for p in report.passes] == [
        ("run", "3 of 4 casters flattened onto actor 'ground'")
    ]
    draw(pl)
    assert [p.status for p in light_report(pl).passes] == ["reused"]
    error = pl.shadows.measure(scene.light)
    assert error.lit_pixels > 100_000
    assert shadowed_pixels(scene) > 10_000
    assert error.misclassified <= BOUND
    pl.camera.azimuth = 5.0  # the mask is screen-space: a new camera draws it again
    draw(pl)
    assert [p.status for p in light_report(pl).passes] == ["run"]
    pl.ren_win.MakeCurrent()
    gl = opengl_for(pl.ren_win)
    assert gl.glGetError() == gl.GL_NO_ERROR


def test_light_below_the_plane_casts_no_shadow_on_it():
    # Seen from above, the ground faces away from a light under it: unlit, nothing drawn.
    scene = only_ground(standard_scene(light_position=(0.3, -0.2, -3.5)))
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    draw(pl)
    report = light_report(pl)
    assert report.passes[0].status == "skipped"
    assert any("faces away from the light" in note for note in report.notes)
    ground = pl.shadows.visibility(scene.light)
    assert np.isfinite(ground).sum() > 100_000
    assert np.nanmax(ground) == 0.0
    # Seen from below, the ground's underside is its lit side: the casters above it cast
    # nothing there, a box hanging under it does.
    scene = only_ground(standard_scene(light_position=(0.3, -0.2, -3.5), camera=FROM_BELOW))
    pl = scene.plotter
    under = pl.add_mesh(pv.Box(bounds=(-1, 0, -1, 0, -2, -1.5)), name="under")
    pl.shadows.set_receiver(under, False)
    pl.shadows.enable(technique="planar")
    draw(pl)
    assert light_report(pl).passes[0].detail == "1 of 5 casters flattened onto actor 'ground'"
    error = pl.shadows.measure(scene.light)
    assert error.lit_pixels > 100_000
    assert error.misclassified <= BOUND
    pl.remove_actor(under)
    shown = pl.shadows.visibility(scene.light)
    assert np.nanmin(shown) == 1.0  # the casters above the plane leave its underside lit


def test_shadow_ends_where_the_plane_ends():
    # A low sun throws the box's and the sphere's shadows past the ground's edge.
    scene = only_ground(standard_scene(light="directional", sun_elevation=15.0))
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    with_shadows = draw(pl).astype(int)
    ground = np.isfinite(pl.shadows.visibility(scene.light))
    mask = pl.shadows._renderers[0].technique("planar").mask_of(scene.light).read()[::-1]
    pl.shadows.disable()
    without = draw(pl).astype(int)
    changed = np.abs(with_shadows - without).max(axis=2) > 2
    near_ground = ground.copy()  # anti-aliased edges may change a little, nothing beyond
    for axis in (0, 1):
        for step in (-1, 1):
            near_ground |= np.roll(ground, step, axis=axis)
    assert ((mask == 0) & ~near_ground).sum() > 5_000  # flattened beyond the ground ...
    assert changed.sum() > 10_000
    assert not (changed & ~near_ground).any()  # ... and not shown there


@pytest.mark.parametrize(
    "light",
    [{"light_position": (0.3, -0.2, 0.02)}, {"light": "directional", "sun_elevation": 1.0}],
    ids=["point light 0.02 above the ground", "sun 1 degree above the horizon"],
)
def test_light_almost_in_the_plane(light):
    # Only what lies below the light's height casts: long thin shadows to the
    # ground's edge and beyond.
    scene = only_ground(standard_scene(**light))
    error = measured(scene)
    assert shadowed_pixels(scene) > 10_000
    assert error.misclassified <= BOUND


def test_flattening_in_float32_a_million_units_away():
    offset = np.array([1e6, -1e6, 1e6])
    ground = np.array([0.0, 0.0, 1.0, -offset[2]])
    bulb = np.append(offset + np.array([0.3, -0.2, 3.5]), 1.0)
    eye = offset + np.array([11.0, -12.5, 9.5])
    view = look_rotation(offset - eye, np.array([0.0, 0.0, 1.0])) @ translation(-eye)
    projection = perspective(30.0, 4.0 / 3.0, 1.0, 100.0)
    model = translation(offset + np.array([1.6, 1.4, 0.7]))  # a sphere's centre
    sphere = pv.Sphere(radius=0.7).points.astype(np.float64)
    points = np.vstack([sphere, [[0.0, 0.0, 3.0], [0.5, 0.0, -1.0]]])  # above the light, buried
    flats = planar.FlatCasters([], *planar.flatten_models(model[None], ground, bulb))
    to_clip = flats.to_clip(projection @ view)[0]
    plane, w = flats.planes_model[0], flats.flat_ws[0]
    homogeneous = np.hstack([points, np.ones((len(points), 1))])
    # The GPU's float32 arithmetic ...
    clip = homogeneous.astype(np.float32) @ to_clip.astype(np.float32).T
    shown = clip[:, :2] / clip[:, 3:]
    # ... against the line from the light through each point meeting the plane, in float64.
    height = points[:, 2] + 0.7
    world = points + np.array([1.6, 1.4, 0.7])
    light = bulb[:3] - offset
    meets = light + (world - light) * (3.5 / (3.5 - height))[:, None]
    exact = (projection @ view @ translation(offset) @ np.hstack([meets, homogeneous[:, 3:]]).T).T
    exact = exact[:, :2] / exact[:, 3:]
    np.testing.assert_allclose(shown[:-2], exact[:-2], atol=2e-6)
    np.testing.assert_allclose(homogeneous @ plane, height, atol=1e-9)  # clip distance 0
    assert (homogeneous[:-2] @ w > 0).all()
    assert homogeneous[-2] @ w < 0  # beyond the light's height: clipped (no anti-shadow)
    assert homogeneous[-1] @ plane < 0  # under the plane: clipped


def test_caster_crossing_the_plane_casts_only_above_it(monkeypatch):
    pl = pv.Plotter(off_screen=True, window_size=[480, 360], lighting="none")
    pl.add_mesh(pv.Plane(i_size=12, j_size=12), name="ground")
    pole = pv.Cylinder(center=(0, 0, 0), direction=(1, 0, 1), radius=0.3, height=5.0)
    pl.shadows.set_receiver(pl.add_mesh(pole, name="pole"), False)
    light = point_light((-3.0, 0.5, 4.0))
    pl.add_light(light)
    pl.camera_position = [(-2, -9, 6), (0, 0, 0), (0, 0, 1)]
    pl.shadows.enable(technique="planar")
    error = pl.shadows.measure(light)
    assert error.misclassified <= BOUND
    assert error.false_shadow <= 0.0005
    # Unclipped, the buried half lands between the pole's foot and the light.
    flat_draws = planar.flat_draws

    def unclipped(*args):
        draws = flat_draws(*args)
        (name, planes), *others = draws.vectors
        lowered = np.ascontiguousarray(planes + np.float32([0.0, 0.0, 0.0, 100.0]))
        return dataclasses.replace(draws, vectors=((name, lowered), *others))

    monkeypatch.setattr(planar, "flat_draws", unclipped)
    pl.camera.azimuth = 1.0
    assert pl.shadows.measure(light).false_shadow > 0.005


@pytest.mark.parametrize(
    ("scale", "offset"),
    [(1.0, (1e6, 1e6, 1e6)), (1e6, (1e6, 1e6, 1e6)), (1e-4, (0, 0, 0))],
    ids=["translated 1e6", "scaled and translated 1e6", "scaled 1e-4"],
)
def test_error_independent_of_scale_and_position(scale, offset):
    scene = only_ground(standard_scene(scale=scale, offset=offset))
    assert measured(scene).misclassified <= BOUND
    assert shadowed_pixels(scene) > 10_000


def test_tilted_ground_actor_in_a_parallel_projection():
    scene = only_ground(standard_scene(light="spot"))
    scene.ground.rotate_x(15.0)
    scene.ground.position = (0.0, 0.0, -0.9)
    scene.plotter.enable_parallel_projection()
    assert measured(scene).misclassified <= BOUND
    assert shadowed_pixels(scene) > 10_000


def test_overlapping_casters_do_not_darken_twice():
    pl = pv.Plotter(off_screen=True, window_size=[480, 360], lighting="none")
    pl.add_mesh(
        pv.Plane(i_size=12, j_size=12), color="white", ambient=0.3, specular=0.0, name="ground"
    )
    low = pl.add_mesh(pv.Box(bounds=(1, 3, -1, 0.5, 1, 1.05)), name="low")
    high = pl.add_mesh(pv.Box(bounds=(2.5, 4.5, -0.5, 1, 2, 2.05)), name="high")
    for plate in (low, high):
        pl.shadows.set_receiver(plate, False)
    sun = pv.Light(position=(1, 0, 1), focal_point=(0, 0, 0), intensity=0.9)
    pl.add_light(sun)
    pl.camera_position = [(-6, -6, 8), (1, 0, 0), (0, 0, 1)]
    pl.shadows.enable(technique="planar")
    image = draw(pl).astype(int)

    def pixel(x, y):
        renderer = pl.renderer
        renderer.SetWorldPoint(x, y, 0.0, 1.0)
        renderer.WorldToDisplay()
        col, row = (round(v) for v in renderer.GetDisplayPoint()[:2])
        return image[image.shape[0] - 1 - row, col]

    # The sun shifts each plate's shadow by its height: the low one covers x in
    # [0, 2], y in [-1, 0.5], the high one x in [0.5, 2.5], y in [-0.5, 1].
    twice, once, lit = pixel(1.2, 0.0), pixel(0.25, -0.75), pixel(-1.5, -1.5)
    assert lit.sum() > once.sum() + 200
    assert once.sum() > 150  # ambient light stays in the shadow: a second darkening would show
    np.testing.assert_array_equal(twice, once)


def facing_agrees(shown, traced, where):
    """Whether visibility shows the reference's facing test alone.

    The shaders' facing test takes the normal from screen-space derivatives,
    which straddle two faces on edges and the terminator: about 1 % of pixels.
    """
    where = where & np.isfinite(shown) & np.isfinite(traced.visibility)
    disagree = (shown[where] >= 0.5) != traced.lit_side[where]
    return where.sum() > 10_000 and disagree.mean() <= 0.02


def test_other_receivers_get_the_facing_test_only():
    scene = standard_scene()
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    draw(pl)
    assert any(
        note.startswith("objects do not shadow each other with planar shadows: no shadow")
        and "falls on actor 'box', actor 'sphere', actor 'cylinder'" in note
        for note in light_report(pl).notes
    )
    shown = pl.shadows.visibility(scene.light)
    traced = pl.shadows._trace(scene.light)
    ground = np.isfinite(only_ground(scene).plotter.shadows.reference(scene.light))
    assert facing_agrees(shown, traced, ~ground)


def test_plane_fits():
    # A 10 x 4 grid in a tilted plane a million units away, in float64.
    normal = np.array([1.0, 2.0, 3.0]) / np.sqrt(14.0)
    across = np.cross(normal, [0.0, 0.0, 1.0])
    across /= np.linalg.norm(across)
    along = np.cross(normal, across)
    u, v = np.meshgrid(np.linspace(-5, 5, 11), np.linspace(-2, 2, 5))
    centre = np.array([1e6, -2e6, 3e6])
    points = centre + u.reshape(-1, 1) * across + v.reshape(-1, 1) * along
    fit = planes.fit_plane(points)
    assert fit.planar
    assert abs(abs(fit.plane[:3] @ normal) - 1.0) < 1e-12
    assert abs(fit.plane[:3] @ centre + fit.plane[3]) < 1e-6
    bumpy = points.copy()
    bumpy[0] += 1e-3 * normal
    assert not planes.fit_plane(bumpy).planar  # 1e-3 of 10.8 is more than the tolerance
    bumpy[0] -= 0.99e-3 * normal
    assert planes.fit_plane(bumpy).planar
    line = np.outer(np.linspace(0, 1, 5), [1.0, 2.0, 3.0])
    assert not planes.fit_plane(line).planar
    assert not planes.fit_plane(np.zeros((0, 3))).planar


def test_float32_plane_far_away_and_sole_plane():
    pl = pv.Plotter(off_screen=True)
    far = pl.add_mesh(pv.Plane(center=(1e6, 1e6, 1e6), i_size=10, j_size=10))
    reader = SceneReader(lambda actor: "an actor")
    found = planes.sole_plane(reader.read(pl.renderer).receivers)
    assert found is not None
    np.testing.assert_allclose(np.abs(found[1]), [0, 0, 1, 1e6], atol=1e-6)
    pl.add_mesh(pv.Sphere())
    assert planes.sole_plane(reader.read(pl.renderer).receivers) is None
    assert [s.actor for s, _ in planes.receiving_planes(reader.read(pl.renderer).receivers)] == [
        far
    ]


def test_named_plane_comes_first_and_the_largest_is_found_otherwise():
    pl = pv.Plotter(off_screen=True, window_size=[320, 240], lighting="none")
    pl.add_mesh(pv.Plane(i_size=10, j_size=10), name="floor")
    table = pl.add_mesh(pv.Plane(center=(0, 0, 1), i_size=2, j_size=2), name="table")
    sphere = pl.add_mesh(pv.Sphere(radius=0.3, center=(0.2, 0.1, 1.8)), name="ball")
    pl.add_light(point_light((0.0, 0.0, 4.0)))
    pl.shadows.enable(technique="planar")
    draw(pl)
    notes = light_report(pl).notes
    assert "receiving plane: actor 'floor', the largest of 2 planes (found on its own)" in notes
    pl.shadows.set_receiver(table, plane=True)
    draw(pl)
    notes = light_report(pl).notes
    assert "receiving plane: actor 'table' (named with set_receiver(plane=True))" in notes
    assert light_report(pl).passes[0].detail == "1 of 3 casters flattened onto actor 'table'"
    with pytest.raises(ValueError, match=r"actor 'ball' is not a plane: its points lie up to 0\.3"):
        pl.shadows.set_receiver(sphere, plane=True)
    with pytest.raises(ValueError, match="needs receive=True"):
        pl.shadows.set_receiver(table, False, plane=True)
    with pytest.raises(TypeError, match="plane must be True or False"):
        pl.shadows.set_receiver(table, plane="yes")
    pl.shadows.set_receiver(table)  # no longer named: the floor again
    draw(pl)
    assert any("actor 'floor'" in note for note in light_report(pl).notes)


def test_named_plane_that_stops_being_flat_and_no_plane_at_all():
    pl = pv.Plotter(off_screen=True, window_size=[320, 240], lighting="none")
    sheet = pv.Plane(i_size=4, j_size=4)
    floor = pl.add_mesh(sheet, name="sheet")
    pl.add_mesh(pv.Sphere(radius=0.3, center=(0, 0, 1)), name="ball")
    light = point_light((0.0, 0.0, 4.0))
    pl.add_light(light)
    pl.shadows.set_receiver(floor, plane=True)
    pl.shadows.enable(technique="planar")
    sheet.points[0, 2] = 0.5
    sheet.Modified()
    draw(pl)
    report = light_report(pl)
    assert report.notes[-1].startswith("actor 'sheet' was named a plane but is no longer flat")
    assert report.notes[-1].endswith("no receiver is a plane: planar shadows fall on nothing")
    assert report.passes[0].status == "skipped"
    shown = pl.shadows.visibility(light)
    assert facing_agrees(shown, pl.shadows._trace(light), np.isfinite(shown))


def test_two_lights_each_have_a_mask_released_on_disable():
    scene = only_ground(standard_scene(window_size=(320, 240)))
    pl = scene.plotter
    sun = pv.Light(position=(-3, -4, 6), focal_point=(0, 0, 0), intensity=0.4)
    pl.add_light(sun)
    pl.shadows.enable(technique="planar")
    draw(pl)
    technique = pl.shadows._renderers[0].technique("planar")
    masks = [technique.mask_of(light) for light in (scene.light, sun)]
    assert len({mask.handle for mask in masks}) == 2
    assert pl.shadows.measure(sun).misclassified <= BOUND
    pl.shadows.disable()
    assert all(mask.handle == 0 for mask in masks)


def test_read_triangles_of_a_plane_without_area():
    pl = pv.Plotter(off_screen=True)
    line = pl.add_mesh(pv.Line())
    with pytest.raises(ValueError, match="has no triangles"):
        pl.shadows.set_receiver(line, plane=True)
    assert read_triangles(line) is None
