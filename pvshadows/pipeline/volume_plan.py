"""What a shadow-volume light casts this frame, decided before it draws.

For a light whose technique is ``"volume"``, the planner sorts its casters
into closed ones (which cast volumes) and open ones (which raise, or cast
from a shadow map: :data:`pvshadows.model.plan.FALLBACK_TECHNIQUES`), moves
the light a hair off any caster face it lies in, finds a closed caster that
holds the light (a room around the light and every other receiver shadows
none of them and is dropped; any other holds everything outside it in
shadow) and chooses z-pass or z-fail
(:func:`pvshadows.pipeline.volume_zmode.choose_zmode`). The technique then
only counts what the plan says.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.boxes import CasterBoxes
from pvshadows.geometry.volume_casters import VolumeMesh
from pvshadows.model.plan import FALLBACK_TECHNIQUES, SERVES, Cast, VolumePlan
from pvshadows.pipeline.cube_passes import cube_passes
from pvshadows.pipeline.volume_zmode import OUTSIDE, choose_zmode, zpass_clearance
from pvshadows.scene.actor_state import ActorState, hides_what_is_behind
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.triangles import vtk_id
from pvshadows.scene.view import FrameView
from pvshadows.techniques import TECHNIQUE_CLASSES
from pvshadows.techniques.volume_light import (
    enclosing_caster,
    holds_the_rest,
    off_surfaces,
)
from pvshadows.techniques.volume_meshes import (
    HOW_COUNTED,
    OpenMeshError,
    open_reason,
    prepared_mesh,
    split_closed,
)

#: A split is patched for at most this many replaced casters; more are split afresh.
PATCHED_AT_MOST = 16


class ClosedSplit(NamedTuple):
    """A volume light's casters sorted into closed and open ones (:func:`split_casters`)."""

    #: The casters it sorted, in order.
    casters: list[ActorState]
    closed: list[tuple[ActorState, VolumeMesh]]
    open_casters: list[ActorState]
    #: The closed casters' boxes, stacked.
    boxes: CasterBoxes
    #: Per caster, its number among the closed ones, -1 for one open or scaled flat.
    closed_rows: list[int]

    def patched(self, casters: list[ActorState]) -> ClosedSplit | None:
        """Return this split over new states of some of its casters, or ``None`` to split afresh.

        Casters replaced by new states of the same actors (moved, say) that
        stay closed and unflattened are patched into the closed casters and
        their boxes; the rest of the split, and what its notes said, holds.

        Parameters
        ----------
        casters : list of ActorState
            The light's casters now.

        Returns
        -------
        ClosedSplit or None
            ``None`` for other casters, more than :data:`PATCHED_AT_MOST`
            replaced, or one that is not closed now or was not before.
        """
        before = self.casters
        if len(casters) != len(before):
            return None
        pairs = enumerate(zip(casters, before, strict=True))
        changed = [i for i, (now, then) in pairs if now is not then]
        if len(changed) > PATCHED_AT_MOST:
            return None
        closed = list(self.closed)
        low, high, names = self.boxes.low.copy(), self.boxes.high.copy(), list(self.boxes.names)
        for i in changed:
            row, state = self.closed_rows[i], casters[i]
            if row < 0 or state.actor is not before[i].actor or state.determinant == 0.0:
                return None
            try:
                mesh = prepared_mesh(state.triangles, state.name)
            except OpenMeshError:
                return None
            closed[row] = (state, mesh)
            (low[row], high[row]), names[row] = state.bounds, state.name
        boxes = CasterBoxes(
            tuple(names),
            low,
            high,
            float(max(np.abs(low).max(initial=0.0), np.abs(high).max(initial=0.0))),
            np.linalg.norm(high - low, axis=1),
        )
        return ClosedSplit(casters, closed, self.open_casters, boxes, self.closed_rows)


def boxes_of(closed: list[tuple[ActorState, VolumeMesh]]) -> CasterBoxes:
    """Return the names and world bounds of closed casters, stacked."""
    return CasterBoxes.of([(caster.name, caster.bounds) for caster, _ in closed])


def split_casters(plan: Cast) -> ClosedSplit:
    """Sort a volume light's casters into closed and open ones; stack the closed ones' boxes.

    Parameters
    ----------
    plan : Cast
        The light's cast: its notes say what a caster scaled flat casts.

    Returns
    -------
    ClosedSplit
        :func:`~pvshadows.techniques.volume_meshes.split_closed`, and the boxes.

    Raises
    ------
    OpenMeshError
        With ``on_open="raise"``, naming the first open caster.
    """
    closed, open_casters = split_closed(plan)
    number = {id(caster): row for row, (caster, _) in enumerate(closed)}
    rows = [number.get(id(caster), -1) for caster in plan.casters]
    return ClosedSplit(plan.casters, closed, open_casters, boxes_of(closed), rows)


def plan_volume(
    plan: Cast,
    renderer: vtk.vtkRenderer,
    snapshot: Snapshot,
    warned: set[tuple],
    extrude_on_gpu: Callable[[], bool],
    choose_zmode: Callable[[Cast, VolumePlan], None],
    split: Callable[[Cast], ClosedSplit],
) -> VolumePlan:
    """Decide what a volume light casts this frame; say it in ``plan.notes``.

    Parameters
    ----------
    plan : Cast
        The light's cast, technique ``"volume"``.
    renderer : vtk.vtkRenderer
        The renderer (its camera decides z-pass or z-fail).
    snapshot : Snapshot
        This frame's actors.
    warned : set of tuple
        Warnings already given, kept between frames: one per open caster,
        version of its data, kind of light and outcome, and one per light
        and reason its forced z-pass may miscount.
    extrude_on_gpu : callable
        Tells whether the window compiles the extruding geometry shader
        (asked only when the settings want it).
    choose_zmode : callable
        Chooses the plan's z-pass or z-fail for this frame's camera
        (:meth:`pvshadows.pipeline.plan_memo.PlanMemo.choose_zmode`, which
        calls :func:`choose_volume_zmode` where it must).
    split : callable
        Sorts the casters into closed and open ones and stacks the closed
        ones' boxes (:meth:`pvshadows.pipeline.plan_memo.PlanMemo.split_closed`,
        which calls :func:`split_casters` where it must).

    Returns
    -------
    VolumePlan
        Closed casters, the light they are cast from, an enclosing caster,
        the counting and the open casters' fallback.

    Raises
    ------
    OpenMeshError
        With ``on_open="raise"``, naming the first open caster.
    """
    _, closed, open_casters, boxes, _ = split(plan)
    fallback = _fallback(plan, open_casters, snapshot, warned)
    light = off_surfaces(plan.pose.homogeneous(), closed, boxes, plan.notes)
    enclosing = enclosing_caster(light, closed, boxes)
    while enclosing is not None and holds_the_rest(enclosing, closed, snapshot):
        plan.notes.append(
            f"the light and every other receiver are inside {enclosing.name}: it shadows "
            "none of them, so it casts no volume"
        )
        closed = [(c, m) for c, m in closed if c is not enclosing]
        boxes = boxes_of(closed)
        enclosing = enclosing_caster(light, closed, boxes)
    if enclosing is not None:
        plan.notes.append(
            f"the light is inside {enclosing.name}: everything outside it is in its shadow"
        )
        return VolumePlan(closed, boxes, light, enclosing, "", "gpu", fallback)
    for caster, mesh in closed:
        if mesh.how != "closed":
            plan.notes.append(f"{caster.name} counted as {HOW_COUNTED[mesh.how]}")
    extrude = plan.settings.extrude
    if extrude == "gpu" and not extrude_on_gpu():
        extrude = "cpu"
        plan.notes.append("the extruding geometry shader does not compile here: cpu extrusion")
    volume = VolumePlan(closed, boxes, light, None, "", extrude, fallback)
    choose_zmode(plan, volume)
    return volume


def choose_volume_zmode(
    plan: Cast,
    volume: VolumePlan,
    renderer: vtk.vtkRenderer,
    warned: set[tuple],
    view: FrameView | None = None,
    outside: bool = False,
) -> None:
    """Choose z-pass or z-fail for the renderer's camera now; say it in ``plan.notes``.

    The rest of a volume plan holds while only the camera moves: this part
    alone is chosen again then. A forced ``zmode="zpass"`` is kept, but
    where ``"auto"`` would count with z-fail the note says why z-pass may
    miscount, and a warning says it once per light and reason.

    Parameters
    ----------
    plan : Cast
        The light's cast; its note on the counting is replaced.
    volume : VolumePlan
        Its volume plan, changed in place; one whose light is inside a
        caster counts nothing and is left alone.
    renderer : vtk.vtkRenderer
        The renderer, whose camera decides.
    warned : set of tuple
        Warnings already given, kept between frames.
    view : FrameView, optional
        This frame's view of the renderer's camera, whose inverse projection
        is taken (:func:`~pvshadows.pipeline.volume_zmode.near_region`).
    outside : bool, default: False
        Whether the camera is known to be outside every volume (a kept
        z-pass's :class:`ZpassRoom` holds): ``"auto"`` then counts with
        z-pass, and a forced z-pass is not at risk, without testing again.
    """
    if volume.enclosing is not None:
        return
    wanted = plan.settings.zmode
    if outside and wanted == "auto":
        zmode, why = "zpass", OUTSIDE
    else:
        zmode, why = _zmode_for(wanted, volume, renderer, view)
    if wanted == "zpass" and not outside:
        auto, risk = _zmode_for("auto", volume, renderer, view)
        if auto == "zfail":
            why = f"{why}, although z-pass may miscount here: {risk}"
            key = ("zpass forced", vtk_id(plan.light), risk)
            if key not in warned:
                warned.add(key)
                warnings.warn(
                    f"pvshadows: light {plan.index} counts its shadow volumes with "
                    f"zmode='zpass', which may miscount here: {risk}; zmode='auto' would "
                    "count them with z-fail",
                    stacklevel=2,
                )
    note = f"{zmode}: {why}"
    old = f"{volume.zmode}: {volume.zmode_reason}"
    if volume.zmode and old in plan.notes:
        plan.notes[plan.notes.index(old)] = note
    else:
        plan.notes.append(note)
    volume.zmode, volume.zmode_reason = zmode, why


@dataclass(frozen=True)
class ZpassRoom:
    """The room a volume light's z-pass had when it was chosen.

    While the light and the camera's near region move less than
    :attr:`room` (per coordinate) and the closed casters are the same, the
    box around them stays apart from every caster's box, so ``"auto"``
    would count with z-pass again, for the same reason
    (:func:`~pvshadows.pipeline.volume_zmode.zpass_clearance`).

    Attributes
    ----------
    closed : tuple of ActorState
        The closed casters it was chosen among.
    boxes : CasterBoxes
        Their boxes: a plan with the very same boxes has the same casters.
    hidden : bool
        The renderer's hidden-line removal then.
    light : numpy.ndarray
        ``(4,)`` the light the volumes were cast from.
    region : numpy.ndarray
        ``(5, 3)`` the camera's near region.
    room : float
        How far each may move.
    """

    closed: tuple[ActorState, ...]
    boxes: CasterBoxes
    hidden: bool
    light: np.ndarray
    region: np.ndarray
    room: float

    @classmethod
    def of(cls, cast: Cast, volume: VolumePlan, view: FrameView, hidden: bool) -> ZpassRoom | None:
        """Return the room of a z-mode just chosen, or ``None`` where it has none.

        Parameters
        ----------
        cast : Cast
            The light's cast.
        volume : VolumePlan
            Its volume plan, its z-mode just chosen for ``view``
            (:func:`choose_volume_zmode`).
        view : FrameView
            The view it was chosen for.
        hidden : bool
            The renderer's hidden-line removal.

        Returns
        -------
        ZpassRoom or None
            ``None`` for z-fail, a forced z-fail, a light inside a caster,
            a caster open to view (``"auto"`` counts with z-fail then),
            a directional light, a parallel projection, or a z-pass by a
            narrow margin: the choice is made again at the next view.
        """
        if (
            volume.enclosing is not None
            or volume.zmode != "zpass"
            or cast.settings.zmode == "zfail"
        ):
            return None
        if not hidden and not all(caster.faces_drawn for caster, _ in volume.closed):
            return None
        region = view.near_region
        room = zpass_clearance(volume.light, region, volume.caster_boxes)
        if region is None or room <= 0.0:
            return None
        closed = tuple(c for c, _ in volume.closed)
        return cls(closed, volume.caster_boxes, hidden, volume.light, region, room)

    def holds(self, volume: VolumePlan, view: FrameView, hidden: bool) -> bool:
        """Whether ``"auto"`` would count a volume plan seen from ``view`` with z-pass.

        Parameters
        ----------
        volume : VolumePlan
            A plan of the same light (this frame's, or the one the room was made for).
        view : FrameView
            This frame's view.
        hidden : bool
            The renderer's hidden-line removal now.

        Returns
        -------
        bool
            ``True`` when its closed casters are the same, hidden-line removal
            is as it was, and neither its light nor the near region moved out
            of the room.
        """
        closed = volume.closed
        if hidden != self.hidden or len(closed) != len(self.closed):
            return False
        if volume.caster_boxes is not self.boxes and any(
            c is not kept for (c, _), kept in zip(closed, self.closed, strict=True)
        ):
            return False
        region = view.near_region
        if region is None:
            return False
        moved = max(
            float(np.abs(region - self.region).max()),
            float(np.abs(volume.light - self.light).max()),
        )
        return moved < self.room


def _zmode_for(
    wanted: str, volume: VolumePlan, renderer: vtk.vtkRenderer, view: FrameView | None
) -> tuple[str, str]:
    """Return the counting ``zmode=wanted`` gives a volume plan now, and why."""
    open_to_view = [c.name for c, _ in volume.closed if not hides_what_is_behind(c, renderer)]
    if wanted == "auto" and open_to_view:
        return "zfail", (
            f"{open_to_view[0]} is drawn without faces: the camera sees into its shadow volume "
            "through them, which only z-fail counts"
        )
    return choose_zmode(wanted, volume.light, renderer, volume.caster_boxes, view)


def _fallback(
    plan: Cast, open_casters: list[ActorState], snapshot: Snapshot, warned: set[tuple]
) -> tuple[str, Cast] | None:
    """Plan the shadow map that casts a volume light's open casters; warn once per caster."""
    if not open_casters:
        return None
    name = FALLBACK_TECHNIQUES.get(plan.kind)
    usable = name in TECHNIQUE_CLASSES and plan.kind in SERVES.get(name, ())
    names = ", ".join(c.name for c in open_casters)
    if usable:
        plan.notes.append(f"open casters cast from a {name} shadow map instead: {names}")
    else:
        plan.notes.append(
            f"open casters cast no shadow from this {plan.kind.value} light "
            f"(no shadow-map fallback for it yet): {names}"
        )
    for caster in open_casters:
        key = (vtk_id(caster.actor), caster.triangles.version, plan.kind, usable)
        if key in warned:
            continue
        warned.add(key)
        then = (
            f"it casts its shadow from a {name} shadow map instead"
            if usable
            else f"it casts no shadow from {plan.kind.value} lights until a shadow-map "
            "fallback serves them"
        )
        warnings.warn(f"pvshadows: {open_reason(caster)}; {then}", stacklevel=2)
    if not usable:
        return None
    assert name is not None
    settings = plan.settings
    if name == "cubemap" and settings.passes == "auto":
        settings = cube_passes(settings, open_casters, snapshot, plan.notes)
    return name, replace(plan, casters=open_casters, technique=name, settings=settings, notes=[])
