"""Culling against a spot light's cone and the view: conservative, exact where plain."""

import numpy as np
import pytest
import vtk

from pvshadows.scene.culling import (
    box_inside_frustum,
    boxes_in_frustum,
    boxes_in_spot,
    frustum_planes,
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
def test_a_box_wholly_inside_the_view_holds_only_boxes_in_view(seed):
    rng = np.random.default_rng(seed)
    camera = vtk.vtkCamera()
    camera.SetPosition(*rng.normal(size=3) * 5.0)
    camera.SetFocalPoint(*rng.normal(size=3))
    planes = frustum_planes(camera, 1.5)
    inside = 0
    for _ in range(200):
        centre = np.array(camera.GetFocalPoint()) + rng.normal(size=3) * 0.8
        half = rng.uniform(0.02, 1.0, size=3)
        whole = np.array([centre - half, centre + half])
        # corners and random points of the box, as tiny boxes
        t = rng.uniform(size=(64, 3))
        t[:8] = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
        points = whole[0] + t * (whole[1] - whole[0])
        seen = boxes_in_frustum(np.stack([points, points], axis=1), planes)
        # a frustum is convex: a box is wholly inside exactly when its eight corners are
        wholly = box_inside_frustum(whole, planes)
        assert wholly == _corners_inside(points[:8], planes)
        if wholly:
            inside += 1
            assert seen.all()
    assert 10 < inside < 190


def _corners_inside(corners, planes):
    return bool(np.all(corners @ planes[:, :3].T + planes[:, 3] >= 0.0))


def test_a_box_reaching_out_of_the_view_is_not_wholly_inside():
    camera = vtk.vtkCamera()  # at (0, 0, 1) looking down -z, 30 degrees
    planes = frustum_planes(camera, 1.0)
    assert box_inside_frustum(np.array([[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]]), planes)
    assert not box_inside_frustum(np.array([[-0.1, -0.1, -1.0], [5.0, 0.1, -0.5]]), planes)
    assert not box_inside_frustum(np.array([[-0.1, -0.1, -1.0], [0.1, 0.1, 2.0]]), planes)
    assert not box_inside_frustum(np.full((2, 3), np.nan), planes)
