"""Casters made ready for shadow volumes: closed meshes kept per version of their data.

A caster's surface is welded, checked and closed where it can be
(:func:`pvshadows.geometry.volume_casters.prepare_volume_mesh`) once per
version of its triangles; a light's casters are sorted into closed ones and
open ones, and the closed ones into the stencil batches they are counted in
(opaque casters together, each translucent one on its own).
"""

from __future__ import annotations

import weakref

from pvshadows.geometry.closed import OpenMeshError
from pvshadows.geometry.volume_casters import VolumeMesh, batches, prepare_volume_mesh
from pvshadows.model.plan import Cast
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.triangles import ActorTriangles

#: How a caster that is not plainly closed is counted, in words.
HOW_COUNTED = {
    "repaired": "a closed surface after repair (welding, rewinding or closing small holes)",
    "two-sided sheet": "a two-sided slab of zero thickness (it is a flat open sheet)",
}


#: Each prepared mesh (or why it cannot be), by the id of the triangles it was made from.
_PREPARED: dict[int, tuple[weakref.ref, VolumeMesh | OpenMeshError]] = {}


def _reason(error: OpenMeshError) -> str:
    return str(error).split("cannot be made closed: ", 1)[-1]


def prepared_mesh(triangles: ActorTriangles, name: str) -> VolumeMesh:
    """Return an actor's surface made ready for shadow volumes, once per version of its data.

    Parameters
    ----------
    triangles : ActorTriangles
        The actor's triangles (the result is kept as long as they live).
    name : str
        How messages name the actor.

    Returns
    -------
    VolumeMesh
        Closed and outward wound, in the frame of ``triangles.points``.

    Raises
    ------
    OpenMeshError
        When it is open and cannot be closed; the message names the actor.
    """
    entry = _PREPARED.get(id(triangles))
    if entry is None or entry[0]() is not triangles:
        try:
            result: VolumeMesh | OpenMeshError = prepare_volume_mesh(
                triangles.points, triangles.triangles, name
            )
        except OpenMeshError as error:
            result = OpenMeshError(
                f"{name} is not a closed surface and cannot be closed ({_reason(error)}), "
                "so it cannot cast a shadow volume"
            )
        key = id(triangles)
        _PREPARED[key] = (weakref.ref(triangles), result)
        weakref.finalize(triangles, _PREPARED.pop, key, None)
        entry = _PREPARED[key]
    if isinstance(entry[1], OpenMeshError):
        raise entry[1]
    return entry[1]


def require_closed(casters: list[tuple[str, ActorTriangles]]) -> None:
    """Raise for the first caster that cannot cast a shadow volume (``on_open="raise"``).

    Parameters
    ----------
    casters : list of (str, ActorTriangles)
        Each caster's name and triangles.

    Raises
    ------
    ValueError
        Naming the actor and what is wrong, and what to do.
    """
    for name, triangles in casters:
        try:
            prepared_mesh(triangles, name)
        except OpenMeshError as error:
            msg = (
                f"{error}. With on_open='raise' every caster of a volume light must be "
                "closed: close the mesh, use on_open='fallback' (it then casts from a shadow "
                "map), or pl.shadows.set_caster(actor, False)"
            )
            raise OpenMeshError(msg) from None


def translucent_batches(
    closed: list[tuple[ActorState, VolumeMesh]],
) -> tuple[list[list[tuple]], list[float]]:
    """Batch the closed casters: opaque ones together, each translucent one on its own.

    Parameters
    ----------
    closed : list of tuple
        ``(caster, volume mesh)`` in drawing order.

    Returns
    -------
    batches : list of list of tuple
        As :func:`pvshadows.geometry.volume_casters.batches`: opaque casters first.
    passing : list of float
        Per batch, the light its shadow lets through: 0 for opaque casters,
        ``(1 - opacity)`` squared for a translucent closed caster (a shadow
        ray crosses two of its surfaces), ``1 - opacity`` for a flat sheet.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pvshadows.techniques.volume_meshes import translucent_batches
    >>> glass = SimpleNamespace(transmittance=0.5)
    >>> stone = SimpleNamespace(transmittance=0.0)
    >>> body = SimpleNamespace(n_bodies=1, how="closed")
    >>> translucent_batches([(glass, body), (stone, body)])
    ([[(1, 0, 1)], [(0, 0, 1)]], [0.0, 0.25])
    """
    through = [caster.transmittance for caster, _ in closed]
    counts = [mesh.n_bodies for _, mesh in closed]
    result = batches([c if t == 0.0 else 0 for c, t in zip(counts, through, strict=True)])
    passing = [0.0] * len(result)
    for number, (t, (_, mesh)) in enumerate(zip(through, closed, strict=True)):
        if t > 0.0:
            own = batches([0] * number + [counts[number]])
            result += own
            passing += [t if mesh.how == "two-sided sheet" else t * t] * len(own)
    return result, passing


def split_closed(plan: Cast) -> tuple[list[tuple[ActorState, VolumeMesh]], list[ActorState]]:
    """Sort a volume light's casters into closed ones (with their volume meshes) and open ones.

    A caster scaled flat to nothing casts nothing (said in ``plan.notes``).

    Parameters
    ----------
    plan : Cast
        The light's plan.

    Returns
    -------
    closed : list of (ActorState, VolumeMesh)
        The casters that cast volumes, in order.
    open_casters : list of ActorState
        The casters that cannot be closed.

    Raises
    ------
    OpenMeshError
        With ``on_open="raise"``, naming the first open caster.
    """
    closed, open_casters = [], []
    for caster in plan.casters:
        if caster.determinant == 0.0:
            plan.notes.append(f"{caster.name} is scaled flat to nothing: it casts no shadow")
            continue
        try:
            closed.append((caster, prepared_mesh(caster.triangles, caster.name)))
        except OpenMeshError as error:
            if plan.settings.on_open == "raise":
                require_closed([(caster.name, caster.triangles)])
                raise error  # pragma: no cover - require_closed raised already
            open_casters.append(caster)
    return closed, open_casters


def open_reason(caster: ActorState) -> str:
    """Return why a caster cannot cast a shadow volume, naming it."""
    try:
        prepared_mesh(caster.triangles, caster.name)
    except OpenMeshError as error:
        return str(error)
    return f"{caster.name} is open"  # pragma: no cover
