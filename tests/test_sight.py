"""What the view sees of the receivers: the witnesses' answers are the full test's answers."""

import numpy as np
import pytest
import vtk

from pvshadows.pipeline.sight import ViewSight
from pvshadows.scene.culling import boxes_in_frustum, frustum_planes


@pytest.mark.parametrize("seed", range(3))
def test_answers_from_witnesses_equal_the_full_test_frame_after_frame(seed):
    rng = np.random.default_rng(seed)
    centres = rng.uniform(-10.0, 10.0, size=(300, 3))
    halves = rng.uniform(0.1, 1.0, size=(300, 3))
    bounds = np.stack([centres - halves, centres + halves], axis=1)
    whole = np.array([bounds[:, 0].min(axis=0), bounds[:, 1].max(axis=0)])
    masks = [rng.uniform(size=300) < p for p in (0.01, 0.1, 0.5)]
    camera = vtk.vtkCamera()
    camera.SetPosition(0.0, -30.0, 5.0)
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetViewAngle(20.0)
    witnesses: dict[int, int] = {}
    spared = partial = 0
    for _ in range(60):
        camera.Azimuth(float(rng.uniform(0.0, 3.0)))
        camera.Elevation(float(rng.uniform(-1.0, 1.0)))
        camera.OrthogonalizeViewUp()
        planes = frustum_planes(camera, 1.0)
        seen = boxes_in_frustum(bounds, planes)
        sight = ViewSight(bounds, whole, planes, witnesses)
        assert sight.sees_some() == bool(seen.any())
        for mask in masks:
            assert sight.sees_some(mask) == bool((seen & mask).any())
        spared += sight.tested < len(bounds)
        partial += 0 < seen.sum() < len(seen)
        assert np.array_equal(sight.every, seen)
    assert partial > 30  # the view held some receivers but not all
    assert spared > 10  # the witnesses did answer in many frames


def test_receivers_all_in_view_are_not_tested_one_by_one():
    camera = vtk.vtkCamera()  # at (0, 0, 1) looking down -z, 30 degrees
    planes = frustum_planes(camera, 1.0)
    bounds = np.array(
        [[[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]], [[0.0, 0.0, -3.0], [0.2, 0.2, -2.0]]]
    )
    whole = np.array([bounds[:, 0].min(axis=0), bounds[:, 1].max(axis=0)])
    sight = ViewSight(bounds, whole, planes)
    assert sight.every.tolist() == [True, True] and sight.tested == 0
    # a box reaching out of the view: tested one by one
    wide = bounds.copy()
    wide[1, 1, 0] = 5.0
    whole = np.array([wide[:, 0].min(axis=0), wide[:, 1].max(axis=0)])
    sight = ViewSight(wide, whole, planes)
    assert sight.every.tolist() == [True, True] and sight.tested == 2
