"""Where a spot light's 2D shadow map looks: a perspective view that just holds its cone.

The map looks along the light's axis and holds its cone, or only the
casters that can shadow a receiver when they all lie in front of the light
(its texels are then finer than the cone's); the casters are measured by
their boxes (distance, spread about the axis) in one pass. All of it is
computed in double precision.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from pvshadows.geometry.transforms import (
    AFFINE_LAST_ROW,
    look_axes,
    squared_length,
    squared_lengths,
)
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.culling import CORNER_SIDES, box_corners_along, box_offsets
from pvshadows.scene.fitting import MARGIN_TEXELS, flat_and_lit_above, up_for
from pvshadows.scene.lights import LightPose
from pvshadows.scene.snapshot import Snapshot

#: A spot's map keeps its fit while its casters need no more than it and at least
#: ``1 / REFIT_SLACK`` of it, in far distance and in spread (:func:`spot_fit_holds`).
REFIT_SLACK = 1.1


class SpotFit(NamedTuple):
    """A spot light's perspective map.

    Attributes
    ----------
    light_to_clip : numpy.ndarray
        ``(4, 4)`` from light space (world axes centred on the light) to clip space.
    texel : float
        Size of a texel at the centre of the map, per unit of distance.
    """

    light_to_clip: np.ndarray
    texel: float


def spot_fit(
    pose: LightPose,
    resolution: int,
    near: float,
    far: float,
    spread: float | None = None,
    about: LightPose | None = None,
) -> SpotFit:
    """Return the perspective map holding a spot light's cone, or the casters in it.

    Parameters
    ----------
    pose : LightPose
        The spot light.
    resolution : int
        Texels per side.
    near, far : float
        Clip distances (depth clamp makes them matter only for precision).
    spread : float, optional
        The widest :attr:`ConeMeasures.spread` of the casters that can
        shadow a receiver: when they all lie in front of the light, the map
        holds only them (its texels are then finer than the cone's); when
        not (infinite) or not given, the whole cone.
    about : LightPose, optional
        The pose whose direction the map looks along (the light's by
        default): the one ``spread`` was measured about, which the light may
        have turned from since (:class:`pvshadows.scene.measures.CasterMeasureCache`).
        The whole cone is then held about it: its angle grows by the turn.

    Returns
    -------
    SpotFit
        Rotation, projection and texel size.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.spot_fitting import spot_fit
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 45.0)
    >>> fit = spot_fit(pose, 1000, 0.1, 10.0)
    >>> round(fit.texel, 4)
    0.002
    >>> tilt = np.array([np.sin(np.radians(1.0)), 0.0, -np.cos(np.radians(1.0))])
    >>> tilted = LightPose(LightKind.SPOT, np.zeros(3), tilt, 45.0)
    >>> round(spot_fit(pose, 1000, 0.1, 10.0, about=tilted).texel / fit.texel, 3)  # tan 46°/tan 45°
    1.036
    """
    about = pose if about is None else about
    (rx, ry, rz), (ux, uy, uz), (bx, by, bz) = _axes_along(tuple(about.direction.tolist()))
    turned = 0.0 if about is pose else pose.degrees_from(about)
    cone = math.tan(math.radians(min(pose.cone_angle + turned, 89.0)))
    half = cone if spread is None else min(cone, spread)
    half *= 1.0 + 2.0 * MARGIN_TEXELS / resolution
    fov = 2.0 * math.degrees(math.atan(half))
    # perspective(fov, 1, near, far) @ rotation, written out in plain floats: each
    # element has one non-zero term, so it is the product's to the bit (``+ 0.0``
    # gives the product's +0 where the term is a signed zero).
    f = 1.0 / math.tan(math.radians(fov) / 2.0)
    depth, offset = (far + near) / (near - far), 2.0 * far * near / (near - far)
    projection = np.array(
        [
            [f * rx + 0.0, f * ry + 0.0, f * rz + 0.0, 0.0],
            [f * ux + 0.0, f * uy + 0.0, f * uz + 0.0, 0.0],
            [depth * bx + 0.0, depth * by + 0.0, depth * bz + 0.0, offset],
            [0.0 - bx, 0.0 - by, 0.0 - bz, 0.0],
        ]
    )
    return SpotFit(projection, 2.0 * half / resolution)


def spot_fit_holds(kept: tuple[float, float | None], needed: tuple[float, float | None]) -> bool:
    """Tell whether a spot's map fitted to ``kept`` can stand in for one fitted to ``needed``.

    It can when it reaches as far and spreads as wide, and neither by more
    than :data:`REFIT_SLACK` (its texels then are at most that much larger):
    a caster swaying at the edge of the fit leaves the map's projection as
    it was, so the map is redrawn over its still casters' depth
    (:mod:`pvshadows.techniques.still_casters`).

    Parameters
    ----------
    kept, needed : tuple
        ``(far, spread)`` of :func:`spot_fit`, ``spread`` ``None`` for the
        whole cone.

    Returns
    -------
    bool
        Whether to keep the map's fit.

    Examples
    --------
    >>> from pvshadows.scene.spot_fitting import spot_fit_holds
    >>> spot_fit_holds((10.0, 0.5), (9.8, 0.49)), spot_fit_holds((10.0, 0.5), (10.2, 0.5))
    (True, False)
    """
    (far, spread), (far_needed, spread_needed) = kept, needed
    if not far_needed <= far <= REFIT_SLACK * far_needed:
        return False
    if spread is None or spread_needed is None:
        return spread is spread_needed
    return spread_needed <= spread <= REFIT_SLACK * spread_needed


def _spot_rotation(pose: LightPose) -> np.ndarray:
    return _rotation_along(tuple(pose.direction.tolist()))


@lru_cache(maxsize=256)
def _rotation_along(direction: tuple[float, float, float]) -> np.ndarray:
    """Return a spot map's rotation, worked out once per direction (read-only)."""
    right, up, backward = _axes_along(direction)
    rotation = np.array([[*right, 0.0], [*up, 0.0], [*backward, 0.0], AFFINE_LAST_ROW])
    rotation.setflags(write=False)
    return rotation


@lru_cache(maxsize=256)
def _axes_along(direction: tuple[float, float, float]) -> tuple[tuple[float, ...], ...]:
    """Return the rows of a spot map's rotation (:func:`look_axes`), once per direction."""
    return look_axes(direction, up_for(direction))


def box_distances_squared(position: np.ndarray, boxes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return the squared distances from a point to each box and to its farthest corner.

    Parameters
    ----------
    position : numpy.ndarray
        ``(3,)`` the point (a light).
    boxes : numpy.ndarray
        ``(n, 2, 3)`` world bounds.

    Returns
    -------
    near, far : numpy.ndarray
        ``(n,)`` each: squared distance to the box (0 inside it) and to the
        corner farthest from the point.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.spot_fitting import box_distances_squared
    >>> near, far = box_distances_squared(np.zeros(3), np.array([[[1.0, -1, -1], [2, 1, 1]]]))
    >>> near.tolist(), far.tolist()
    ([1.0], [6.0])
    """
    return _distances_squared(box_offsets(boxes, position))


def _distances_squared(offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return :func:`box_distances_squared` of boxes less the point (:func:`box_offsets`).

    ``offsets`` may be a stack ``(..., 2, 3, n)``, one per light.
    """
    lo, hi = offsets.swapaxes(0, -3)  # a view: the sides first
    outside = np.maximum(np.maximum(lo, -hi), 0.0)
    corner = np.maximum(np.abs(lo), np.abs(hi))
    return squared_lengths(outside), squared_lengths(corner)


def _one_box_cone_measures(box: np.ndarray, pose: LightPose) -> tuple[float, float, float]:
    """Measure one box as :func:`cone_measures` does, in plain floats, to the same bits.

    The same operations in the same order (IEEE arithmetic rounds each alike,
    and min and max are exact): the squared lengths are
    :func:`~pvshadows.geometry.transforms.squared_length`'s; a corner's
    rotated coordinate sums its x, y and z terms in that order.
    """
    position = pose.position.tolist()
    low, high = box.tolist()
    low = [a - p for a, p in zip(low, position, strict=True)]
    high = [b - p for b, p in zip(high, position, strict=True)]
    outside = [max(max(a, -b), 0.0) for a, b in zip(low, high, strict=True)]
    corner = [max(abs(a), abs(b)) for a, b in zip(low, high, strict=True)]
    # The terms of each rotated coordinate: along each axis, from the min and max corners.
    (x0, x1, x2), (y0, y1, y2), (z0, z1, z2) = (
        [(row[axis] * low[axis], row[axis] * high[axis]) for axis in range(3)]
        for row in _spot_rotation(pose)[:3, :3].tolist()
    )
    spread = -math.inf
    for i, j, k in CORNER_SIDES:
        depth = -((z0[i] + z1[j]) + z2[k])
        if not depth > 0.0:  # a corner beside or behind the light: no bound
            return squared_length(outside), squared_length(corner), math.inf
        x, y = (x0[i] + x1[j]) + x2[k], (y0[i] + y1[j]) + y2[k]
        spread = max(spread, max(abs(x), abs(y)) / depth)
    return squared_length(outside), squared_length(corner), spread


class ConeMeasures(NamedTuple):
    """What a spot light's map is fitted to, for each caster of a snapshot.

    Attributes
    ----------
    near, far : numpy.ndarray
        ``(n,)`` squared distances from the light to each caster's bounds
        and to their farthest corner (:func:`box_distances_squared`).
    spread : numpy.ndarray
        ``(n,)`` tangent of the widest angle off the map's axis of each
        caster's bound corners; infinite when a corner is not in front of
        the light.
    """

    near: np.ndarray
    far: np.ndarray
    spread: np.ndarray


def cone_measures(pose: LightPose, boxes: np.ndarray) -> ConeMeasures:
    """Measure casters' bounds from a spot light, for its map's range and fit.

    Parameters
    ----------
    pose : LightPose
        The spot light.
    boxes : numpy.ndarray
        ``(n, 2, 3)`` world bounds.

    Returns
    -------
    ConeMeasures
        One row per box.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.spot_fitting import cone_measures
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> pose = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 45.0)
    >>> boxes = np.array([[[-1.0, -1, -4], [1, 1, -2]], [[-1.0, -1, -1], [1, 1, 1]]])
    >>> cone_measures(pose, boxes).spread.tolist()
    [0.5, inf]
    """
    if len(boxes) == 1:  # one moved caster: numpy's cost per call outweighs its speed
        return ConeMeasures(
            *(np.array([value]) for value in _one_box_cone_measures(boxes[0], pose))
        )
    offsets = box_offsets(boxes, pose.position)[None]
    measured = _stacked_measures(offsets, _spot_rotation(pose)[None, :3, :3])
    return ConeMeasures(*(values[0] for values in measured))


def cone_measures_many(poses: list[LightPose], boxes: np.ndarray) -> ConeMeasures:
    """Measure boxes from several spot lights at once, each as :func:`cone_measures` does.

    The same operations in the same order, with a first axis over the
    lights: each row has the bits :func:`cone_measures` gives for its light.

    Parameters
    ----------
    poses : list of LightPose
        The spot lights (the poses their casters are measured about).
    boxes : numpy.ndarray
        ``(lights, n, 2, 3)`` world bounds: each light's own boxes (widened
        by its own margin, say).

    Returns
    -------
    ConeMeasures
        Each of ``(lights, n)``: a row per light.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.spot_fitting import cone_measures_many
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> down = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 45.0)
    >>> up = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, 1.0]), 45.0)
    >>> box = np.array([[-1.0, -1, -4], [1, 1, -2]])
    >>> cone_measures_many([down, up], np.array([[box], [box]])).spread.tolist()
    [[0.5], [inf]]
    """
    positions = np.array([pose.position for pose in poses])[:, None, :, None]
    # (lights, 2, 3, n): as box_offsets lays out each light's boxes, less its position
    offsets = boxes.transpose(0, 2, 3, 1) - positions
    rotations = np.array([_spot_rotation(pose)[:3, :3] for pose in poses])
    return _stacked_measures(offsets, rotations)


def _stacked_measures(offsets: np.ndarray, rotations: np.ndarray) -> ConeMeasures:
    """Return :class:`ConeMeasures` of ``(lights, 2, 3, n)`` box offsets, each in its rotation."""
    near, far = _distances_squared(offsets)
    x, y, z = box_corners_along(offsets, rotations).swapaxes(0, -3)
    depth = np.negative(z)
    in_front = depth.min(axis=-2) > 0.0
    # a box with a corner beside or behind the light spreads without bound: divided by 1
    # here (no warning), then marked infinite
    np.copyto(depth, 1.0, where=~in_front[..., None, :])
    spread = (np.maximum(np.abs(x), np.abs(y)) / depth).max(axis=-2)
    spread[~in_front] = np.inf
    return ConeMeasures(near, far, spread)


def spot_shadowing_rows(
    pose: LightPose, casters: list[ActorState], snapshot: Snapshot
) -> np.ndarray:
    """Return where the casters that can shadow a receiver of a point or spot light sit.

    A flat caster (a ground) with every other receiver on the light's side of
    it shadows nothing, as for a directional light.

    Parameters
    ----------
    pose : LightPose
        The light.
    casters : list of ActorState
        The light's casters.
    snapshot : Snapshot
        This frame's actors: the receivers and their bounds.

    Returns
    -------
    numpy.ndarray
        ``(n,)`` rows of the casters that matter for the fit of the light's map;
        not to be written to (it may be the snapshot's own).
    """
    flat = snapshot.flat_caster_rows
    if not flat:
        return snapshot.caster_rows(casters)
    every = casters is snapshot.casters
    rows = None if every else snapshot.caster_rows(casters)
    flat_here = snapshot.caster_flat if rows is None else snapshot.caster_flat[rows]
    if rows is not None:
        flat = np.flatnonzero(flat_here).tolist()
    # plain floats for three-vectors: numpy's per-call cost outweighs its speed here
    px, py, pz = pose.position.tolist()
    shadowing = [
        position
        for position in flat
        if not flat_and_lit_above(casters[position], _away(casters[position], px, py, pz), snapshot)
    ]
    if rows is None:
        if not shadowing:
            return snapshot.solid_caster_rows  # the same array at every frame
        rows = snapshot.caster_rows(casters)
    if len(shadowing) == len(flat):
        return rows
    keep = ~flat_here
    if shadowing:
        keep[shadowing] = True
    return rows[keep]


def _away(state: ActorState, px: float, py: float, pz: float) -> tuple[float, float, float]:
    """Return the offset from a light at ``(px, py, pz)`` to the centre of an actor's bounds."""
    cx, cy, cz = state.bounds_center
    return cx - px, cy - py, cz - pz
