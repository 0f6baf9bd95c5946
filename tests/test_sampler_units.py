"""Receivers read their samplers on texture units kept frame after frame.

Where the context offers ``GL_ARB_shading_language_420pack`` (Mesa does),
the units are written into the receivers' source and receivers carry no
custom uniform, which VTK would set at every draw. Elsewhere they are custom
uniforms whose values never change. Both ways must draw the same pixels;
the units go back to VTK after each frame; a unit taken by someone else
fails one frame clearly and the next one picks other units.
"""

import re

import numpy as np
import pytest
import pyvista as pv

import pvshadows.gl.sampler_units as sampler_units
from conftest import draw, point_light
from pvshadows.gl.textures import DepthTexture
from pvshadows.model.settings import ShadowSettings
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.library import group_samplers, group_uniforms
from pvshadows.techniques.filtering import FilterBindings, lookup_shading
from pvshadows.tools.scenes import spot_light

#: How each case enables shadows, and its lights.
CASES = {
    "maps": dict(filter="pcss", light_size=0.15),
    "volume": dict(technique="volume"),
    "planar": dict(technique="planar"),
}


def _scene():
    plotter = pv.Plotter(off_screen=True, window_size=[240, 180], lighting="none")
    plotter.add_mesh(pv.Plane(i_size=10, j_size=10), color="white", name="ground")
    plotter.add_mesh(pv.Sphere(radius=0.6, center=(-1, 0, 1.2)), color="tan", name="ball")
    plotter.add_mesh(pv.Cube(center=(1.2, 0.5, 0.6)), color="tan", name="box")
    lights = [
        spot_light((0.5, 0.3, 6.0), (0, 0, 0), cone_angle=50, intensity=0.5),
        spot_light((-2.0, 1.0, 5.0), (0, 0, 0), cone_angle=50, intensity=0.4),
        point_light((1.0, -1.5, 4.0), intensity=0.4),
    ]
    for light in lights:
        plotter.add_light(light)
    plotter.camera_position = [(6, -8, 7), (0, 0, 0.5), (0, 0, 1)]
    return plotter, lights


def _frames(options):
    """Draw four frames (the camera, then a light, moves); return the images and the plotter."""
    plotter, lights = _scene()
    plotter.shadows.enable(lights=lights, **options)
    images = [draw(plotter)]
    plotter.camera.Azimuth(10)
    images.append(draw(plotter))
    x, y, z = lights[0].GetPosition()
    lights[0].SetPosition(x + 0.3, y, z)
    images.append(draw(plotter))
    plotter.camera.Elevation(5)
    images.append(draw(plotter))
    return images, plotter


def _receiver_edits(plotter, name):
    edits = plotter.shadows._renderers[0]._edits.of(vtk_id(plotter.actors[name]))
    return "".join(new for _, new in edits.replacements)


def test_mesa_gives_samplers_their_units_in_the_source():
    _, plotter = _frames(CASES["maps"])
    units = plotter.shadows._renderers[0]._units
    assert units.binding
    ground = plotter.actors["ground"].GetShaderProperty()
    assert ground.GetFragmentCustomUniforms().GetNumberOfUniforms() == 0
    total = plotter.ren_win.GetTextureUnitManager().GetNumberOfTextureUnits()
    declared = re.findall(
        r"layout\(binding = (\d+)\) uniform (\w+) (\w+)", _receiver_edits(plotter, "ground")
    )
    # the two spot lights' arrays of two (map, plain view) and their one offset
    # texture, then the point light's cube array, each block below the last, from the
    # top of the range down
    assert [(total - int(unit), kind, name) for unit, kind, name in declared] == [
        (2, "sampler2DShadow", "pvsSpotPcssx32Depth"),
        (4, "sampler2D", "pvsSpotPcssx32Raw"),
        (5, "sampler3D", "pvsSpotPcssx32Offsets"),
        (6, "samplerCubeArrayShadow", "pvsCubesPcss1024x32Depth"),
        (7, "samplerCubeArray", "pvsCubesPcss1024x32Raw"),
        (8, "sampler3D", "pvsCubesPcss1024x32Offsets"),
    ]
    assert plotter.shadows.measure().misclassified < 0.005


@pytest.mark.parametrize("case", list(CASES))
def test_units_in_the_source_and_as_custom_uniforms_draw_the_same_pixels(case, monkeypatch):
    bound, plotter = _frames(CASES[case])
    assert plotter.shadows._renderers[0]._units.binding
    plain = plotter.shadows.measure().misclassified
    monkeypatch.setattr(sampler_units, "binding_supported", lambda window: False)
    uniforms, plotter = _frames(CASES[case])
    renderer = plotter.shadows._renderers[0]
    assert not renderer._units.binding
    ground = plotter.actors["ground"].GetShaderProperty().GetFragmentCustomUniforms()
    assert ground.GetNumberOfUniforms() > 0
    for first, second in zip(bound, uniforms, strict=True):
        assert np.array_equal(first, second)
    assert plain < 0.005
    # the units never change, so after the first frame no value is sent again
    calls = renderer._edits.uniform_calls
    plotter.camera.Azimuth(5)
    draw(plotter)
    assert renderer._edits.uniform_calls == calls


def test_units_go_back_to_vtk_after_each_frame_and_stay_the_same():
    _, plotter = _frames(CASES["maps"])
    manager = plotter.ren_win.GetTextureUnitManager()
    units = plotter.shadows._renderers[0]._units
    blocks = dict(units._blocks)
    assert blocks
    assert not any(manager.IsAllocated(u) for u in range(manager.GetNumberOfTextureUnits()))
    edited = plotter.shadows._renderers[0]._edits.edited
    for _ in range(3):
        plotter.camera.Azimuth(7)
        draw(plotter)
    assert units._blocks == blocks
    assert plotter.shadows._renderers[0]._edits.edited == edited  # nothing recompiled
    plotter.shadows.disable()
    assert not any(manager.IsAllocated(u) for u in range(manager.GetNumberOfTextureUnits()))


def test_a_unit_held_by_another_texture_fails_one_frame_and_the_next_picks_others():
    _, plotter = _frames(CASES["maps"])
    units = plotter.shadows._renderers[0]._units
    manager = plotter.ren_win.GetTextureUnitManager()
    taken = max(units._blocks.values())
    manager.Allocate(taken)
    with pytest.warns(UserWarning, match=f"texture unit {taken}, kept for pvs"):
        draw(plotter)
    assert plotter.shadows.last_frame.failure is not None
    draw(plotter)
    assert plotter.shadows.last_frame.failure is None
    assert taken not in units._blocks.values()
    assert plotter.shadows.measure().misclassified < 0.005
    manager.Free(taken)


def test_soft_lights_take_a_unit_each_and_one_for_their_offsets():
    plotter = pv.Plotter(off_screen=True, window_size=[160, 120], lighting="none")
    plotter.add_mesh(pv.Plane(i_size=10, j_size=10), color="white", name="ground")
    plotter.add_mesh(pv.Sphere(radius=0.6, center=(0, 0, 1.0)), color="tan")
    lights = []
    for k in range(4):
        angle = 2 * np.pi * k / 4
        position = (2 * np.cos(angle), 2 * np.sin(angle), 5.0)
        lights.append(spot_light(position, (0, 0, 0), cone_angle=45, intensity=0.2))
        plotter.add_light(lights[-1])
    plotter.shadows.enable(lights=lights, filter="random", samples=16)
    draw(plotter)
    assert plotter.shadows.last_frame.failure is None
    blocks = plotter.shadows._renderers[0]._units._blocks
    assert sorted(len(key) for key in blocks) == [1, 4]  # the offsets, the maps
    assert plotter.shadows.measure(lights[0]).misclassified < 0.005


def test_too_few_free_units_is_a_clear_error():
    plotter, _ = _scene()
    plotter.render()
    units = sampler_units.SamplerUnits(plotter.ren_win)
    manager = plotter.ren_win.GetTextureUnitManager()
    total = manager.GetNumberOfTextureUnits()
    with pytest.raises(RuntimeError, match=f"needs {total + 1} consecutive free texture units"):
        units._reserve(total + 1)


def test_a_group_reads_one_offset_texture_and_other_sample_counts_form_their_own():
    def lookup(index, samples):
        settings = ShadowSettings(filter="random", samples=samples)
        return lookup_shading("spot", index, settings).needs[0]

    first, other, third = lookup(0, 16), lookup(1, 64), lookup(2, 16)
    assert first.group == third.group != other.group
    samplers = group_samplers([first, other, third])
    assert samplers[f"pvs{first.group}Offsets"] == ("sampler3D", None)
    assert samplers[f"pvs{first.group}Depth"] == ("sampler2DShadow", 2)
    own = {"pvsDepth0": 1, "pvsOffsets0": 7, "pvsDepth2": 2, "pvsOffsets2": 7}
    packed = group_uniforms([first, third], own)
    assert packed[f"pvs{first.group}Offsets"] == 7
    assert packed[f"pvs{first.group}Depth"] == [1, 2]


def test_a_lights_textures_are_named_once_per_map_and_handed_out_in_a_new_dict():
    pl = pv.Plotter(off_screen=True, window_size=(64, 48))
    pl.ren_win.Render()
    filters = FilterBindings(pl.ren_win)
    depth, other = DepthTexture(pl.ren_win, 16), DepthTexture(pl.ren_win, 16)
    hard = ShadowSettings(filter="hard")
    first = filters.samplers(0, hard, depth)
    first["pvsDepth0"] = None  # a caller's change does not reach the next frame's
    again = filters.samplers(0, hard, depth)
    assert again["pvsDepth0"] is filters.samplers(0, hard, depth)["pvsDepth0"]
    assert again["pvsDepth0"].handle == depth.handle
    moved = filters.samplers(0, hard, other)  # another map for the same light
    assert moved["pvsDepth0"].handle == other.handle != depth.handle
    pcss = filters.samplers(0, ShadowSettings(filter="pcss", light_size=0.1), other)
    assert sorted(pcss) == ["pvsDepth0", "pvsOffsets0", "pvsRaw0"]
    assert sorted(filters.samplers(1, hard, other)) == ["pvsDepth1"]
    filters.release()
    depth.release()
    other.release()
    pl.close()
