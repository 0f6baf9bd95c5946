"""Where a volume light stands against its casters.

Its homogeneous vector, moved a hair off any caster face it lies in; whether
a closed caster holds it (everything outside is then in its shadow) or holds
it and every other receiver (a room: it shadows none of them); and how far
volumes reach under a parallel projection.
"""

from __future__ import annotations

import numpy as np

from pvshadows.geometry.boxes import CasterBoxes
from pvshadows.geometry.volume_casters import VolumeMesh, winding_number
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot
from pvshadows.techniques.base import FrameContext

#: A light this close to a caster's face plane (fraction of the caster's size) lies in it.
ON_SURFACE = 1e-6
#: How far such a light is moved off the face for its volumes (fraction of the caster's size).
OFF_SURFACE = 1e-5


def off_surfaces(
    light: np.ndarray,
    closed: list[tuple[ActorState, VolumeMesh]],
    boxes: CasterBoxes,
    notes: list[str],
) -> np.ndarray:
    """Move a point light lying in the plane of a caster's face a hair off it, outwards.

    A face in the light's plane is neither lit nor unlit, and the silhouette
    edges around it come out inconsistent: whole volumes go missing. Cast
    from 1e-5 of the caster's size outside every such face, the shadows
    differ from the exact ones by far less than a pixel. Only the casters
    whose boxes (``boxes``, stacked) come that near the light are looked at.
    """
    if light[3] == 0.0:
        return light
    position = light[:3]
    push = np.zeros(3)
    for number in boxes.around(position, ON_SURFACE * boxes.diagonals):
        caster, mesh = closed[number]
        size = caster.diagonal
        model = caster.model_matrix()
        points = mesh.points @ model[:3, :3].T + model[:3, 3]
        corners = points[mesh.triangles]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normals, axis=1)
        keep = length > 0.0
        unit = normals[keep] / length[keep, None]
        distance = np.einsum("ij,ij->i", unit, position - corners[keep, 0])
        touching = np.abs(distance) <= ON_SURFACE * size
        if touching.any():
            notes.append(
                f"the light lies in the plane of a face of {caster.name}: its volumes are cast "
                f"from {OFF_SURFACE:g} of its size off that face"
            )
            push += OFF_SURFACE * size * unit[touching].sum(axis=0) / max(touching.sum(), 1)
    if not push.any():
        return light
    return np.array([*(position + push), 1.0])


def enclosing_caster(
    light: np.ndarray, closed: list[tuple[ActorState, VolumeMesh]], boxes: CasterBoxes
) -> ActorState | None:
    """Return the first closed caster whose inside holds a positional light, or ``None``.

    Only the casters whose boxes (``boxes``, stacked) hold the light are looked at.
    """
    if light[3] == 0.0:
        return None
    for number in boxes.around(light[:3]):
        caster, mesh = closed[number]
        if mesh.how == "two-sided sheet":
            continue
        model = caster.model_inverse @ np.append(light[:3], 1.0)
        if winding_number(mesh.points, mesh.triangles, model[:3] / model[3]) > 0.5:
            return caster
    return None


def finite_reach(context: FrameContext, light: np.ndarray) -> float:
    """Return 0 (extrude to infinity), or how far to extrude for a parallel projection.

    Far enough that every volume reaches past every actor: four times the
    diagonal of the box around the actors and a positional light.
    """
    if not context.camera.GetParallelProjection():
        return 0.0
    boxes = [actor.bounds for actor in context.snapshot.actors]
    if light[3] != 0.0:
        boxes.append(np.stack([light[:3], light[:3]]))
    corners = np.concatenate(boxes)
    return 4.0 * max(float(np.linalg.norm(np.ptp(corners, axis=0))), 1e-300)


def holds_the_rest(
    enclosing: ActorState, closed: list[tuple[ActorState, VolumeMesh]], snapshot: Snapshot
) -> bool:
    """Whether every receiver but ``enclosing`` lies inside it (a room around the scene)."""
    mesh = next(m for c, m in closed if c is enclosing)
    others = [r for r in snapshot.receivers if r is not enclosing]
    inverse = np.linalg.inv(enclosing.model_matrix())
    for receiver in others:
        centre = inverse @ np.append(receiver.bounds.mean(axis=0), 1.0)
        if winding_number(mesh.points, mesh.triangles, centre[:3] / centre[3]) < 0.5:
            return False
    return bool(others)
