"""Point-light shadows from a depth cube map: distance to the light over ``far``, six faces.

Where the context has cube map arrays, every light's cube is a slot of one
array per resolution (:mod:`pvshadows.gl.cube_array`), so that receivers read
all of them in one loop with one sampler; elsewhere each light has a cube of
its own, read with one sampler per light.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import cast

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import translation
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.cube_array import CubeArray, CubeSlot, cube_arrays_supported
from pvshadows.gl.textures import DepthCube
from pvshadows.model.plan import LightPlan
from pvshadows.model.report import PassReport
from pvshadows.passes.cube_depth import CubeCaster, CubeDepthPass, caster_face_mask
from pvshadows.scene.lights import LightKind
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext
from pvshadows.techniques.filtering import lookup_shading
from pvshadows.techniques.per_light import PerLightMaps, face_to_cull

#: Bytes up to which an array that must grow makes room at once for every point
#: light of the renderer without a cube yet (so a first frame allocates once);
#: beyond, and for spot lights given cubes, it doubles.
AT_ONCE = 1 << 30


@dataclass
class CubeState:
    """The depth cube kept for one light between frames."""

    cube: DepthCube | CubeSlot
    key: tuple | None = None
    far: float = 1.0
    nearest: float = 0.0
    frame: int = -1

    def release(self) -> None:
        """Release the cube."""
        self.cube.release()


def distance_range(position: np.ndarray, casters: list) -> tuple[float, float]:
    """Return the nearest and farthest distance from a light to its casters' bounds.

    Parameters
    ----------
    position : numpy.ndarray
        The light's position.
    casters : list of ActorState
        The casters.

    Returns
    -------
    tuple of float
        ``(nearest, far)``: the distance to the closest box (0 inside one) and
        a distance beyond every corner, the depth that maps to 1.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from pvshadows.techniques.cubemap import distance_range
    >>> box = SimpleNamespace(bounds=np.array([[1.0, -1, -1], [2, 1, 1]]))
    >>> near, far = distance_range(np.zeros(3), [box])
    >>> near, round(far, 3)
    (1.0, 2.474)
    """
    nearest, far = np.inf, 0.0
    if casters:
        boxes = np.array([caster.bounds for caster in casters]).reshape(-1, 2, 3)
        lo, hi = boxes[:, 0] - position, boxes[:, 1] - position
        outside = np.maximum(np.maximum(lo, -hi), 0.0)
        nearest = float(np.linalg.norm(outside, axis=1).min())
        far = float(np.linalg.norm(np.maximum(np.abs(lo), np.abs(hi)), axis=1).max())
    return nearest, cast(float, max(far * 1.01, np.finfo(np.float32).tiny * 1e6))


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
        #: Cube map arrays by resolution; ``None`` where the context has none.
        self.arrays: dict[int, CubeArray] | None = (
            {} if cube_arrays_supported(opengl_for(window)) else None
        )
        self._frame = -1
        self._activated: list[LightPlan] = []
        self._allocations = 0

    def _new_cube(self, resolution: int, context: FrameContext) -> DepthCube | CubeSlot:
        if self.arrays is None:
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

    def update(self, plan: LightPlan, context: FrameContext) -> list[PassReport]:
        """Bring the light's cube up to date for this frame.

        Parameters
        ----------
        plan : LightPlan
            The light's plan (technique ``"cubemap"``).
        context : FrameContext
            This frame's renderer, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The passes run, reused or skipped.
        """
        settings = plan.settings
        assert settings is not None and plan.pose is not None
        state = self._states.get(vtk_id(plan.light))
        if state is None or state.cube.resolution != settings.resolution:
            if state is not None:
                state.release()
            state = CubeState(self._new_cube(settings.resolution, context))
            self._states[vtk_id(plan.light)] = state
        position = plan.pose.position
        key = (
            plan.pose.key(),
            settings.resolution,
            settings.passes,
            settings.cull_front,
            tuple(c.key() for c in plan.casters),
        )
        if key == state.key:
            return [
                PassReport(
                    "cube depth",
                    "reused",
                    f"light and casters unchanged since frame {state.frame}: map still right",
                )
            ]
        casters = []
        for caster in plan.casters:
            casters.append(
                CubeCaster(
                    context.buffers.get(caster),
                    translation(-position) @ caster.model_matrix(),
                    caster_face_mask(caster.bounds - position),
                    face_to_cull(caster, settings),
                )
            )
        state.nearest, state.far = distance_range(position, plan.casters)
        assert self._pass is not None
        reports = self._pass.render(state.cube, casters, state.far, settings.passes, context.timer)
        state.key, state.frame = key, context.frame
        return reports

    def shading(self, plan: LightPlan) -> LightShading:
        """Return how receivers read this light's cube.

        Parameters
        ----------
        plan : LightPlan
            The light's plan.

        Returns
        -------
        LightShading
            The lookup call with the light's filter, and its samplers.
        """
        assert plan.settings is not None
        if self.arrays is None:
            return lookup_shading("cube", plan.vtk_index, plan.settings)
        texture = str(plan.settings.resolution)
        return lookup_shading("cubes", plan.vtk_index, plan.settings, texture=texture)

    def activate(self, plan: LightPlan, context: FrameContext) -> dict[str, object]:
        """Bind the light's cube and filter textures and return the receivers' uniforms.

        Parameters
        ----------
        plan : LightPlan
            The light's plan.
        context : FrameContext
            This frame's renderer and camera.

        Returns
        -------
        dict
            Uniform names and values for every receiver.
        """
        state = self._states[vtk_id(plan.light)]
        settings = plan.settings
        pose = plan.pose
        assert settings is not None and pose is not None
        i = plan.vtk_index
        spot = pose.kind is LightKind.SPOT
        cone = np.cos(np.radians(pose.cone_angle)) if spot else -2.0
        uniforms = self._array_units(plan, context)
        uniforms.update(self._filters.activate(i, settings, state.cube))
        if isinstance(state.cube, CubeSlot):
            uniforms[f"pvsLayer{i}"] = float(state.cube.slot)
        uniforms.update(
            {
                f"pvsViewToLight{i}": translation(-pose.position) @ context.view.view_to_world,
                f"pvsParams{i}": (
                    state.far,
                    2.0 / settings.resolution,
                    settings.light_size,
                    state.nearest,
                ),
                f"pvsCone{i}": (*pose.direction, cone),
            }
        )
        return uniforms

    def _array_units(self, plan: LightPlan, context: FrameContext) -> dict[str, object]:
        """Bind again the maps of this frame's earlier lights if their array grew since.

        An array grows while the lights are brought up one by one; the units of
        lights activated before then point at the array it grew out of, which
        lacks the cubes drawn after.
        """
        if context.frame != self._frame:
            self._frame, self._activated = context.frame, []
        allocations = sum(a.allocations for a in self.arrays.values()) if self.arrays else 0
        uniforms: dict[str, object] = {}
        if allocations != self._allocations:
            for earlier in self._activated:
                assert earlier.settings is not None
                cube = self._states[vtk_id(earlier.light)].cube
                uniforms.update(self._filters.activate(earlier.vtk_index, earlier.settings, cube))
        self._allocations = allocations
        self._activated.append(plan)
        return uniforms

    def deactivate(self) -> None:
        """Free the texture units bound by ``activate`` and the arrays grown out of."""
        super().deactivate()
        for array in (self.arrays or {}).values():
            array.end_frame()

    def release(self) -> None:
        """Release every cube, the arrays, the pass's programs and the filters' textures."""
        super().release()
        for array in (self.arrays or {}).values():
            array.release()
        if self.arrays is not None:
            self.arrays.clear()

    def cube_of(self, light: vtk.vtkLight) -> DepthCube | CubeSlot | None:
        """Return the cube kept for a light, if any (for tests and debugging)."""
        state = self._states.get(vtk_id(light))
        return state.cube if state else None
