"""Z-pass or z-fail: whether the camera may be inside a shadow volume this frame.

Z-pass counts the volume faces in front of the visible surface, starting
from zero at the camera; it is wrong where the camera itself is inside a
volume. Z-fail (Carmack's reverse) counts the faces behind the surface and
is always right once the volumes are capped and nothing is clipped at the
far plane, but it draws the caps and covers more pixels. So the choice is
made per light and per frame, conservatively, on the CPU:

A point ``x`` lies in the shadow volume of a caster only if the segment from
the light to ``x`` meets the caster, hence its bounding box. The points the
view rays start from (the camera and the near-plane rectangle, with depth
clamping the rays start at the camera) lie in the convex hull of the
camera's near region; if the hull of that region and the light (swept
towards the light to beyond the box for a directional light) misses every
caster's box, no view ray starts inside a volume and z-pass is right.
Otherwise z-fail is used.

A parallel projection cannot draw points at infinity (they all have
``w = 0`` in clip space), and its view rays start at infinity behind the
camera. With it the volumes are extruded to a finite distance beyond every
receiver instead, so they are finite and closed, the view rays start outside
all of them, and z-pass is right.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from itertools import combinations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.boxes import CasterBoxes
from pvshadows.scene.view import FrameView

#: The values ``zmode`` takes.
ZMODES = ("auto", "zpass", "zfail")
#: Why ``"auto"`` counts with z-pass where no caster's volume may hold the camera.
OUTSIDE = "the camera is outside every shadow volume"


def near_region(renderer: vtk.vtkRenderer, view: FrameView | None = None) -> np.ndarray | None:
    """Return the camera position and the four corners of its near-plane rectangle.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer; its active camera and aspect ratio are read.
    view : FrameView, optional
        This frame's view of that camera, whose :attr:`FrameView.near_region`
        is taken (made once per view) instead of reading the camera again.

    Returns
    -------
    numpy.ndarray or None
        ``(5, 3)`` float64 world points, or ``None`` for a parallel projection.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.pipeline.volume_zmode import near_region
    >>> pl = pv.Plotter(off_screen=True)
    >>> near_region(pl.renderer).shape
    (5, 3)
    """
    return (view if view is not None else FrameView.of(renderer)).near_region


def hull_touches_box(points: np.ndarray, box: np.ndarray, margin: float = 1e-9) -> bool:
    """Tell whether the convex hull of a few points meets an axis-aligned box.

    Separating-axis test over the box's axes and every cross product of
    point differences (a superset of the hull's face normals and edge
    directions), so it is exact up to ``margin``, which leans towards
    "touches".

    Parameters
    ----------
    points : numpy.ndarray
        ``(k, 3)`` points, ``k`` at most a dozen or so.
    box : numpy.ndarray
        ``(2, 3)`` min and max corners.
    margin : float, default: 1e-9
        Relative tolerance (of the sizes involved) counted as touching.

    Returns
    -------
    bool
        ``True`` when they may touch.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.pipeline.volume_zmode import hull_touches_box
    >>> box = np.array([[0.0, 0, 0], [1, 1, 1]])
    >>> hull_touches_box(np.array([[2.0, 0.5, 0.5], [3, 0.5, 0.5], [2, 2, 0.5]]), box)
    False
    >>> hull_touches_box(np.array([[2.0, 0.5, 0.5], [-1, 0.5, 0.5], [2, 2, 0.5]]), box)
    True
    """
    points = np.asarray(points, dtype=np.float64)
    box = np.asarray(box, dtype=np.float64)
    slack = margin * max(float(np.abs(points).max()), float(np.abs(box).max()), 1e-300)
    if np.any(points.min(axis=0) > box[1] + slack) or np.any(points.max(axis=0) < box[0] - slack):
        return False  # the boxes around them do not even meet
    centre = 0.5 * (box[0] + box[1])
    points = points - centre
    half = 0.5 * (box[1] - box[0])
    differences = [b - a for a, b in combinations(points, 2)]
    axis_list = list(np.eye(3))
    axis_list += [np.cross(u, v) for u, v in combinations(differences, 2)]
    axis_list += [np.cross(u, e) for u in differences for e in np.eye(3)]
    axes = np.array(axis_list)
    lengths = np.linalg.norm(axes, axis=1)
    scale = max(float(np.abs(points).max()), float(half.max()), 1e-300)
    keep = lengths > 1e-12 * scale * scale
    axes = axes[keep] / lengths[keep, None]
    projected = points @ axes.T
    reach = np.abs(axes) @ half
    slack = margin * scale
    separated = (projected.min(axis=0) > reach + slack) | (projected.max(axis=0) < -reach - slack)
    return not bool(separated.any())


def light_region(light: np.ndarray, region: np.ndarray, box: np.ndarray) -> np.ndarray:
    """Return points whose hull holds every segment from the light to the region.

    Parameters
    ----------
    light : numpy.ndarray
        ``(x, y, z, 1)`` point light or ``(dx, dy, dz, 0)`` direction
        *towards* a directional light.
    region : numpy.ndarray
        ``(k, 3)`` points (the camera's near region).
    box : numpy.ndarray
        ``(2, 3)`` the box the hull is tested against (a directional light's
        sweep is cut beyond it).

    Returns
    -------
    numpy.ndarray
        ``(k + 1, 3)`` or ``(2 k, 3)`` points.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.pipeline.volume_zmode import light_region
    >>> region = np.zeros((5, 3))
    >>> light_region(np.array([0, 0, 5, 1.0]), region, np.zeros((2, 3))).shape
    (6, 3)
    """
    light = np.asarray(light, dtype=np.float64)
    if light[3] != 0.0:
        return np.vstack([light[:3] / light[3], region])
    towards = light[:3] / np.linalg.norm(light[:3])
    span = float(np.linalg.norm(np.ptp(np.vstack([box, region]), axis=0)))
    return np.vstack([region, region + 2.0 * span * towards])


def choose_zmode(
    zmode: str,
    light: np.ndarray,
    renderer: vtk.vtkRenderer,
    casters: Sequence[tuple[str, np.ndarray]] | CasterBoxes,
    view: FrameView | None = None,
) -> tuple[str, str]:
    """Decide between z-pass and z-fail for one light in one frame.

    Parameters
    ----------
    zmode : {"auto", "zpass", "zfail"}
        The setting: ``"auto"`` decides, the others force.
    light : numpy.ndarray
        ``(x, y, z, 1)`` point or spot light, or ``(dx, dy, dz, 0)`` the
        direction towards a directional light, in world coordinates.
    renderer : vtk.vtkRenderer
        The renderer (its camera).
    casters : sequence of (str, numpy.ndarray) or CasterBoxes
        Each volume caster's name and world bounds ``(2, 3)``, or the same
        stacked once (:class:`CasterBoxes`).
    view : FrameView, optional
        This frame's view of the renderer's camera (:func:`near_region`).

    Returns
    -------
    tuple of str
        ``"zpass"`` or ``"zfail"``, and why in words.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.pipeline.volume_zmode import choose_zmode
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.camera_position = [(0, -10, 1), (0, 0, 0), (0, 0, 1)]
    >>> box = np.array([[-1.0, -1, 0], [1, 1, 2]])
    >>> choose_zmode("auto", np.array([0, 0, 5, 1.0]), pl.renderer, [("box", box)])[0]
    'zpass'
    >>> pl.camera_position = [(0, 0, -3), (0, 0, -4), (0, 1, 0)]  # under the box
    >>> choose_zmode("auto", np.array([0, 0, 5, 1.0]), pl.renderer, [("box", box)])[0]
    'zfail'
    """
    if zmode in ("zpass", "zfail"):
        return zmode, f"{zmode} forced by zmode={zmode!r}"
    region = near_region(renderer, view)
    if region is None:
        return "zpass", (
            "parallel projection: the volumes end beyond the scene instead of at infinity, "
            "and the view rays start outside every one of them"
        )
    boxes = casters if isinstance(casters, CasterBoxes) else CasterBoxes.of(casters)
    for number in _maybe_touched(light, region, boxes):
        box = boxes.box(number)
        if hull_touches_box(light_region(light, region, box), box):
            return "zfail", (
                f"the camera may be inside the shadow volume of {boxes.names[number]} (the "
                "region between the light and the camera's near plane meets its bounds)"
            )
    return "zpass", OUTSIDE


def _maybe_touched(light: np.ndarray, region: np.ndarray, boxes: CasterBoxes) -> list[int]:
    """Return the numbers of the casters, in order, whose boxes the light's region may meet.

    One test over every caster at once: around a hull that holds each
    caster's :func:`light_region` (a directional light's sweep as long as
    the longest), with a slack no smaller than :func:`hull_touches_box`
    allows any of them. A caster left out is one whose own test would find
    the boxes apart; the others are tested one by one.
    """
    if len(boxes.names) < 2:
        return list(range(len(boxes.names)))
    around = np.array([boxes.low.min(axis=0), boxes.high.max(axis=0)])
    hull = light_region(light, region, around)
    gaps, slack = _box_gaps(hull, boxes)
    return np.flatnonzero(gaps <= slack).tolist()


def _box_gaps(hull: np.ndarray, boxes: CasterBoxes) -> tuple[np.ndarray, float]:
    """Return how far the box around ``hull`` lies from each caster's box, and the tests' slack.

    A gap is the widest separation along any axis (negative where the
    boxes overlap on every axis); a box more than the slack away cannot
    meet the hull.
    """
    gaps = np.maximum(hull.min(axis=0) - boxes.high, boxes.low - hull.max(axis=0)).max(axis=1)
    return gaps, 1e-9 * max(float(np.abs(hull).max()), boxes.size, 1e-300)


def zpass_clearance(light: np.ndarray, region: np.ndarray | None, boxes: CasterBoxes) -> float:
    """Return how far the camera's near region and the light may move with z-pass still the choice.

    Where the box around a positional light and the near region lies apart
    from every caster's box (the one-array test of :func:`choose_zmode`
    then answers z-pass), it stays apart while neither the light nor any
    point of the region moves, along any axis, by as much as the
    narrowest of the gaps (less the tests' slack): each face of the box
    around them moves no further than they do, so the next test would
    answer z-pass again, with the same words. Nothing is kept
    for a directional light (its sweep grows with the region), for a
    parallel projection, or where some box is within reach of the region.

    Parameters
    ----------
    light : numpy.ndarray
        ``(x, y, z, 1)`` point or spot light, or ``(dx, dy, dz, 0)``.
    region : numpy.ndarray or None
        The camera's near region (:func:`near_region`).
    boxes : CasterBoxes
        The volume casters' bounds.

    Returns
    -------
    float
        The largest move, per coordinate, of any point of the region
        (infinite without casters; 0 where nothing may be kept).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.boxes import CasterBoxes
    >>> from pvshadows.pipeline.volume_zmode import zpass_clearance
    >>> boxes = CasterBoxes.of([("box", np.array([[-1.0, -1, 0], [1, 1, 2]]))])
    >>> region = np.array([[5.0, 0, 1]] * 5)  # the camera 4 from the box
    >>> round(zpass_clearance(np.array([5.0, 0, 6, 1]), region, boxes), 6)
    4.0
    """
    if region is None or light[3] == 0.0:
        return 0.0
    if not boxes.names:
        return math.inf
    gaps, slack = _box_gaps(np.vstack([light[:3] / light[3], region]), boxes)
    return max(0.0, float(gaps.min()) - 4.0 * slack)
