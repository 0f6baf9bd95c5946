"""The depth pass of 2D shadow maps (spot and directional lights)."""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major
from pvshadows.gl.caster_draws import CasterDraws, draw_casters
from pvshadows.gl.programs import ProgramCache, bind_program, compile_files
from pvshadows.gl.textures import DepthMap, copy_depth
from pvshadows.gl.timing import PassTimer
from pvshadows.model.report import PassReport
from pvshadows.passes.gl_state import DepthOnlyState, FaceCulling


class MapDepthPass:
    """Fills a :class:`~pvshadows.gl.textures.DepthMap` with linear depth.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the pass.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._programs = ProgramCache(window)

    def _program(self, along_z: bool, rows: int) -> vtk.vtkShaderProgram:
        defines: dict[str, object] = {"DEPTH_ALONG_Z": True} if along_z else {}
        if rows:
            defines["BATCHED"] = rows
        return self._programs.get(
            (along_z, rows),
            lambda: compile_files(
                self._window, "map_depth.vert", "distance_depth.frag", defines=defines
            ),
        )

    def render(
        self,
        depth: DepthMap,
        casters: CasterDraws,
        light_to_clip: np.ndarray,
        depth_range: float,
        *,
        along_z: bool,
        timer: PassTimer,
        detail: str,
        under: DepthMap | None = None,
    ) -> list[PassReport]:
        """Render the casters into the map.

        Parameters
        ----------
        depth : DepthMap
            The target.
        casters : CasterDraws
            What to draw.
        light_to_clip : numpy.ndarray
            The map's projection.
        depth_range : float
            Distance (spot) or depth (directional) that maps to depth 1.
        along_z : bool
            Store depth along light-space z (directional) instead of distance.
        timer : PassTimer
            Records the pass's GPU time.
        detail : str
            What the report says about the pass.
        under : DepthMap, optional
            A map of the same size whose depth the casters are drawn over
            (copied in first); the map starts cleared when not given.

        Returns
        -------
        list of PassReport
            The pass's report.
        """
        to_clip = column_major(light_to_clip)

        def program(batched: bool) -> vtk.vtkShaderProgram:
            rows = casters.batch.chunk if batched and casters.batch is not None else 0
            chosen = self._program(along_z, rows)
            bind_program(self._window, chosen)
            chosen.SetUniformf("invFar", 1.0 / depth_range)
            chosen.SetUniformMatrix4x4v("lightToClip", 1, to_clip)
            return chosen

        report = PassReport("map depth", "run", detail)
        with timer.measure(report), DepthOnlyState(self._window):
            if under is None:
                depth.bind_cleared()
            else:
                copy_depth(under, depth)
                depth.bind_as_target()
            draw_casters(program, casters, FaceCulling(self._window))
        return [report]

    def release(self) -> None:
        """Release the compiled programs."""
        self._programs.release()
