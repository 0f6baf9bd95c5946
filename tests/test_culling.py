"""Culling against a spot light's cone: conservative, and exact where the answer is plain."""

import numpy as np
import pytest

from pvshadows.pipeline.reach import COVER_DEGREES, cover_holds
from pvshadows.scene.culling import (
    FEW_BOXES,
    boxes_in_frustum,
    boxes_in_spot,
    boxes_seen,
    clip_planes,
    widened_boxes,
)
from pvshadows.scene.lights import LightKind, LightPose


def _random_pose(rng):
    direction = rng.normal(size=3)
    direction /= np.linalg.norm(direction)
    return LightPose(LightKind.SPOT, rng.normal(size=3), direction, float(rng.uniform(2.0, 85.0)))


@pytest.mark.parametrize("seed", range(5))
def test_a_box_holding_a_point_of_the_cone_is_never_culled(seed):
    rng = np.random.default_rng(seed)
    pose = _random_pose(rng)
    centres = pose.position + rng.normal(size=(400, 3)) * 3.0
    halves = rng.uniform(0.05, 1.5, size=(400, 3))
    boxes = np.stack([centres - halves, centres + halves], axis=1)
    # Points spread over each box, corners included.
    t = rng.uniform(size=(400, 64, 3))
    t[:, :8] = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    points = boxes[:, None, 0] + t * (boxes[:, None, 1] - boxes[:, None, 0])
    away = points - pose.position
    cosine = away @ pose.direction / np.linalg.norm(away, axis=2)
    touches = np.any(cosine >= np.cos(np.radians(pose.cone_angle)), axis=1)
    kept = boxes_in_spot(boxes, pose)
    assert touches.sum() > 20 and (~touches).sum() > 20  # both kinds were drawn
    assert np.all(kept[touches])


def _touching(boxes, pose, rng):
    """Which boxes hold a point of the cone, among points spread over each box."""
    t = rng.uniform(size=(len(boxes), 64, 3))
    t[:, :8] = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    points = boxes[:, None, 0] + t * (boxes[:, None, 1] - boxes[:, None, 0])
    away = points - pose.position
    cosine = away @ pose.direction / np.linalg.norm(away, axis=2)
    return np.any(cosine >= np.cos(np.radians(pose.cone_angle)), axis=1)


@pytest.mark.parametrize("seed", range(5))
def test_what_a_cover_reaches_holds_for_every_light_it_holds(seed):
    rng = np.random.default_rng(seed)
    pose = _random_pose(rng)
    back = float(rng.uniform(0.05, 0.5))
    cover = LightPose(
        LightKind.SPOT,
        pose.position - back * pose.direction,
        pose.direction,
        min(pose.cone_angle + COVER_DEGREES, 89.9),
    )
    centres = pose.position + rng.normal(size=(400, 3)) * 3.0
    halves = rng.uniform(0.05, 1.5, size=(400, 3))
    boxes = np.stack([centres - halves, centres + halves], axis=1)
    kept = boxes_in_spot(boxes, cover)
    held = 0
    for _ in range(100):
        turned = pose.direction + rng.normal(size=3) * 0.008
        moved = LightPose(
            LightKind.SPOT,
            pose.position + rng.normal(size=3) * 0.03,
            turned / np.linalg.norm(turned),
            pose.cone_angle,
        )
        if not cover_holds(cover, moved):
            continue
        held += 1
        assert np.all(kept[_touching(boxes, moved, rng)])
    assert held >= 20  # many moves stayed in the cover, and were checked


def test_a_cover_holds_a_light_that_moved_forward_not_one_beside_or_turned_away():
    cover = LightPose(LightKind.SPOT, np.array([0, 0, 1.0]), np.array([0, 0, -1.0]), 12.0)
    down = np.array([0, 0, -1.0])
    tilted = np.array([np.sin(np.radians(3)), 0, -np.cos(np.radians(3))])
    poses = [
        (np.array([0, 0, -5.0]), down),  # far forward along the axis
        (np.array([0.2, 0, 0.0]), down),  # beside, within the cover's edge (tan 12° > 0.2)
        (np.array([0.3, 0, 0.0]), down),  # beside, past it
        (np.zeros(3), tilted),  # turned by more than the two degrees it has to spare
    ]
    held = [cover_holds(cover, LightPose(LightKind.SPOT, p, d, 10.0)) for p, d in poses]
    assert held == [True, True, False, False]


def test_boxes_behind_the_light_or_beside_a_narrow_cone_are_culled():
    pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0.0, 0.0, -1.0]), 10.0)
    boxes = np.array(
        [
            [[-1, -1, 0.5], [1, 1, 2]],  # behind the light
            [[3, -0.5, -3], [4, 0.5, -2]],  # beside the cone
            [[-0.1, -0.1, -5], [0.1, 0.1, -4]],  # on its axis
            [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]],  # holds the light
        ]
    )
    assert boxes_in_spot(boxes, pose).tolist() == [False, False, True, True]


@pytest.mark.parametrize("seed", range(3))
def test_one_box_tested_alone_gets_the_answer_it_gets_among_many(seed):
    rng = np.random.default_rng(seed)
    inside = 0
    for _ in range(40):
        direction = rng.normal(size=3)
        direction /= np.linalg.norm(direction)
        pose = LightPose(
            LightKind.SPOT, rng.uniform(-2, 2, 3), direction, float(rng.uniform(5, 89))
        )
        centres, halves = rng.uniform(-6, 6, (100, 3)), rng.uniform(0.01, 1.5, (100, 3))
        boxes = np.stack([centres - halves, centres + halves], axis=1)
        together = boxes_in_spot(boxes, pose)
        alone = np.concatenate([boxes_in_spot(box[None], pose) for box in boxes])
        assert np.array_equal(alone, together)
        inside += int(together.sum())
    assert 0 < inside < 40 * 100


@pytest.mark.parametrize("seed", range(3))
def test_boxes_tested_in_plain_floats_get_the_answers_numpy_gives(seed):
    rng = np.random.default_rng(seed)
    seen = 0
    for _ in range(20):
        # A random perspective camera: a projection times a random rigid view.
        near, far, f = 0.5, 20.0, float(rng.uniform(0.5, 3.0))
        projection = np.array(
            [
                [f, 0.0, 0.0, 0.0],
                [0.0, f, 0.0, 0.0],
                [0.0, 0.0, (far + near) / (near - far), 2 * far * near / (near - far)],
                [0.0, 0.0, -1.0, 0.0],
            ]
        )
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        view = np.eye(4)
        view[:3, :3], view[:3, 3] = q, rng.uniform(-3, 3, 3)
        planes = clip_planes(projection @ view)
        for count in (FEW_BOXES, FEW_BOXES + 1):
            centres, halves = rng.uniform(-8, 8, (count, 3)), rng.uniform(0.01, 2.0, (count, 3))
            boxes = np.stack([centres - halves, centres + halves], axis=1)
            answers = boxes_seen(boxes, planes)
            assert answers == boxes_in_frustum(boxes, planes).tolist()
            seen += sum(answers)
    assert 0 < seen < 20 * (2 * FEW_BOXES + 1)


@pytest.mark.parametrize("seed", range(3))
def test_boxes_tested_against_many_spots_at_once_get_each_spots_own_answers(seed):
    from pvshadows.scene.culling import SpotCones, boxes_in_spots

    rng = np.random.default_rng(seed)
    inside = 0
    for _ in range(20):
        poses = [_random_pose(rng) for _ in range(int(rng.integers(2, 17)))]
        centres, halves = rng.uniform(-6, 6, (5, 3)), rng.uniform(0.01, 1.5, (5, 3))
        boxes = np.stack([centres - halves, centres + halves], axis=1)
        together = boxes_in_spots(boxes, SpotCones(poses))
        assert together.tolist() == [boxes_in_spot(boxes, pose).tolist() for pose in poses]
        inside += int(together.sum())
    assert 0 < inside < together.size * 20


@pytest.mark.parametrize("seed", range(3))
def test_boxes_measured_from_many_spots_at_once_get_each_spots_own_bits(seed):
    from pvshadows.scene.spot_fitting import cone_measures, cone_measures_many

    rng = np.random.default_rng(seed)
    for trial in range(30):
        scale = 10.0 ** rng.uniform(-6, 9)
        poses = [_random_pose(rng) for _ in range(int(rng.integers(2, 9)))]
        poses = [LightPose(LightKind.SPOT, p.position * scale, p.direction, 40.0) for p in poses]
        count = int(rng.integers(1, 5))
        centres = np.array([p.position for p in poses])[:, None] + rng.normal(
            size=(len(poses), count, 3)
        ) * (4 * scale)
        halves = rng.uniform(0.01, 1.5, (len(poses), count, 3)) * scale
        boxes = np.stack([centres - halves, centres + halves], axis=2)
        together = np.array(cone_measures_many(poses, boxes))
        pairs = zip(poses, boxes, strict=True)
        apart = np.stack([np.array(cone_measures(p, b)) for p, b in pairs], axis=1)
        assert together.tobytes() == apart.tobytes(), trial


@pytest.mark.parametrize("seed", range(3))
def test_one_box_measured_alone_from_a_spot_gets_the_bits_it_gets_among_many(seed):
    """A moved caster is measured alone in plain floats: the same distances and spread,
    to the last bit, as numpy's among many, at every scale, beside and behind the light."""
    from pvshadows.scene.spot_fitting import cone_measures

    rng = np.random.default_rng(seed)
    unbounded = 0
    for trial in range(60):
        scale = 10.0 ** rng.uniform(-6, 9)
        pose = _random_pose(rng)
        pose = LightPose(LightKind.SPOT, pose.position * scale, pose.direction, pose.cone_angle)
        centres = pose.position + rng.normal(size=(50, 3)) * 4 * scale
        halves = rng.uniform(0.01, 1.5, (50, 3)) * scale
        boxes = np.stack([centres - halves, centres + halves], axis=1)
        together = np.array(cone_measures(pose, boxes))
        alone = np.concatenate([np.array(cone_measures(pose, box[None])) for box in boxes], axis=1)
        assert alone.tobytes() == together.tobytes(), trial
        unbounded += int(np.isinf(together[2]).sum())
    assert 0 < unbounded < 60 * 50  # boxes beside or behind the light were drawn too


@pytest.mark.parametrize("seed", range(3))
def test_one_box_measured_alone_from_a_point_light_gets_the_bits_it_gets_among_many(seed):
    """A moved caster is measured alone in plain floats for a cube: the same distances and
    faces, to the last bit, as numpy's among many, at every scale, around the light too."""
    from pvshadows.techniques.cubemap import cube_measures

    rng = np.random.default_rng(seed)
    holding = 0
    for trial in range(60):
        scale = 10.0 ** rng.uniform(-6, 9)
        pose = LightPose(LightKind.POINT, rng.normal(size=3) * scale, np.array([0, 0, -1.0]), 180)
        centres = pose.position + rng.normal(size=(50, 3)) * 3 * scale
        halves = rng.uniform(0.01, 2.0, (50, 3)) * scale
        boxes = np.stack([centres - halves, centres + halves], axis=1)
        together = [np.asarray(column) for column in cube_measures(pose, boxes)]
        alone = [cube_measures(pose, box[None]) for box in boxes]
        for column, values in enumerate(together):
            single = np.concatenate([np.asarray(measures[column]) for measures in alone])
            assert single.dtype == values.dtype and single.tobytes() == values.tobytes(), trial
        holding += int((together[2] == 63).sum())
    assert 0 < holding < 60 * 50  # boxes around the light (every face) were drawn too


def _faces_by_plane(box: np.ndarray) -> int:
    """A cube face's pyramid against a box, plane by plane: its forward plane and four sides."""
    from pvshadows.geometry.transforms import CUBE_FACE_AXES

    mask = 0
    for face, (forward, _) in enumerate(CUBE_FACE_AXES):
        axis = int(np.argmax(np.abs(forward)))
        normals = [np.array(forward)]
        for other in (o for o in range(3) if o != axis):
            for side in (-1.0, 1.0):
                normal = np.array(forward)
                normal[other] = side
                normals.append(normal)
        # a box may overlap a half-space when its farthest corner along the normal is in it
        if all(np.maximum(n * box[0], n * box[1]).sum() >= 0.0 for n in normals):
            mask |= 1 << face
    return mask


@pytest.mark.parametrize("scale", [1e-6, 1.0, 1e9])
def test_cube_faces_touching_boxes_match_a_test_plane_by_plane(scale):
    from pvshadows.geometry.transforms import boxes_from_origin, faces_touching_boxes
    from pvshadows.scene.spot_fitting import box_distances_squared

    rng = np.random.default_rng(7)
    boxes = rng.normal(size=(400, 2, 3)) * scale
    boxes[:40, 1] = boxes[:40, 0]  # points
    boxes[40:80, :, 2] = 0.0  # flat in the plane of two faces' edges
    boxes = np.sort(boxes, axis=1)
    expected = [_faces_by_plane(box) for box in boxes]
    assert faces_touching_boxes(boxes).tolist() == expected
    # the same pass measures the distances, bit for bit as the spot light's measure does
    near, far, _ = boxes_from_origin(boxes)
    near_alone, far_alone = box_distances_squared(np.zeros(3), boxes)
    assert np.array_equal(near, near_alone) and np.array_equal(far, far_alone)
    assert near[[i for i, mask in enumerate(expected) if mask == 63]].max() == 0.0
    # boxes seen by one face only, and boxes around the light, seen by all six
    assert {1, 63} <= set(expected)


@pytest.mark.parametrize("seed", range(3))
@pytest.mark.parametrize("light", ["spot", "point"])
def test_measures_of_widened_boxes_hold_for_a_light_moved_within_the_margin(light, seed):
    """A moving light is served the measures of boxes widened round where it was: nearer
    than every box, farther than its corners, spread as wide about the kept axis, and on
    every cube face it touches from anywhere within the margin."""
    from pvshadows.scene.spot_fitting import _rotation_along, cone_measures
    from pvshadows.techniques.cubemap import cube_measures

    measure = cone_measures if light == "spot" else cube_measures
    rng = np.random.default_rng(seed)
    base = _random_pose(rng)
    centres = base.position + rng.normal(size=(300, 3)) * 4.0
    halves = rng.uniform(0.01, 1.5, (300, 3))
    boxes = np.stack([centres - halves, centres + halves], axis=1)
    margin = 0.05
    kept = measure(base, widened_boxes(boxes, margin))
    turn = _rotation_along(tuple(base.direction.tolist()))[:3, :3]
    for _ in range(20):
        step = rng.normal(size=3)
        moved = LightPose(
            base.kind,
            base.position + step / np.linalg.norm(step) * margin * rng.uniform(0.2, 1.0),
            base.direction,
            base.cone_angle,
        )
        exact = measure(moved, boxes)
        assert np.all(kept.near <= exact.near) and np.all(kept.far >= exact.far)
        if light == "point":
            assert np.all(kept.faces & exact.faces == exact.faces)
            continue
        # The spread about the kept axis, from where the light is now, over every corner.
        sides = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
        corners = np.stack([np.where(side, boxes[:, 1], boxes[:, 0]) for side in sides], axis=1)
        x, y, z = np.moveaxis((corners - moved.position) @ turn.T, -1, 0)
        depth = -z
        in_front = (depth > 0).all(axis=1)
        across = np.maximum(np.abs(x), np.abs(y)) / np.where(in_front[:, None], depth, 1.0)
        spread = np.where(in_front, across.max(axis=1), np.inf)
        assert in_front.sum() > 20  # spreads were compared, not only infinities
        assert np.all(kept.spread >= spread * (1 - 1e-12))
