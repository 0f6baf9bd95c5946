"""Many small casters drawn through one batch: the same depths as one draw per caster, in few calls.

Each scene is drawn twice, through the batch and one caster at a time (the
batch's threshold raised out of reach), frame after frame while the light
moves, a caster moves, a caster's points change in place and a caster's
mesh is replaced: every pixel must agree. The calls a pass submits and the
times the batch is built are counted; the shadows are judged against ray
casting.
"""

import itertools

import numpy as np
import pytest
import pyvista as pv

import pvshadows.gl.caster_batch as caster_batch
import pvshadows.gl.volume_batch as volume_batch
from conftest import draw, point_light
from pvshadows.geometry.transforms import translation
from pvshadows.techniques.per_light import ADD_FROM, _ModelColumns
from pvshadows.tools.scenes import spot_light

#: Casters on the grid besides the ground and the floating disc.
GRID = 5


def _scene(kind):
    plotter = pv.Plotter(off_screen=True, window_size=[240, 180], lighting="none")
    plotter.add_mesh(pv.Plane(i_size=12, j_size=12), color="white")
    meshes = []
    for i in range(GRID):
        for j in range(GRID):
            centre = (-4.0 + 2.0 * i, -4.0 + 2.0 * j, 0.6)
            if (i + j) % 3:
                mesh = pv.Sphere(radius=0.5, center=centre, theta_resolution=8, phi_resolution=8)
            else:
                mesh = pv.Cube(center=centre, x_length=0.8, y_length=0.8, z_length=1.2)
            plotter.add_mesh(mesh, color="tan")
            meshes.append(mesh)
    # an open caster: neither side culled when cull_front is set
    disc = pv.Disc(center=(0.5, 0.5, 2.5), inner=0.0, outer=0.8, normal=(0, 0, 1), c_res=12)
    plotter.add_mesh(disc, color="tan")
    if kind == "spot":
        light = spot_light((0.5, 0.3, 9.0), (0, 0, 0), cone_angle=40, intensity=1.0)
    elif kind == "point":
        light = point_light((0.7, -0.4, 5.0))
    else:
        light = pv.Light(position=(4, 2, 8), focal_point=(0, 0, 0))
    plotter.add_light(light)
    plotter.camera_position = [(8, -11, 9), (0, 0, 0.5), (0, 0, 1)]
    return plotter, light, meshes


def _frames(kind, options, threshold, monkeypatch, parallel=False):
    """Draw the scene's five frames; return the images and the renderer's batch keeper."""
    monkeypatch.setattr(caster_batch, "MIN_CASTERS", threshold)
    monkeypatch.setattr(volume_batch, "MIN_VOLUMES", threshold)
    plotter, light, meshes = _scene(kind)
    if parallel:
        plotter.enable_parallel_projection()
    plotter.shadows.enable(lights=[light], **options)
    images = [draw(plotter)]
    x, y, z = light.GetPosition()
    light.SetPosition(x + 0.4, y - 0.3, z)
    images.append(draw(plotter))
    plotter.renderer.actors[list(plotter.renderer.actors)[3]].AddPosition(0.3, 0.2, 0.0)
    images.append(draw(plotter))
    meshes[7].points = meshes[7].points + np.array([0.0, 0.0, 0.4])
    images.append(draw(plotter))
    meshes[1].copy_from(pv.Sphere(radius=0.7, center=meshes[1].center, theta_resolution=12))
    images.append(draw(plotter))
    keeper = plotter.shadows._renderers[0]._buffers.batches
    return plotter, light, images, keeper


CASES = [
    ("spot", {}),
    ("point", {"passes": "single"}),
    ("point", {"passes": "six"}),
    ("directional", {}),
    ("spot", {"cull_front": True}),
    ("point", {"cull_front": True}),
    ("spot", {"technique": "volume"}),  # the depth pre-pass draws the batch
    ("point", {"technique": "volume"}),
]


@pytest.mark.parametrize(("kind", "options"), CASES)
def test_batched_casters_draw_the_same_depths_as_one_by_one(kind, options, monkeypatch):
    _, _, alone, unused = _frames(kind, options, 10**9, monkeypatch)
    assert unused.builds == 0
    plotter, light, batched, keeper = _frames(kind, options, 16, monkeypatch)
    for frame, (one, other) in enumerate(zip(alone, batched, strict=True)):
        assert np.array_equal(one, other), f"frame {frame}: {(one != other).any(-1).sum()} px"
    # the frames differ from one another: each change was drawn
    assert all(not np.array_equal(a, b) for a, b in itertools.pairwise(batched))
    # built once, patched in place for new points, built again for a new mesh
    assert keeper.builds == 2
    assert plotter.shadows.measure(light).misclassified <= 0.005


def test_a_pass_submits_a_chunk_and_a_draw_per_side(monkeypatch):
    plotter, light, _, keeper = _frames("spot", {}, 16, monkeypatch)
    batch = keeper._kept[1]
    casters = GRID * GRID + 2
    assert len(batch) == casters
    before = batch.calls
    light.SetPosition(*(np.array(light.GetPosition()) + 0.1))
    draw(plotter)
    (report,) = plotter.shadows.last_frame.lights[0].passes
    assert report.status == "run" and report.detail.startswith(f"{casters} of {casters}")
    assert batch.calls - before == 2  # one chunk of matrices, one multi-draw


def test_the_volume_depth_pre_pass_draws_every_actor_through_the_batch(monkeypatch):
    plotter, _, _, keeper = _frames("spot", {"technique": "volume"}, 16, monkeypatch)
    batch = keeper._kept[1]
    actors = GRID * GRID + 2
    assert len(batch) == actors
    before = batch.calls
    plotter.camera.azimuth = 5.0
    draw(plotter)
    reports = plotter.shadows.last_frame.lights[0].passes
    (depth,) = [r for r in reports if r.name == "volume depth pre-pass"]
    assert depth.status == "run" and depth.detail == f"{actors} actors"
    assert batch.calls - before == 2  # one chunk of matrices, one multi-draw


VOLUME_CASES = [
    ("spot", "zpass", False),
    ("point", "zfail", False),
    ("directional", "zfail", False),
    ("spot", "zfail", True),  # parallel projection: volumes of finite reach
]


@pytest.mark.parametrize(("kind", "zmode", "parallel"), VOLUME_CASES)
@pytest.mark.parametrize("chunk", [256, 8])
def test_batched_volumes_count_the_same_shadows_as_one_by_one(
    kind, zmode, parallel, chunk, monkeypatch
):
    options = {"technique": "volume", "zmode": zmode}
    _, _, alone, _ = _frames(kind, options, 10**9, monkeypatch, parallel)
    monkeypatch.setattr(caster_batch, "MAX_CHUNK", chunk)
    plotter, light, batched, _ = _frames(kind, options, 16, monkeypatch, parallel)
    (state,) = plotter.shadows._renderers[0].technique("volume")._lights.values()
    assert state.batch is not None and state.batch.in_batch.sum() >= 16
    rows = caster_batch.chunk_rows(plotter.ren_win, volume_batch.ROW_VECTORS, geometry=True)
    assert state.batch.chunk == rows <= chunk
    for frame, (one, other) in enumerate(zip(alone, batched, strict=True)):
        assert np.array_equal(one, other), f"frame {frame}: {(one != other).any(-1).sum()} px"
    assert all(not np.array_equal(a, b) for a, b in itertools.pairwise(batched))
    assert plotter.shadows.measure(light).misclassified <= 0.005


def test_a_volume_count_submits_one_multi_draw_per_chunk_of_rows(monkeypatch):
    monkeypatch.setattr(caster_batch, "MAX_CHUNK", 8)
    plotter, _, _, _ = _frames("spot", {"technique": "volume"}, 16, monkeypatch)
    (state,) = plotter.shadows._renderers[0].technique("volume")._lights.values()
    batch = state.batch
    rows = len(batch.in_batch)
    before = batch.calls
    plotter.camera.azimuth = 5.0
    draw(plotter)
    assert batch.calls - before == -(-rows // 8)  # the batch holds every closed caster
    assert state.batch is batch  # the camera moved: the same batch


@pytest.mark.parametrize("kind", ["spot", "point", "directional"])
@pytest.mark.parametrize("chunk", [256, 8])
def test_batched_flattened_casters_draw_the_same_planar_mask_as_one_by_one(
    kind, chunk, monkeypatch
):
    _, _, alone, _ = _frames(kind, {"technique": "planar"}, 10**9, monkeypatch)
    monkeypatch.setattr(caster_batch, "MAX_CHUNK", chunk)
    plotter, _, batched, keeper = _frames(kind, {"technique": "planar"}, 16, monkeypatch)
    assert keeper.builds == 2
    for frame, (one, other) in enumerate(zip(alone, batched, strict=True)):
        assert np.array_equal(one, other), f"frame {frame}: {(one != other).any(-1).sum()} px"
    assert all(not np.array_equal(a, b) for a, b in itertools.pairwise(batched))
    batch = keeper._kept[1]
    before = batch.calls
    plotter.camera.azimuth = 5.0
    draw(plotter)
    rows = len(batch)
    assert batch.calls - before == 2 * -(-rows // batch.chunk)  # a chunk and a draw each


@pytest.mark.parametrize("kind", ["spot", "point"])
def test_chunks_of_few_rows_draw_the_same_depths(kind, monkeypatch):
    _, _, alone, _ = _frames(kind, {"cull_front": True}, 10**9, monkeypatch)
    monkeypatch.setattr(caster_batch, "MAX_CHUNK", 8)
    _, _, batched, keeper = _frames(kind, {"cull_front": True}, 16, monkeypatch)
    assert keeper._kept[1].chunk == 8
    for frame, (one, other) in enumerate(zip(alone, batched, strict=True)):
        assert np.array_equal(one, other), f"frame {frame}"


def test_big_casters_are_drawn_on_their_own_beside_the_batch(monkeypatch):
    _, _, alone, _ = _frames("spot", {}, 10**9, monkeypatch)
    monkeypatch.setattr(caster_batch, "SMALL", 20)  # spheres (84+ triangles) alone, cubes batched
    _, _, batched, keeper = _frames("spot", {}, 4, monkeypatch)
    rows = keeper._kept[1].rows
    assert 0 < (rows >= 0).sum() < len(rows)
    for frame, (one, other) in enumerate(zip(alone, batched, strict=True)):
        assert np.array_equal(one, other), f"frame {frame}"


def test_the_batch_is_released_when_few_casters_are_left():
    plotter, light, _ = _scene("spot")
    plotter.shadows.enable(lights=[light])
    draw(plotter)
    keeper = plotter.shadows._renderers[0]._buffers.batches
    assert keeper._kept is not None
    for name in list(plotter.renderer.actors)[1:20]:
        plotter.remove_actor(name)
    draw(plotter)
    assert keeper._kept is None
    assert plotter.shadows.measure(light).misclassified <= 0.005


def test_a_translating_view_gives_the_products_float32_columns_without_the_product():
    rng = np.random.default_rng(7)
    models = rng.normal(size=(ADD_FROM, 4, 4)) * 1e6  # far from the origin, as at 1e6 scale
    models[:, 3] = (0.0, 0.0, 0.0, 1.0)
    columns = np.ascontiguousarray(models.transpose(0, 2, 1))
    kept = _ModelColumns(columns)
    assert kept._affine is not None
    turned = translation((-1.5e6, 2.25, -3.3e-3))
    turned[:3, :3] = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    for view in (translation((-1.5e6, 2.25, -3.3e-3)), turned):
        moved = kept.to_light(view)
        expected = np.ascontiguousarray((view @ models).transpose(0, 2, 1), dtype=np.float32)
        assert moved.dtype == np.float32 and moved.flags.c_contiguous
        np.testing.assert_array_equal(moved, expected)
    models[5, 3] = (1e-3, 0.0, 0.0, 1.0)  # a projective matrix: the product, always
    projective = _ModelColumns(np.ascontiguousarray(models.transpose(0, 2, 1)))
    assert projective._affine is None
    view = translation((4.0, 5.0, 6.0))
    expected = np.ascontiguousarray((view @ models).transpose(0, 2, 1), dtype=np.float32)
    np.testing.assert_array_equal(projective.to_light(view), expected)
    assert _ModelColumns(columns[: ADD_FROM - 1])._affine is None  # few: the product
