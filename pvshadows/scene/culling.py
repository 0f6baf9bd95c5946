"""Conservative tests of boxes against what a camera sees and what a light reaches."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import from_vtk_matrix, look_rotation, squared_lengths
from pvshadows.scene.lights import LightPose


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
    >>> from pvshadows.scene.culling import frustum_planes
    >>> frustum_planes(vtk.vtkCamera(), 1.0).shape
    (6, 4)
    """
    matrix = camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)
    return clip_planes(from_vtk_matrix(matrix))


#: Picks each frustum plane out of a clip matrix's rows: the last plus or minus one other.
_PLANE_ROWS = np.array(
    [
        [sign if row == axis else 0.0 for row in range(3)] + [1.0]
        for axis in range(3)
        for sign in (1.0, -1.0)
    ]
)


def clip_planes(m: np.ndarray) -> np.ndarray:
    """Return the six frustum planes of a world-to-clip matrix (depth in [-1, 1]).

    Parameters
    ----------
    m : numpy.ndarray
        ``(4, 4)`` world-to-clip matrix.

    Returns
    -------
    numpy.ndarray
        ``(6, 4)`` planes, as :func:`frustum_planes` returns them (not
        normalised: only the side of a point is read).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import clip_planes
    >>> clip_planes(np.eye(4))[0].tolist()
    [1.0, 0.0, 0.0, 1.0]
    """
    # Each plane is the last row plus or minus one of the first three.
    return _PLANE_ROWS @ m


def boxes_in_frustum(boxes: np.ndarray, planes: np.ndarray) -> np.ndarray:
    """Test many world boxes against a frustum at once (conservative: never misses one seen).

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.
    planes : numpy.ndarray
        ``(6, 4)`` frustum planes from :func:`frustum_planes`.

    Returns
    -------
    numpy.ndarray
        ``(n,)`` bool, ``False`` only for boxes wholly outside one plane.

    Examples
    --------
    >>> import numpy as np
    >>> import vtk
    >>> from pvshadows.scene.culling import boxes_in_frustum, frustum_planes
    >>> boxes = np.array([[[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]], [[0, 0, 2], [1, 1, 3]]])
    >>> boxes_in_frustum(boxes, frustum_planes(vtk.vtkCamera(), 1.0)).tolist()
    [True, False]
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    # Each plane's distance to the box corner farthest along its normal: the
    # normal's positive parts meet the maximum corner, its negative parts the minimum.
    normals = planes[:, :3]
    distance = boxes[:, 1] @ np.maximum(normals, 0.0).T + boxes[:, 0] @ np.minimum(normals, 0.0).T
    distance += planes[:, 3]
    return np.all(distance >= 0.0, axis=1)


#: Up to this many boxes, :func:`boxes_seen` tests them in plain floats: numpy's
#: calls cost more than their arithmetic.
FEW_BOXES = 32


def box_seen(
    low: list[float], high: list[float], planes: list[tuple[float, float, float, float]]
) -> bool:
    """Test one box against a frustum in plain floats, like :func:`boxes_in_frustum`.

    Parameters
    ----------
    low, high : list of float
        The box's min and max corners.
    planes : list of tuple
        The frustum's planes as rows of four floats (``planes.tolist()``).

    Returns
    -------
    bool
        ``False`` only for a box wholly outside one plane.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.scene.culling import box_seen, frustum_planes
    >>> planes = frustum_planes(vtk.vtkCamera(), 1.0).tolist()  # at z = 1, looking down -z
    >>> box_seen([-0.1, -0.1, -1.0], [0.1, 0.1, -0.5], planes)
    True
    >>> box_seen([0.0, 0.0, 2.0], [1.0, 1.0, 3.0], planes)
    False
    """
    for a, b, c, d in planes:
        x = high[0] if a > 0.0 else low[0]
        y = high[1] if b > 0.0 else low[1]
        z = high[2] if c > 0.0 else low[2]
        if a * x + b * y + c * z + d < 0.0:
            return False
    return True


def boxes_seen(boxes: np.ndarray, planes: np.ndarray) -> list[bool]:
    """Return :func:`boxes_in_frustum` as a list, testing a few boxes in plain floats.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.
    planes : numpy.ndarray
        ``(6, 4)`` frustum planes from :func:`frustum_planes`.

    Returns
    -------
    list of bool
        ``False`` only for boxes wholly outside one plane; the same answers
        whichever way they are tested.

    Examples
    --------
    >>> import numpy as np
    >>> import vtk
    >>> from pvshadows.scene.culling import boxes_seen, frustum_planes
    >>> boxes = np.array([[[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]], [[0, 0, 2], [1, 1, 3]]])
    >>> boxes_seen(boxes, frustum_planes(vtk.vtkCamera(), 1.0))
    [True, False]
    """
    if len(boxes) > FEW_BOXES:
        return boxes_in_frustum(boxes, planes).tolist()
    rows = planes.tolist()
    return [box_seen(low, high, rows) for low, high in np.asarray(boxes).tolist()]


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
    >>> from pvshadows.scene.culling import box_in_spot
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 10.0)
    >>> box_in_spot(np.array([[-0.1, -0.1, -2], [0.1, 0.1, -1]]), pose)
    True
    >>> box_in_spot(np.array([[3, 3, -2], [4, 4, -1]]), pose)
    False
    """
    lo, hi = np.asarray(box, dtype=np.float64).tolist()
    return _one_box_in_spot(lo, hi, pose)


def box_around(boxes: np.ndarray) -> np.ndarray:
    """Return the box around boxes.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.

    Returns
    -------
    numpy.ndarray
        ``(2, 3)``: the least of the min corners and the greatest of the max
        corners (NaN when there is no box).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import box_around
    >>> box_around(np.array([[[0, 0, 0], [1, 1, 1]], [[2, -1, 0], [3, 0, 4]]])).tolist()
    [[0, -1, 0], [3, 1, 4]]
    """
    if not len(boxes):
        return np.full((2, 3), np.nan)
    return np.array([boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)])


#: Which of the min (0) or max (1) corner each coordinate of a box's eight corners takes.
CORNER_SIDES = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
_CORNERS = np.array(CORNER_SIDES, dtype=bool)


def box_corners(boxes: np.ndarray) -> np.ndarray:
    """Return the eight corners of each box, in one call.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.

    Returns
    -------
    numpy.ndarray
        ``(n, 8, 3)``: x from the min or max corner, then y, then z, the
        min first in each.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import box_corners
    >>> box_corners(np.array([[[0, 0, 0], [1, 2, 3]]]))[0, [0, 1, 7]].tolist()
    [[0, 0, 0], [0, 0, 3], [1, 2, 3]]
    """
    boxes = np.asarray(boxes)
    return np.where(_CORNERS[None], boxes[:, 1, None, :], boxes[:, 0, None, :])


def widened_boxes(boxes: np.ndarray, margin: float) -> np.ndarray:
    """Return boxes grown by ``margin`` on every side.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.
    margin : float
        How far each face moves out.

    Returns
    -------
    numpy.ndarray
        ``(n, 2, 3)``: ``boxes`` itself when ``margin`` is 0, else new boxes.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import widened_boxes
    >>> widened_boxes(np.array([[[0.0, 0, 0], [1, 2, 3]]]), 0.5)[0].tolist()
    [[-0.5, -0.5, -0.5], [1.5, 2.5, 3.5]]
    """
    if margin == 0.0:
        return boxes
    return boxes + np.array([[-margin] * 3, [margin] * 3])


def box_offsets(boxes: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """Return each box's min and max corners less a point, one coordinate per row.

    Laid out so that every row is contiguous: numpy works through a
    ``(3, n)`` row of coordinates several times faster than through the
    strided columns of ``(n, 2, 3)`` boxes.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` min/max corners.
    origin : numpy.ndarray
        ``(3,)`` the point.

    Returns
    -------
    numpy.ndarray
        ``(2, 3, n)``: ``[0]`` the min corners less ``origin``, ``[1]`` the
        max corners, each a C-contiguous ``(3, n)``.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import box_offsets
    >>> box_offsets(np.array([[[0.0, 0, 0], [1, 2, 3]]]), np.ones(3))[:, :, 0].tolist()
    [[-1.0, -1.0, -1.0], [0.0, 1.0, 2.0]]
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    offsets = np.empty((2, 3, len(boxes)))
    np.subtract(boxes.transpose(1, 2, 0), np.asarray(origin)[None, :, None], out=offsets)
    return offsets


def box_corners_along(offsets: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    """Return the eight corners of each box of :func:`box_offsets`, in rotated axes.

    The corners of :func:`box_corners` less the offsets' origin, turned by
    ``rotation``, one coordinate per row, built from each axis's two
    terms: no ``(8 n, 3)`` array goes through a matrix product.

    Parameters
    ----------
    offsets : numpy.ndarray
        ``(2, 3, n)`` boxes' corners less a point, from :func:`box_offsets`
        (or ``(..., 2, 3, n)``: a stack, one per rotation).
    rotation : numpy.ndarray
        ``(3, 3)`` rows: the new axes in world coordinates (or ``(..., 3, 3)``).

    Returns
    -------
    numpy.ndarray
        ``(..., 3, 8, n)``: coordinate, corner (in :func:`box_corners`'
        order), box.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import box_corners_along, box_offsets
    >>> offsets = box_offsets(np.array([[[0.0, 0, 0], [1, 2, 3]]]), np.zeros(3))
    >>> swap = np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]])
    >>> box_corners_along(offsets, swap)[:, 7, 0].tolist()
    [2.0, 1.0, 3.0]
    """
    # terms[..., k, side, axis]: rotated coordinate k of the min or max corner's offset
    # along an axis
    terms = np.asarray(rotation)[..., :, None, :, None] * offsets[..., None, :, :, :]
    x = terms[..., :, :, 0, None, None, :]
    y = terms[..., :, None, :, 1, None, :]
    z = terms[..., :, None, None, :, 2, :]
    return (x + y + z).reshape(*terms.shape[:-4], 3, 8, terms.shape[-1])


@lru_cache(maxsize=256)
def _cone_planes(direction: tuple[float, float, float], cone_angle: float) -> np.ndarray:
    """Return the apex plane and the four sides of the pyramid around a cone, ``(5, 3)``.

    Worked out once per direction and angle: a light tested again and again
    (one moved actor per frame, say) does not pay for the cross products.
    """
    # Missed whenever the light turns: plain floats, as numpy's cross products cost ten times more.
    hint = (0.0, 0.0, 1.0) if abs(direction[2]) < 0.9 else (1.0, 0.0, 0.0)
    (right, up, backward) = (row[:3] for row in look_rotation(direction, hint).tolist()[:3])
    forward = [-b for b in backward]
    spread = math.tan(math.radians(min(cone_angle, 89.9)))
    planes = np.array(
        [forward]
        + [
            [spread * f + sign * a for f, a in zip(forward, axis, strict=True)]
            for axis in (right, up)
            for sign in (-1.0, 1.0)
        ]
    )
    planes.setflags(write=False)
    return planes


@lru_cache(maxsize=256)
def _cone_plane_sides(
    direction: tuple[float, float, float], cone_angle: float
) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Return what :func:`boxes_in_spot` reads of a cone, once per direction and angle.

    The planes' normals as rows, split into their positive and negative
    parts (which meet a box's max and min corner), and the cosine and sine
    of the cone's angle.
    """
    normals = _cone_planes(direction, cone_angle)
    positive, negative = np.maximum(normals, 0.0), np.minimum(normals, 0.0)
    angle = np.radians(min(cone_angle, 89.9))
    return positive, negative, float(np.cos(angle)), float(np.sin(angle))


@lru_cache(maxsize=256)
def _cone_plane_rows(
    direction: tuple[float, float, float], cone_angle: float
) -> tuple[tuple[float, ...], ...]:
    """Return :func:`_cone_planes` as plain floats, for one box tested alone."""
    return tuple(tuple(row) for row in _cone_planes(direction, cone_angle).tolist())


def _one_box_in_spot(lo: list[float], hi: list[float], pose: LightPose) -> bool:
    """Test one box as :func:`boxes_in_spot` does, in plain floats.

    For one box, numpy's cost per call outweighs its speed: an actor that
    moved is tested alone under each spot light.
    """
    position = pose.position.tolist()
    lo = [a - p for a, p in zip(lo, position, strict=True)]
    hi = [b - p for b, p in zip(hi, position, strict=True)]
    if all(a <= 0.0 for a in lo) and all(b >= 0.0 for b in hi):
        return True
    direction = pose.direction.tolist()
    for normal in _cone_plane_rows(tuple(direction), float(pose.cone_angle)):
        farthest = sum((b if n > 0.0 else a) * n for a, b, n in zip(lo, hi, normal, strict=True))
        if farthest < 0.0:
            return False
    center = [0.5 * (a + b) for a, b in zip(lo, hi, strict=True)]
    radius = 0.5 * math.dist(lo, hi)
    along = sum(c * d for c, d in zip(center, direction, strict=True))
    across = math.hypot(*(c - along * d for c, d in zip(center, direction, strict=True)))
    angle = math.radians(min(pose.cone_angle, 89.9))
    return across * math.cos(angle) - along * math.sin(angle) <= radius


def boxes_in_spot(boxes: np.ndarray, pose: LightPose) -> np.ndarray:
    """Test many world boxes against a spot light's cone at once, like :func:`box_in_spot`.

    A box passes when it holds the light, or when it is inside the apex
    plane and the four sides of the pyramid around the cone and the sphere
    around it reaches the cone's surface.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` world bounds.
    pose : LightPose
        The spot light.

    Returns
    -------
    numpy.ndarray
        ``(n,)`` bool, ``False`` only for boxes certainly outside the cone.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import boxes_in_spot
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 10.0)
    >>> boxes = np.array([[[-0.1, -0.1, -2], [0.1, 0.1, -1]], [[3, 3, -2], [4, 4, -1]]])
    >>> boxes_in_spot(boxes, pose).tolist()
    [True, False]
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    if len(boxes) == 1:
        lo_, hi_ = boxes[0].tolist()
        return np.array([_one_box_in_spot(lo_, hi_, pose)])
    direction = pose.direction
    lo, hi = box_offsets(boxes, pose.position)
    holds_light = ((lo <= 0.0) & (hi >= 0.0)).all(axis=0)
    # A box is behind a plane through the light when its corner farthest along the
    # plane's normal is: the normal's positive parts meet ``hi``, its negative ones ``lo``.
    positive, negative, cos, sin = _cone_plane_sides(
        tuple(direction.tolist()), float(pose.cone_angle)
    )
    behind_a_plane = (positive @ hi + negative @ lo).min(axis=0) < 0.0
    center = 0.5 * (lo + hi)
    size = hi - lo
    radius = 0.5 * np.sqrt(squared_lengths(size))
    along = direction @ center
    aside = center - direction[:, None] * along
    across = np.sqrt(squared_lengths(aside))
    # Distance from the centre of the sphere around the box to the cone's surface.
    outside = across * cos - along * sin
    return holds_light | (~behind_a_plane & (outside <= radius))


#: From this many spot lights on, one numpy call that tests (or measures) a moved
#: actor's box for all of them costs less than a plain-float call per light.
MANY_LIGHTS = 3


class SpotCones:
    """Several spot lights' cones, stacked once for :func:`boxes_in_spots` to test boxes against.

    Parameters
    ----------
    poses : list of LightPose
        The spot lights (or their covers).
    """

    def __init__(self, poses: list[LightPose]) -> None:
        sides = [_cone_plane_sides(tuple(p.direction.tolist()), float(p.cone_angle)) for p in poses]
        #: ``(lights, 5, 3)`` the positive and negative parts of each cone's planes' normals.
        self.positive = np.array([s[0] for s in sides])
        self.negative = np.array([s[1] for s in sides])
        #: ``(lights, 1)`` the cosine and sine of each cone's angle.
        self.cos = np.array([[s[2]] for s in sides])
        self.sin = np.array([[s[3]] for s in sides])
        #: ``(lights, 1, 3)`` each light's direction, ``(lights, 3, 1)`` its position.
        self.directions = np.array([p.direction for p in poses])[:, None, :]
        self.positions = np.array([p.position for p in poses])[:, :, None]


def boxes_in_spots(boxes: np.ndarray, cones: SpotCones) -> np.ndarray:
    """Test a few world boxes against several spot lights' cones at once.

    Each light's answers are :func:`boxes_in_spot`'s, worked out for every
    light in the same few numpy calls: an actor that moved under many spot
    lights is tested against all of them in one go.

    Parameters
    ----------
    boxes : numpy.ndarray
        ``(n, 2, 3)`` world bounds.
    cones : SpotCones
        The spot lights.

    Returns
    -------
    numpy.ndarray
        ``(lights, n)`` bool, ``False`` only for a box certainly outside
        that light's cone.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.culling import SpotCones, boxes_in_spots
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> down = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 10.0)
    >>> aside = LightPose(LightKind.SPOT, np.array([3.5, 3.5, 0]), np.array([0, 0, -1.0]), 10.0)
    >>> boxes = np.array([[[-0.1, -0.1, -2], [0.1, 0.1, -1]], [[3, 3, -2], [4, 4, -1]]])
    >>> boxes_in_spots(boxes, SpotCones([down, aside])).tolist()
    [[True, False], [False, True]]
    """
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 2, 3)
    # (lights, 3, boxes): the boxes' min and max corners less each light's position, as
    # box_offsets lays them out for one
    corners = boxes.transpose(1, 2, 0)
    lo, hi = corners[0] - cones.positions, corners[1] - cones.positions
    holds_light = ((lo <= 0.0) & (hi >= 0.0)).all(axis=1)
    # A box is behind a plane through the light when its corner farthest along the
    # plane's normal is: the normal's positive parts meet ``hi``, its negative ones ``lo``.
    behind_a_plane = (cones.positive @ hi + cones.negative @ lo).min(axis=1) < 0.0
    center = 0.5 * (lo + hi)
    radius = 0.5 * np.sqrt(squared_lengths(hi - lo))
    along = (cones.directions @ center)[:, 0]
    aside = center - cones.directions.transpose(0, 2, 1) * along[:, None]
    across = np.sqrt(squared_lengths(aside))
    # Distance from the centre of the sphere around the box to the cone's surface.
    outside = across * cones.cos - along * cones.sin
    return holds_light | (~behind_a_plane & (outside <= radius))
