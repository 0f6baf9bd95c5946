"""Far lights' maps: how a light sees its casters, and the map it gets when they are far.

A point light whose casters subtend a small cone gets a perspective map of
that cone instead of a cube; a point or spot light so far from its casters
that its rays are nearly parallel there gets an orthographic map along them
(float32 depths at that distance round by more than a perspective map's
bias). The planner (:mod:`pvshadows.pipeline.planner`) asks these.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.culling import box_corners
from pvshadows.scene.lights import LightKind, LightPose

#: A point light's casters within a cone of this half angle (degrees) get a map of that cone.
FIT_CONE_BELOW = 30.0
#: Casters' radius over their distance below which a point or spot light casts from an
#: orthographic map. Farther, float32 positions at the light's distance round by more than
#: a perspective map's depth bias (the standard scene: 0.57 % wrong at 1e4, 7.3 % at 2e4),
#: while the rays' spread over the casters moves no edge by a texel (0.026-0.028 % there).
PARALLEL_BELOW = 2e-3
#: The sine of :data:`FIT_CONE_BELOW`.
_FIT_CONE_SINE = float(np.sin(np.radians(FIT_CONE_BELOW)))


class SeenFrom(NamedTuple):
    """The sphere around casters' box as a light sees it."""

    radius: float
    distance: float
    #: From the light to the sphere's centre, in plain floats.
    away: list[float]

    @property
    def direction(self) -> np.ndarray:
        """The unit vector from the light to the centre."""
        return np.array(self.away) / max(self.distance, 1e-300)


def casters_seen_from(pose: LightPose, box: np.ndarray) -> SeenFrom:
    """Return the sphere around casters' ``(2, 3)`` box: its radius, distance and offset."""
    # Plain floats for three-vectors, written out: numpy's calls, and a generator's, cost
    # more than the sums.
    lo, hi = box.tolist()
    (lx, ly, lz), (hx, hy, hz) = lo, hi
    px, py, pz = pose.position.tolist()
    away = [(lx + hx) / 2.0 - px, (ly + hy) / 2.0 - py, (lz + hz) / 2.0 - pz]
    return SeenFrom(math.dist(lo, hi) / 2.0, math.hypot(*away), away)


def _parallel(pose: LightPose, seen_from: SeenFrom, notes: list[str]) -> LightPose:
    radius, distance, _ = seen_from
    half = float(np.degrees(np.arcsin(radius / distance)))
    notes.append(
        f"the casters subtend {2 * half:.3g} degrees from the light: its rays are nearly "
        "parallel there, and a perspective map this far away would round depths by more "
        "than its bias, so an orthographic map along them"
    )
    return LightPose(LightKind.DIRECTIONAL, pose.position, seen_from.direction, 180.0)


def is_far(seen_from: SeenFrom) -> bool:
    """Whether casters (:func:`casters_seen_from`) are so far that the rays are nearly parallel."""
    radius, distance, _ = seen_from
    return distance > 0.0 and radius / distance < PARALLEL_BELOW


def fit_far_spot(
    pose: LightPose,
    seen_from: SeenFrom,
    seen: list[ActorState],
    notes: list[str],
) -> LightPose:
    """Give a spot light far from its casters (:func:`is_far`) an orthographic map along its rays.

    Its map is already fitted to the casters; only past :data:`PARALLEL_BELOW`
    does it change, for the float32 precision of depths at that distance,
    and only when the cone holds every receiver the camera sees (an
    orthographic lookup has no cone to leave the rest unlit). ``seen_from``
    is what :func:`casters_seen_from` says of the casters.
    """
    corners = box_corners(np.array([r.bounds for r in seen]).reshape(-1, 2, 3)).reshape(-1, 3)
    rays = corners - pose.position
    cosines = rays @ pose.direction / np.linalg.norm(rays, axis=1)
    if np.any(cosines < np.cos(np.radians(pose.cone_angle))):
        return pose
    return _parallel(pose, seen_from, notes)


def fitted_to_casters(technique: str, pose: LightPose, box: np.ndarray) -> SeenFrom | None:
    """Return how a light sees its casters when its map is to be fitted to them, else ``None``.

    A point light's cube gives way to a map of its casters' cone when they
    subtend less than :data:`FIT_CONE_BELOW` (:func:`fit_far_point`); a
    spot light's map turns orthographic when they are :func:`is_far`
    (:func:`fit_far_spot`). ``box`` is the ``(2, 3)`` box around the casters.
    """
    if technique == "cubemap" and pose.kind is LightKind.POINT:
        seen_from = casters_seen_from(pose, box)
        return None if seen_from.distance <= seen_from.radius / _FIT_CONE_SINE else seen_from
    if technique == "map" and pose.kind is LightKind.SPOT:
        seen_from = casters_seen_from(pose, box)
        return seen_from if is_far(seen_from) else None
    return None


def fit_far_point(pose: LightPose, seen_from: SeenFrom, notes: list[str]) -> tuple[str, LightPose]:
    """Give a point light whose casters subtend a small angle a perspective map of their cone.

    Seen from far away, casters cover a few texels of one cube face and the
    texel-sized biases swallow their shadows; a map aimed at them spends
    every texel on them, at any distance. Receivers outside the cone stay
    lit (nothing there can shadow them). ``seen_from`` is what
    :func:`fitted_to_casters` says of the casters.
    """
    radius, distance, _ = seen_from
    half = float(np.degrees(np.arcsin(radius / distance)))
    if radius / distance < PARALLEL_BELOW:
        return "map", _parallel(pose, seen_from, notes)
    notes.append(
        f"the casters subtend {2 * half:.3g} degrees from the light: a perspective map "
        "aimed at them instead of a cube"
    )
    return "map", LightPose(LightKind.SPOT, pose.position, seen_from.direction, half)
