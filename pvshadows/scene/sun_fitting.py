"""Where a directional light's 2D shadow map looks: an orthographic box fitted to what matters.

The map is fitted to the casters that can shadow a receiver the camera sees,
snapped to its own texel grid and to discrete sizes, so that a camera moving
alone never moves shadow edges. All of it is computed in double precision.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from pvshadows._cached import cached
from pvshadows.geometry.transforms import AFFINE_LAST_ROW, look_axes, translation
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.culling import widened_boxes
from pvshadows.scene.fitting import MARGIN_TEXELS, flat_and_lit_above, up_for
from pvshadows.scene.lights import LightPose
from pvshadows.scene.snapshot import Snapshot

#: Sizes of the sun's map are rounded up to steps of 2 ** (1 / SIZE_STEPS_PER_OCTAVE).
SIZE_STEPS_PER_OCTAVE = 8
#: Degrees a moving directional light may turn before its fit reads its actors again
#: (:func:`sun_actors`, :meth:`SunActors.holds`).
SUN_TURN_DEGREES = 0.5


@dataclass
class SunFit:
    """A directional light's orthographic map.

    Attributes
    ----------
    rotation : numpy.ndarray
        ``(4, 4)`` rotation from world axes to light axes (z along the light).
    origin : numpy.ndarray
        World point at the centre of the map's near plane.
    half_width : float
        Half the map's width (and height) in world units.
    depth : float
        Depth range covered, from the near plane.
    resolution : int
        Texels per side.
    """

    rotation: np.ndarray
    origin: np.ndarray
    half_width: float
    depth: float
    resolution: int

    @property
    def texel(self) -> float:
        """World size of one texel."""
        return 2.0 * self.half_width / self.resolution

    def world_to_light(self) -> np.ndarray:
        """Return the ``(4, 4)`` matrix from world to light space (worked out once; read-only)."""
        return self._world_to_light

    @cached
    def _world_to_light(self) -> np.ndarray:
        matrix = self.rotation @ translation(-self.origin)
        matrix.setflags(write=False)
        return matrix

    def light_to_clip(self) -> np.ndarray:
        """Return the ``(4, 4)`` orthographic projection across the map (made once; read-only).

        Light-space x and y within :attr:`half_width` map to [-1, 1]; depth
        is written by the pass itself, so z maps to 0.
        """
        return _orthographic(self.half_width)

    def key(self) -> tuple:
        """Return a value that changes whenever the map's coverage changes."""
        return self._key

    @cached
    def _key(self) -> tuple:
        return (self.rotation.tobytes(), self.origin.tobytes(), self.half_width, self.depth)

    @cached
    def near_center(self) -> np.ndarray:
        """The centre of the map's near plane, in light axes."""
        return self.rotation[:3, :3] @ self.origin

    def covers(self, needed: SunFit) -> bool:
        """Return whether this map can stand in for ``needed`` without drawing it again.

        It can when both look along the same light, this map's coverage holds
        the needed one in all three directions, and its texels are at most
        twice as large: the camera can move and the map stays (no re-render,
        no shimmering) until the view needs much finer or other coverage.

        Parameters
        ----------
        needed : SunFit
            The fit this frame asks for.

        Returns
        -------
        bool
            Whether to keep this map.
        """
        if needed is self:
            return True
        if self.resolution != needed.resolution or (
            self.rotation is not needed.rotation
            and self.rotation.tobytes() != needed.rotation.tobytes()
        ):
            return False
        (x, y, z), (x_needed, y_needed, z_needed) = self.near_center, needed.near_center
        slack = self.half_width - needed.half_width
        across = abs(x_needed - x) <= slack and abs(y_needed - y) <= slack
        along = z <= z_needed and z_needed + needed.depth <= z + self.depth
        return bool(across and along and self.half_width <= 2.0 * needed.half_width)


@lru_cache(maxsize=64)
def _orthographic(half_width: float) -> np.ndarray:
    """Return the read-only orthographic projection of :meth:`SunFit.light_to_clip`.

    Kept by width: a turning light's fits round the same region share it.
    """
    scale = 1.0 / half_width
    matrix = np.array(
        [[scale, 0.0, 0.0, 0.0], [0.0, scale, 0.0, 0.0], [0.0] * 4, [0.0, 0.0, 0.0, 1.0]]
    )
    matrix.setflags(write=False)
    return matrix


def _light_boxes(rotation: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Return the bounds in light axes of ``(n, 2, 3)`` world boxes.

    A turned box's centre is the turned centre, and its half-size along each
    new axis is the old half-sizes weighted by the absolute rotation: no
    corner is made.
    """
    turn = rotation[:3, :3]
    center = ((boxes[:, 0] + boxes[:, 1]) * 0.5) @ turn.T
    half = ((boxes[:, 1] - boxes[:, 0]) * 0.5) @ np.abs(turn).T
    turned = np.empty_like(boxes)
    np.subtract(center, half, out=turned[:, 0])
    np.add(center, half, out=turned[:, 1])
    return turned


#: The corners of clip space's cube, homogeneous.
_CLIP_CORNERS = np.array([[x, y, z, 1.0] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])


def sun_rotation(pose: LightPose) -> np.ndarray:
    """Return the rotation from world axes to a directional light's axes (z along the light).

    Parameters
    ----------
    pose : LightPose
        The directional light.

    Returns
    -------
    numpy.ndarray
        ``(4, 4)`` right-handed rotation whose third row is the light's direction.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.sun_fitting import sun_rotation
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.DIRECTIONAL, np.zeros(3), np.array([0, 0, -1.0]), 90.0)
    >>> sun_rotation(pose)[2, :3].tolist()
    [0.0, 0.0, -1.0]
    """
    direction = pose.direction.tolist()
    (rx, ry, rz), up, (bx, by, bz) = look_axes(direction, up_for(direction))
    # The camera's x and z turned round (the zeros' signs too, as a negated row has them).
    return np.array([[-rx, -ry, -rz, -0.0], [*up, 0.0], [-bx, -by, -bz, -0.0], AFFINE_LAST_ROW])


#: What a sun's map is fitted round, across and along the light, from the actors' pivot:
#: low and high corners across, near and far along (:func:`_region_over`).
SunRegion = tuple[np.ndarray, np.ndarray, float, float]
#: A sun's map but for its rotation (:func:`_shape_around`): the centre of its near plane
#: across the light and its near end along it, from the actors' pivot, half its width,
#: and its depth.
SunShape = tuple[float, float, float, float, float]


@dataclass(frozen=True)
class SunActors:
    """What a directional light's fit reads of the actors, in the light's axes.

    It stays right while the actors do and the light turns by at most
    ``slack`` (see :func:`sun_actors`), however the camera moves. Its boxes
    are measured from ``pivot`` (light-axis coordinates of ``point - pivot``)
    and widened by ``slack`` times the distance from the pivot to the
    farthest corner, so that they hold every box turned by any rotation
    within ``slack`` of ``rotation``.

    Attributes
    ----------
    rotation : numpy.ndarray
        ``(4, 4)`` rotation from world axes to light axes the boxes were turned by.
    pivot : numpy.ndarray
        ``(3,)`` world point the boxes are measured from: the centre of the actors.
    slack : float
        Radians the light may turn from ``rotation`` with the boxes still holding.
    receivers : numpy.ndarray
        ``(n, 2, 3)`` the receivers' boxes in light axes.
    casters : numpy.ndarray
        ``(m, 2, 3)`` in light axes, the boxes of the casters that can shadow
        a receiver: a flat caster (a ground) with every other receiver on its
        lit side is left out.
    every_caster : numpy.ndarray
        ``(k, 2, 3)`` in light axes, the boxes of every caster of the snapshot.
    """

    rotation: np.ndarray
    pivot: np.ndarray
    slack: float
    receivers: np.ndarray
    casters: np.ndarray
    every_caster: np.ndarray

    def holds(self, rotation: np.ndarray) -> bool:
        """Tell whether these boxes hold the actors turned by ``rotation``.

        Parameters
        ----------
        rotation : numpy.ndarray
            ``(4, 4)`` a directional light's rotation this frame (:func:`sun_rotation`).

        Returns
        -------
        bool
            Whether it turns by at most :attr:`slack` from :attr:`rotation`.
        """
        if rotation is self.rotation:
            return True
        # The angle of the rotation from one to the other: trace(A Bᵀ) = 1 + 2 cos(angle).
        mine = rotation[:3, :3].ravel().tolist()
        trace = sum(map(operator.mul, mine, self._rotation_entries))  # no generator: it costs more
        return math.acos(max(-1.0, min(1.0, 0.5 * (trace - 1.0)))) <= self.slack

    def offset(self, rotation: np.ndarray) -> list[float]:
        """Return the pivot in the light axes of ``rotation``: what the boxes are measured from.

        Worked out again only for another rotation than last asked: a light
        that stays keeps its rotation, however the camera moves.
        """
        kept = self._offset
        if kept[0] is not rotation:
            kept[:] = rotation, (rotation[:3, :3] @ self.pivot).tolist()
        return kept[1]

    @cached
    def _rotation_entries(self) -> list[float]:
        return self.rotation[:3, :3].ravel().tolist()

    @cached
    def _offset(self) -> list:
        return [None, None]

    def casters_in(self, fit: SunFit, snapshot: Snapshot) -> list[ActorState]:
        """Return the casters whose bounds overlap a map's coverage across the light.

        Parameters
        ----------
        fit : SunFit
            The map, looking along this light (turned by at most :attr:`slack`).
        snapshot : Snapshot
            The renderer's actors these boxes were read from.

        Returns
        -------
        list of ActorState
            The casters to draw into the map.
        """
        x, y, _ = self.offset(fit.rotation)
        (center_x, center_y, _), half, texel = fit.near_center.tolist(), fit.half_width, fit.texel
        # The square's centre, from the pivot, in texels (a fit snaps it to them): the same
        # square as the last fit's has the same casters (a light turning within the slack
        # keeps the scene's fit's square).
        square = (round((center_x - x) / texel), round((center_y - y) / texel), half)
        kept = self.casters_of_square
        if kept and kept[0] == square:
            return kept[1]
        boxes, center = self.every_caster, np.array([center_x - x, center_y - y])
        inside = np.all(boxes[:, 1, :2] >= center - half, axis=1) & np.all(
            boxes[:, 0, :2] <= center + half, axis=1
        )
        # Made by the snapshot, the list knows its rows (the snapshot's own list when it
        # holds every caster): what is gathered for it later costs no lookup per caster.
        casters = snapshot.casters_at(np.flatnonzero(inside))
        kept[:] = [square, casters]
        return casters

    @cached
    def receiver_extents(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The receivers' low and high corners across the light, and their far ends."""
        return (
            self.receivers[:, 0, :2].copy(),
            self.receivers[:, 1, :2].copy(),
            self.receivers[:, 1, 2].copy(),
        )

    @cached
    def receivers_across(self) -> tuple[float, float, float, float]:
        """The box holding every receiver across the light: low x, low y, high x, high y."""
        low, high = self.receivers[:, 0, :2].min(axis=0), self.receivers[:, 1, :2].max(axis=0)
        return (*low.tolist(), *high.tolist())

    @cached
    def fits_of_whole_scene(self) -> dict[int, tuple[np.ndarray, SunFit | None]]:
        """For a view that holds every receiver, the last rotation and its fit, by resolution."""
        return {}

    @cached
    def shapes_of_whole_scene(self) -> dict[int, SunShape | None]:
        """For a view that holds every receiver, the map's shape round it, by resolution.

        It is :func:`_shape_around` the region of :func:`_region_over`, and
        does not depend on the rotation (within :attr:`slack`): a light
        turning a little is fitted to it at the cost of one small product.
        """
        return {}

    @cached
    def casters_of_square(self) -> list:
        """The last square :meth:`casters_in` tested (from the pivot), and its casters."""
        return []

    @cached
    def caster_extents(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The casters' lowest and highest corners across the light, their near and far ends."""
        boxes = self.casters
        return (
            boxes[:, 0, :2].copy(),
            boxes[:, 1, :2].copy(),
            boxes[:, 0, 2].copy(),
            boxes[:, 1, 2].copy(),
        )


def sun_actors(
    pose: LightPose, rotation: np.ndarray, snapshot: Snapshot, slack_degrees: float = 0.0
) -> SunActors | None:
    """Return what a directional light's fit reads of the actors (``None`` if it can cast nothing).

    Parameters
    ----------
    pose : LightPose
        The directional light.
    rotation : numpy.ndarray
        Its rotation (:func:`sun_rotation`).
    snapshot : Snapshot
        The renderer's actors this frame.
    slack_degrees : float, default: 0.0
        How far the light may turn with the boxes still holding (a moving
        light's): each box is widened by that angle (in radians) times the
        distance from the actors' centre to their farthest corner, and a flat
        caster that the turn could bring into the light is kept.

    Returns
    -------
    SunActors or None
        ``None`` without a receiver or a caster that can shadow one.
    """
    casters, receivers = snapshot.casters, snapshot.receivers
    if not casters or not receivers:
        return None
    slack = math.radians(slack_degrees)
    keep = ~snapshot.caster_flat
    flat = np.flatnonzero(snapshot.caster_flat).tolist()
    grazing = math.sin(slack)
    towards = pose.direction.tolist()
    for row in flat:
        sheet = casters[row].sheet
        turns_over = (
            slack > 0.0 and sheet is not None and abs(sheet.normal @ pose.direction) <= grazing
        )
        keep[row] = turns_over or not flat_and_lit_above(casters[row], towards, snapshot)
    if len(flat) == len(casters) and not keep.any():
        return None
    low, high = snapshot.scene_box
    pivot = 0.5 * (low + high)
    margin = slack * 0.5 * snapshot.scene_size
    # One pass over every actor: receivers and casters are mostly the same actors.
    boxes = widened_boxes(_light_boxes(rotation, snapshot.actor_bounds - pivot), margin)
    every_caster = boxes[snapshot.caster_index]
    return SunActors(
        rotation, pivot, slack, boxes[snapshot.receiver_index], every_caster[keep], every_caster
    )


def sun_fit(
    actors: SunActors, rotation: np.ndarray, clip_to_world: np.ndarray, resolution: int
) -> SunFit | None:
    """Fit a directional light's map to the casters that can shadow a visible receiver.

    The region across the light is what the camera sees of the receivers,
    cut down to the casters over it (:func:`sun_actors` has already left out
    a flat caster with every other receiver on its lit side). The region's
    size is rounded up to one of ``SIZE_STEPS_PER_OCTAVE`` sizes per octave
    and its centre snapped to the map's texels, so shadow edges stay put
    while only the camera moves. A view that holds every receiver across the
    light gets the scene's fit, worked out once per rotation and kept on
    ``actors``: the same object however such a camera moves.

    Parameters
    ----------
    actors : SunActors
        The light's receivers and casters in its axes, holding for ``rotation``
        (:meth:`SunActors.holds`).
    rotation : numpy.ndarray
        ``(4, 4)`` the light's rotation this frame (:func:`sun_rotation`): the map's.
    clip_to_world : numpy.ndarray
        ``(4, 4)`` the inverse of the camera's world-to-clip matrix
        (:attr:`pvshadows.scene.view.FrameView.clip_to_world`).
    resolution : int
        Texels per side.

    Returns
    -------
    SunFit or None
        ``None`` when no caster can shadow a visible receiver.
    """
    # The view's corners in light axes, from the actors' pivot: the rotation keeps the
    # homogeneous weight. Eight corners: plain floats cost less than numpy's calls.
    x0, y0, _ = actors.offset(rotation)
    corners = (_CLIP_CORNERS @ (rotation @ clip_to_world).T).tolist()
    xs, ys = [x / w - x0 for x, _, _, w in corners], [y / w - y0 for _, y, _, w in corners]
    view_x_lo, view_y_lo, view_x_hi, view_y_hi = min(xs), min(ys), max(xs), max(ys)
    x_lo, y_lo, x_hi, y_hi = actors.receivers_across
    if view_x_lo <= x_lo and view_y_lo <= y_lo and view_x_hi >= x_hi and view_y_hi >= y_hi:
        # Every receiver is in the region: the fit is the scene's, whatever the camera.
        fits, shapes = actors.fits_of_whole_scene, actors.shapes_of_whole_scene
        kept = fits.get(resolution)
        if kept is None or kept[0] is not rotation:
            if resolution not in shapes:
                view = np.array([x_lo, y_lo]), np.array([x_hi, y_hi])
                region = _region_over(actors, *view, None)
                shapes[resolution] = None if region is None else _shape_around(*region, resolution)
            shape, pivot = shapes[resolution], actors.pivot
            fit = None if shape is None else _fit_of_shape(rotation, shape, resolution, pivot)
            kept = fits[resolution] = (rotation, fit)
        return kept[1]
    receiver_lo, receiver_hi, _ = actors.receiver_extents
    lo = np.maximum(receiver_lo, np.array([view_x_lo, view_y_lo]))
    hi = np.minimum(receiver_hi, np.array([view_x_hi, view_y_hi]))
    visible = (lo <= hi).all(axis=1)
    if not visible.any():
        return None
    region = _region_over(actors, lo[visible].min(axis=0), hi[visible].max(axis=0), visible)
    if region is None:
        return None
    return _fit_of_shape(rotation, _shape_around(*region, resolution), resolution, actors.pivot)


def _region_over(
    actors: SunActors, view_lo: np.ndarray, view_hi: np.ndarray, visible: np.ndarray | None
) -> SunRegion | None:
    """Return the region to fit: the casters over what visible receivers span of the view.

    ``visible`` marks the visible receivers; ``None`` when every one is.
    Measured from the actors' pivot, as their boxes are: low and high
    corners across the light, near and far along it (``None`` when no
    caster is over it).
    """
    receiver_far = actors.receiver_extents[2]
    caster_lo, caster_hi, caster_near, caster_far = actors.caster_extents
    over = (caster_hi >= view_lo).all(axis=1) & (caster_lo <= view_hi).all(axis=1)
    if not over.any():
        return None
    fit_lo = np.maximum(caster_lo[over].min(axis=0), view_lo)
    fit_hi = np.minimum(caster_hi[over].max(axis=0), view_hi)
    near = float(caster_near[over].min())
    receiver_far = receiver_far if visible is None else receiver_far[visible]
    far = max(float(caster_far[over].max()), float(receiver_far.max()))
    return fit_lo, fit_hi, near, far


def _shape_around(
    fit_lo: np.ndarray, fit_hi: np.ndarray, near: float, far: float, resolution: int
) -> SunShape:
    """Return the map's shape round a region across the light, ``near`` to ``far`` along.

    Its size rounded up to one of ``SIZE_STEPS_PER_OCTAVE`` per octave, its
    centre snapped to its texels, its depths to a sixteenth of their range.
    """
    size = max(float((fit_hi - fit_lo).max()), 1e-30)
    size = 2.0 ** (math.ceil(math.log2(size) * SIZE_STEPS_PER_OCTAVE) / SIZE_STEPS_PER_OCTAVE)
    texel = size / (resolution - 2 * MARGIN_TEXELS)
    # Python's round, like numpy's, rounds halves to even.
    center_x, center_y = (
        round(0.5 * (lo + hi) / texel) * texel
        for lo, hi in zip(fit_lo.tolist(), fit_hi.tolist(), strict=True)
    )
    step = 2.0 ** math.ceil(math.log2(max(far - near, 1e-30))) / 16.0
    near = math.floor(near / step) * step - step
    far = math.ceil(far / step) * step + step
    return center_x, center_y, near, texel * resolution / 2.0, far - near


def _fit_of_shape(
    rotation: np.ndarray, shape: SunShape, resolution: int, pivot: np.ndarray | None = None
) -> SunFit:
    """Return the map of ``shape`` looking along ``rotation``.

    The shape is measured from ``pivot`` (from the world's origin without one).
    """
    center_x, center_y, near, half_width, depth = shape
    origin = rotation[:3, :3].T @ np.array([center_x, center_y, near])
    if pivot is not None:
        origin += pivot
    return SunFit(rotation, origin, half_width, depth, resolution)


def sun_fit_over_both(kept: SunFit, needed: SunFit) -> SunFit | None:
    """Return a sun's map holding both fits' regions, if it can stand in for ``needed``.

    For a fit that must change because casters moved (the camera did not): an
    actor swaying at the edge of the fit would otherwise change it, and redraw
    the whole map, at every frame; the map over both stays while it sways
    (:mod:`pvshadows.techniques.still_casters`). Its texels are at most one
    size step (``2 ** (1 / SIZE_STEPS_PER_OCTAVE)``) larger than ``needed``'s:
    an actor moved farther is fitted afresh.

    Parameters
    ----------
    kept : SunFit
        The fit the map holds.
    needed : SunFit
        The fit this frame asks for, along the same light at the same resolution.

    Returns
    -------
    SunFit or None
        The fit over both regions; ``None`` when the lights or resolutions
        differ, or when it would be more than one size step coarser than
        ``needed``.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.sun_fitting import SunFit, sun_fit_over_both
    >>> half = 1024 / 1020  # a 2-wide region and 2 texels of margin each side
    >>> here = SunFit(np.eye(4), np.zeros(3), half, 2.0, 1024)
    >>> there = SunFit(np.eye(4), np.array([0.1, 0.0, 0.0]), half, 2.0, 1024)
    >>> both = sun_fit_over_both(here, there)
    >>> both.covers(here), both.covers(there), round(both.half_width / half, 3)
    (True, True, 1.091)
    >>> far = SunFit(np.eye(4), np.array([0.5, 0.0, 0.0]), half, 2.0, 1024)
    >>> sun_fit_over_both(here, far) is None  # more than one size step coarser
    True
    """
    if kept.resolution != needed.resolution or not np.array_equal(kept.rotation, needed.rotation):
        return None
    inner = 1.0 - 2.0 * MARGIN_TEXELS / kept.resolution  # the region within the margins
    los, his, nears, fars = [], [], [], []
    for fit in (kept, needed):
        x, y, z = fit.near_center
        half = fit.half_width * inner
        los.append((x - half, y - half))
        his.append((x + half, y + half))
        nears.append(z)
        fars.append(z + fit.depth)
    shape = _shape_around(
        np.min(los, axis=0), np.max(his, axis=0), min(nears), max(fars), kept.resolution
    )
    both = _fit_of_shape(kept.rotation, shape, kept.resolution)
    one_step = 2.0 ** (1.0 / SIZE_STEPS_PER_OCTAVE) * (1.0 + 1e-9)
    if both.half_width > one_step * needed.half_width:
        return None
    if not (both.covers(kept) and both.covers(needed)):
        return None
    return both
