"""A frame costs what changed: counted, not timed (the bench measures the time)."""

import numpy as np
import pytest
import pyvista as pv

from conftest import draw
from pvshadows.scene.triangles import vtk_id
from pvshadows.tools.scenes import crowd_scene, standard_scene


def counters(pl):
    shadows = pl.shadows._renderers[0]
    return {
        "reread": pl.shadows._reader.reread,
        "compared": pl.shadows._reader.compared,
        "cone tests": shadows.reach.tests,
        "edits": shadows._edits.edited,
        "received": shadows._edits.received,
        "uniforms": shadows._edits.uniform_calls,
        "waited": shadows._timer.waited,
        "block uploads": shadows._block.uploads,
        "planned": shadows.memo.made,
        "view tests": shadows.memo.view_tests,
        "waiting tested": shadows._edits.waiting.tested,
        "fit measures": sum(
            state.measures.measured
            for state in getattr(shadows._techniques.get("map"), "_states", {}).values()
        ),
    }


def change(before, after):
    return {name: after[name] - before[name] for name in before}


def hard_standard(light):
    """Return the standard scene under ``light`` with hard shadows, drawn once, and its frames."""
    scene = standard_scene(window_size=(200, 150), light=light)
    scene.plotter.shadows.enable(filter="hard")
    draw(scene.plotter)
    return scene, scene.plotter.shadows._renderers[0]


def crowd():
    pl, light, _ = crowd_scene(200)
    pl.shadows.enable(filter="hard")
    draw(pl)
    draw(pl)  # the receivers edited at the last frame are tried for a watch in this view
    return pl, light


def test_a_new_camera_rereads_no_actor_and_tests_no_cone():
    pl, _ = crowd()
    before = counters(pl)
    pl.camera.Azimuth(10)
    draw(pl)
    counted = change(before, counters(pl))
    assert counted["reread"] == 0
    assert counted["cone tests"] == 0
    assert counted["edits"] == 0
    # The camera-dependent matrix goes to the frame's uniform block, once for all
    # 200 receivers: no receiver is given a uniform.
    assert counted["uniforms"] == 0
    assert counted["block uploads"] == 1
    assert counted["waited"] == 0
    assert pl.shadows.last_frame.passes_run == 0


def test_a_camera_that_sees_the_same_receivers_keeps_the_plans():
    pl, _ = crowd()
    before = counters(pl)
    for _ in range(3):
        pl.camera.Azimuth(0.5)
        draw(pl)
    counted = change(before, counters(pl))
    assert counted["planned"] == 0
    assert counted["block uploads"] == 3
    assert counted["uniforms"] == 0


def test_a_camera_tests_every_receiver_only_when_last_frames_witness_left_the_view():
    pl, _ = crowd()
    pl.camera.Dolly(0.1)
    pl.renderer.ResetCameraClippingRange()
    draw(pl)
    before = counters(pl)
    for _ in range(3):
        pl.camera.Azimuth(5)
        pl.renderer.ResetCameraClippingRange()
        draw(pl)
    # the box round every receiver is in view: none is tested on its own
    assert change(before, counters(pl))["view tests"] == 0
    pl.camera.Zoom(20)  # part of the crowd only
    draw(pl)
    counted = change(before, counters(pl))
    # last frame's witnesses (one for "some receiver", one for the light's reach) answer
    assert counted["view tests"] == 2
    assert counted["planned"] == 0
    receivers = len(pl.shadows._renderers[0].snapshot.receivers)
    pl.camera_position = [(0.0, 0.0, 50.0), (0.0, 0.0, 100.0), (0.0, 1.0, 0.0)]
    draw(pl)
    counted = change(before, counters(pl))
    assert receivers + 2 <= counted["view tests"] <= receivers + 4
    assert pl.shadows.last_frame.lights[0].technique is None


def test_receivers_coming_into_view_and_leaving_it_keep_the_plans():
    pl, _ = crowd()
    before = counters(pl)
    for _ in range(4):
        pl.camera.Azimuth(20)
        pl.camera.Zoom(1.5)
        draw(pl)
    counted = change(before, counters(pl))
    # The spheres in view change from frame to frame; the light still reaches some of
    # them, so what it casts and from which casters does not change.
    assert counted["planned"] == 0
    assert counted["cone tests"] == 0
    assert pl.shadows.last_frame.passes_run == 0


def test_a_camera_that_turns_away_from_every_receiver_plans_again():
    pl, _ = crowd()
    before = counters(pl)
    pl.camera_position = [(0.0, 0.0, 50.0), (0.0, 0.0, 100.0), (0.0, 1.0, 0.0)]
    draw(pl)
    assert change(before, counters(pl))["planned"] == 1
    assert pl.shadows.last_frame.lights[0].technique is None
    pl.camera_position = [(0.0, 0.0, 50.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    draw(pl)
    assert change(before, counters(pl))["planned"] == 2
    assert pl.shadows.last_frame.lights[0].technique == "map"


def test_nothing_changed_costs_no_vtk_call():
    pl, _ = crowd()
    before = counters(pl)
    draw(pl)
    assert change(before, counters(pl)) == dict.fromkeys(before, 0)


def test_moving_one_actor_rereads_and_tests_that_actor_only():
    pl, light = crowd()
    shadows = pl.shadows._renderers[0]
    ground = shadows.snapshot.receivers[0].actor
    # one of the spot's own casters, so that its map is drawn again
    moved = next(s.actor for s in shadows.plans[0].cast.casters if s.actor is not ground)
    before = counters(pl)
    for _ in range(3):
        moved.AddPosition(0.01, 0.0, 0.0)
        draw(pl)
    counted = change(before, counters(pl))
    assert counted["compared"] == 3  # of 200 actors, only the one whose times moved
    assert counted["reread"] == 3
    assert counted["cone tests"] == 3
    assert counted["fit measures"] == 3  # the spot's fit and range: the moved box alone
    # A receiver's edits follow its kind: the moved one keeps its edits, and every
    # receiver takes the changed uniforms with the others of its kind.
    assert counted["edits"] == 0
    assert counted["received"] == 0
    # The receivers VTK never drew (out of view) were tested against this view before.
    assert counted["waiting tested"] == 0
    assert counted["view tests"] <= 3
    assert pl.shadows._renderers[0].snapshot.changed == {moved.__this__}
    assert pl.shadows.measure(light).misclassified <= 0.005  # and it is shadowed where it is


def test_a_new_camera_compares_no_actor():
    """VTK's modification events say no actor changed: none of the 200 is even compared."""
    pl, _ = crowd()
    before = counters(pl)
    pl.camera.Azimuth(5)
    draw(pl)
    assert change(before, counters(pl))["compared"] == 0


@pytest.mark.parametrize("edit", ["points", "point array", "user matrix", "property"])
def test_raw_vtk_edits_below_the_dataset_are_noticed(edit):
    """Modifying what an actor's shadow depends on, without modifying the actor or its
    dataset (as raw VTK code may), marks that actor and no other."""
    pl, _ = crowd()
    state = pl.shadows._renderers[0].snapshot.casters[1]
    data = state.actor.GetMapper().GetInputDataObject(0, 0)
    points = data.GetPoints()
    before = counters(pl)
    if edit == "points":
        x, y, z = points.GetPoint(0)
        points.SetPoint(0, x, y, z + 3.0)
        points.Modified()
    elif edit == "point array":
        array = points.GetData()
        x, y, z = array.GetTuple3(0)
        array.SetTuple3(0, x, y, z + 3.0)
        array.Modified()
    elif edit == "user matrix":
        matrix = state.actor.GetUserMatrix()
        matrix.SetElement(2, 3, matrix.GetElement(2, 3) + 3.0)
    else:
        state.actor.GetProperty().SetOpacity(0.5)
    draw(pl)
    counted = change(before, counters(pl))
    assert counted["compared"] == 1 and counted["reread"] == 1
    (now,) = (s for s in pl.shadows._renderers[0].snapshot.casters if s.actor is state.actor)
    if edit == "property":
        assert now.transmittance == pytest.approx(0.5)
    else:
        assert now.bounds[1, 2] == pytest.approx(state.bounds[1, 2] + 3.0)


def test_receivers_never_drawn_are_tried_for_a_watch_only_where_the_view_meets_them():
    pl, _ = crowd()
    edits = pl.shadows._renderers[0]._edits
    draw(pl)  # VTK has drawn the receivers in view once: their programs are watched
    waiting = set(edits.waiting)
    # Most of the 200 spheres lie outside the view: VTK never drew them, so they
    # have no OpenGL mapper to watch yet.
    assert 100 < len(waiting) < 201
    before = edits.waiting.tries
    for _ in range(3):
        pl.camera.Azimuth(0.2)
        draw(pl)
    assert edits.waiting.tries == before  # none of them is in view: none is tried
    assert set(edits.waiting) == waiting
    pl.reset_camera()  # every receiver in view
    draw(pl)
    draw(pl)
    assert not edits.waiting
    assert all(edits.of(key).check.settled for key in waiting)


def test_disabling_removes_every_observer_from_the_actors():
    pl, _ = crowd()
    state = pl.shadows._renderers[0].snapshot.casters[1]
    data = state.actor.GetMapper().GetInputDataObject(0, 0)
    watched = [state.actor, state.actor.GetProperty(), state.actor.GetMapper(), data]
    watched += [data.GetPoints(), data.GetPoints().GetData(), data.GetPolys()]
    assert all(item.HasObserver("ModifiedEvent") for item in watched)
    pl.shadows.disable()
    assert not any(item.HasObserver("ModifiedEvent") for item in watched)


def test_a_moved_actor_keeps_its_triangles_and_their_bounds():
    """Only the eight corners of its model bounds move, not a pass over its points."""
    pl, _ = crowd()
    state = pl.shadows._renderers[0].snapshot.casters[1]
    model_bounds = state.triangles.model_bounds()
    state.actor.AddPosition(0.5, 0.0, 0.0)
    draw(pl)
    (moved,) = (s for s in pl.shadows._renderers[0].snapshot.casters if s.actor is state.actor)
    assert moved is not state and moved.triangles is state.triangles
    assert moved.triangles.model_bounds() is model_bounds
    assert moved.bounds[:, 0] == pytest.approx(state.bounds[:, 0] + 0.5)


def test_a_moved_flat_actor_keeps_its_model_plane():
    """Whether an actor is flat is found once for its triangles, not again when it moves."""
    pl, _ = crowd()
    flat = next(s for s in pl.shadows._renderers[0].snapshot.actors if s.sheet is not None)
    plane = flat.triangles.model_plane()
    assert plane is not None
    flat.actor.AddPosition(0.0, 0.0, 0.25)
    draw(pl)
    (moved,) = (s for s in pl.shadows._renderers[0].snapshot.actors if s.actor is flat.actor)
    assert moved is not flat and moved.triangles.model_plane() is plane
    assert moved.sheet.anchor[2] == pytest.approx(flat.sheet.anchor[2] + 0.25)


def test_a_light_moved_a_little_tests_no_actor_and_runs_its_pass():
    pl, light = crowd()
    before = counters(pl)
    for step in range(1, 4):
        light.position = (0.01 * step, 0.0, 20.0)
        draw(pl)
    counted = change(before, counters(pl))
    assert counted["reread"] == 0
    # The actors were tested against a cover wider than the cone, which still holds it,
    # and measured once, with a margin that holds the light's next two moves too.
    assert counted["cone tests"] == 0
    assert counted["fit measures"] == len(pl.shadows._renderers[0].snapshot.casters)
    assert counted["received"] == 0
    # Its far distance, fit and cone go to the frame's block: no receiver is given a uniform.
    assert counted["uniforms"] == 0
    assert counted["block uploads"] == 3
    assert pl.shadows.last_frame.passes_run == 1


@pytest.mark.parametrize(
    ("position", "focal_point"),
    [((3.0, 0.0, 20.0), (0.0, 0.0, 0.0)), ((0.0, 0.0, 20.0), (2.0, 0.0, 0.0))],
    ids=["moved", "turned"],
)
def test_a_light_that_leaves_its_cover_tests_every_actor_once(position, focal_point):
    pl, light = crowd()
    actors = len(pl.shadows._renderers[0].snapshot.actors)
    before = counters(pl)
    light.position, light.focal_point = position, focal_point
    draw(pl)
    assert change(before, counters(pl))["cone tests"] == actors
    assert pl.shadows.last_frame.passes_run == 1


def test_changed_property_rereads_that_actor():
    pl = pv.Plotter(off_screen=True, window_size=(200, 150), lighting="none")
    ground = pl.add_mesh(pv.Plane(i_size=10, j_size=10))
    box = pl.add_mesh(pv.Cube(center=(0, 0, 1)))
    pl.add_light(pv.Light(position=(0, 0, 4), positional=True, cone_angle=180))
    pl.shadows.enable(filter="hard")
    draw(pl)
    before = counters(pl)
    box.prop.lighting = False  # it stops receiving: the reader must notice through its property
    draw(pl)
    snapshot = pl.shadows._renderers[0].snapshot
    assert change(before, counters(pl))["reread"] == 1
    assert [s.actor for s in snapshot.receivers] == [ground]
    assert snapshot.bystanders == [box]


def test_a_sun_reads_its_actors_once_while_only_the_camera_moves():
    """The fit's light-space boxes follow the light and actors; only the view is redone."""
    scene = standard_scene(window_size=(320, 240), light="directional")
    pl = scene.plotter
    pl.shadows.enable(technique="map", filter="hard")
    draw(pl)
    state = pl.shadows._renderers[0].technique("map")._states[vtk_id(scene.light)]
    read = state.sun_actors[2]
    assert read is not None and len(read.receivers) == 4
    assert len(read.casters) == 3  # the ground, flat and under the others, shadows nothing
    whole = state.fitted
    for _ in range(3):
        pl.camera.Azimuth(10)
        draw(pl)
        assert state.sun_actors[2] is read
        # The view holds every receiver across the light: the scene's fit, not fitted again.
        assert state.fitted is whole
    assert pl.shadows.measure(scene.light).misclassified <= 0.01
    pl.camera.Zoom(8.0)  # the view holds part of the ground: a finer fit to that part
    draw(pl)
    assert state.fitted.half_width < whole.half_width
    assert pl.shadows.measure(scene.light).misclassified <= 0.01
    pl.camera.Zoom(1 / 8.0)
    draw(pl)
    assert state.fitted is whole
    scene.light.position = (4.0, 2.0, 8.0)
    draw(pl)
    assert state.sun_actors[2] is not read


def test_moving_one_of_two_lights_plans_and_draws_that_light_only():
    scene = standard_scene(window_size=(320, 240), light="spot")
    pl = scene.plotter
    pl.add_light(pv.Light(position=(-2, 2, 4), positional=True, cone_angle=50, intensity=0.5))
    pl.shadows.enable(filter="hard")
    draw(pl)
    shadows = pl.shadows._renderers[0]
    assert [plan.technique for plan in shadows.plans].count("map") == 2
    kept = shadows.plans[1]
    planned = shadows.memo.planned
    x, y, z = scene.light.position
    scene.light.position = (x + 0.05, y, z)
    draw(pl)
    assert shadows.memo.planned - planned == 1
    assert shadows.plans[1] is kept  # the other light's plan, and so its map, are kept
    assert pl.shadows.last_frame.passes_run == 1


def test_an_actor_given_new_data_is_watched_through_that_data():
    """After its mapper's input is swapped, edits to the new input are noticed too."""
    pl, _ = crowd()
    state = pl.shadows._renderers[0].snapshot.casters[1]
    mesh = pv.Sphere(radius=0.2, center=state.bounds.mean(axis=0))
    state.actor.GetMapper().SetInputData(mesh)
    draw(pl)
    before = counters(pl)
    mesh.translate((0.0, 0.0, 0.5), inplace=True)
    draw(pl)
    counted = change(before, counters(pl))
    assert counted["compared"] == 1 and counted["reread"] == 1
    (moved,) = (s for s in pl.shadows._renderers[0].snapshot.casters if s.actor is state.actor)
    assert moved.bounds[1, 2] == pytest.approx(mesh.bounds[5])


def _derived(snapshot):
    """What a snapshot derives from its actors, in comparable form."""
    return {
        "casters": [id(s) for s in snapshot.casters],
        "receivers": [id(s) for s in snapshot.receivers],
        "caster_index": snapshot.caster_index.tolist(),
        "receiver_index": snapshot.receiver_index.tolist(),
        "actor_bounds": snapshot.actor_bounds.tolist(),
        "caster_bounds": snapshot.caster_bounds.tolist(),
        "receiver_bounds": snapshot.receiver_bounds.tolist(),
        "caster_model_columns": snapshot.caster_model_columns.tolist(),
        "caster_sides": snapshot.caster_sides,
        "caster_keys": snapshot.caster_keys,
        "caster_flat": snapshot.caster_flat.tolist(),
        "caster_triangles": snapshot.caster_triangles.tolist(),
        "caster_serials": snapshot.caster_serials.tolist(),
        "rows": snapshot.caster_rows(snapshot.casters[::-1]).tolist(),
        "boxes": [snapshot.receivers_box.tolist(), snapshot.casters_box.tolist()],
    }


def test_a_snapshot_after_moved_actors_follows_the_last_and_derives_what_a_fresh_one_would():
    """Moving actors patches last frame's derived arrays in their rows: the same values as
    deriving them from every actor again, each row in its place."""
    from pvshadows.scene.snapshot import Snapshot

    pl, _ = crowd()
    shadows = pl.shadows._renderers[0]
    first = shadows.snapshot
    flat = next(s for s in first.actors if s.sheet is not None)
    moved = [first.casters[3].actor, first.casters[150].actor, flat.actor]
    for step, actor in enumerate(moved):
        actor.AddPosition(0.25 * (step + 1), -0.5, 0.1)
    draw(pl)
    following = shadows.snapshot
    assert following.parent is first
    rows = [next(i for i, s in enumerate(first.actors) if s.actor is a) for a in moved]
    assert following.replaced == tuple(sorted(rows))
    fresh = Snapshot(list(following.actors), following.bystanders)
    assert _derived(following) == _derived(fresh)
    # The follower took over the parent's arrays to patch them in place: the parent,
    # asked again, derives its own afresh from its actors.
    assert _derived(first) == _derived(Snapshot(list(first.actors), first.bystanders))
    assert _derived(following) != _derived(first)
    # Only one generation back is kept: the next one cuts this one from its parent.
    moved[0].AddPosition(0.1, 0.0, 0.0)
    draw(pl)
    assert shadows.snapshot.parent is following and following.parent is None


def test_a_flat_receivers_span_after_moved_actors_is_patched_to_what_every_corner_gives():
    """Moving receivers measures again their heights over a ground that stayed: the
    same span as measuring every receiver afresh, and as every box corner gives."""
    from pvshadows.scene.culling import box_corners
    from pvshadows.scene.snapshot import Snapshot

    pl, _ = crowd()
    shadows = pl.shadows._renderers[0]
    first = shadows.snapshot
    ground = next(s for s in first.actors if s.sheet is not None)
    first.sheet_span(ground)
    for row, lift in ((3, 2.5), (150, -1.75)):
        first.casters[row].actor.AddPosition(0.3, -0.2, lift)
    draw(pl)
    following = shadows.snapshot
    assert following.parent is first and ground in following.actors
    patched = following.sheet_span(ground)
    fresh = Snapshot(list(following.actors), following.bystanders).sheet_span(ground)
    assert patched == fresh != first.sheet_span(ground)
    others = [s.bounds for s in following.receivers if s is not ground]
    heights = box_corners(np.array(others)).reshape(-1, 3) @ ground.sheet.normal
    offset = ground.sheet.anchor @ ground.sheet.normal
    assert np.allclose(patched, (heights.min() - offset, heights.max() - offset), atol=1e-12)


def test_the_boxes_round_every_actor_widen_over_moved_actors_unless_one_left_a_face(
    monkeypatch,
):
    import pvshadows.scene.snapshot as snapshot_module
    from pvshadows.scene.snapshot import Snapshot

    pl, _ = crowd()
    shadows = pl.shadows._renderers[0]
    top, inner = shadows.snapshot.casters[3].actor, shadows.snapshot.casters[150].actor
    top.AddPosition(0.0, 0.0, 2.5)  # now the highest: it holds the boxes' top face
    inner.AddPosition(0.0, 0.0, 0.5)  # off the ground: it holds no face of either box
    draw(pl)
    before = shadows.snapshot
    _ = before.receivers_box, before.casters_box  # derived, as a frame does
    rounds = []
    measured = snapshot_module.box_around
    monkeypatch.setattr(snapshot_module, "box_around", lambda b: rounds.append(1) or measured(b))
    inner.AddPosition(0.3, -0.2, 1.5)  # rises above every other sphere, under the top one
    draw(pl)
    following = shadows.snapshot
    assert following.parent is before and following.replaced
    boxes = [following.receivers_box.tolist(), following.casters_box.tolist()]
    assert rounds == []  # widened from last frame's boxes, no walk over every actor
    fresh = Snapshot(list(following.actors), following.bystanders)
    assert boxes == [fresh.receivers_box.tolist(), fresh.casters_box.tolist()]
    rounds.clear()  # (the fresh snapshot's)
    top.AddPosition(0.1, 0.0, 0.0)  # it keeps the top face it holds: widened again
    draw(pl)
    assert rounds == []
    top.AddPosition(0.0, 0.0, -2.5)  # it leaves the top face: the boxes are found afresh
    draw(pl)
    latest = shadows.snapshot
    assert latest.casters_box.tolist() == measured(latest.caster_bounds).tolist()
    assert latest.receivers_box.tolist() == measured(latest.receiver_bounds).tolist()
    assert rounds


def test_an_actor_that_changes_role_gives_a_fresh_snapshot():
    pl, _ = crowd()
    shadows = pl.shadows._renderers[0]
    sphere = shadows.snapshot.casters[5].actor
    sphere.prop.lighting = False  # no longer a receiver
    draw(pl)
    assert pl.shadows.last_frame.failure is None
    assert shadows.snapshot.parent is None
    assert sphere not in [s.actor for s in shadows.snapshot.receivers]
    assert sphere in [s.actor for s in shadows.snapshot.casters]


def _two_pools():
    """Two spot lights over two far-apart boxes on one ground, each light over one box."""
    from pvshadows.tools.scenes import spot_light

    pl = pv.Plotter(off_screen=True, window_size=(320, 240), lighting="none")
    pl.add_mesh(pv.Plane(i_size=40, j_size=12), color="white")
    left = pl.add_mesh(pv.Cube(center=(-12, 0, 1)), color="tan")
    right = pl.add_mesh(pv.Cube(center=(12, 0, 1)), color="tan")
    lights = [spot_light((x, 0, 8), (x, 0, 0), 25, 0.5) for x in (-12.0, 12.0)]
    for light in lights:
        pl.add_light(light)
    pl.camera_position = [(0, -30, 25), (0, 0, 0), (0, 0, 1)]
    pl.shadows.enable(filter="hard")
    draw(pl)
    return pl, lights, left, right


def test_an_actor_moving_outside_a_lights_reach_keeps_that_lights_plan():
    pl, lights, left, _ = _two_pools()
    shadows = pl.shadows._renderers[0]
    kept, planned = shadows.plans[1], shadows.memo.planned
    before = counters(pl)
    left.AddPosition(0.3, 0.0, 0.0)
    draw(pl)
    counted = change(before, counters(pl))
    assert counted["cone tests"] == 2  # the moved box, once per light
    assert shadows.memo.planned - planned == 1
    assert shadows.plans[1] is kept  # the right light reaches neither where it was nor is
    assert pl.shadows.last_frame.passes_run == 1
    for light in lights:
        assert pl.shadows.measure(light).misclassified <= 0.002


def test_an_actor_moving_into_a_lights_reach_plans_that_light_again():
    pl, lights, left, _ = _two_pools()
    shadows = pl.shadows._renderers[0]
    kept = shadows.plans[1]
    left.SetPosition(22.0, 0.0, 0.0)  # from under the left light to under the right one
    draw(pl)
    assert shadows.plans[1] is not kept
    assert len(shadows.plans[1].cast.casters) == 3  # the ground and both boxes
    assert pl.shadows.last_frame.passes_run == 2
    for light in lights:
        assert pl.shadows.measure(light).misclassified <= 0.002


def test_a_caster_is_tested_for_closure_only_when_a_light_culls_front_faces(monkeypatch):
    import pvshadows.scene.triangles as triangles

    tested = []
    closed = triangles.is_closed_outward

    def counted(points, faces):
        tested.append(len(faces))
        return closed(points, faces)

    monkeypatch.setattr(triangles, "is_closed_outward", counted)
    scene = standard_scene()
    pl = scene.plotter
    pl.shadows.enable(technique="cubemap", filter="hard")
    draw(pl)
    assert tested == []  # a pass over every caster's triangles that nothing would read
    pl.shadows.configure(scene.light, cull_front=True)
    draw(pl)
    # each caster once: ground, box, sphere, cylinder
    assert sorted(tested) == sorted(
        pl.shadows._reader.triangles_of(a).n_triangles
        for a in (scene.ground, scene.box, scene.sphere, scene.cylinder)
    )
    assert pl.shadows.measure(scene.light).misclassified <= 0.002


def test_a_spots_measures_patched_over_moved_actors_match_measures_taken_afresh():
    from pvshadows.scene.measures import CasterMeasureCache
    from pvshadows.scene.spot_fitting import cone_measures

    pl, _ = crowd()
    shadows = pl.shadows._renderers[0]
    ground = shadows.snapshot.receivers[0].actor
    movers = [s.actor for s in shadows.plans[0].cast.casters if s.actor is not ground][:3]
    for step, actor in enumerate(movers * 2):
        actor.AddPosition(0.05 * (step + 1), -0.03, 0.02)
        draw(pl)
    cast = shadows.plans[0].cast
    (state,) = shadows.technique("map")._states.values()
    patched = state.measures.of(cast.pose, shadows.snapshot).values
    fresh = CasterMeasureCache(cone_measures).of(cast.pose, shadows.snapshot).values
    assert state.measures.measured == len(shadows.snapshot.casters) + 2 * len(movers)
    for name in ("near", "far", "spread"):
        assert getattr(patched, name).tolist() == getattr(fresh, name).tolist()


def test_an_actor_moved_under_many_spot_lights_is_tested_and_measured_for_all_in_one_call():
    from pvshadows.scene.measures import CasterMeasureCache
    from pvshadows.scene.spot_fitting import cone_measures
    from pvshadows.tools.overhead import OverheadScene, build_scene

    pl, lights, moved = build_scene(OverheadScene("lights", "spot", lights=5), (200, 150))
    pl.shadows.enable(lights=lights, filter="hard")
    draw(pl)
    shadows = pl.shadows._renderers[0]
    group = shadows.technique("map")._spot_measures
    batches, tests = (shadows.reach.batches, group.batches), shadows.reach.tests
    for step in range(3):
        moved.AddPosition(0.05, 0.02 * step, 0.0)
        draw(pl)
    assert (shadows.reach.batches, group.batches) == (batches[0] + 3, batches[1] + 3)
    assert shadows.reach.tests - tests == 3 * len(lights)  # the moved box, once per light
    assert pl.shadows.last_frame.passes_run == len(lights)
    states = shadows.technique("map")._states
    for plan in shadows.plans:
        if plan.cast is None:
            continue
        patched = states[plan.key].measures.of(plan.cast.pose, shadows.snapshot).values
        fresh = CasterMeasureCache(cone_measures).of(plan.cast.pose, shadows.snapshot).values
        assert np.array(patched).tobytes() == np.array(fresh).tobytes()
    for light in lights:
        assert pl.shadows.measure(light).misclassified <= 0.002


def test_a_snapshot_remembers_the_rows_of_its_latest_subsets_only():
    from pvshadows.scene.snapshot import KEPT_SUBSETS

    pl, _ = crowd()
    snapshot = pl.shadows._renderers[0].snapshot
    made = [snapshot.casters_at(np.array([0, row])) for row in range(1, 3 * KEPT_SUBSETS)]
    assert len(snapshot._subsets) == KEPT_SUBSETS
    # the oldest, forgotten, and the newest, remembered, are found at the same rows
    newest = 3 * KEPT_SUBSETS - 1
    assert [snapshot.caster_rows(made[i]).tolist() for i in (0, -1)] == [[0, 1], [0, newest]]


def test_a_point_light_measures_only_the_moved_actor_for_its_cube():
    scene = standard_scene(window_size=(200, 150), light="point")
    pl = scene.plotter
    pl.shadows.enable(lights=[scene.light])
    draw(pl)
    shadows = pl.shadows._renderers[0]
    (state,) = shadows.technique("cubemap")._states.values()
    casters = len(shadows.snapshot.casters)
    assert state.measures.measured == casters
    scene.sphere.AddPosition(0.05, 0.0, 0.0)
    draw(pl)
    assert state.measures.measured == casters + 1
    assert pl.shadows.last_frame.passes_run == 1
    scene.light.position = (0.5, -0.25, 6.0)
    draw(pl)
    assert state.measures.measured == 2 * casters + 1


@pytest.mark.parametrize("light", ["point", "spot"])
def test_a_redrawn_map_reuses_its_framebuffer_as_attached(light, monkeypatch):
    """The map's framebuffer is attached and checked once; each redraw only binds and clears."""
    import pvshadows.gl.cube_array
    import pvshadows.gl.textures

    scene = standard_scene(window_size=(320, 240), light=light)
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    checks = []
    for module in (pvshadows.gl.cube_array, pvshadows.gl.textures):
        checked = module.finish_binding
        monkeypatch.setattr(
            module, "finish_binding", lambda *a, checked=checked: (checks.append(a), checked(*a))
        )
    x, y, z = scene.light.position
    for step in range(1, 4):
        scene.light.position = (x + 0.1 * step, y, z)
        draw(pl)
        assert pl.shadows.last_frame.passes_run == 1
        assert pl.shadows.measure(scene.light).misclassified <= 0.01
    assert checks == []


def test_a_frame_says_the_cpu_time_of_pvshadows_own_code_the_passes_within_it():
    """``last_frame.cpu_ms`` holds pvshadows' own work on both sides of VTK's draw, the
    passes' issuing among it; with subplots, every renderer's."""
    pl = pv.Plotter(off_screen=True, shape=(1, 2), window_size=(320, 160), lighting="none")
    lights = []
    for column in range(2):
        pl.subplot(0, column)
        pl.add_mesh(pv.Plane(i_size=6, j_size=6), color="white")
        pl.add_mesh(pv.Sphere(center=(0, 0, 1)), color="tan")
        lights.append(pv.Light(position=(1, 1, 5), positional=True, cone_angle=180))
        pl.add_light(lights[-1], only_active=True)
    pl.shadows.enable(filter="hard")
    draw(pl)
    lights[0].position = (1.2, 1, 5)  # the left subplot's cube is drawn again
    pl.render()
    frame = pl.shadows.last_frame
    own = [renderer.last_frame.cpu_ms for renderer in pl.shadows._renderers]
    assert frame.passes_run == 1
    assert frame.cpu_ms == sum(own)
    assert own[0] > frame.pass_cpu_ms > 0.0  # the pass is part of the left one's frame
    assert own[1] > 0.0  # nothing to draw on the right, but the frame was still read


def test_a_read_that_fails_half_way_leaves_the_next_read_right(monkeypatch):
    """An error while reading the moved actors again (the first one read, the second
    not) is not the end of them: the next read gives both where they are now."""
    from pvshadows.scene.reader import SceneReader

    pl = pv.Plotter(off_screen=True)
    first, second = pl.add_mesh(pv.Cube()), pl.add_mesh(pv.Sphere(center=(3, 0, 0)))
    reader = SceneReader(lambda actor: "an actor")
    reader.read(pl.renderer)
    first.AddPosition(1.0, 0.0, 0.0)
    second.AddPosition(0.0, 2.0, 0.0)
    entry, reads = reader._entry, []

    def fails_at_the_second(actor, camera):
        reads.append(actor)
        if len(reads) == 2:
            raise RuntimeError("a VTK error while reading")
        return entry(actor, camera)

    monkeypatch.setattr(reader, "_entry", fails_at_the_second)
    with pytest.raises(RuntimeError, match="a VTK error"):
        reader.read(pl.renderer)
    monkeypatch.setattr(reader, "_entry", entry)
    snapshot = reader.read(pl.renderer)
    placed = {vtk_id(state.actor): state.matrix[:3, 3].tolist() for state in snapshot.actors}
    assert placed == {vtk_id(first): [1.0, 0.0, 0.0], vtk_id(second): [0.0, 2.0, 0.0]}
    assert np.allclose(snapshot.casters_box, [[0.5, -0.5, -0.5], [3.5, 2.5, 0.5]], atol=0.01)
    pl.close()


PLACES = pytest.mark.parametrize(
    ("scale", "offset"),
    [(1.0, (0, 0, 0)), (1e-4, (0, 0, 0)), (1e6, (0, 0, 0)), (1.0, (1e6, 1e6, 1e6))],
    ids=["unit", "scaled 1e-4", "scaled 1e6", "translated 1e6"],
)


@PLACES
@pytest.mark.parametrize("light", ["spot", "point"])
def test_a_light_moving_and_turning_a_little_keeps_its_shadows_right(light, scale, offset):
    """Frames of a light dragged a little at a time: each draws its map again, from
    measures taken once with a margin, and each frame's shadows match ray casting,
    at every scale and far from the origin."""
    scene = standard_scene(window_size=(240, 180), light=light, scale=scale, offset=offset)
    pl = scene.plotter
    pl.shadows.enable(lights=[scene.light], filter="hard")
    draw(pl)
    (state,) = (
        pl.shadows._renderers[0]
        ._techniques["map" if light == "spot" else "cubemap"]
        ._states.values()
    )
    position, focal_point = np.array(scene.light.position), np.array(scene.light.focal_point)
    errors = []
    for step in range(1, 4):
        scene.light.position = position + np.array([0.01, -0.005, 0.0]) * step * scale
        # about 0.3 degrees a step
        scene.light.focal_point = focal_point + np.array([0.03, 0.0, 0.0]) * step * scale
        draw(pl)
        assert pl.shadows.last_frame.passes_run == 1
        if step == 1:
            measured = state.measures.measured
        errors.append(pl.shadows.measure(scene.light).misclassified)
    assert state.measures.measured == measured  # the margin held the later moves
    assert max(errors) <= 0.002


def test_a_suns_widened_boxes_hold_every_box_turned_within_its_slack():
    from pvshadows.scene.lights import LightKind, LightPose
    from pvshadows.scene.sun_fitting import SUN_TURN_DEGREES, sun_actors, sun_rotation

    pl, _ = crowd()
    snapshot = pl.shadows._renderers[0].snapshot
    rng = np.random.default_rng(0)
    checked = 0
    for _ in range(20):
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        base = LightPose(LightKind.DIRECTIONAL, np.zeros(3), direction, 180.0)
        widened = sun_actors(base, sun_rotation(base), snapshot, SUN_TURN_DEGREES)
        for _ in range(10):
            turned = direction + rng.normal(size=3) * 0.006
            pose = LightPose(
                LightKind.DIRECTIONAL, np.zeros(3), turned / np.linalg.norm(turned), 180.0
            )
            rotation = sun_rotation(pose)
            if not widened.holds(rotation):
                continue
            checked += 1
            # The boxes turned exactly, from the same pivot, lie inside the widened ones.
            exact = sun_actors(pose, rotation, snapshot)
            for name in ("receivers", "every_caster"):
                inner, outer = getattr(exact, name), getattr(widened, name)
                assert np.all(outer[:, 0] <= inner[:, 0]) and np.all(outer[:, 1] >= inner[:, 1])
    assert checked > 50


@PLACES
def test_a_sun_turning_a_little_reads_its_actors_once_and_keeps_its_shadows_right(scale, offset):
    scene = standard_scene(window_size=(240, 180), light="directional", scale=scale, offset=offset)
    pl = scene.plotter
    pl.shadows.enable(lights=[scene.light], filter="hard")
    draw(pl)
    state = pl.shadows._renderers[0].technique("map")._states[vtk_id(scene.light)]
    position = np.array(scene.light.position)
    errors, read = [], []
    for step in range(1, 5):
        # about 0.1 degree a step
        scene.light.position = position + np.array([0.02, -0.01, 0.0]) * step * scale
        draw(pl)
        assert pl.shadows.last_frame.passes_run == 1
        read.append(state.sun_actors[2])
        errors.append(pl.shadows.measure(scene.light).misclassified)
    # read once, widened, at the first move; the later moves stay within the slack
    assert read[0].slack > 0 and all(each is read[0] for each in read)
    assert max(errors) <= 0.002


def lit_twice():
    """The standard scene under a spot light (a 2D map) and a point light (a cube)."""
    scene = standard_scene(window_size=(200, 150), light="spot")
    bulb = pv.Light(position=(-2, 1, 4), focal_point=(-2, 1, 3), positional=True, cone_angle=180)
    scene.plotter.add_light(bulb)
    scene.plotter.shadows.enable(filter="hard")
    draw(scene.plotter)
    draw(scene.plotter)
    return scene.plotter


def test_a_camera_frame_takes_each_still_light_again_and_fills_the_block_as_afresh():
    pl = lit_twice()
    shadows = pl.shadows._renderers[0]
    kept = shadows.lights_kept
    for _ in range(3):
        pl.camera.Azimuth(10)
        taken_again = draw(pl)
    # neither light is brought up again: its map, shading and textures are last frame's,
    # and its entry's view-to-light matrix is made for the new camera
    assert shadows.lights_kept - kept == 6
    assert pl.shadows.last_frame.passes_run == 0
    block = shadows._block.floats
    shadows.memo.forget()  # new casts: both lights are brought up to date in full
    afresh = draw(pl)
    assert shadows.lights_kept - kept == 6
    assert shadows._block.floats.tobytes() == block.tobytes()
    assert np.array_equal(afresh, taken_again)


def test_a_frame_in_which_nothing_changed_packs_and_sends_no_light_again():
    pl = lit_twice()
    shadows = pl.shadows._renderers[0]
    before = counters(pl)
    kept = shadows.lights_kept
    draw(pl)
    assert shadows.lights_kept - kept == 2
    assert change(before, counters(pl))["block uploads"] == 0


def test_a_moved_spot_light_is_brought_up_to_date_and_the_other_light_taken_again():
    pl = lit_twice()
    shadows = pl.shadows._renderers[0]
    kept = shadows.lights_kept
    spot = next(light for light in pl.renderer.lights if light.cone_angle < 90)
    spot.position = np.add(spot.position, (0.3, 0.0, 0.0))
    draw(pl)
    assert shadows.lights_kept - kept == 1
    assert [light.passes[0].status for light in pl.shadows.last_frame.lights] == ["run", "reused"]


def test_a_lights_pose_is_read_from_vtk_only_when_its_pose_time_moved():
    pl = lit_twice()
    memo = pl.shadows._renderers[0].memo
    read = memo.poses_read
    sphere = pl.renderer.actors["sphere"]
    for _ in range(3):
        sphere.AddPosition(0.01, 0.0, 0.0)
        pl.camera.Azimuth(5)
        draw(pl)
    assert memo.poses_read == read
    spot = next(light for light in pl.renderer.lights if light.cone_angle < 90)
    spot.position = np.add(spot.position, (0.3, 0.0, 0.0))
    draw(pl)
    assert memo.poses_read == read + 1
    assert pl.shadows.measure(spot).misclassified <= 0.005


@pytest.mark.parametrize("light", ["spot", "point", "directional"])
def test_a_light_that_only_moved_takes_its_last_plan_to_its_new_pose(light):
    scene, shadows = hard_standard(light)
    pl = scene.plotter
    memo, (plan,) = shadows.memo, shadows.plans
    cast, reposed, planned = plan.cast, memo.reposed, memo.planned
    scene.light.position = np.add(scene.light.position, (0.05, 0.0, 0.0))
    draw(pl)
    (moved,) = shadows.plans
    assert (memo.reposed - reposed, memo.planned - planned) == (1, 1)
    assert moved.cast is not cast and moved.cast.casters is cast.casters
    assert moved.cast.pose.position.tolist() == list(scene.light.position)
    assert pl.shadows.last_frame.passes_run >= 1
    assert pl.shadows.measure(scene.light).misclassified <= 0.005


@pytest.mark.parametrize(
    "change",
    ["switched off", "widened to a point light", "out of its cover"],
)
def test_a_moved_spot_light_whose_decisions_change_is_planned_afresh(change):
    scene, shadows = hard_standard("spot")
    pl = scene.plotter
    memo = shadows.memo
    reposed, planned = memo.reposed, memo.planned
    scene.light.position = np.add(scene.light.position, (0.05, 0.0, 0.0))
    if change == "switched off":
        scene.light.switch_off()
    elif change == "widened to a point light":
        scene.light.cone_angle = 120.0
    else:
        scene.light.position = np.add(scene.light.position, (3.0, 0.0, 0.0))
    draw(pl)
    (plan,) = pl.shadows._renderers[0].plans
    assert (memo.reposed - reposed, memo.planned - planned) == (0, 1)
    if change == "switched off":
        assert plan.cast is None
        assert pl.shadows.last_frame.passes_run == 0
    else:
        assert plan.technique == ("cubemap" if change == "widened to a point light" else "map")
        assert pl.shadows.measure(scene.light).misclassified <= 0.005


def test_a_dragged_spot_light_keeps_its_casters_distances_while_their_measures_hold():
    """Its map is drawn again and fitted afresh at each move, from the casters'
    distances kept while the measures they come from hold; the shadows match ray
    casting."""
    scene = standard_scene(window_size=(240, 180), light="spot")
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    (state,) = pl.shadows._renderers[0]._techniques["map"]._states.values()
    position = np.array(scene.light.position)
    abouts, projections, distances = [], set(), []  # the lists hold them: ids stay apart
    for step in range(1, 13):
        scene.light.position = np.add(position, (0.005 * step, 0.0, 0.0))
        draw(pl)
        assert pl.shadows.last_frame.passes_run == 1
        abouts.append(state.fitted_about)
        projections.add(state.light_to_clip.tobytes())
        distances.append(state.distances.range)
    assert len({id(d) for d in distances}) == len({id(a) for a in abouts}) <= 3
    assert len(projections) == 12
    assert pl.shadows.measure(scene.light).misclassified <= 0.005


@pytest.mark.parametrize("light", ["point", "spot", "directional"])
def test_a_dragged_light_gathers_its_casters_once_and_keeps_its_shadows_right(light):
    """Each move draws the light's map again, multiplying the same gathered casters by
    its new view (a point light's cube also keeps its casters' distances while their
    measures hold); the shadows match ray casting."""
    scene = standard_scene(window_size=(240, 180), light=light)
    pl = scene.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    technique = pl.shadows._renderers[0]._techniques["cubemap" if light == "point" else "map"]
    (state,) = technique._states.values()
    gathered, drawn = technique.drawn_rows.gathered, technique.casters_drawn
    position = np.array(scene.light.position)
    ranges = []
    for step in range(1, 9):
        scene.light.position = np.add(position, (0.005 * step, 0.0, 0.0))
        draw(pl)
        assert pl.shadows.last_frame.passes_run >= 1
        if light == "point":
            ranges.append(state.distances.range)
    assert technique.casters_drawn - drawn >= 8 * 3
    assert technique.drawn_rows.gathered - gathered <= 1
    if light == "point":
        assert len({id(taken) for taken in ranges}) <= 2
    assert pl.shadows.measure(scene.light).misclassified <= 0.005


def test_a_light_swapped_for_an_equal_one_is_planned_and_the_old_one_forgotten():
    scene, shadows = hard_standard("spot")
    pl = scene.plotter
    twin = scene.light.copy()
    assert twin == scene.light  # pyvista's lights compare by their settings: not the same light
    pl.renderer.RemoveLight(scene.light)
    pl.add_light(twin)
    draw(pl)
    # What was kept of the light that left is forgotten, though an equal light took its place.
    assert list(shadows.memo._plans) == [id(twin)]
    assert list(shadows.reach._lights) == [vtk_id(twin)]
    assert pl.shadows.measure(twin).misclassified <= 0.005


def test_a_sun_is_taken_again_while_the_camera_stays_and_brought_up_when_it_moves():
    scene, shadows = hard_standard("directional")
    pl = scene.plotter
    kept, still = shadows.lights_kept, draw(pl)
    assert shadows.lights_kept - kept == 1
    pl.camera.Azimuth(20)  # a sun's map is fitted to the view: it follows the camera
    draw(pl)
    assert shadows.lights_kept - kept == 1
    pl.camera.Azimuth(-20)
    assert np.array_equal(draw(pl), still)
    assert pl.shadows.measure(scene.light).misclassified <= 0.005


def test_the_lights_are_listed_from_vtk_again_only_when_the_renderer_gains_or_loses_one():
    pl = lit_twice()
    shadows = pl.shadows._renderers[0]
    memo, listed = shadows.memo, shadows.memo.listings
    spot = next(light for light in pl.renderer.lights if light.cone_angle < 90)
    for _ in range(3):  # the camera, a light and an actor move: the same lights
        pl.camera.Azimuth(5)
        spot.position = np.add(spot.position, (0.05, 0.0, 0.0))
        pl.renderer.actors["sphere"].AddPosition(0.01, 0.0, 0.0)
        draw(pl)
    assert memo.listings == listed
    pl.renderer.RemoveLight(spot)
    draw(pl)
    assert memo.listings == listed + 1
    assert [plan.light for plan in shadows.plans] == list(pl.renderer.lights)
    assert all(plan.light is not spot for plan in shadows.plans)
    pl.add_light(spot)
    draw(pl)
    assert memo.listings == listed + 2
    assert shadows.plans[-1].light is spot and shadows.plans[-1].cast is not None
    assert pl.shadows.measure(spot).misclassified <= 0.005


#: What each screen-mask technique is held to against the ray-cast reference.
MASK_BOUNDS = {"volume": 0.003, "planar": 0.005}


@pytest.mark.parametrize("technique", ["volume", "planar"])
def test_a_screen_mask_is_drawn_again_only_when_the_camera_or_the_actors_changed(technique):
    scene = standard_scene(window_size=(200, 150), light="spot")
    pl = scene.plotter
    if technique == "planar":  # the ground receives; the box too, which planar shadows say
        for actor in (scene.sphere, scene.cylinder):
            pl.shadows.set_receiver(actor, False)
    pl.shadows.enable(technique=technique)
    drawn = draw(pl)
    shadows = pl.shadows._renderers[0]
    report = lambda: next(lt for lt in pl.shadows.last_frame.lights if lt.technique)  # noqa: E731
    notes = report().notes
    kept = shadows.lights_kept
    for _ in range(3):
        again = draw(pl)
        # the light is taken again as it was: its mask, shading, textures and notes
        assert [p.status for p in report().passes] == ["reused"]
        assert report().notes == notes
    assert shadows.lights_kept - kept == 3
    assert np.array_equal(again, drawn)
    pl.camera.Azimuth(10)  # a screen-space mask follows the camera
    draw(pl)
    assert shadows.lights_kept - kept == 3
    assert "run" in [p.status for p in report().passes]
    scene.sphere.position = (0.2, 0.0, 0.0)
    draw(pl)
    assert shadows.lights_kept - kept == 3
    assert pl.shadows.measure(scene.light).misclassified <= MASK_BOUNDS[technique]


def volume_scene(light="spot", camera=None):
    """The standard scene drawn twice with ``technique="volume"``: it, its renderer's shadows."""
    scene = standard_scene(window_size=(200, 150), light=light)
    if camera is not None:
        scene.plotter.camera_position = camera
    scene.plotter.shadows.enable(technique="volume")
    draw(scene.plotter)
    draw(scene.plotter)
    return scene, scene.plotter.shadows._renderers[0]


def walked_zmodes(scene, shadows, walk, steps):
    """Draw each step of ``walk(t)``; check its z-mode against the full test's for its view."""
    from pvshadows.pipeline.volume_zmode import choose_zmode

    volume = shadows.technique("volume")
    answers = []
    for t in np.linspace(0.0, 1.0, steps):
        walk(t)
        draw(scene.plotter)
        cast, view = shadows.plans[0].cast, shadows._context.view
        light, boxes = cast.volume.light, cast.volume.caster_boxes
        expected, _ = choose_zmode("auto", light, scene.plotter.renderer, boxes, view)
        assert volume.zmode_of(scene.light) == expected, t
        answers.append(expected)
    return answers


def test_a_volume_light_chooses_zpass_or_zfail_again_only_for_a_new_camera_or_hidden_lines():
    scene, shadows = volume_scene()
    pl = scene.plotter
    chosen = shadows.memo.zmodes_chosen
    for _ in range(3):
        draw(pl)
    assert shadows.memo.zmodes_chosen == chosen
    pl.camera.Azimuth(20)  # further than a kept z-pass's room
    draw(pl)
    draw(pl)
    assert shadows.memo.zmodes_chosen == chosen + 1
    pl.enable_hidden_line_removal()
    draw(pl)
    assert shadows.memo.zmodes_chosen == chosen + 2
    notes = pl.shadows.last_frame.lights[0].notes
    assert "zpass: the camera is outside every shadow volume" in notes
    assert pl.shadows.measure(scene.light).misclassified <= MASK_BOUNDS["volume"]


def test_a_kept_zpass_holds_while_the_camera_keeps_its_room_and_never_inside_a_volume():
    scene, shadows = volume_scene()
    pl = scene.plotter
    # The camera walks into the box's shadow (light at (0.3, -0.2, 3.5), box round
    # (-2, -0.3, 1.7)): every frame's choice is the full test's for that frame's view.
    start, end = np.array([-8.0, -6.0, 1.0]), np.array([-3.15, -0.35, 0.8])

    def walk(t):
        pl.camera.position = (1 - t) * start + t * end

    answers = walked_zmodes(scene, shadows, walk, 40)
    assert answers[0] == "zpass" and answers[-1] == "zfail"
    pl.camera.position = (11.0, -12.5, 9.5)  # back out, then a slow orbit
    draw(pl)
    chosen = shadows.memo.zmodes_chosen
    for _ in range(20):  # far from every shadow volume
        pl.camera.Azimuth(1.0)
        draw(pl)
        assert shadows.technique("volume").zmode_of(scene.light) == "zpass"
    assert 1 <= shadows.memo.zmodes_chosen - chosen <= 8


def test_a_moving_volume_light_keeps_its_zpass_only_while_it_keeps_its_room():
    scene, shadows = volume_scene()
    chosen = shadows.memo.zmodes_chosen
    x, y, z = scene.light.position
    for step in range(10):  # a new cast each frame, far from every volume
        scene.light.position = (x + 0.01 * (step + 1), y, z)
        draw(scene.plotter)
        assert shadows.technique("volume").zmode_of(scene.light) == "zpass"
        notes = scene.plotter.shadows.last_frame.lights[0].notes
        assert "zpass: the camera is outside every shadow volume" in notes
    assert shadows.memo.zmodes_chosen - chosen <= 2
    # A point light walks to where the camera is in the box's shadow: every frame's
    # choice is the full test's, though the walk starts with room to spare.
    camera = [(-6, -0.3, 4.5), (0, 0, 0.3), (0, 0, 1)]
    scene, shadows = volume_scene("point", camera)
    start, end = np.array([-6.0, -6, 6]), np.array([0, -0.3, 0.3])

    def walk(t):
        scene.light.position = tuple((1 - t) * start + t * end)

    answers = walked_zmodes(scene, shadows, walk, 30)
    assert answers[0] == "zpass" and answers[-1] == "zfail"


def test_the_receiving_plane_is_chosen_again_only_for_other_receivers():
    scene = standard_scene(window_size=(200, 150), light="spot")
    pl = scene.plotter
    pl.shadows.enable(technique="planar")
    draw(pl)
    memo = pl.shadows._renderers[0].memo
    chosen = memo.planes_chosen
    x, y, z = scene.light.position
    for step in range(4):  # a new plan each frame, the same receivers
        scene.light.position = (x + 0.01 * (step + 1), y, z)
        draw(pl)
    assert memo.planes_chosen == chosen
    assert any(
        "receiving plane: actor 'ground'" in note for note in pl.shadows.last_frame.lights[0].notes
    )
    scene.sphere.AddPosition(0.01, 0.0, 0.0)  # a receiver's state changes
    draw(pl)
    assert memo.planes_chosen == chosen + 1
    assert pl.shadows.measure(scene.light).misclassified <= MASK_BOUNDS["planar"]


def test_a_forced_zpass_says_it_may_miscount_in_every_frame_a_caster_is_open_to_view():
    # Seen through a wireframe caster, "auto" would count with z-fail: the forced
    # z-pass keeps its warning note, frame after frame, however far from any volume.
    scene = standard_scene(window_size=(200, 150), light="spot")
    pl = scene.plotter
    scene.sphere.GetProperty().SetRepresentationToWireframe()
    with pytest.warns(UserWarning, match="may miscount"):
        pl.shadows.enable(technique="volume", zmode="zpass")
        draw(pl)
    x, y, z = scene.light.position
    for step in range(4):  # a new cast each frame, and a new view
        scene.light.position = (x + 0.01 * (step + 1), y, z)
        pl.camera.Azimuth(0.5)
        draw(pl)
        notes = pl.shadows.last_frame.lights[0].notes
        assert any(n.startswith("zpass: zpass forced") and "may miscount" in n for n in notes)


def test_a_still_volume_frame_names_no_caster_however_many_there_are(monkeypatch):
    from pvshadows.techniques import volume as volume_module

    pl, light, _ = crowd_scene(60, window_size=(200, 150))
    pl.shadows.enable(technique="volume")
    draw(pl)
    draw(pl)
    named = []
    real = volume_module.vtk_id
    monkeypatch.setattr(volume_module, "vtk_id", lambda obj: named.append(obj) or real(obj))
    for _ in range(3):
        draw(pl)
    assert named == []  # the same casts: nothing to release, no caster listed
    light.intensity = 0.0  # the light casts nothing now: its mask goes
    draw(pl)
    assert pl.shadows._renderers[0].technique("volume").mask_of(light) is None


@pytest.mark.parametrize("extrude", ["gpu", "cpu"])
def test_a_moving_volume_light_keeps_its_casters_split_and_its_draws(extrude, monkeypatch):
    from pvshadows.techniques import volume as volume_module

    pl, light, _ = crowd_scene(60, window_size=(200, 150))
    pl.shadows.enable(technique="volume", extrude=extrude)
    draw(pl)
    shadows = pl.shadows._renderers[0]
    technique = shadows.technique("volume")
    (state,) = technique._lights.values()
    drawn, splits = state.drawn, shadows.memo.splits
    named = []
    real = volume_module.vtk_id
    monkeypatch.setattr(volume_module, "vtk_id", lambda obj: named.append(obj) or real(obj))
    x, y, z = light.position
    for step in range(4):  # a new cast each frame over the same casters
        light.position = (x + 0.02 * (step + 1), y - 0.01 * step, z)
        pl.camera.Azimuth(1.0)
        draw(pl)
        assert "run" in [p.status for p in pl.shadows.last_frame.lights[0].passes]
    assert shadows.memo.splits == splits  # the casters were sorted once
    if extrude == "gpu":  # the same draws: no caster named
        assert state.drawn is drawn and named == []
    else:  # volumes built on the CPU follow the light
        assert state.drawn is not drawn
    assert pl.shadows.measure(light).misclassified <= MASK_BOUNDS["volume"]
    # A caster that moves is patched into the split; it casts the same volume from
    # elsewhere, so volumes extruded on the GPU keep their draws.
    drawn, depth, named[:] = state.drawn, technique._depth_of, []
    moved = shadows.plans[0].cast.casters[0].actor
    moved.AddPosition(0.05, 0.0, 0.0)
    draw(pl)
    assert (shadows.memo.splits, shadows.memo.split_patches) == (splits, 1)
    if extrude == "gpu":  # the same volumes from elsewhere: the same draws, no caster named
        assert state.drawn is drawn and named == []
    else:
        assert state.drawn is not drawn
    # the depth pre-pass's actors are patched too
    assert technique._depth_of.numbers is depth.numbers and technique._depth_of is not depth
    assert pl.shadows.measure(light).misclassified <= MASK_BOUNDS["volume"]
    moved.mapper.dataset.copy_from(pv.Cube(center=moved.center, x_length=0.3))  # a new mesh
    draw(pl)
    assert (shadows.memo.splits, shadows.memo.split_patches) == (splits, 2)
    assert state.drawn is not drawn
    assert pl.shadows.measure(light).misclassified <= MASK_BOUNDS["volume"]
