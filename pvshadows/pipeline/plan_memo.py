"""Last frame's plans, kept between frames: what a light's plan was made from, saw and reached.

A light keeps last frame's plan while its own inputs hold (the actors, the
light and its pose time, its settings and place, and what the camera sees
of what the plan looked at); a light that only moved takes its last plan to
its new pose where nothing else follows from the move; a volume light's
z-pass or z-fail is chosen again only where the camera or the light may
have changed it. The planner (:func:`pvshadows.pipeline.planner.plan_frame`)
asks :class:`PlanMemo` first and plans from the start what it cannot answer.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.model.plan import Cast, LightPlan, VolumePlan
from pvshadows.model.settings import ShadowSettings
from pvshadows.pipeline.far_lights import fitted_to_casters
from pvshadows.pipeline.reach import ReachCache, same_objects
from pvshadows.pipeline.sight import ViewSight
from pvshadows.pipeline.volume_plan import (
    ClosedSplit,
    ZpassRoom,
    choose_volume_zmode,
    split_casters,
)
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.lights import LightPose, light_pose, renderer_lights
from pvshadows.scene.planes import PlaneChoice, choose_plane
from pvshadows.scene.snapshot import RECEIVERS, Snapshot
from pvshadows.scene.view import FrameView


class Reached(NamedTuple):
    """What a light reaches of a snapshot's actors."""

    #: Its reach's answers (:meth:`ReachCache.reaches`); ``None`` when it reaches every actor.
    hits: np.ndarray | None
    #: The receivers it reaches, a mask over the snapshot's receivers.
    receivers: np.ndarray
    #: The casters it reaches, in the snapshot's order.
    casters: list[ActorState]
    #: The ``(2, 3)`` box around them.
    box: np.ndarray


class PlanMemo:
    """Last frame's plan of each light and what it was made from, kept between frames.

    A light's plan depends on the actors (the snapshot), the light and its
    settings, its place among the lights, and what the camera sees of what
    the plan looked at: whether it sees some receiver in the light's reach
    (and some receiver at all), or, for a far spot light whose map was
    fitted to the view, exactly which receivers it sees. A light whose
    inputs are last frame's keeps last frame's plan (only what the camera
    alone decides, a volume light's z-pass or z-fail, is chosen again): a
    frame in which only the camera moved plans nothing, even when receivers
    come into view and leave it, and one in which one light moved plans
    that light only.

    Attributes
    ----------
    kept : int
        Frames that kept every light's plan.
    made : int
        Frames that planned some light again.
    planned : int
        Lights planned again, over all frames.
    poses_read : int
        Light poses read from VTK, over all frames (a light's pose is read
        again only when its pose time moved).
    reposed : int
        Lights planned again by taking their last plan to their new pose
        (:meth:`repose`), over all frames; counted in :attr:`planned` too.
    listings : int
        Times a renderer's lights were listed from VTK (:meth:`lights_of`).
    zmodes_chosen : int
        Times a kept volume plan chose z-pass or z-fail again
        (:meth:`choose_zmode`): only when the renderer's hidden-line removal
        changed, or the camera changed and z-pass was not known to hold
        there.
    planes_chosen : int
        Times the receiving plane of planar lights was chosen (:meth:`plane`).
    """

    def __init__(self) -> None:
        self.kept = 0
        self.made = 0
        self.planned = 0
        self.poses_read = 0
        self.reposed = 0
        self.listings = 0
        self.zmodes_chosen = 0
        self.planes_chosen = 0
        self._plane: tuple[tuple[ActorState, ...], PlaneChoice] | None = None
        self._lights: tuple[vtk.vtkLightCollection, int, tuple[vtk.vtkLight, ...]] | None = None
        self._poses: dict[int, tuple[vtk.vtkLight, int, LightPose]] = {}
        self._tested = 0
        self._witnesses: dict[int, int] = {}
        self._plans: dict[
            int, tuple[tuple, LightPlan, int, ViewUse, tuple[ViewSight, object], Reached | None]
        ] = {}
        self._in_view: tuple[Snapshot, FrameView, ViewSight] | None = None
        #: The lights of the last :meth:`keep_only`.
        self._kept_for: tuple[vtk.vtkLight, ...] = ()
        #: What each volume light last chose its z-mode for: the volume plan, view
        #: and hidden-line removal, and the room its z-pass had (:class:`ZpassRoom`).
        self._zmodes: dict[int, tuple[VolumePlan, FrameView, bool, ZpassRoom | None]] = {}
        #: Each volume light's last split of its casters: the ``on_open`` it was made
        #: for, the split, and the notes it made.
        self._splits: dict[int, tuple[str, ClosedSplit, list[str]]] = {}
        #: Casters sorted into closed and open ones (:meth:`split_closed`) since made,
        #: and splits patched over casters that moved.
        self.splits = 0
        self.split_patches = 0

    def plane(self, receivers: list[ActorState]) -> PlaneChoice:
        """Return the receiving plane of planar lights, chosen again only for other receivers.

        Parameters
        ----------
        receivers : list of ActorState
            This frame's receivers.

        Returns
        -------
        PlaneChoice
            :func:`~pvshadows.scene.planes.choose_plane`'s, kept while the
            receivers are the very same states (a light that moves does not
            change it).
        """
        if self._plane is None or not same_objects(receivers, self._plane[0]):
            self._plane = (tuple(receivers), choose_plane(receivers))
            self.planes_chosen += 1
        return self._plane[1]

    def forget(self) -> None:
        """Plan every light again next frame."""
        self._plans = {}
        self._poses = {}
        self._in_view = None
        self._zmodes = {}
        self._plane = None

    def lights_of(self, renderer: vtk.vtkRenderer) -> tuple[vtk.vtkLight, ...]:
        """Return a renderer's lights in order, listed again only when its collection changed.

        Adding, inserting, replacing or removing a light moves the modification
        time of the renderer's light collection (a light's own changes do not):
        the same collection at the same time hands back the last call's tuple.

        Parameters
        ----------
        renderer : vtk.vtkRenderer
            The renderer.

        Returns
        -------
        tuple of vtk.vtkLight
            Its lights, in the renderer's order.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows.pipeline.planner import PlanMemo
        >>> pl = pv.Plotter(off_screen=True, lighting=None)
        >>> pl.add_light(pv.Light(position=(0, 0, 1)))
        >>> memo = PlanMemo()
        >>> memo.lights_of(pl.renderer) is memo.lights_of(pl.renderer)
        True
        >>> pl.add_light(pv.Light(position=(1, 0, 1)))
        >>> len(memo.lights_of(pl.renderer)), memo.listings
        (2, 2)
        """
        collection = vtk.vtkRenderer.GetLights(renderer)  # past PyVista's attribute checks
        stamp = vtk.vtkObject.GetMTime(collection)
        kept = self._lights
        if kept is None or kept[0] is not collection or kept[1] != stamp:
            kept = self._lights = (collection, stamp, renderer_lights(renderer))
            self.listings += 1
        return kept[2]

    def pose(self, light: vtk.vtkLight, time: int) -> LightPose:
        """Return a light's pose (:func:`light_pose`), read again only when ``time`` moved.

        Parameters
        ----------
        light : vtk.vtkLight
            The light.
        time : int
            Its :func:`pvshadows.scene.lights.pose_time` this frame.

        Returns
        -------
        LightPose
            The pose read at that pose time.

        Raises
        ------
        ValueError
            As :func:`light_pose` does; such a pose is not kept.
        """
        kept = self._poses.get(id(light))
        if kept is not None and kept[0] is light and kept[1] == time:
            return kept[2]
        pose = light_pose(light)
        self.poses_read += 1
        self._poses[id(light)] = (light, time, pose)
        return pose

    @property
    def view_tests(self) -> int:
        """Receivers tested one by one against the view, over all frames."""
        return self._tested + (0 if self._in_view is None else self._in_view[2].tested)

    def in_view(self, snapshot: Snapshot, view: FrameView) -> ViewSight:
        """Return what the view sees of the snapshot's receivers (new when either changed).

        Last frame's witnesses answer first (:class:`ViewSight`); a snapshot
        that follows last frame's, seen from the same view, tests again only
        its replaced receivers (:meth:`ViewSight.following`).
        """
        kept = self._in_view
        if kept is None or kept[0] is not snapshot or kept[1] is not view:
            self._tested += 0 if kept is None else kept[2].tested
            bounds, whole = snapshot.receiver_bounds, snapshot.receivers_box
            if kept is not None and kept[1] is view and snapshot.parent is kept[0]:
                rows = [row for row, _ in snapshot.patches(RECEIVERS)]
                sight = kept[2].following(bounds, whole, rows)
            else:
                sight = ViewSight(bounds, whole, view.planes, self._witnesses)
            kept = (snapshot, view, sight)
            self._in_view = kept
        return kept[2]

    def recall(
        self,
        inputs: tuple,
        in_view: ViewSight,
        reach: ReachCache | None = None,
        pose_of: Callable[[vtk.vtkLight, int], LightPose] | None = None,
    ) -> LightPlan | None:
        """Return a light's last plan if it was made from the same inputs, else ``None``.

        ``inputs`` are ``(light, pose time, settings, index, VTK index,
        snapshot)``; ``in_view`` says which of the snapshot's receivers the
        camera sees, compared as far as the plan looked at it. A snapshot
        that follows the plan's (:attr:`Snapshot.parent`) counts as the same
        when the actors replaced in it only moved, the light reaches none of
        them before or after (``reach`` tells), and the plan did not look at
        exactly which receivers the camera sees nor choose a receiving
        plane. The plan comes back with the planner's notes only: what
        techniques and the frame added to them last frame is said again
        this frame. ``pose_of`` reads a light's pose given its pose time (the frame's reader
        reads each light once).
        """
        kept = self._plans.get(id(inputs[0]))
        if kept is None:
            return None
        same = _same_inputs(kept[0], inputs)
        if not same and (reach is None or not _moved_out_of_reach(kept, inputs, reach, pose_of)):
            return None
        if not _seen_alike(kept[4], kept[3], in_view):
            return None
        if not same:
            kept = (inputs, *kept[1:])
            self._plans[id(inputs[0])] = kept
        plan, planned = kept[1], kept[2]
        del plan.notes[planned:]
        return plan

    def repose(
        self,
        inputs: tuple,
        in_view: ViewSight,
        reach: ReachCache,
        pose_of: Callable[[vtk.vtkLight, int], LightPose],
        may_cast: Callable[[vtk.vtkLight, ShadowSettings | None], bool],
    ) -> LightPlan | None:
        """Return a light's last plan cast from its new pose, when only where it stands changed.

        A light whose pose time alone moved (the same settings, place and
        snapshot, seen as the plan looked at the view) keeps its technique,
        casters, settings and notes while its new pose decides nothing anew:
        it still may cast (``may_cast``), it keeps its kind, it
        draws a map or a cube (a volume's extrusion and z-mode, and a planar
        mask, follow the light), a spot light's cover still holds its cone
        so that it reaches the very actors it did (:meth:`ReachCache.reaches`
        hands back the same answers), and no map is to be fitted to its
        casters from where it now stands (:func:`fitted_to_casters`). The
        plan then takes the new pose; else ``None``, and the light is
        planned from the start.
        """
        light, time, settings, _, _, snapshot = inputs
        kept = self._plans.get(id(light))
        if kept is None or kept[0][5] is not snapshot:
            return None
        before, plan, planned, use, seen, reached = kept
        cast = plan.cast
        if (
            type(cast) is not Cast
            or isinstance(use, str)
            or not _same_inputs((before[0], time, *before[2:]), inputs)
            or not _seen_alike(seen, use, in_view)
            or not may_cast(light, settings)
        ):
            return None
        try:
            pose = pose_of(light, time)
        except ValueError:
            return None
        if pose.kind is not plan.kind or cast.pose.kind is not plan.kind:
            return None
        if reached is None:
            return None
        if reached.hits is None:  # it reaches every actor: this snapshot's, still
            if reached.casters is not snapshot.casters:
                return None
        elif reach.reaches(plan.key, pose, snapshot) is not reached.hits:
            return None
        if fitted_to_casters(cast.technique, pose, reached.box) is not None:
            return None
        del plan.notes[planned:]
        # field by field: dataclasses.replace costs five times as much, once a frame
        plan.cast = Cast(
            light,
            cast.index,
            cast.vtk_index,
            cast.kind,
            cast.settings,
            cast.technique,
            pose,
            cast.casters,
            cast.notes,
        )
        self._plans[id(light)] = (inputs, *kept[1:])
        self.reposed += 1
        return plan

    def keep(
        self,
        inputs: tuple,
        plan: LightPlan,
        use: ViewUse,
        in_view: ViewSight,
        reached: Reached | None = None,
    ) -> None:
        """Keep a light's plan of this frame, what it was made from, saw and reached."""
        seen = (in_view, _view_key(use, in_view))
        self._plans[id(inputs[0])] = (inputs, plan, len(plan.notes), use, seen, reached)

    def keep_only(self, lights: Sequence[vtk.vtkLight]) -> None:
        """Forget the lights no longer the renderer's (none if they are the last call's)."""
        if same_objects(lights, self._kept_for):
            return
        self._kept_for = tuple(lights)
        alive = {id(light) for light in lights}
        for key in set(self._plans) - alive:
            del self._plans[key]
        for key in set(self._poses) - alive:
            del self._poses[key]
        for key in set(self._zmodes) - alive:
            del self._zmodes[key]
        for key in set(self._splits) - alive:
            del self._splits[key]

    def split_closed(self, cast: Cast) -> ClosedSplit:
        """Sort a volume light's casters into closed and open ones, again only for other casters.

        A light whose casters are the very casters of its last split, in
        the same order (the same snapshot's, or the same reach of a spot
        light: it moved, or only the camera did), gets the very split back
        (:func:`~pvshadows.pipeline.volume_plan.split_casters`), and the
        notes it made are said again; the volume technique then keeps its
        draws while only the light or the camera moves. A few casters that
        moved are patched in (:meth:`ClosedSplit.patched`).

        Parameters
        ----------
        cast : Cast
            The light's cast, technique ``"volume"``.

        Returns
        -------
        ClosedSplit
            The closed casters with their meshes, the open ones, and the
            closed ones' boxes.

        Raises
        ------
        OpenMeshError
            With ``on_open="raise"``, naming the first open caster.
        """
        on_open = cast.settings.on_open
        kept = self._splits.get(id(cast.light))
        if kept is not None and kept[0] == on_open:
            split, notes = kept[1], kept[2]
            if same_objects(split.casters, cast.casters):
                cast.notes.extend(notes)
                return split
            patched = split.patched(cast.casters)
            if patched is not None:
                self.split_patches += 1
                self._splits[id(cast.light)] = (on_open, patched, notes)
                cast.notes.extend(notes)
                return patched
        said = len(cast.notes)
        split = split_casters(cast)
        self.splits += 1
        self._splits[id(cast.light)] = (on_open, split, cast.notes[said:])
        return split

    def choose_zmode(
        self,
        cast: Cast,
        volume: VolumePlan,
        renderer: vtk.vtkRenderer,
        view: FrameView,
        warned: set[tuple],
    ) -> None:
        """Choose a volume plan's z-pass or z-fail where the camera or light may have changed it.

        What decides (:func:`~pvshadows.pipeline.volume_plan.choose_volume_zmode`)
        is the camera, the renderer's hidden-line removal and the plan's own
        light and closed casters: the same plan seen from the same view
        (:meth:`FrameView.of` hands back last frame's while the camera, aspect
        and size hold) keeps the choice it made, and a z-pass made with room
        to spare (:class:`~pvshadows.pipeline.volume_plan.ZpassRoom`) is
        taken again, without a test, while the light's closed casters are
        the same and neither the light nor the camera's near region left
        that room: the test would come out the same.

        Parameters
        ----------
        cast : Cast
            The light's cast, whose notes say the choice.
        volume : VolumePlan
            Its volume plan (a kept one, or one just made).
        renderer : vtk.vtkRenderer
            The renderer, whose camera decides.
        view : FrameView
            This frame's view of that camera.
        warned : set of tuple
            Warnings already given, kept between frames.
        """
        hidden = bool(vtk.vtkRenderer.GetUseHiddenLineRemoval(renderer))
        light = id(cast.light)
        kept = self._zmodes.get(light)
        if kept is not None and kept[0] is volume and kept[1] is view and kept[2] == hidden:
            return
        room = kept[3] if kept is not None else None
        outside = room is not None and room.holds(volume, view, hidden)
        if not (outside and kept is not None and kept[0] is volume):
            choose_volume_zmode(cast, volume, renderer, warned, view, outside)
        if not outside:
            room = ZpassRoom.of(cast, volume, view, hidden)
            self.zmodes_chosen += 1
        self._zmodes[light] = (volume, view, hidden, room)


def _moved_out_of_reach(
    kept: tuple,
    inputs: tuple,
    reach: ReachCache,
    pose_of: Callable[[vtk.vtkLight, int], LightPose] | None,
) -> bool:
    """Whether only actors out of the light's reach moved since its kept plan was made."""
    (light, time, settings, index, vtk_index, before), plan, use = kept[0], kept[1], kept[3]
    now = inputs[5]
    if (
        now.parent is not before
        or not _same_inputs((light, time, settings, index, vtk_index, now), inputs)
        or isinstance(use, str)
        or plan.technique == "planar"
        or any(now.actors[r].triangles is not before.actors[r].triangles for r in now.replaced)
    ):
        return False
    try:
        pose = light_pose(light) if pose_of is None else pose_of(light, time)
    except ValueError:
        return False
    return not reach.touches(plan.key, pose, now)


def _same_inputs(a: tuple, b: tuple) -> bool:
    light, time, settings, index, vtk_index, snapshot = a
    return (
        light is b[0]
        and time == b[1]
        and (settings is b[2] or settings == b[2])
        and index == b[3]
        and vtk_index == b[4]
        and snapshot is b[5]
    )


#: A plan that looked at exactly which receivers the camera sees.
EVERY_RECEIVER = "every receiver"
#: What a light's plan looked at of the view: nothing (``None``), whether the camera
#: sees some receiver and some receiver in the light's reach (that reach, a mask over
#: the snapshot's receivers), or which receivers it sees (:data:`EVERY_RECEIVER`).
ViewUse = None | np.ndarray | str


def _seen_alike(seen: tuple[ViewSight, object], use: ViewUse, in_view: ViewSight) -> bool:
    """Whether the view shows what a plan looked at (``use``) as it did when ``seen`` was kept.

    ``seen`` is the sight the plan was made or last kept with and its
    :func:`_view_key`; the same sight answers alike without a test.
    """
    return seen[0] is in_view or _view_key(use, in_view) == seen[1]


def _view_key(use: ViewUse, in_view: ViewSight) -> object:
    """Return what a plan that looked at ``use`` of the view would see of ``in_view``."""
    if use is None:
        return None
    if isinstance(use, str):
        return in_view.every.tobytes()
    return in_view.sees_some(), in_view.sees_some(use)
