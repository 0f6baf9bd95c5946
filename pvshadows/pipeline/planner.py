"""Decides, each frame, what every light does: the only place such decisions are made.

A light casts only when it is on, has intensity, and some caster and some
receiver the camera sees are in its reach (a spot light's cone; everything
for point and directional lights). Its casters are those in its reach. Its
technique follows its kind, its settings and the quality asked for: with
``technique="auto"``, planar shadows when the only receiver is one plane
(then objects cannot shadow each other, so nothing is lost), else a cube map
for a point light, a 2D map for spot and directional lights, and shadow
volumes for ``quality="exact"``. What each
technique then reuses (maps whose light and casters did not change, cube
faces without casters) it reports in the same frame's words. What is kept
between frames (last frame's plans, a volume light's z-pass) is
:mod:`pvshadows.pipeline.plan_memo`'s; the maps of far lights,
:mod:`pvshadows.pipeline.far_lights`'.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import fields, replace
from functools import partial
from typing import Any

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.model.plan import (
    AUTO_TECHNIQUE,
    SERVES,
    Cast,
    LightPlan,
    PlanarCast,
    VolumeCast,
    VolumePlan,
)
from pvshadows.model.settings import ShadowSettings
from pvshadows.pipeline.cube_passes import cube_passes
from pvshadows.pipeline.far_lights import fit_far_point, fit_far_spot, fitted_to_casters
from pvshadows.pipeline.plan_memo import EVERY_RECEIVER, PlanMemo, Reached, ViewUse
from pvshadows.pipeline.reach import ReachCache
from pvshadows.pipeline.sight import ViewSight
from pvshadows.pipeline.volume_plan import plan_volume
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.culling import box_around
from pvshadows.scene.light_kit import KeyLights, unshadowed_reason
from pvshadows.scene.lights import (
    LightKind,
    casts_light,
    light_kind,
    pose_time,
    renderer_lights,
)
from pvshadows.scene.planes import PlaneChoice, sole_plane
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.view import FrameView


def _technique_for(
    kind: LightKind, settings: ShadowSettings, only_a_plane: bool
) -> tuple[str, str]:
    if settings.technique == "auto":
        if only_a_plane:
            return "planar", (
                f"auto chose planar for a {kind.value} light: the only receiver is one plane, "
                "so flattening the casters onto it is exact and the cheapest"
            )
        if settings.quality == "exact":
            return "volume", (
                f"auto chose volume for a {kind.value} light: quality='exact' asks for "
                "pixel-exact hard shadows"
            )
        technique = AUTO_TECHNIQUE[kind]
        return technique, (
            f"auto chose {technique} for a {kind.value} light (quality={settings.quality!r})"
        )
    if kind not in SERVES[settings.technique]:
        chosen, _ = _technique_for(kind, replace(settings, technique="auto"), only_a_plane)
        return chosen, (
            f"technique {settings.technique!r} cannot serve a {kind.value} light: "
            f"it casts with {chosen}, auto's choice, instead"
        )
    return settings.technique, f"{settings.technique} as configured"


def plan_frame(
    renderer: vtk.vtkRenderer,
    snapshot: Snapshot,
    settings_for: Callable[[vtk.vtkLight], ShadowSettings | None],
    reach: ReachCache | None = None,
    view: FrameView | None = None,
    warned: set[tuple] | None = None,
    memo: PlanMemo | None = None,
    extrude_on_gpu: Callable[[], bool] | None = None,
    key_lights: KeyLights | None = None,
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
    reach : ReachCache, optional
        What each spot light reached in earlier frames, so only changed
        actors and moved lights are tested again; a fresh one by default.
    view : FrameView, optional
        This frame's camera; built from the renderer by default.
    warned : set of tuple, optional
        Warnings of volume lights already given (open casters, a forced
        z-pass that may miscount), kept between frames so each warns once
        (:func:`pvshadows.pipeline.volume_plan.plan_volume`).
    memo : PlanMemo, optional
        Last frame's plans: a light's is kept when the actors, the light,
        its settings and the receivers in view are last frame's.
    extrude_on_gpu : callable, optional
        Tells whether the window compiles the geometry shader that extrudes
        shadow volumes (asked only when a volume light's settings want it);
        assumed when not given.
    key_lights : KeyLights, optional
        This frame's key lights (:class:`pvshadows.scene.light_kit.KeyLights`),
        shared with ``settings_for``, so that the key light is looked for once
        a frame; a fresh one by default.

    Returns
    -------
    list of LightPlan
        One plan per light, in the renderer's order; each that casts holds
        its :class:`pvshadows.model.plan.Cast`.
    """
    lights = renderer_lights(renderer) if memo is None else memo.lights_of(renderer)
    view = FrameView.of(renderer) if view is None else view
    if memo is None:
        in_view = ViewSight(snapshot.receiver_bounds, snapshot.receivers_box, view.planes)
    else:
        in_view = memo.in_view(snapshot, view)
    plans = []
    vtk_index = 0
    reach = ReachCache() if reach is None else reach
    warned = set() if warned is None else warned
    gpu = extrude_on_gpu if extrude_on_gpu is not None else lambda: True
    keys = KeyLights() if key_lights is None else key_lights
    shared = _Shared(snapshot, in_view, memo if memo is not None else PlanMemo(), keys, view)

    def may_cast(light: vtk.vtkLight, settings: ShadowSettings | None) -> bool:
        return _casts_nothing(light, settings, renderer, keys) is None

    planned = 0
    for index, light in enumerate(lights):
        inputs = (light, pose_time(light), settings_for(light), index, vtk_index, snapshot)
        plan = memo.recall(inputs, in_view, reach, shared.pose) if memo is not None else None
        if plan is None:
            if memo is not None:
                plan = memo.repose(inputs, in_view, reach, shared.pose, may_cast)
            if plan is None:
                plan, use, reached = _plan_light(renderer, shared, inputs, reach, warned, gpu)
                if memo is not None:
                    memo.keep(inputs, plan, use, in_view, reached)
            planned += 1
        elif isinstance(plan.cast, VolumeCast):
            assert memo is not None  # plans are recalled from a memo only
            memo.choose_zmode(plan.cast, plan.cast.volume, renderer, view, warned)
        if vtk.vtkLight.GetSwitch(light):
            vtk_index += 1
        plans.append(plan)
    reach.keep_only(lights)
    if memo is not None:
        memo.keep_only(lights)
        memo.planned += planned
        if planned:
            memo.made += 1
        else:
            memo.kept += 1
    return plans


def _reached_of(hits: np.ndarray, snapshot: Snapshot) -> Reached:
    """Split a spot light's reach (a bool per actor of ``snapshot``) into receivers and casters."""
    casters = hits[snapshot.caster_index]
    within = snapshot.casters_at(np.flatnonzero(casters))
    every = within is snapshot.casters
    box = snapshot.casters_box if every else box_around(snapshot.caster_bounds[casters])
    return Reached(hits, hits[snapshot.receiver_index], within, box)


class _Shared:
    """What the lights planned in one frame share, worked out once when first asked."""

    def __init__(
        self,
        snapshot: Snapshot,
        in_view: ViewSight,
        memo: PlanMemo,
        keys: KeyLights,
        view: FrameView,
    ) -> None:
        self.snapshot = snapshot
        self.in_view = in_view
        self.memo = memo
        self.view = view
        #: Reads each light's pose once per pose time (:meth:`PlanMemo.pose`).
        self.pose = memo.pose
        #: The renderer's key light, looked for once (:func:`_casts_nothing`).
        self.keys = keys

    @cached
    def every_actor(self) -> Reached:
        """What a point light or a sun reaches: every actor."""
        snapshot = self.snapshot
        return Reached(None, snapshot.every_receiver, snapshot.casters, snapshot.casters_box)

    @cached
    def seen(self) -> list[ActorState]:
        """The receivers the camera sees."""
        receivers = self.snapshot.receivers
        return [r for r, shown in zip(receivers, self.in_view.every, strict=True) if shown]

    @cached
    def only_a_plane(self) -> bool:
        """Whether the only receiver is one plane."""
        return sole_plane(self.snapshot.receivers) is not None

    @cached
    def plane(self) -> PlaneChoice:
        """The receiving plane of planar lights."""
        return self.memo.plane(self.snapshot.receivers)


def _plan_light(
    renderer: vtk.vtkRenderer,
    shared: _Shared,
    inputs: tuple,
    reach: ReachCache,
    warned: set[tuple],
    extrude_on_gpu: Callable[[], bool],
) -> tuple[LightPlan, ViewUse, Reached | None]:
    """Plan one light (``inputs`` as :meth:`PlanMemo.recall` takes them).

    Returns the plan, what it looked at of the view (:data:`ViewUse`) and,
    for a light that casts, what it reaches.
    """
    light, _, settings, index, vtk_index, _ = inputs
    plan = LightPlan(light, index, vtk_index, light_kind(light), settings)
    snapshot = shared.snapshot
    unlit = _casts_nothing(light, settings, renderer, shared.keys)
    if unlit is not None:
        plan.notes.append(unlit)
        return plan, None, None
    assert settings is not None  # a light without settings casts nothing
    try:
        pose = shared.pose(light, inputs[1])
    except ValueError as error:
        plan.notes.append(f"casts nothing: {error}")
        return plan, None, None
    technique, why = _technique_for(plan.kind, settings, shared.only_a_plane)
    casters = snapshot.casters
    if pose.kind is LightKind.SPOT:
        reached = _reached_of(reach.reaches(plan.key, pose, snapshot), snapshot)
    else:  # a point light or a sun reaches every actor
        reached = shared.every_actor
    use: ViewUse = reached.receivers
    if not shared.in_view.sees_some(reached.receivers):
        plan.notes.append(
            "no receiver the camera sees is in the light's reach: it casts nothing and "
            "costs nothing"
            if shared.in_view.sees_some()
            else "the camera sees no receiver: the light casts nothing and costs nothing"
        )
        return plan, use, None
    within, box = reached.casters, reached.box
    if not within:
        plan.notes.append("no caster is in the light's reach: nothing to shadow, no pass")
        return plan, use, None
    plan.notes.append(why)
    seen_from = fitted_to_casters(technique, pose, box)
    if seen_from is not None and technique == "cubemap":
        technique, pose = fit_far_point(pose, seen_from, plan.notes)
    elif seen_from is not None:
        pose, use = fit_far_spot(pose, seen_from, shared.seen, plan.notes), EVERY_RECEIVER
    if technique == "cubemap" and settings.passes == "auto":
        settings = cube_passes(settings, within, snapshot, plan.notes)
    if pose.kind is LightKind.SPOT and plan.kind is LightKind.SPOT:
        plan.notes.append(f"{len(within)} of {len(casters)} casters inside the cone")
    cast = Cast(
        light, index, plan.vtk_index, plan.kind, settings, technique, pose, within, plan.notes
    )
    if technique == "volume":
        memo = shared.memo
        choose = partial(memo.choose_zmode, renderer=renderer, view=shared.view, warned=warned)
        volume = plan_volume(
            cast, renderer, snapshot, warned, extrude_on_gpu, choose, memo.split_closed
        )
        cast = _volume_cast(cast, volume)
    elif technique == "planar":
        cast = _planar_cast(cast, shared.plane)
        plan.notes.append(shared.plane.reason)
    plan.cast = cast
    return plan, use, reached


def _casts_nothing(
    light: vtk.vtkLight,
    settings: ShadowSettings | None,
    renderer: vtk.vtkRenderer,
    keys: KeyLights,
) -> str | None:
    """Return why a light casts nothing whatever its pose, or ``None`` when it may cast."""
    if settings is None:
        return unshadowed_reason(light, renderer, keys)
    if not casts_light(light):
        return "the light is off or has zero intensity: it casts nothing and costs nothing"
    if settings.strength == 0.0:
        return "strength=0: its shadows would remove nothing, so none is drawn"
    if vtk.vtkLight.LightTypeIsHeadlight(light):
        return "a headlight's shadows hide behind the objects that cast them: none drawn"
    return None


def _volume_cast(cast: Cast, volume: VolumePlan) -> VolumeCast:
    return VolumeCast(**_fields_of(cast), volume=volume)


def _planar_cast(cast: Cast, plane: PlaneChoice) -> PlanarCast:
    return PlanarCast(**_fields_of(cast), plane=plane)


def _fields_of(cast: Cast) -> dict[str, Any]:
    return {f.name: getattr(cast, f.name) for f in fields(Cast)}
