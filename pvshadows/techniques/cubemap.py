"""Point-light shadows from a depth cube map: distance to the light over ``far``, six faces.

Where the context has cube map arrays, every light's cube is a slot of one
array per resolution (:mod:`pvshadows.gl.cube_array`), so that receivers read
all of them in one loop with one sampler; elsewhere each light has a cube of
its own, read with one sampler per light.

The cube holds the opaque casters; translucent ones go to its transmittance
companion (:mod:`pvshadows.techniques.translucent`), made only for a light that
has some, and drawn by the same route (one layered draw, or one per face). A
light with translucent casters keeps a cube of its own, read beside its
companion, outside the arrays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import (
    box_from_origin,
    boxes_from_origin,
    faces_touching_boxes,
    translation,
)
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.cube_array import CubeArray, CubeSlot, cube_arrays_supported
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.textures import DepthCube
from pvshadows.gl.transmittance_textures import TransmittanceCube, TransmittanceTexture
from pvshadows.model.plan import Cast
from pvshadows.model.report import PassReport
from pvshadows.passes.cube_depth import CubeDepthPass
from pvshadows.passes.transmittance import TranslucentCaster
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.lights import LightKind, LightPose
from pvshadows.scene.measures import CasterMeasureCache
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.spot_fitting import ConeMeasures
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext
from pvshadows.techniques.per_light import LightState, PerLightMaps
from pvshadows.techniques.still_casters import StillCasters
from pvshadows.techniques.translucent import (
    Companion,
    Companions,
    split_casters,
    translucent_key,
)

#: Bytes up to which an array that must grow makes room at once for every point
#: light of the renderer without a cube yet (so a first frame allocates once);
#: beyond, and for spot lights given cubes, it doubles.
AT_ONCE = 1 << 30
#: The least far distance of a cube: depths divided by it stay finite in float32.
SMALLEST_FAR = float(np.finfo(np.float32).tiny) * 1e6


class KeptDistances:
    """A light's nearest and farthest caster distances (:func:`distance_range`), kept.

    The same measures of the same casters on the same snapshot give the
    same distances: a light moving within its measures' margin
    (:class:`~pvshadows.scene.measures.CasterMeasureCache`) keeps them. The
    measures and the snapshot are compared by identity, the casters by
    their keys.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.geometry.transforms import boxes_from_origin
    >>> from pvshadows.scene.reader import SceneReader
    >>> from pvshadows.techniques.cubemap import CubeMeasures, KeptDistances
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Cube(center=(3, 0, 0)))
    >>> snapshot = SceneReader(lambda actor: "a cube").read(pl.renderer)
    >>> measures = CubeMeasures(*boxes_from_origin(snapshot.caster_bounds))
    >>> kept, keys = KeptDistances(), snapshot.keys_of(snapshot.casters)
    >>> first = kept.of(measures, snapshot, snapshot.casters, keys)
    >>> round(first[0], 3), round(first[1], 3)  # 2.5 and 1.01 * sqrt(3.5² + 0.5² + 0.5²)
    (2.5, 3.606)
    >>> kept.of(measures, snapshot, snapshot.casters, keys) is first, kept.taken
    (True, 1)
    """

    def __init__(self) -> None:
        self._source: tuple | None = None
        #: The distances last worked out: ``(nearest, far)``.
        self.range: tuple[float, float] = (math.inf, SMALLEST_FAR)
        #: Times they were worked out.
        self.taken = 0

    def of(
        self,
        measures: CubeMeasures | ConeMeasures,
        snapshot: Snapshot,
        casters: list[ActorState],
        keys: tuple,
    ) -> tuple[float, float]:
        """Return the casters' nearest and farthest distances from the light.

        Parameters
        ----------
        measures : CubeMeasures or ConeMeasures
            The snapshot's casters measured from the light.
        snapshot : Snapshot
            This frame's actors.
        casters : list of ActorState
            The light's casters, of ``snapshot``.
        keys : tuple
            Their keys (:meth:`~pvshadows.scene.snapshot.Snapshot.keys_of`).

        Returns
        -------
        tuple of float
            ``(nearest, far)`` of :func:`distance_range`.
        """
        source = self._source
        if (
            source is None
            or source[0] is not measures
            or source[1] is not snapshot
            or source[2] != keys
        ):
            self.range = distance_range(
                snapshot.for_casters(measures.near, casters),
                snapshot.for_casters(measures.far, casters),
            )
            self._source = (measures, snapshot, keys)
            self.taken += 1
        return self.range


@dataclass
class CubeState(LightState):
    """The depth cube kept for one light between frames."""

    cube: DepthCube | CubeSlot
    key: tuple | None = None
    far: float = 1.0
    nearest: float = 0.0
    frame: int = -1
    drawn: bool = False
    companion: Companion | None = None
    #: The plan the cube was last brought up to date for: a plan kept by the planner
    #: (nothing but the camera moved) finds the cube still right.
    planned: Cast | None = None
    measures: CasterMeasureCache[CubeMeasures] = field(
        default_factory=lambda: CasterMeasureCache(cube_measures)
    )
    still: StillCasters[DepthCube] | None = None
    #: The cube arrays' allocations when its textures were last bound
    #: (:meth:`CubemapTechnique.activate`); -1 before.
    bound_after: int = -1
    #: Its casters' nearest and farthest distances, kept while their measures hold.
    distances: KeptDistances = field(default_factory=KeptDistances)

    def release_map(self) -> None:
        """Release the cube."""
        self.cube.release()


def distance_range(near: np.ndarray, far: np.ndarray) -> tuple[float, float]:
    """Return the nearest and farthest distance from a light to its casters' bounds.

    Parameters
    ----------
    near, far : numpy.ndarray
        ``(n,)`` squared distances from the light to each caster's bounds and
        to their farthest corner
        (:func:`pvshadows.geometry.transforms.boxes_from_origin`,
        :func:`pvshadows.scene.spot_fitting.box_distances_squared`).

    Returns
    -------
    tuple of float
        ``(nearest, far)``: the distance to the closest box (0 inside one) and
        a distance beyond every corner, the depth that maps to 1.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.geometry.transforms import boxes_from_origin
    >>> from pvshadows.techniques.cubemap import distance_range
    >>> near, far, _ = boxes_from_origin(np.array([[[1.0, -1, -1], [2, 1, 1]]]))
    >>> near, far = distance_range(near, far)
    >>> near, round(far, 3)
    (1.0, 2.474)
    """
    if not len(near):
        return math.inf, SMALLEST_FAR
    # squared lengths compared, one square root each: the same order, fewer calls
    nearest, farthest = math.sqrt(float(near.min())), math.sqrt(float(far.max()))
    return nearest, max(farthest * 1.01, SMALLEST_FAR)


class CubeMeasures(NamedTuple):
    """What a point light's cube is drawn with, for each caster of a snapshot.

    Attributes
    ----------
    near, far : numpy.ndarray
        ``(n,)`` squared distances from the light to each caster's bounds
        and to their farthest corner.
    faces : numpy.ndarray
        ``(n,)`` bit masks of the cube faces each caster may touch
        (:func:`pvshadows.geometry.transforms.boxes_from_origin`).
    """

    near: np.ndarray
    far: np.ndarray
    faces: np.ndarray


def cube_measures(pose: LightPose, boxes: np.ndarray) -> CubeMeasures:
    """Measure casters' bounds from a point light, for its cube's range and faces.

    Parameters
    ----------
    pose : LightPose
        The light.
    boxes : numpy.ndarray
        ``(n, 2, 3)`` world bounds.

    Returns
    -------
    CubeMeasures
        One row per box.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.techniques.cubemap import cube_measures
    >>> pose = LightPose(LightKind.POINT, np.zeros(3), np.array([0, 0, -1.0]), 180.0)
    >>> cube_measures(pose, np.array([[[2.0, -0.5, -0.5], [3, 0.5, 0.5]]])).faces.tolist()
    [1]
    """
    if len(boxes) == 1:  # one moved caster: numpy's cost per call outweighs its speed
        low, high = (boxes[0] - pose.position).tolist()
        return CubeMeasures(*(np.array([value]) for value in box_from_origin(low, high)))
    return CubeMeasures(*boxes_from_origin(boxes - pose.position))


class CubemapTechnique(PerLightMaps[CubeState, CubeDepthPass]):
    """Keeps a depth cube per point light and renders it only when it changed.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the cubes.
    """

    name = "cubemap"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        super().__init__(window)
        self._pass = CubeDepthPass(window)
        self._companions = Companions(window)
        #: Cube map arrays by resolution; ``None`` where the context has none.
        self.arrays: dict[int, CubeArray] | None = (
            {} if cube_arrays_supported(opengl_for(window)) else None
        )
        self._frame = -1
        self._activated: list[Cast] = []
        self._allocations = 0

    def _new_cube(self, resolution: int, context: FrameContext, own: bool) -> DepthCube | CubeSlot:
        if own or self.arrays is None:
            return DepthCube(self._window, resolution)
        if resolution not in self.arrays:
            self.arrays[resolution] = CubeArray(self._window, resolution)
        array = self.arrays[resolution]
        held = sum(len(each.taken) for each in self.arrays.values())
        bulbs = sum(
            1
            for light in context.renderer.GetLights()
            if light.GetSwitch()
            and light.GetIntensity() > 0
            and light.GetPositional()
            and light.GetConeAngle() >= 90
        )
        wanted = len(array.taken) + max(bulbs - held, 1)
        most = max(len(array.taken) + 1, AT_ONCE // (6 * 4 * resolution**2))
        return CubeSlot(array, min(wanted, most))

    def update(self, plan: Cast, context: FrameContext) -> list[PassReport]:
        """Bring the light's cube up to date for this frame.

        Parameters
        ----------
        plan : Cast
            The light's cast (technique ``"cubemap"``).
        context : FrameContext
            This frame's renderer, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The passes run, reused or skipped.
        """
        settings = plan.settings
        state = self._states.get(plan.key)
        opaque, translucent = split_casters(plan.casters, context.snapshot)
        own = bool(translucent) or self.arrays is None
        if (
            state is None
            or state.cube.resolution != settings.resolution
            or isinstance(state.cube, DepthCube) != own
        ):
            if state is not None:
                state.release()
            resolution = settings.resolution
            state = CubeState(self._new_cube(resolution, context, own))
            state.still = self._still_casters(lambda: DepthCube(self._window, resolution))
            self._states[plan.key] = state
        if self._still_right(state, plan):
            return self._reused(state)
        state.planned = None
        position, snapshot = plan.pose.position, context.snapshot
        measures = state.measures.of(plan.pose, snapshot).values
        keys = snapshot.keys_of(plan.casters)
        state.nearest, state.far = state.distances.of(measures, snapshot, plan.casters, keys)
        companion = self._update_companion(plan, context, state, translucent)
        state.drawn = bool(opaque)
        if not opaque:
            state.key = None
            return [PassReport("cube depth", "skipped", "every caster is translucent"), *companion]
        key = (
            plan.pose.key(),
            settings.resolution,
            settings.passes,
            settings.cull_front,
            state.far,
            keys if opaque is plan.casters else snapshot.keys_of(opaque),
        )
        if key == state.key:
            state.planned = plan
            return [*self._reused(state), *companion]
        assert self._pass is not None
        reports = []
        steps = self._drawn_steps(
            state.still, key, opaque, state.cube, translation(-position), context, settings
        )
        for step, drawn in steps:
            masks = snapshot.for_casters(measures.faces, step.casters)
            reports += step.named(
                self._pass.render(
                    step.target,
                    drawn,
                    masks,
                    state.far,
                    settings.passes,
                    context.timer,
                    under=step.under,
                )
            )
        state.key, state.frame, state.planned = key, context.frame, plan
        return reports + companion

    def _update_companion(
        self, plan: Cast, context: FrameContext, state: CubeState, translucent: list
    ) -> list[PassReport]:
        """Draw the light's translucent casters into its companion, or drop it when none."""
        settings, pose = plan.settings, plan.pose
        if not translucent:
            state.drop_companion()
            return []
        position, far = pose.position, state.far

        def draw(target: TransmittanceTexture) -> list[PassReport]:
            assert isinstance(target, TransmittanceCube)
            masks = faces_touching_boxes(context.snapshot.bounds_of(translucent) - position)
            drawn = [
                TranslucentCaster(
                    context.buffers.get(caster),
                    translation(-position) @ caster.model_matrix(),
                    caster.transmittance,
                    int(mask),
                )
                for caster, mask in zip(translucent, masks, strict=True)
            ]
            return self._companions.drawer.render_cube(
                target, drawn, far, settings.passes, context.timer
            )

        key = (pose.key(), settings.resolution, settings.passes, far)
        state.companion, reports = self._companions.update(
            state.companion,
            resolution=settings.resolution,
            cube=True,
            key=(*key, translucent_key(translucent)),
            frame=context.frame,
            draw=draw,
        )
        return reports

    def release(self) -> None:
        """Release every cube, companion and array, and the passes' programs."""
        super().release()
        self._companions.release()
        for array in (self.arrays or {}).values():
            array.release()
        if self.arrays is not None:
            self.arrays.clear()

    def shading(self, plan: Cast) -> LightShading:
        """Return how receivers read this light's cube.

        Parameters
        ----------
        plan : Cast
            The light's cast.

        Returns
        -------
        LightShading
            The lookup call with the light's filter, and its samplers; one
            with translucent casters multiplies in what they let through.
        """
        state = self._states[plan.key]
        if isinstance(state.cube, CubeSlot):
            texture = str(plan.settings.resolution)
            return self._lookup_shading("cubes", plan, has_map=state.drawn, texture=texture)
        return self._lookup_shading(
            "cube",
            plan,
            has_map=state.drawn,
            translucent=state.companion is not None,
        )

    def _reused(self, state: CubeState) -> list[PassReport]:
        reused = f"light and casters unchanged since frame {state.frame}: map still right"
        return [PassReport("cube depth", "reused", reused)]

    def _view_to_light(self, state: CubeState, plan: Cast, context: FrameContext) -> np.ndarray:
        return context.view.to_frame_at(plan.pose.position)

    def _holds_again(
        self, state: CubeState, plan: Cast, context: FrameContext, same_view: bool
    ) -> bool:
        """Whether no cube array grew since the light's textures were bound (it is noted bound)."""
        if state.bound_after != self._allocations_now():
            return False
        self._array_bindings(plan, context)  # no array grew: it rebinds nothing
        return True

    def activate(self, plan: Cast, context: FrameContext, entry: LightEntry) -> dict[str, object]:
        """Fill the light's block entry (its matrix and parameters); return its textures.

        Parameters
        ----------
        plan : Cast
            The light's cast.
        context : FrameContext
            This frame's renderer and camera.
        entry : LightEntry
            The light's entry of the frame's uniform block.

        Returns
        -------
        dict
            The cube's and filter's textures by uniform name, and those of
            this frame's earlier lights whose cube array grew.
        """
        state = self._states[plan.key]
        settings = plan.settings
        pose = plan.pose
        i = plan.vtk_index
        spot = pose.kind is LightKind.SPOT
        cone = math.cos(math.radians(pose.cone_angle)) if spot else -2.0
        uniforms = self._array_bindings(plan, context)
        state.bound_after = self._allocations
        drawn = state.cube if state.drawn else None
        uniforms.update(self._filters.activate(i, settings, drawn, entry))
        if state.companion is not None:
            uniforms.update(self._filters.activate_transmittance(i, state.companion.texture))
        if isinstance(state.cube, CubeSlot):
            entry.layer = float(state.cube.slot)
        entry.view_to_light = self._view_to_light(state, plan, context)
        entry.params = (state.far, 2.0 / settings.resolution, settings.light_size, state.nearest)
        entry.cone = (*pose.direction.tolist(), cone)
        return uniforms

    def _array_bindings(self, plan: Cast, context: FrameContext) -> dict[str, object]:
        """Name again the maps of this frame's earlier lights if their array grew since.

        An array grows while the lights are brought up one by one; the
        bindings of lights activated before then name the array it grew out
        of, which lacks the cubes drawn after.
        """
        if context.frame != self._frame:
            self._frame, self._activated = context.frame, []
        allocations = self._allocations_now()
        uniforms: dict[str, object] = {}
        if allocations != self._allocations:
            for earlier in self._activated:
                state = self._states[earlier.key]
                if isinstance(state.cube, CubeSlot) and state.drawn:
                    uniforms.update(
                        self._filters.samplers(earlier.vtk_index, earlier.settings, state.cube)
                    )
        self._allocations = allocations
        self._activated.append(plan)
        return uniforms

    def _allocations_now(self) -> int:
        """Return how many times the cube arrays were allocated, growing included."""
        return sum(a.allocations for a in self.arrays.values()) if self.arrays else 0

    def end_frame(self) -> None:
        """Delete the arrays grown out of this frame."""
        for array in (self.arrays or {}).values():
            array.end_frame()

    def cube_of(self, light: vtk.vtkLight) -> DepthCube | CubeSlot | None:
        """Return the cube kept for a light, if any (for tests and debugging)."""
        state = self._states.get(vtk_id(light))
        return state.cube if state else None
