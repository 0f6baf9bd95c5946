"""What the fits of 2D shadow maps share: their margin, their up vector, the ground test.

A spot light's map (:mod:`pvshadows.scene.spot_fitting`) is a perspective
view along its axis that just holds its cone, or its casters; a directional
light's (:mod:`pvshadows.scene.sun_fitting`) an orthographic view fitted to
the casters that can shadow a receiver the camera sees. Both keep a margin
of texels round what they hold, and both leave out a flat caster (a
ground) with every other receiver on its lit side: it shadows nothing.
All of it is computed in double precision.
"""

from __future__ import annotations

from collections.abc import Sequence

from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot

#: Texels of margin kept on each side of the fitted region.
MARGIN_TEXELS = 2
#: A map looking along a direction whose z is at least this (in size) is turned by
#: world y rather than world z (:func:`up_for`).
UP_SWITCH = 0.99


def up_for(direction: Sequence[float]) -> tuple[float, float, float]:
    """Return the up vector a map looking along ``direction`` is turned by.

    Parameters
    ----------
    direction : sequence of float
        ``(3,)`` unit vector the map looks along (plain floats or a numpy array).

    Returns
    -------
    tuple of float
        World z, or world y when ``direction`` is within about 8 degrees of z.

    Examples
    --------
    >>> from pvshadows.scene.fitting import up_for
    >>> up_for((0.0, 0.0, -1.0))
    (0.0, 1.0, 0.0)
    """
    return (0.0, 0.0, 1.0) if abs(direction[2]) < UP_SWITCH else (0.0, 1.0, 0.0)


def flat_and_lit_above(state: ActorState, direction: Sequence[float], snapshot: Snapshot) -> bool:
    """Return whether a caster is a flat sheet with every other receiver on its lit side.

    Such a caster (a ground) shadows nothing, so a map's fit leaves it out.

    Parameters
    ----------
    state : ActorState
        The caster.
    direction : sequence of float
        ``(3,)`` from the light along its rays at the caster, in plain floats
        (or a numpy array).
    snapshot : Snapshot
        This frame's actors: the receivers and their bounds.

    Returns
    -------
    bool
        ``True`` when the caster is flat and no receiver lies on its dark side.
    """
    sheet = state.sheet
    if sheet is None:
        return False
    low, high = snapshot.sheet_span(state)
    if sheet.size == 0.0 or low > high:
        return True
    tolerance = 1e-6 * sheet.size
    # The lit side is the one the light is on: against the rays.
    (nx, ny, nz), (dx, dy, dz) = sheet.normal.tolist(), direction
    if nx * dx + ny * dy + nz * dz > 0.0:
        return high <= tolerance
    return low >= -tolerance
