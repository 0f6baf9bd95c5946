"""Many shadowed point lights: one cube map array, one loop, one filter in the receiver's shader.

The receiver's shader must not grow with lights x filter taps: 32 point lights
with the default 4-tap PCF once compiled for minutes on llvmpipe. These tests
count the mechanism (samplers and texture units in the compiled program, cube
arrays allocated) and judge each light's shadow against ray casting; the time
itself is measured outside the tests.
"""

import re

import numpy as np
import pytest
from vtkmodules.util.misc import calldata_type

from conftest import draw, point_light
from pvshadows import _vtk as vtk
from pvshadows.shaders.landing import opengl_mapper
from pvshadows.shaders.library import MapLookup, shadow_functions
from pvshadows.tools.scenes import standard_scene

SAMPLER = re.compile(r"uniform (sampler\w+) (\w+)(\[\d+\])?;")


def lights_around(count):
    """Point lights on a ring round the standard scene, each dimmed so the sum stays 1."""
    lights = []
    for i, angle in enumerate(np.linspace(0.0, 2.0 * np.pi, count, endpoint=False)):
        radius, height = 3.0 + i % 3, 2.5 + 0.5 * (i % 4)
        position = (radius * np.cos(angle), radius * np.sin(angle), height)
        lights.append(point_light(position, intensity=1.0 / count))
    return lights


def ringed_scene(count):
    scene = standard_scene(window_size=(400, 300))
    scene.plotter.remove_all_lights()
    lights = lights_around(count)
    for light in lights:
        scene.plotter.add_light(light)
    return scene, lights


def receiver_source(plotter, actor):
    """Return the fragment source of the program VTK draws ``actor`` with, after one more frame."""
    sources = []

    @calldata_type(vtk.VTK_OBJECT)
    def seen(mapper, event, program):
        sources.append(program.GetFragmentShader().GetSource())

    mapper = opengl_mapper(actor)
    tag = mapper.AddObserver(vtk.vtkCommand.UpdateShaderEvent, seen)
    draw(plotter)
    mapper.RemoveObserver(tag)
    return sources[-1]


def cube_samplers(source):
    return [match for match in SAMPLER.findall(source) if "Cube" in match[0]]


@pytest.mark.parametrize("count", [2, 5])
def test_one_cube_sampler_for_every_point_light(count):
    scene, lights = ringed_scene(count)
    scene.plotter.shadows.enable()
    draw(scene.plotter)
    source = receiver_source(scene.plotter, scene.ground)
    assert cube_samplers(source) == [("samplerCubeArrayShadow", "pvsCubesPcf1024Depth", "")]
    assert "#extension GL_ARB_texture_cube_map_array : require" in source
    technique = scene.plotter.shadows._renderers[0].technique("cubemap")
    (array,) = technique.arrays.values()
    assert (array.capacity, array.allocations, len(array.taken)) == (count, 1, count)
    for light in lights[:2]:
        assert scene.plotter.shadows.measure(light).misclassified <= 0.005


def test_lookup_code_grows_by_names_not_filters():
    def code(count):
        return shadow_functions([MapLookup("cubes", "pcf", i, 2, "1024") for i in range(count)])

    few, many = code(2), code(32)
    assert few.count("#define PVS_GROUP_LOOKUP") == many.count("#define PVS_GROUP_LOOKUP") == 1
    # only the list of the lights' visibility names grows
    assert len(many) - len(few) < 30 * len("EACH(31, pvsMapVisibility31) ") * 2


def test_array_grows_when_lights_are_added_and_every_light_stays_right():
    scene, lights = ringed_scene(2)
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    more = lights_around(5)[2:]
    for light in more:
        pl.add_light(light)
    pl.shadows.enable(filter="hard")
    draw(pl)
    (array,) = pl.shadows._renderers[0].technique("cubemap").arrays.values()
    assert (array.allocations, len(array.taken)) == (2, 5)
    assert array.capacity >= 5
    for light in [*lights, more[0]]:  # the cubes copied across, and a new one
        assert pl.shadows.measure(light).misclassified <= 0.005


def test_without_cube_arrays_each_light_has_its_cube_and_the_same_shadows(monkeypatch):
    scene, lights = ringed_scene(3)
    scene.plotter.shadows.enable()
    looped = [scene.plotter.shadows.visibility(light) for light in lights]
    scene.plotter.close()

    monkeypatch.setattr("pvshadows.techniques.cubemap.cube_arrays_supported", lambda gl: False)
    scene, lights = ringed_scene(3)
    scene.plotter.shadows.enable()
    draw(scene.plotter)
    source = receiver_source(scene.plotter, scene.ground)
    assert cube_samplers(source) == [("samplerCubeShadow", "pvsCubePcfDepth", "[3]")]
    assert scene.plotter.shadows._renderers[0].technique("cubemap").arrays is None
    for light, before in zip(lights, looped, strict=True):
        alone = scene.plotter.shadows.visibility(light)
        both = np.isfinite(alone) & np.isfinite(before)
        assert np.abs(alone[both] - before[both]).max() < 1e-3


def test_disable_releases_the_arrays():
    scene, _ = ringed_scene(2)
    pl = scene.plotter
    pl.shadows.enable()
    draw(pl)
    (array,) = pl.shadows._renderers[0].technique("cubemap").arrays.values()
    pl.shadows.disable()
    assert array.texture is None and array.capacity == 0
