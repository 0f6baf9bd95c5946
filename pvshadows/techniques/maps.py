"""Spot and directional shadows from a 2D depth map.

A spot light's map is a perspective view holding its cone and storing the
distance to the light; a directional light's map is an orthographic view
fitted to the casters that can shadow what the camera sees, storing depth
along the light. Either is rendered again only when its light, its casters
or (directional) its fitted coverage changed. The map holds the opaque
casters; translucent ones go to its transmittance companion
(:mod:`pvshadows.techniques.translucent`), made only for a light that has some.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import translation
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.textures import DepthMap
from pvshadows.gl.transmittance_textures import TransmittanceTexture
from pvshadows.model.plan import Cast
from pvshadows.model.report import PassReport
from pvshadows.model.settings import ShadowSettings
from pvshadows.passes.map_depth import MapDepthPass
from pvshadows.passes.transmittance import TranslucentCaster
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.measures import CasterMeasureCache, MeasureGroup
from pvshadows.scene.spot_fitting import (
    ConeMeasures,
    cone_measures,
    cone_measures_many,
    spot_fit,
    spot_fit_holds,
    spot_shadowing_rows,
)
from pvshadows.scene.sun_fitting import (
    SUN_TURN_DEGREES,
    SunFit,
    sun_actors,
    sun_fit,
    sun_fit_over_both,
    sun_rotation,
)
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext
from pvshadows.techniques.cubemap import KeptDistances
from pvshadows.techniques.per_light import LightState, PerLightMaps
from pvshadows.techniques.still_casters import StillCasters
from pvshadows.techniques.translucent import (
    Companion,
    Companions,
    split_casters,
    translucent_key,
)


@dataclass
class MapState(LightState):
    """The map kept for one light between frames, and the light space it was drawn in."""

    depth: DepthMap
    #: A spot light's casters measured from it (shared with its kind: ``MeasureGroup``).
    measures: CasterMeasureCache[ConeMeasures]
    key: tuple | None = None
    frame: int = -1
    drawn: bool = False
    fit: SunFit | None = None
    #: The light, resolution and camera a sun's map's fit was last chosen for.
    fit_view: tuple | None = None
    world_to_light: np.ndarray | None = None
    light_to_clip: np.ndarray | None = None
    params: tuple = ()
    range_key: tuple | None = None
    range: tuple[float, float] = (0.0, 1.0)
    range_snapshot: object = None
    #: The far distance and spread a spot's map is fitted to (:func:`spot_fit_holds`).
    fitted_for: tuple[float, float | None] = (0.0, None)
    #: A spot's nearest and farthest caster distances, kept while their measures hold.
    distances: KeptDistances = field(default_factory=KeptDistances)
    #: The widest spread of a spot's shadowing casters, with the measures and the
    #: rows it was taken from (compared by identity).
    spread_of: tuple | None = None
    #: The pose whose direction a spot's map looks along
    #: (:attr:`pvshadows.scene.measures.Measured.base`).
    fitted_about: LightPose | None = None
    texel: float = 1.0
    sun_actors: tuple | None = None
    fit_key: tuple | None = None
    fitted: SunFit | None = None
    casters_of: tuple | None = None
    companion: Companion | None = None
    #: The plan the map was last brought up to date for: a spot plan kept by the planner
    #: (nothing but the camera moved) finds the map still right; a sun's, with the fit
    #: it was drawn for (:attr:`planned_fit`) kept too.
    planned: Cast | None = None
    planned_fit: SunFit | None = None
    still: StillCasters[DepthMap] | None = None
    #: The pose a spot map's cone (its axis and cosine, or -2 where it lights beyond
    #: it) was last worked out for, and that cone.
    cone: tuple[LightPose | None, tuple] = (None, ())

    def cone_of(self, plan: Cast) -> tuple:
        """Return the light's axis and its cone's cosine (-2 for a point light's map)."""
        pose, cone = self.cone
        if pose is not plan.pose:
            lit = plan.kind is LightKind.SPOT
            cosine = math.cos(math.radians(plan.pose.cone_angle)) if lit else -2.0
            cone = (*plan.pose.direction.tolist(), cosine)
            self.cone = (plan.pose, cone)
        return cone

    def release_map(self) -> None:
        """Release the map."""
        self.depth.release()


def _kind(plan: Cast) -> str:
    return "sun" if plan.pose.kind is LightKind.DIRECTIONAL else "spot"


class MapTechnique(PerLightMaps[MapState, MapDepthPass]):
    """Keeps a 2D depth map per spot or directional light.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the maps.
    """

    name = "map"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        super().__init__(window)
        self._pass = MapDepthPass(window)
        self._companions = Companions(window)
        #: Every spot light's caster measures: a caster moved under many is measured in one call.
        self._spot_measures: MeasureGroup[ConeMeasures] = MeasureGroup(cone_measures_many)

    def _state(self, plan: Cast) -> MapState:
        key = plan.key
        state = self._states.get(key)
        if state is None or state.depth.resolution != plan.settings.resolution:
            if state is not None:
                state.release()
            resolution = plan.settings.resolution
            measures = CasterMeasureCache(cone_measures, turns=True, group=self._spot_measures)
            state = MapState(DepthMap(self._window, resolution), measures=measures)
            state.still = self._still_casters(lambda: DepthMap(self._window, resolution))
            self._states[key] = state
        return state

    def update(self, plan: Cast, context: FrameContext) -> list[PassReport]:
        """Bring the light's map up to date for this frame.

        Parameters
        ----------
        plan : Cast
            The light's cast (technique ``"map"``).
        context : FrameContext
            This frame's renderer, camera, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The pass run, reused or skipped.
        """
        state = self._state(plan)
        if plan.pose.kind is LightKind.DIRECTIONAL:
            return self._update_sun(plan, context, state)
        return self._update_spot(plan, context, state)

    def _update_spot(self, plan: Cast, context: FrameContext, state: MapState) -> list[PassReport]:
        pose, settings = plan.pose, plan.settings
        if self._still_right(state, plan):
            return self._reused(state)
        state.planned = None
        inside = plan.casters
        ranged = inside or context.snapshot.casters
        range_key = (pose.key(), settings.resolution, context.snapshot.keys_of(ranged))
        if range_key != state.range_key or state.range_snapshot is not context.snapshot:
            snapshot = context.snapshot
            measured = state.measures.of(pose, snapshot)
            measures = measured.values
            nearest, far = state.distances.of(measures, snapshot, ranged, range_key[2])
            shadowing = spot_shadowing_rows(pose, inside, snapshot)
            taken = state.spread_of
            if taken is None or taken[0] is not measures or taken[1] is not shadowing:
                spread = float(measures.spread[shadowing].max()) if len(shadowing) else None
                state.spread_of = taken = (measures, shadowing, spread)
            spread = taken[2]
            kept = (
                state.range_key is not None
                and state.range_key[:2] == range_key[:2]
                and state.fitted_about is measured.base
            )
            if not (kept and spot_fit_holds(state.fitted_for, (far, spread))):
                # The map looks along the axis the spread was measured about: the light's
                # own, or one it has turned from by a little since.
                about = measured.base
                fit = spot_fit(pose, settings.resolution, far * 1e-4, far, spread, about)
                state.world_to_light = translation(-pose.position)
                state.light_to_clip, state.texel = fit.light_to_clip, fit.texel
                state.fitted_for, state.fitted_about = (far, spread), measured.base
            state.range_key, state.range = range_key, (nearest, state.fitted_for[0])
            state.range_snapshot = context.snapshot
        nearest, far = state.range
        state.params = (far, state.texel, settings.light_size, nearest)
        state.drawn = bool(inside)
        if not inside:
            state.key = None
            state.drop_companion()
            return [PassReport("map depth", "skipped", "no caster inside the spot's cone")]
        assert state.light_to_clip is not None
        projection = (state.light_to_clip.tobytes(), far)
        key = (pose.key(), settings.resolution, settings.cull_front, projection)
        detail = f"{len(inside)} of {len(context.snapshot.casters)} casters inside the cone"
        reports = self._render(
            state, key, inside, context, far, along_z=False, detail=detail, settings=settings
        )
        state.planned = plan
        return reports

    def _update_sun(self, plan: Cast, context: FrameContext, state: MapState) -> list[PassReport]:
        pose, settings = plan.pose, plan.settings
        actors = context.snapshot.actors
        # What the fit reads of the actors follows the light and the actors; the fit itself
        # the view too: the same ones give the same answers.
        kept = state.sun_actors
        key = pose.key()
        if kept is None or kept[0] != key or kept[1] is not actors:
            rotation = sun_rotation(pose)
            seen = kept[2] if kept is not None and kept[1] is actors else None
            if seen is None or not seen.holds(rotation):
                # A light that moved reads boxes that hold while it turns a little more.
                turning = kept is not None and kept[0] != key
                slack = SUN_TURN_DEGREES if turning else 0.0
                seen = sun_actors(pose, rotation, context.snapshot, slack)
            kept = state.sun_actors = (key, actors, seen, rotation)
        seen_by_sun, rotation = kept[2], kept[3]
        fit_key = (key, settings.resolution, context.view.world_to_clip.tobytes())
        if state.fit_key is None or state.fit_key[0] != fit_key or state.fit_key[1] is not actors:
            state.fitted = (
                None
                if seen_by_sun is None
                else sun_fit(seen_by_sun, rotation, context.view.clip_to_world, settings.resolution)
            )
            state.fit_key = (fit_key, actors)
        fit: SunFit | None = state.fitted
        state.drawn = fit is not None
        if fit is None:
            state.key = None
            state.drop_companion()
            state.world_to_light = rotation
            state.params = (1.0, 1.0, 1.0, 0.0)
            return [PassReport("map depth", "skipped", "no caster can shadow a visible receiver")]
        if state.fit is not None and state.fit.covers(fit):
            fit = state.fit
        elif state.fit is not None and state.fit_view == fit_key:
            # Casters moved, not the camera: a fit over both regions stays while they sway.
            fit = sun_fit_over_both(state.fit, fit) or fit
        state.fit_view = fit_key
        if state.planned_fit is fit and self._still_right(state, plan):
            return self._reused(state)
        state.planned = None
        state.fit = fit
        kept = state.casters_of
        if kept is None or kept[0] is not fit or kept[1] is not actors:
            assert seen_by_sun is not None  # a fit is made from it
            kept = state.casters_of = (fit, actors, seen_by_sun.casters_in(fit, context.snapshot))
        drawn = kept[2]
        state.world_to_light, state.light_to_clip = fit.world_to_light(), fit.light_to_clip()
        tangent = math.tan(math.radians(settings.light_size))
        state.params = (fit.depth, fit.texel, fit.half_width, tangent)
        key = (pose.key(), settings.resolution, settings.cull_front, fit.key())
        detail = (
            f"fitted {2 * fit.half_width:.4g} wide to {len(drawn)} of "
            f"{len(plan.casters)} casters ({fit.texel:.3g} per texel)"
        )
        reports = self._render(
            state, key, drawn, context, fit.depth, along_z=True, detail=detail, settings=settings
        )
        state.planned, state.planned_fit = plan, fit
        return reports

    def _render(
        self,
        state: MapState,
        key: tuple,
        casters: list,
        context: FrameContext,
        depth_range: float,
        *,
        along_z: bool,
        detail: str,
        settings: ShadowSettings,
    ) -> list[PassReport]:
        opaque, translucent = split_casters(casters, context.snapshot)
        companion = self._render_companion(
            state, key, translucent, context, depth_range, along_z=along_z, settings=settings
        )
        state.drawn = bool(opaque)
        if not opaque:
            state.key = None
            return [PassReport("map depth", "skipped", "every caster is translucent"), *companion]
        key = (*key, context.snapshot.keys_of(opaque))
        if key == state.key:
            return [*self._reused(state), *companion]
        assert self._pass is not None and state.light_to_clip is not None
        assert state.world_to_light is not None  # set with the fit, before any draw
        reports = []
        steps = self._drawn_steps(
            state.still, key, opaque, state.depth, state.world_to_light, context, settings
        )
        for step, drawn in steps:
            if step.under is not None:
                moving = len(step.casters)
                detail = f"{moving} moving caster{'s' * (moving != 1)} over the still ones' depth"
            reports += step.named(
                self._pass.render(
                    step.target,
                    drawn,
                    state.light_to_clip,
                    depth_range,
                    along_z=along_z,
                    timer=context.timer,
                    detail=detail,
                    under=step.under,
                )
            )
        state.key, state.frame = key, context.frame
        return reports + companion

    def _render_companion(
        self,
        state: MapState,
        key: tuple,
        translucent: list,
        context: FrameContext,
        depth_range: float,
        *,
        along_z: bool,
        settings: ShadowSettings,
    ) -> list[PassReport]:
        """Draw the light's translucent casters into its companion, or drop it when none."""
        if not translucent:
            state.drop_companion()
            return []
        assert state.light_to_clip is not None and state.world_to_light is not None
        light_to_clip, world_to_light = state.light_to_clip, state.world_to_light

        def draw(target: TransmittanceTexture) -> list[PassReport]:
            drawn = [
                TranslucentCaster(
                    context.buffers.get(caster),
                    world_to_light @ caster.model_matrix(),
                    caster.transmittance,
                )
                for caster in translucent
            ]
            return self._companions.drawer.render_map(
                target, drawn, light_to_clip, depth_range, along_z=along_z, timer=context.timer
            )

        state.companion, reports = self._companions.update(
            state.companion,
            resolution=settings.resolution,
            cube=False,
            key=(*key, translucent_key(translucent)),
            frame=context.frame,
            draw=draw,
        )
        return reports

    def release(self) -> None:
        """Release every map and companion, and the passes' programs."""
        super().release()
        self._companions.release()

    def shading(self, plan: Cast) -> LightShading:
        """Return how receivers read this light's map.

        Parameters
        ----------
        plan : Cast
            The light's cast.

        Returns
        -------
        LightShading
            The lookup call with the light's filter, and its samplers; a light
            whose map was skipped (nothing to shadow) shows no shadow, and
            one with translucent casters multiplies in what they let through.
        """
        state = self._states[plan.key]
        return self._lookup_shading(
            _kind(plan),
            plan,
            has_map=state.drawn,
            translucent=state.companion is not None,
        )

    def _reused(self, state: MapState) -> list[PassReport]:
        reused = f"light, casters and coverage unchanged since frame {state.frame}"
        return [PassReport("map depth", "reused", reused)]

    def _view_to_light(self, state: MapState, plan: Cast, context: FrameContext) -> np.ndarray:
        assert state.world_to_light is not None  # set with the fit, before any draw
        return state.world_to_light @ context.view.view_to_world

    def _holds_again(
        self, state: MapState, plan: Cast, context: FrameContext, same_view: bool
    ) -> bool:
        """Whether a light's map is not a sun's, or the camera stayed: a sun's follows the view."""
        return same_view or plan.pose.kind is not LightKind.DIRECTIONAL

    def activate(self, plan: Cast, context: FrameContext, entry: LightEntry) -> dict[str, object]:
        """Fill the light's block entry (its matrices and parameters); return its textures.

        Parameters
        ----------
        plan : Cast
            The light's cast.
        context : FrameContext
            This frame's camera.
        entry : LightEntry
            The light's entry of the frame's uniform block.

        Returns
        -------
        dict
            The map's and filter's textures, by uniform name.
        """
        state = self._states[plan.key]
        i = plan.vtk_index
        samplers = self._filters.activate(
            i, plan.settings, state.depth if state.drawn else None, entry
        )
        if state.companion is not None:
            samplers.update(self._filters.activate_transmittance(i, state.companion.texture))
        entry.view_to_light = self._view_to_light(state, plan, context)
        entry.params = state.params
        if _kind(plan) == "spot":
            # A point light's map covers only its casters' cone; it lights beyond it.
            entry.light_to_clip = state.light_to_clip
            entry.cone = state.cone_of(plan)
        return samplers
