"""A map redrawn for a moving actor draws that actor alone, over the still casters' depth."""

import numpy as np
import pytest
import pyvista as pv

from conftest import draw
from pvshadows.gl.binding import opengl_for
from pvshadows.techniques import still_casters
from pvshadows.tools.overhead import OverheadScene, build_scene
from pvshadows.tools.scenes import standard_scene

# Casters drawn by each frame of a swaying sphere (of 4): a first move draws every caster;
# the second the 3 still ones into the still map, and the sphere over them; then the sphere
# alone. A sun's fit is the casters' (each holds an edge of it here): the first move fits
# the map over both places of the sphere, so its still map starts a frame later.
CASES = [
    ("point", "single", [4, 4, 1, 1]),
    ("point", "six", [4, 4, 1, 1]),
    ("spot", "single", [4, 4, 1, 1]),
    ("directional", "single", [4, 4, 4, 1]),
]


def technique_of(scene):
    name = "cubemap" if scene.light.GetConeAngle() >= 90 and scene.light.GetPositional() else "map"
    return scene.plotter.shadows._renderers[0]._techniques[name]


@pytest.fixture(autouse=True)
def _few_casters_are_worth_a_still_map(monkeypatch):
    """Two still casters of the standard scene count as enough (see the last test)."""
    monkeypatch.setattr(still_casters, "STILL_CASTERS", 2)


def scenes(light, passes):
    """The standard scene twice: the second always draws every caster (its still maps off)."""
    pair = [standard_scene(light=light, window_size=(400, 300)) for _ in range(2)]
    for scene in pair:
        scene.plotter.shadows.enable(filter="hard", passes=passes)
        draw(scene.plotter)
    for state in technique_of(pair[1])._states.values():
        state.still = None
    return pair


def caster_count(scene):
    return len(scene.plotter.shadows._reader.read(scene.plotter.renderer).casters)


def drawn_per_frame(pair, move, frames):
    """Move both scenes ``frames`` times; return the casters each frame drew, frames equal."""
    technique = technique_of(pair[0])
    counts = []
    for _ in range(frames):
        before = technique.casters_drawn
        for scene in pair:
            move(scene)
        shown, full = (draw(scene.plotter) for scene in pair)
        assert np.array_equal(shown, full)  # the same map, texel for texel
        counts.append(technique.casters_drawn - before)
    return counts


def sway(actor, step=0.04):
    """Move an actor to and fro along x."""
    actor.AddPosition(-step if actor.GetPosition()[0] > 0 else step, 0.0, 0.0)


@pytest.mark.parametrize(("light", "passes", "expected"), CASES)
def test_a_moving_actor_is_drawn_alone_and_the_map_is_the_full_redraws(light, passes, expected):
    pair = scenes(light, passes)
    assert caster_count(pair[0]) == 4
    assert drawn_per_frame(pair, lambda scene: sway(scene.sphere), 4) == expected
    names = [p.name for p in pair[0].plotter.shadows.last_frame.lights[0].passes]
    assert not any("still" in name for name in names)
    assert pair[0].plotter.shadows.measure(pair[0].light).misclassified <= 0.01


def test_the_still_map_is_drawn_again_when_another_actor_starts_moving():
    pair = scenes("spot", "single")
    casters = caster_count(pair[0])
    counts = drawn_per_frame(pair, lambda scene: sway(scene.sphere), 3)
    counts += drawn_per_frame(pair, lambda scene: sway(scene.cylinder), 3)
    # The cylinder's first move draws every caster, its second the still map without it
    # (2 casters) and both over it, then both alone.
    assert counts == [casters, casters, 1, casters, 2 + 2, 2]


def test_a_moved_light_or_most_casters_moving_draws_every_caster():
    pair = scenes("spot", "single")
    casters = caster_count(pair[0])
    counts = drawn_per_frame(pair, lambda scene: sway(scene.sphere), 3)
    counts += drawn_per_frame(pair, lambda scene: scene.light.SetPosition(0.3, -0.25, 3.5), 1)

    def move_most(scene):  # three of the four casters
        for actor in (scene.sphere, scene.box, scene.cylinder):
            sway(actor)

    counts += drawn_per_frame(pair, move_most, 2)
    assert counts == [casters, casters, 1, casters, casters, casters]


def test_too_few_still_casters_are_drawn_again_and_many_are_kept(monkeypatch):
    monkeypatch.setattr(still_casters, "STILL_CASTERS", 16)
    pair = scenes("spot", "single")
    assert drawn_per_frame(pair, lambda scene: sway(scene.sphere), 3) == [4, 4, 4]
    # Casters of enough triangles are worth it, however few.
    monkeypatch.setattr(still_casters, "STILL_TRIANGLES", 14)  # ground 2, box 12, cylinder more
    pair = scenes("spot", "single")
    assert drawn_per_frame(pair, lambda scene: sway(scene.sphere), 3) == [4, 4, 1]


@pytest.mark.parametrize("light", ["point", "spot", "directional"])
def test_fifty_spheres_one_swaying_draw_it_alone_without_a_lowered_threshold(light, monkeypatch):
    monkeypatch.undo()
    twins = [build_scene(OverheadScene("actors", light, actors=50), (320, 240)) for _ in range(2)]
    for plotter, lights, _ in twins:
        plotter.shadows.enable(lights=lights, filter="hard")
        draw(plotter)
    name = "cubemap" if light == "point" else "map"
    for state in twins[1][0].shadows._renderers[0]._techniques[name]._states.values():
        state.still = None
    technique = twins[0][0].shadows._renderers[0]._techniques[name]
    counts = []
    for _ in range(4):
        before = technique.casters_drawn
        for _, _, moved in twins:
            sway(moved, 1e-3)  # the bench's motion: the corner sphere holds an edge of the fits
        shown, full = (draw(plotter) for plotter, _, _ in twins)
        assert np.array_equal(shown, full)
        counts.append(technique.casters_drawn - before)
    assert counts[-2:] == [1, 1]
    assert sum(counts) <= 3 * 51 + 2


def test_a_small_actor_beside_a_big_static_mesh_is_drawn_without_it(monkeypatch):
    monkeypatch.undo()

    def scene():
        pl = pv.Plotter(off_screen=True, window_size=(320, 240), lighting="none")
        pl.add_mesh(pv.Plane(i_size=12, j_size=12))
        # 111 390 triangles: over STILL_TRIANGLES, alone beside the ground
        pl.add_mesh(pv.Sphere(radius=1.2, center=(0, 0, 1.4), theta_resolution=237,
                              phi_resolution=237))  # fmt: skip
        small = pl.add_mesh(pv.Sphere(radius=0.3, center=(2, 0, 0.5)), color="red")
        light = pv.Light(position=(0.5, -0.3, 6), focal_point=(0.5, -0.3, 0), positional=True,
                         cone_angle=180)  # fmt: skip
        pl.add_light(light)
        pl.shadows.enable(lights=[light], filter="hard")
        draw(pl)
        return pl, small

    (shown, small), (full, twin_small) = scene(), scene()
    for state in full.shadows._renderers[0]._techniques["cubemap"]._states.values():
        state.still = None
    technique = shown.shadows._renderers[0]._techniques["cubemap"]
    counts = []
    for _ in range(4):
        before = technique.casters_drawn
        sway(small, 0.01)
        sway(twin_small, 0.01)
        assert np.array_equal(draw(shown), draw(full))
        counts.append(technique.casters_drawn - before)
    assert counts == [3, 3, 1, 1]


@pytest.mark.parametrize("light", ["point", "spot"])
def test_a_still_map_is_released_with_its_light_state(light, monkeypatch):
    monkeypatch.undo()
    pl, lights, moved = build_scene(OverheadScene("actors", light, actors=50), (160, 120))
    pl.shadows.enable(lights=lights)
    draw(pl)
    technique = pl.shadows._renderers[0]._techniques["cubemap" if light == "point" else "map"]
    gl = opengl_for(pl.ren_win)

    def still_map_after_sway():
        for _ in range(4):
            sway(moved, 1e-3)
            draw(pl)
        (state,) = technique._states.values()
        handle = state.still._map.handle
        assert gl.glIsTexture(handle)
        return state.still, handle

    still, handle = still_map_after_sway()
    pl.shadows.configure(lights[0], resolution=512)  # a new map, a new light state
    draw(pl)
    assert still._map is None  # released (its name may serve the new map already)
    still, handle = still_map_after_sway()
    pl.shadows.disable()
    pl.ren_win.MakeCurrent()
    assert still._map is None and not gl.glIsTexture(handle)
