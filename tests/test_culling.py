"""Culling against a spot light's cone: conservative, and exact where the answer is plain."""

import numpy as np
import pytest

from pvshadows.scene.culling import boxes_in_spot
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
