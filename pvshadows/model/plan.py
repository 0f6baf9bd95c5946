"""What the planner hands each technique: one light's plan and cast per frame, who serves whom.

The planner (:mod:`pvshadows.pipeline.planner`) fills these; techniques only
read them, so they live below both.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.geometry.boxes import CasterBoxes
from pvshadows.geometry.volume_casters import VolumeMesh
from pvshadows.model.settings import ShadowSettings
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.planes import PlaneChoice
from pvshadows.scene.triangles import vtk_id

#: Technique ``"auto"`` picks for each kind of light.
AUTO_TECHNIQUE = {LightKind.POINT: "cubemap", LightKind.SPOT: "map", LightKind.DIRECTIONAL: "map"}
#: Kinds of light each technique can serve.
SERVES = {
    "cubemap": (LightKind.POINT, LightKind.SPOT),
    "map": (LightKind.SPOT, LightKind.DIRECTIONAL),
    "volume": (LightKind.POINT, LightKind.SPOT, LightKind.DIRECTIONAL),
    "planar": (LightKind.POINT, LightKind.SPOT, LightKind.DIRECTIONAL),
}
#: The technique that casts the shadows of a volume light's open casters
#: (``on_open="fallback"``), per kind of light. A name that is not (yet) a
#: registered technique serving that kind of light leaves open casters without
#: shadows from such lights, with a warning naming them.
FALLBACK_TECHNIQUES = {
    LightKind.POINT: "cubemap",
    LightKind.SPOT: "cubemap",
    LightKind.DIRECTIONAL: "map",
}


@dataclass
class VolumePlan:
    """What a shadow-volume light casts in one frame, decided by the planner.

    Attributes
    ----------
    closed : list of (ActorState, VolumeMesh)
        The casters that cast volumes, with their closed meshes.
    caster_boxes : CasterBoxes
        Their names and world bounds, stacked once for every test of them
        (the same object while the casters are).
    light : numpy.ndarray
        The light the volumes are cast from, ``(position, 1)`` or
        ``(direction towards it, 0)``, moved a hair off any face it lies in.
    enclosing : ActorState or None
        A closed caster that holds the light: everything outside it is in
        its shadow, and nothing is counted.
    zmode : str
        ``"zpass"`` or ``"zfail"`` (``""`` when ``enclosing`` holds the light).
    extrude : str
        ``"gpu"`` (a geometry shader extrudes the silhouettes) or ``"cpu"``.
    fallback : tuple of (str, Cast) or None
        The shadow-map technique and its cast of the open casters only.
    zmode_reason : str
        Why ``zmode`` was chosen (the camera decides it, so it is chosen
        again each frame the camera moves).
    """

    closed: list[tuple[ActorState, VolumeMesh]]
    caster_boxes: CasterBoxes
    light: np.ndarray
    enclosing: ActorState | None = None
    zmode: str = ""
    extrude: str = "gpu"
    fallback: tuple[str, Cast] | None = None
    zmode_reason: str = ""


@dataclass
class LightSlot:
    """A light and its places: what every plan and cast of a light starts from.

    Attributes
    ----------
    light : vtk.vtkLight
        The light.
    index : int
        Its position in the renderer's light list.
    vtk_index : int
        Its index among switched-on lights, as VTK's shaders number them.
    kind : LightKind
        Point, spot or directional, as the user set it up.
    """

    light: vtk.vtkLight
    index: int
    vtk_index: int
    kind: LightKind

    @cached
    def key(self) -> str:
        """The light's key (:func:`pvshadows.scene.triangles.vtk_id`), read once."""
        return vtk_id(self.light)


@dataclass
class Cast(LightSlot):
    """What one shadowed light draws in one frame: every field is set.

    The planner makes one for each light that casts, and techniques only
    draw it. Besides the :class:`LightSlot`'s:

    Attributes
    ----------
    settings : ShadowSettings
        Its settings.
    technique : str
        The technique that draws it.
    pose : LightPose
        The world pose its shadows are cast from (a far point or spot light
        may be cast as a directional one).
    casters : list of ActorState
        The casters that can shadow a receiver for this light.
    notes : list of str
        Decisions in words (the same list as its :class:`LightPlan`'s).
    """

    settings: ShadowSettings
    technique: str
    pose: LightPose
    casters: list[ActorState]
    notes: list[str]


@dataclass
class VolumeCast(Cast):
    """A cast by shadow volumes, with what the planner decided for them.

    Attributes
    ----------
    volume : VolumePlan
        Its closed casters, the light they are cast from, the counting, the
        extrusion and the open casters' fallback.
    """

    volume: VolumePlan


@dataclass
class PlanarCast(Cast):
    """A cast flattened onto one receiving plane.

    Attributes
    ----------
    plane : PlaneChoice
        The receiving plane (or none, and why).
    """

    plane: PlaneChoice


@dataclass
class LightPlan(LightSlot):
    """What one light does in one frame, whether or not it casts.

    Besides the :class:`LightSlot`'s:

    Attributes
    ----------
    settings : ShadowSettings or None
        Its settings, ``None`` when shadows are not enabled for it.
    notes : list of str
        Decisions in words.
    cast : Cast or None
        What it draws; ``None`` when it casts no shadow (the notes say why).
    """

    settings: ShadowSettings | None
    notes: list[str] = field(default_factory=list)
    cast: Cast | None = None

    @property
    def technique(self) -> str | None:
        """The technique that draws the light, ``None`` when it casts no shadow."""
        return None if self.cast is None else self.cast.technique
