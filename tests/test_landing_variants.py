"""Receivers VTK draws with one program share one landing check, and only those.

A landing check puts observers on the receiver's OpenGL mapper, and VTK then
walks that mapper's observer list at every draw for good. So one receiver
per shader variant and edits is watched, the others follow its verdict, and
the variant key (:func:`pvshadows.shaders.variant.shader_variant`) must never
join two receivers VTK draws with different programs.
"""

import numpy as np
import pytest
import pyvista as pv
from test_variants import VARIANTS
from vtkmodules.util.misc import calldata_type

import pvshadows.shaders.landing as landing
import pvshadows.shaders.landing_views as landing_views
import pvshadows.shaders.shading
from conftest import draw, point_light
from pvshadows import _vtk as vtk
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.landing import opengl_mapper
from pvshadows.shaders.variant import shader_variant


def _watched(actor):
    """Whether pvshadows (or anyone) observes the mapper that compiles the actor's shaders."""
    mapper = opengl_mapper(actor)
    return mapper is not None and (
        mapper.HasObserver(vtk.vtkCommand.ErrorEvent)
        or mapper.HasObserver(vtk.vtkCommand.UpdateShaderEvent)
    )


def _spheres(count, spacing=1.0, lit=True):
    pl = pv.Plotter(off_screen=True, window_size=(200, 150))
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white")
    spheres = [
        pl.add_mesh(pv.Sphere(radius=0.3, center=(spacing * (i - count // 2), 0.0, 0.5)))
        for i in range(count)
    ]
    if lit:
        pl.add_light(point_light((0.0, 0.0, 6.0)))
    pl.camera_position = [(0.0, -9.0, 6.0), (0.0, 0.0, 0.5), (0.0, 0.0, 1.0)]
    return pl, spheres


def _checks(pl, actors):
    edits = pl.shadows._renderers[0]._edits
    return [edits.of(vtk_id(actor)).check for actor in actors]


def test_receivers_alike_share_one_watched_program(monkeypatch):
    """Five identical spheres: one mapper is watched, its source searched once, all settled."""
    monkeypatch.setattr(landing, "_VERDICTS", {})
    searched = []
    search = landing.missing_edits
    monkeypatch.setattr(
        landing, "missing_edits", lambda edits, source: searched.append(1) or search(edits, source)
    )
    pl, spheres = _spheres(5)
    pl.shadows.enable(filter="hard")
    draw(pl)
    draw(pl)
    checks = _checks(pl, spheres)
    assert all(check.settled and check.missing == [] for check in checks)
    assert sorted(check.checked for check in checks) == [0, 0, 0, 0, 1]
    assert sum(_watched(sphere) for sphere in spheres) == 1
    assert len(searched) <= 2  # the spheres' program, and the plane's where it is another


def test_the_variant_key_never_joins_receivers_drawn_with_different_programs():
    """Every variant of the variants test, twice, in one scene: equal keys, equal programs.

    Depth peeling is on: a receiver whose colours are translucent (its
    lookup table's opacity) is drawn in the translucent pass with other
    programs than an opaque one with the same settings.
    """
    pl = pv.Plotter(off_screen=True, window_size=(320, 240))
    pl.enable_depth_peeling()  # its passes edit the translucent actors' shaders
    pl.add_mesh(pv.Plane(i_size=30, j_size=30), color="white")
    pl.add_light(point_light((0.0, 0.0, 12.0)))
    actors = {}
    for place, (name, make) in enumerate(VARIANTS.items()):
        for copy in range(2):
            mesh, keywords = make()
            x, y = 3.0 * (place % 6) - 9.0, 6.0 * (place // 6) + 3.0 * copy - 9.0
            if "scalars" not in keywords and "texture" not in keywords:
                keywords["color"] = "tan"
            actors[(name, copy)] = pl.add_mesh(
                mesh.translate((x, y, 0.0)), show_scalar_bar=False, **keywords
            )
    actors[("translucent", 0)] = pl.add_mesh(
        pv.Sphere(radius=0.6, center=(9.0, -9.0, 1.2)), color="tan", opacity=0.5
    )
    coloured, keywords = VARIANTS["surface with scalars"]()  # made as that variant's copies
    actors[("translucent colours", 0)] = pl.add_mesh(
        coloured.translate((9.0, 3.0, 0.0)), opacity="linear", show_scalar_bar=False, **keywords
    )
    actors[("backface", 0)] = pl.add_mesh(
        pv.Sphere(radius=0.6, center=(9.0, -6.0, 1.2)),
        color="tan",
        backface_params={"color": "red"},
    )
    clipped = pl.add_mesh(pv.Sphere(radius=0.6, center=(9.0, -3.0, 1.2)), color="tan")
    plane = vtk.vtkPlane()
    plane.SetOrigin(9.0, -3.0, 1.2)
    plane.SetNormal(0.0, 0.0, 1.0)
    clipped.GetMapper().AddClippingPlane(plane)
    actors[("clipped", 0)] = clipped
    user = pl.add_mesh(pv.Sphere(radius=0.6, center=(9.0, 0.0, 1.2)), color="tan")
    user.GetShaderProperty().AddFragmentShaderReplacement(
        "//VTK::Light::Impl", True, "//VTK::Light::Impl\n  diffuse *= 0.5;\n", False
    )
    actors[("user edit", 0)] = user
    pl.camera_position = [(0.0, -24.0, 26.0), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0)]
    pl.shadows.enable(filter="hard")
    draw(pl)
    draw(pl)
    programs = {key: set() for key in actors}
    for key, actor in actors.items():

        @calldata_type(vtk.VTK_OBJECT)
        def seen(mapper, event, program, key=key):
            programs[key].add(program.GetHash())

        opengl_mapper(actor).AddObserver(vtk.vtkCommand.UpdateShaderEvent, seen)
    draw(pl)
    assert all(programs.values()), [key for key, found in programs.items() if not found]
    by_variant = {}
    for key, actor in actors.items():
        by_variant.setdefault(shader_variant(actor), []).append(key)
    for joined in by_variant.values():
        assert len({frozenset(programs[key]) for key in joined}) == 1, joined
    # The two copies of each variant share a key, so one of them is watched.
    for name in VARIANTS:
        assert shader_variant(actors[(name, 0)]) == shader_variant(actors[(name, 1)]), name
    assert len({frozenset(found) for found in programs.values()}) > 0.8 * len(by_variant)
    assert pl.shadows.last_frame.receivers == []


def test_a_verdict_reaches_every_receiver_alike(monkeypatch):
    """Edits that did not land are named on each sphere, though one was watched."""
    hooks = pvshadows.shaders.shading._light_hooks

    def reworded(*args):
        return [(original.replace("(df * ", "(df*"), new) for original, new in hooks(*args)]

    monkeypatch.setattr(pvshadows.shaders.shading, "_light_hooks", reworded)
    pl, spheres = _spheres(4)
    draw(pl)
    with pytest.warns(UserWarning, match="did not land"):
        pl.shadows.enable()
        draw(pl)
    notes = pl.shadows.last_frame.receivers
    assert len(notes) == 5  # the plane and the four spheres
    assert sum(_watched(sphere) for sphere in spheres) == 1


def test_a_failed_compile_leaves_every_receiver_alike_as_vtk_built_it(monkeypatch):
    monkeypatch.setattr(pvshadows.shaders.shading, "_FACET_NORMAL", "\n  pvsFacetVC = ;")
    pl, _ = _spheres(3)
    plain = draw(pl).astype(int)
    pl.shadows.enable()
    from pyvista.core.utilities.observers import VtkErrorCatcher

    with VtkErrorCatcher(), pytest.warns(UserWarning, match="does not compile"):
        draw(pl)
        drawn = draw(pl).astype(int)
    assert np.abs(drawn - plain).max() <= 2
    notes = pl.shadows.last_frame.receivers
    assert len(notes) == 4 and all("does not compile" in note for note in notes)


def test_a_watcher_out_of_view_hands_the_watch_to_a_receiver_in_it():
    """The first sphere, watched, is out of the view: VTK never draws it, so a sphere
    VTK draws takes the watch, and every sphere is settled."""
    pl, spheres = _spheres(5, spacing=6.0)
    pl.camera_position = [(0.0, -30.0, 20.0), (0.0, 0.0, 0.5), (0.0, 0.0, 1.0)]
    draw(pl)  # every sphere drawn once: each has its OpenGL mapper
    pl.camera_position = [(6.0, -3.0, 3.0), (6.0, 0.0, 0.5), (0.0, 0.0, 1.0)]
    pl.shadows.enable(filter="hard")
    draw(pl)  # two frames: the first sphere's watch is handed over in the second
    checks = _checks(pl, spheres)
    watchers = pl.shadows._renderers[0]._edits._watchers
    assert watchers.handed_over == 1
    assert _watched(spheres[3]) and checks[3].checked == 1  # the sphere in view
    assert all(check.settled and check.missing == [] for check in checks)
    assert sum(_watched(sphere) for sphere in spheres) == 2


def test_a_receiver_that_changes_variant_is_checked_on_its_own():
    pl, spheres = _spheres(3)
    pl.shadows.enable(filter="hard")
    draw(pl)
    draw(pl)
    spheres[1].GetProperty().SetRepresentationToWireframe()
    draw(pl)
    draw(pl)
    checks = _checks(pl, spheres)
    assert all(check.settled for check in checks)
    assert shader_variant(spheres[1]) != shader_variant(spheres[0])
    assert _watched(spheres[1])
    # A new sphere like the first ones follows their watcher, once VTK made its mapper.
    new = pl.add_mesh(pv.Sphere(radius=0.3, center=(0.0, 1.5, 0.5)))
    draw(pl)
    draw(pl)
    (check,) = _checks(pl, [new])
    assert check.settled and check.checked == 0 and not _watched(new)


def test_removing_the_watcher_leaves_its_followers_settled():
    pl, spheres = _spheres(3)
    pl.shadows.enable(filter="hard")
    draw(pl)
    draw(pl)
    watched = [sphere for sphere in spheres if _watched(sphere)]
    assert len(watched) == 1
    pl.remove_actor(watched[0])
    draw(pl)
    rest = [sphere for sphere in spheres if sphere is not watched[0]]
    assert all(check.settled for check in _checks(pl, rest))
    assert pl.shadows.last_frame.receivers == []


def test_an_unread_watcher_costs_one_box_test_per_new_view(monkeypatch):
    """Nothing alike in view: the watch stays, its boxes are tested once per view, not per frame."""
    tested = []
    seen = landing_views.boxes_seen
    monkeypatch.setattr(
        landing_views,
        "boxes_seen",
        lambda boxes, planes: tested.append(len(boxes)) or seen(boxes, planes),
    )
    pl, spheres = _spheres(5, spacing=6.0)
    pl.camera_position = [(0.0, -30.0, 20.0), (0.0, 0.0, 0.5), (0.0, 0.0, 1.0)]
    draw(pl)  # every sphere drawn once: each has its OpenGL mapper
    pl.camera_position = [(0.0, 30.0, 3.0), (0.0, 60.0, 3.0), (0.0, 0.0, 1.0)]  # away from all
    pl.shadows.enable(filter="hard")
    for _ in range(4):
        draw(pl)
    watchers = pl.shadows._renderers[0]._edits._watchers
    assert watchers.handed_over == 0 and tested.count(5) == 1  # the watcher and 4 followers
    checks = _checks(pl, spheres)
    assert not any(check.settled for check in checks)
    pl.camera_position = [(6.0, -3.0, 3.0), (6.0, 0.0, 0.5), (0.0, 0.0, 1.0)]  # sphere 3 in view
    draw(pl)
    assert watchers.handed_over == 1
    assert all(check.settled for check in checks)
