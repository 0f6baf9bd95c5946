"""What the planner hands each technique: one light's plan for one frame, and who serves whom.

The planner (:mod:`pvshadows.pipeline.planner`) fills these; techniques only
read them, so they live below both.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from pvshadows import _vtk as vtk
from pvshadows.model.settings import ShadowSettings
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.snapshot import ActorState

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
