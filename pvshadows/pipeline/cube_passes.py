"""How a cube map is filled when its settings say ``passes="auto"``: a planner's choice."""

from __future__ import annotations

from dataclasses import replace
from weakref import WeakKeyDictionary

from pvshadows.model.settings import ShadowSettings
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot

#: Caster triangles from which ``passes="auto"`` fills a cube one face at a time. A
#: geometry shader sending each triangle to its faces is one draw per caster, the least
#: CPU work for many small casters; but it runs per triangle, and on llvmpipe a frame
#: redrawing one 1-million-triangle sphere's cube took 0.54-0.58 s through it against
#: 0.31-0.33 s face by face (plain frame 0.25-0.27 s; first frame 0.99-1.16 s against
#: 0.74-0.77 s), with the same depths (the bench's cube errors are equal either way).
SIX_PASSES_FROM = 100_000


def cube_passes(
    settings: ShadowSettings, casters: list[ActorState], snapshot: Snapshot, notes: list[str]
) -> ShadowSettings:
    """Return ``settings`` with ``passes="auto"`` resolved for these casters.

    Parameters
    ----------
    settings : ShadowSettings
        The light's settings, ``passes="auto"``.
    casters : list of ActorState
        The casters its cube draws.
    snapshot : Snapshot
        This frame's actors, ``casters`` among them (their triangle counts).
    notes : list of str
        The light's notes; the choice of six passes is explained there.

    Returns
    -------
    ShadowSettings
        A copy with ``passes`` ``"single"`` or ``"six"``
        (:data:`SIX_PASSES_FROM`).

    Examples
    --------
    >>> from pvshadows.model.settings import ShadowSettings
    >>> from pvshadows.pipeline.cube_passes import cube_passes
    >>> from pvshadows.scene.snapshot import Snapshot
    >>> cube_passes(ShadowSettings(), [], Snapshot([], []), []).passes
    'single'
    """
    triangles = int(snapshot.for_casters(snapshot.caster_triangles, casters).sum())
    if triangles < SIX_PASSES_FROM:
        return _with_passes(settings, "single")
    notes.append(
        f"its casters hold {triangles:,} triangles: the cube is filled one face at a time, "
        "each face drawing the casters in its frustum, faster than a geometry shader "
        "sending every triangle to the faces"
    )
    return _with_passes(settings, "six")


#: Each light's settings with ``passes`` resolved, kept while the settings live.
_RESOLVED: WeakKeyDictionary[ShadowSettings, dict[str, ShadowSettings]] = WeakKeyDictionary()


def _with_passes(settings: ShadowSettings, passes: str) -> ShadowSettings:
    """Return ``settings`` with ``passes`` set: the same object for the same choice.

    A light that moves is planned again each frame; the same settings object
    spares the copy and lets the next frame's plan compare it by identity.
    """
    resolved = _RESOLVED.get(settings)
    if resolved is None:
        resolved = _RESOLVED[settings] = {}
    if passes not in resolved:
        resolved[passes] = replace(settings, passes=passes)
    return resolved[passes]
