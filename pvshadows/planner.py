"""Decides, each frame, what every light does: the only place such decisions are made.

A light casts only when it is on, has intensity, and there is a caster and a
receiver; its technique follows its kind and settings. Which faces and which
maps are reused is decided by the technique from what this plan hands it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import vtk

from pvshadows.lights import LightKind, LightPose, casts_light, light_kind, light_pose
from pvshadows.settings import ShadowSettings
from pvshadows.snapshot import ActorState, Snapshot

#: Technique ``"auto"`` picks for each kind of light.
AUTO_TECHNIQUE = {LightKind.POINT: "cubemap", LightKind.SPOT: "map", LightKind.DIRECTIONAL: "map"}
#: Kinds of light each technique can serve.
SERVES = {
    "cubemap": (LightKind.POINT, LightKind.SPOT),
    "map": (LightKind.SPOT, LightKind.DIRECTIONAL),
    "volume": (LightKind.POINT, LightKind.SPOT, LightKind.DIRECTIONAL),
    "planar": (LightKind.POINT, LightKind.SPOT, LightKind.DIRECTIONAL),
}


@dataclass
class LightPlan:
    """What one light does in one frame.

    Attributes
    ----------
    light : vtk.vtkLight
        The light.
    index : int
        Its position in the renderer's light list.
    vtk_index : int
        Its index among switched-on lights, as VTK's shaders number them.
    kind : LightKind
        Point, spot or directional.
    settings : ShadowSettings or None
        Its settings, ``None`` when shadows are not enabled for it.
    technique : str or None
        The technique chosen, ``None`` when it casts no shadow.
    pose : LightPose or None
        Its world pose (``None`` when it casts no shadow).
    casters : list of ActorState
        The casters that can shadow a receiver for this light.
    notes : list of str
        Decisions in words.
    """

    light: vtk.vtkLight
    index: int
    vtk_index: int
    kind: LightKind
    settings: ShadowSettings | None
    technique: str | None = None
    pose: LightPose | None = None
    casters: list[ActorState] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


def _technique_for(kind: LightKind, settings: ShadowSettings) -> tuple[str | None, str]:
    if settings.technique == "auto":
        technique = AUTO_TECHNIQUE.get(kind)
        if technique is None:
            return None, f"no technique of this version serves a {kind.value} light yet"
        return technique, f"auto chose {technique} for a {kind.value} light"
    if kind not in SERVES[settings.technique]:
        return None, f"technique {settings.technique!r} cannot serve a {kind.value} light"
    return settings.technique, f"{settings.technique} as configured"


def plan_frame(
    renderer: vtk.vtkRenderer,
    snapshot: Snapshot,
    settings_for: Callable[[vtk.vtkLight], ShadowSettings | None],
) -> list[LightPlan]:
    """Plan every light of a renderer for this frame.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer; its lights are read in order.
    snapshot : Snapshot
        Its actors this frame.
    settings_for : callable
        Returns a light's settings, or ``None`` if shadows are not enabled
        for it.

    Returns
    -------
    list of LightPlan
        One plan per light, in the renderer's order.
    """
    plans = []
    vtk_index = 0
    lights = renderer.GetLights()
    lights.InitTraversal()
    casters = snapshot.casters
    receivers = snapshot.receivers
    for index in range(lights.GetNumberOfItems()):
        light = lights.GetNextItem()
        plan = LightPlan(light, index, vtk_index, light_kind(light), settings_for(light))
        if light.GetSwitch():
            vtk_index += 1
        plans.append(plan)
        if plan.settings is None:
            plan.notes.append("shadows are not enabled for this light")
            continue
        if not casts_light(light):
            plan.notes.append(
                "the light is off or has zero intensity: it casts nothing and costs nothing"
            )
            continue
        if light.LightTypeIsHeadlight():
            plan.notes.append(
                "a headlight's shadows hide behind the objects that cast them: none drawn"
            )
            continue
        technique, why = _technique_for(plan.kind, plan.settings)
        plan.notes.append(why)
        if technique is None:
            continue
        if not receivers:
            plan.notes.append("no actor receives shadows")
            continue
        if not casters:
            plan.notes.append("no actor casts shadows")
            continue
        try:
            plan.pose = light_pose(light)
        except ValueError as error:
            plan.notes.append(f"casts nothing: {error}")
            continue
        plan.casters = casters
        plan.technique = technique
    return plans
