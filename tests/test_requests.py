"""Requests pvshadows cannot honour as asked: a fallback that says so, or a clear refusal."""

import pytest
import pyvista as pv

from conftest import draw, point_light
from pvshadows.tools.scenes import standard_scene

SMALL = (400, 300)


@pytest.mark.parametrize(
    ("kind", "technique", "fallback"),
    [("directional", "cubemap", "map"), ("point", "map", "cubemap")],
)
def test_a_technique_that_cannot_serve_a_light_falls_back_and_says_so(kind, technique, fallback):
    scene = standard_scene(window_size=SMALL, light=kind)
    with pytest.warns(UserWarning, match=rf"technique='{technique}' cannot serve 1 light\(s\)"):
        scene.plotter.shadows.enable(technique=technique, filter="hard")
    draw(scene.plotter)
    report = scene.plotter.shadows.last_frame.lights[0]
    assert report.technique == fallback
    assert f"it casts with {fallback}, auto's choice, instead" in " ".join(report.notes)
    assert scene.plotter.shadows.measure(scene.light).misclassified <= 0.02


def test_all_biases_zero_warns_and_shows_acne():
    scene = standard_scene(window_size=SMALL)
    with pytest.warns(UserWarning, match="bias, slope_bias and normal_offset are all 0"):
        scene.plotter.shadows.enable(filter="hard", bias=0, slope_bias=0, normal_offset=0)
    assert scene.plotter.shadows.measure(scene.light).false_shadow > 0.1


@pytest.mark.parametrize("how", ["close", "show"])
def test_enable_on_a_closed_plotter_raises(how):
    pl = pv.Plotter(off_screen=True, window_size=list(SMALL))
    pl.add_mesh(pv.Sphere())
    getattr(pl, how)()
    with pytest.raises(RuntimeError, match=r"enable\(\): this plotter is closed"):
        pl.shadows.enable()
    assert not pl.shadows.enabled


def _outsiders(scene):
    """Actors that are not in the scene's plotter, each with how it got there."""
    other = pv.Plotter(off_screen=True)
    removed = scene.plotter.add_mesh(pv.Sphere(center=(3, 3, 1)), name="gone")
    scene.plotter.remove_actor(removed)
    return {
        "from another plotter": other.add_mesh(pv.Sphere()),
        "removed": removed,
        "never added": pv.Actor(mapper=pv.DataSetMapper(pv.Sphere())),
    }


@pytest.mark.parametrize("call", ["caster", "receiver", "plane"])
def test_actors_not_in_this_plotter_are_refused(call):
    scene = standard_scene(window_size=SMALL)
    shadows = scene.plotter.shadows
    for actor in _outsiders(scene).values():
        with pytest.raises(ValueError, match=r"^actor: this Actor is not in this plotter"):
            if call == "caster":
                shadows.set_caster(actor, False)
            elif call == "receiver":
                shadows.set_receiver(actor, False)
            else:
                shadows.set_receiver(actor, plane=True)


def test_lights_accepts_one_light_and_refuses_what_is_not_a_light():
    scene = standard_scene(window_size=SMALL)
    other = point_light((2, 2, 3))
    scene.plotter.add_light(other)
    shadows = scene.plotter.shadows
    with pytest.raises(TypeError, match=r"lights must be a pyvista\.Light or an iterable.*got int"):
        shadows.enable(lights=5)
    with pytest.raises(TypeError, match=r"lights must be a pyvista\.Light .* got str"):
        shadows.enable(lights="bulb")
    shadows.enable(lights=scene.light, filter="hard")
    draw(scene.plotter)
    techniques = [light.technique for light in shadows.last_frame.lights]
    assert techniques == ["cubemap", None]


@pytest.mark.parametrize("call", ["visibility", "measure", "reference"])
@pytest.mark.parametrize("light", ["bulb", 5])
def test_readers_refuse_what_is_not_a_light(scene, call, light):
    scene.plotter.shadows.enable(filter="hard")
    with pytest.raises(TypeError, match=r"^light must be a pyvista\.Light of this plotter, got"):
        getattr(scene.plotter.shadows, call)(light)
