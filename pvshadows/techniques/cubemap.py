"""Point-light shadows from a depth cube map: distance to the light over ``far``, six faces."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import vtk

from pvshadows.gl.textures import DepthCube
from pvshadows.passes.cube_depth import CubeCaster, CubeDepthPass, caster_face_mask
from pvshadows.planner import LightPlan
from pvshadows.report import PassReport
from pvshadows.scene import vtk_id
from pvshadows.shading import LightShading
from pvshadows.techniques.base import FrameContext
from pvshadows.transforms import translation, view_to_light

#: Side of the tap grid for each ``pcf_taps`` value.
PCF_GRID = {4: 2, 16: 4}


@dataclass
class CubeState:
    """The depth cube kept for one light between frames."""

    cube: DepthCube
    key: tuple | None = None
    far: float = 1.0
    frame: int = -1


def _far(position: np.ndarray, casters: list) -> float:
    corners = []
    for caster in casters:
        lo, hi = caster.bounds
        corners.append(np.maximum(np.abs(lo - position), np.abs(hi - position)))
    far = float(np.linalg.norm(np.max(corners, axis=0)))
    return max(far * 1.01, np.finfo(np.float32).tiny * 1e6)


class CubemapTechnique:
    """Keeps a depth cube per point light and renders it only when it changed.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the cubes.
    """

    name = "cubemap"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._pass = CubeDepthPass(window)
        self._states: dict[str, CubeState] = {}

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
        state = self._states.get(vtk_id(plan.light))
        if state is None or state.cube.resolution != settings.resolution:
            if state is not None:
                state.cube.release()
            state = CubeState(DepthCube(self._window, settings.resolution))
            self._states[vtk_id(plan.light)] = state
        state.cube.set_linear(settings.filter == "pcf")
        position = plan.pose.position
        key = (
            plan.pose.key(),
            settings.resolution,
            settings.passes,
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
            shift = translation(caster.triangles.center)
            casters.append(
                CubeCaster(
                    context.buffers.get(caster),
                    translation(-position) @ caster.matrix @ shift,
                    caster_face_mask(caster.bounds - position),
                )
            )
        state.far = _far(position, plan.casters)
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
            The lookup call, its sampler and its GLSL source.
        """
        i = plan.vtk_index
        args = (
            f"pvsCube{i}, pvsViewToLight{i}, pvsCubeParams{i}, pvsCubeSlope{i}, "
            "vertexVC.xyz, pvsNormalVC"
        )
        if plan.settings.filter == "pcf":
            call = f"pvsPointShadowPcf({args}, {PCF_GRID[plan.settings.pcf_taps]})"
            define = "PVS_CUBE_PCF"
        else:
            call = f"pvsPointShadowHard({args})"
            define = "PVS_CUBE_HARD"
        return LightShading(
            i, call, {f"pvsCube{i}": "samplerCubeShadow"}, ("shadow_cube.glsl",), (define,)
        )

    def activate(self, plan: LightPlan, context: FrameContext) -> dict[str, object]:
        """Bind the light's cube to a texture unit and return the receivers' uniforms.

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
        state.cube.texture.Activate()
        settings = plan.settings
        i = plan.vtk_index
        return {
            f"pvsCube{i}": state.cube.texture.GetTextureUnit(),
            f"pvsViewToLight{i}": view_to_light(context.camera, plan.pose.position),
            f"pvsCubeParams{i}": (
                state.far,
                2.0 / settings.resolution,
                settings.normal_offset,
                settings.bias,
            ),
            f"pvsCubeSlope{i}": settings.slope_bias,
        }

    def deactivate(self) -> None:
        """Free the texture units bound by :meth:`activate`."""
        for state in self._states.values():
            state.cube.texture.Deactivate()

    def cube_of(self, light: vtk.vtkLight) -> DepthCube | None:
        """Return the cube kept for a light, if any (for tests and debugging)."""
        state = self._states.get(vtk_id(light))
        return state.cube if state else None

    def keep_only(self, plans: list[LightPlan]) -> None:
        """Release the cubes of lights that no longer use this technique.

        Parameters
        ----------
        plans : list of LightPlan
            This frame's plans.
        """
        alive = {vtk_id(p.light) for p in plans if p.technique == self.name}
        for key in set(self._states) - alive:
            self._states.pop(key).cube.release()

    def release(self) -> None:
        """Release every cube and program."""
        self.keep_only([])
        self._pass.release()
