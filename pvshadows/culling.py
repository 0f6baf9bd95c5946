"""Conservative tests of boxes against what a camera sees and what a light reaches."""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.lights import LightPose


def frustum_planes(camera: vtk.vtkCamera, aspect: float) -> np.ndarray:
    """Return the six planes of a camera's view frustum in world coordinates.

    Parameters
    ----------
    camera : vtk.vtkCamera
        The camera.
    aspect : float
        The renderer's width over height.

    Returns
    -------
    numpy.ndarray
        ``(6, 4)`` planes ``(a, b, c, d)``; a point is inside when every
        ``a x + b y + c z + d >= 0``.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.culling import frustum_planes
    >>> frustum_planes(vtk.vtkCamera(), 1.0).shape
    (6, 4)
    """
    matrix = camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)
    m = np.array([[matrix.GetElement(i, j) for j in range(4)] for i in range(4)])
    planes = np.array(
        [m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2], m[3] - m[2]]
    )
    return planes / np.linalg.norm(planes[:, :3], axis=1, keepdims=True)


def box_in_frustum(box: np.ndarray, planes: np.ndarray) -> bool:
    """Return whether a world box may be seen (conservative: never misses one that is).

    Parameters
    ----------
    box : numpy.ndarray
        ``(2, 3)`` min/max corners.
    planes : numpy.ndarray
        ``(6, 4)`` frustum planes from :func:`frustum_planes`.

    Returns
    -------
    bool
        ``False`` only when the box is wholly outside one plane.

    Examples
    --------
    >>> import numpy as np
    >>> import vtk
    >>> from pvshadows.culling import box_in_frustum, frustum_planes
    >>> camera = vtk.vtkCamera()  # at (0, 0, 1) looking down -z
    >>> planes = frustum_planes(camera, 1.0)
    >>> box_in_frustum(np.array([[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]]), planes)
    True
    >>> box_in_frustum(np.array([[-0.1, -0.1, 2.0], [0.1, 0.1, 3.0]]), planes)
    False
    """
    farthest = np.where(planes[:, :3] >= 0.0, box[1], box[0])
    return bool(np.all(np.sum(planes[:, :3] * farthest, axis=1) + planes[:, 3] >= 0.0))


def box_in_spot(box: np.ndarray, pose: LightPose) -> bool:
    """Return whether a world box may touch a spot light's cone (conservative).

    Parameters
    ----------
    box : numpy.ndarray
        ``(2, 3)`` world bounds.
    pose : LightPose
        The spot light.

    Returns
    -------
    bool
        ``False`` only when the box is certainly outside the cone.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.culling import box_in_spot
    >>> from pvshadows.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 10.0)
    >>> box_in_spot(np.array([[-0.1, -0.1, -2], [0.1, 0.1, -1]]), pose)
    True
    >>> box_in_spot(np.array([[3, 3, -2], [4, 4, -1]]), pose)
    False
    """
    lo, hi = box - pose.position
    if np.all(lo <= 0.0) and np.all(hi >= 0.0):
        return True
    corners = np.array(
        [[x, y, z] for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    )
    forward = pose.direction
    right = np.cross(forward, [0.0, 0.0, 1.0] if abs(forward[2]) < 0.9 else [1.0, 0.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    spread = np.tan(np.radians(min(pose.cone_angle, 89.9)))
    # The apex plane and the four sides of the pyramid around the cone.
    planes = [forward] + [
        spread * forward + sign * axis for axis in (right, up) for sign in (-1, 1)
    ]
    if any(np.all(corners @ plane < 0.0) for plane in planes):
        return False
    center = 0.5 * (lo + hi)
    radius = 0.5 * float(np.linalg.norm(hi - lo))
    along = float(center @ pose.direction)
    across = float(np.linalg.norm(center - along * pose.direction))
    angle = np.radians(min(pose.cone_angle, 89.9))
    # Distance from the centre of the sphere around the box to the cone's surface.
    outside = across * np.cos(angle) - along * np.sin(angle)
    return bool(outside <= radius)
