"""The transmittance pass of shadow maps: what a light's translucent casters let through.

It draws only the translucent casters, with the depth pass's projection
(a spot's or sun's 2D map, or a point light's cube, in one layered draw or
one draw per face), into the map's transmittance companion
(:mod:`pvshadows.gl.transmittance_textures`): per texel the product of every
translucent surface's ``1 - opacity`` and the nearest one's depth.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major, cube_face_projections
from pvshadows.gl.buffers import TriangleBuffers
from pvshadows.gl.programs import ProgramCache, bind_program, compile_files
from pvshadows.gl.timing import PassTimer
from pvshadows.gl.transmittance_textures import TransmittanceCube, TransmittanceTexture
from pvshadows.model.report import PassReport
from pvshadows.passes.gl_state import transmittance_state

#: Name of the pass in reports.
PASS_NAME = "transmittance"


@dataclass
class TranslucentCaster:
    """One translucent caster as the transmittance pass draws it.

    Attributes
    ----------
    buffers : TriangleBuffers
        Its triangles on the GPU, in shifted model coordinates.
    model_to_light : numpy.ndarray
        ``(4, 4)`` float64 from those coordinates to the light's space.
    transmittance : float
        Share of light each of its surfaces lets through, in (0, 1).
    face_mask : int, default: 0b111111
        For a cube: bit mask of the faces whose frustum may hold it.
    """

    buffers: TriangleBuffers
    model_to_light: np.ndarray
    transmittance: float
    face_mask: int = 0b111111


class TransmittancePass:
    """Fills transmittance companions, 2D or cube.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the pass.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._programs = ProgramCache(window)

    def _program(self, variant: str) -> vtk.vtkShaderProgram:
        vertex = "map_depth.vert" if variant in ("spot", "sun") else "cube_depth.vert"
        geometry = "cube_depth.geom" if variant == "single" else ""
        defines = {"DEPTH_ALONG_Z": variant == "sun", "SIX_PASSES": variant == "six"}
        chosen = {name: True for name, wanted in defines.items() if wanted}
        return self._programs.get(
            variant,
            lambda: compile_files(
                self._window, vertex, "transmittance.frag", geometry, defines=chosen
            ),
        )

    def _draw(self, program: vtk.vtkShaderProgram, casters: list[TranslucentCaster]) -> None:
        for caster in casters:
            program.SetUniformMatrix4x4v("modelToLight", 1, column_major(caster.model_to_light))
            program.SetUniformf("transmittance", float(caster.transmittance))
            caster.buffers.draw_triangles(program)

    def render_map(
        self,
        target: TransmittanceTexture,
        casters: list[TranslucentCaster],
        light_to_clip: np.ndarray,
        depth_range: float,
        *,
        along_z: bool,
        timer: PassTimer,
    ) -> list[PassReport]:
        """Render the translucent casters into a 2D companion.

        Parameters
        ----------
        target : TransmittanceTexture
            The companion of the light's depth map.
        casters : list of TranslucentCaster
            What to draw.
        light_to_clip : numpy.ndarray
            The map's projection.
        depth_range : float
            Distance (spot) or depth (directional) that maps to depth 1.
        along_z : bool
            Depth along light-space z (directional) instead of distance.
        timer : PassTimer
            Records the pass's GPU time.

        Returns
        -------
        list of PassReport
            The pass's report.
        """
        program = self._program("sun" if along_z else "spot")
        report = PassReport(PASS_NAME, "run", _detail(casters))
        with timer.measure(report), transmittance_state(self._window) as gl:
            target.bind_as_target()
            gl.glClear(gl.GL_COLOR_BUFFER_BIT)
            bind_program(self._window, program)
            program.SetUniformf("invFar", 1.0 / depth_range)
            program.SetUniformMatrix4x4v("lightToClip", 1, column_major(light_to_clip))
            self._draw(program, casters)
        return [report]

    def render_cube(
        self,
        target: TransmittanceCube,
        casters: list[TranslucentCaster],
        far: float,
        passes: str,
        timer: PassTimer,
    ) -> list[PassReport]:
        """Render the translucent casters into a cube companion, as the depth cube is drawn.

        Parameters
        ----------
        target : TransmittanceCube
            The companion of the light's depth cube.
        casters : list of TranslucentCaster
            What to draw, with the faces each may touch.
        far : float
            Distance that maps to depth 1.
        passes : {"single", "six"}
            One layered draw through the geometry shader, or one draw per
            face with only the casters that may touch it.
        timer : PassTimer
            Records the pass's GPU time.

        Returns
        -------
        list of PassReport
            The pass's report (one for all six faces).
        """
        projections = cube_face_projections(far * 1e-4, far)
        program = self._program(passes)
        report = PassReport(f"{PASS_NAME} (cube, {passes})", "run", _detail(casters))
        with timer.measure(report), transmittance_state(self._window) as gl:
            bind_program(self._window, program)
            program.SetUniformf("invFar", 1.0 / far)
            if passes == "single":
                target.bind_as_target()
                gl.glClear(gl.GL_COLOR_BUFFER_BIT)
                face_mask = 0
                for caster in casters:
                    face_mask |= caster.face_mask
                program.SetUniformMatrix4x4v("faceProjection", 6, column_major(projections))
                program.SetUniformi("faceMask", face_mask)
                self._draw(program, casters)
                return [report]
            for face in range(6):
                target.bind_as_target(face)
                gl.glClear(gl.GL_COLOR_BUFFER_BIT)
                program.SetUniformMatrix4x4v("faceProjection", 1, column_major(projections[face]))
                self._draw(program, [c for c in casters if c.face_mask & (1 << face)])
        return [report]

    def release(self) -> None:
        """Release the compiled programs."""
        self._programs.release()


def _detail(casters: list[TranslucentCaster]) -> str:
    return f"{len(casters)} translucent caster{'s' * (len(casters) != 1)}"
