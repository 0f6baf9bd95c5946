"""The depth-cube pass for point lights: one layered draw, or one draw per face."""

from __future__ import annotations

from collections.abc import Callable
from functools import cache

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major, cube_face_projections
from pvshadows.gl.caster_draws import CasterDraws, draw_casters
from pvshadows.gl.cube_array import CubeSlot
from pvshadows.gl.programs import ProgramCache, bind_program, compile_files
from pvshadows.gl.textures import DepthCube, copy_depth
from pvshadows.gl.timing import PassTimer
from pvshadows.model.report import PassReport
from pvshadows.passes.gl_state import DepthOnlyState, FaceCulling

#: Every face of a cube, as the bits of a caster's face mask.
_ALL_FACES = 0b111111


class CubeDepthPass:
    """Fills a :class:`~pvshadows.gl.textures.DepthCube` with distance-to-light over ``far``.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the pass.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._programs = ProgramCache(window)

    def _program(self, passes: str, rows: int) -> vtk.vtkShaderProgram:
        defines: dict[str, object] = {"BATCHED": rows} if rows else {}
        if passes == "single":
            stages = ("cube_depth.vert", "distance_depth.frag", "cube_depth.geom")
        else:
            stages = ("cube_depth.vert", "distance_depth.frag", "")
            defines["SIX_PASSES"] = True
        return self._programs.get(
            (passes, rows), lambda: compile_files(self._window, *stages, defines=defines)
        )

    def render(
        self,
        cube: DepthCube | CubeSlot,
        casters: CasterDraws,
        face_masks: np.ndarray,
        far: float,
        passes: str,
        timer: PassTimer,
        under: DepthCube | None = None,
    ) -> list[PassReport]:
        """Render the casters into the cube.

        Parameters
        ----------
        cube : DepthCube or CubeSlot
            The target: a cube of its own or one in a cube map array.
        casters : CasterDraws
            What to draw.
        face_masks : numpy.ndarray
            ``(n,)`` the faces each caster may touch
            (:func:`~pvshadows.geometry.transforms.boxes_from_origin`).
        far : float
            Distance that maps to depth 1.
        passes : {"single", "six"}
            One layered draw through the geometry shader, or one draw per
            face with the casters culled against that face's frustum.
        timer : PassTimer
            Records each pass's GPU time.
        under : DepthCube, optional
            A cube of the same size whose depth the casters are drawn over
            (copied in first); the cube starts cleared when not given.

        Returns
        -------
        list of PassReport
            One report per pass, run or skipped; GPU times arrive when the
            timer collects them after the frame.
        """
        if passes not in ("single", "six"):
            msg = f"the cube pass draws passes='single' or 'six', not {passes!r} (planned?)"
            raise ValueError(msg)
        face_mask = int(np.bitwise_or.reduce(face_masks, initial=0))
        #: The faces every caster touches: drawn with them all, no subset made.
        every_face = int(np.bitwise_and.reduce(face_masks, initial=_ALL_FACES)) & face_mask
        projections = column_major(cube_face_projections(far * 1e-4, far))
        records: list[PassReport] = []
        chunk = 0 if casters.batch is None else casters.batch.chunk

        def programs(face: int) -> Callable[[bool], vtk.vtkShaderProgram]:
            """Bind a program for one face (-1: every face in one draw), its uniforms set."""

            def program(batched: bool) -> vtk.vtkShaderProgram:
                chosen = self._program(passes, chunk if batched else 0)
                bind_program(self._window, chosen)
                chosen.SetUniformf("invFar", 1.0 / far)
                if face < 0:
                    chosen.SetUniformMatrix4x4v("faceProjection", 6, projections)
                    chosen.SetUniformi("faceMask", face_mask)
                    chosen.SetUniformi("layerBase", cube.layer_base)
                else:
                    chosen.SetUniformMatrix4x4v(
                        "faceProjection", 1, projections[16 * face : 16 * face + 16]
                    )
                return chosen

            return program

        if passes == "single":
            record = PassReport("cube depth (six faces, one draw)", "run", _faces_text(face_mask))
            records.append(record)
            with timer.measure(record), DepthOnlyState(self._window):
                _bind(cube, None, under, copy=True)
                draw_casters(programs(-1), casters, FaceCulling(self._window))
            return records
        with DepthOnlyState(self._window):
            cull = FaceCulling(self._window)
            for face in range(6):
                bit = 1 << face
                drawn = (
                    casters
                    if every_face & bit
                    else casters.subset(face_masks & bit != 0)
                    if face_mask & bit
                    else None
                )
                record = PassReport(f"cube face {_FACE_NAMES[face]}", "run")
                records.append(record)
                with timer.measure(record):
                    _bind(cube, face, under, copy=face == 0)
                    if drawn is None:
                        record.status = "skipped"
                        record.detail = "no caster in this face's frustum" + (
                            "" if under is None else ": it holds the still casters' depth"
                        )
                        continue
                    record.detail = f"{len(drawn)} of {len(casters)} casters"
                    draw_casters(programs(face), drawn, cull)
        return records

    def release(self) -> None:
        """Release the compiled programs."""
        self._programs.release()


def _bind(
    cube: DepthCube | CubeSlot, face: int | None, under: DepthCube | None, *, copy: bool
) -> None:
    """Bind a face (``None``: all six) to draw into: cleared, or holding ``under``'s depth.

    ``copy`` copies ``under``'s six faces in first (once per cube).
    """
    if under is None:
        cube.bind_cleared(face)
        return
    if copy:
        copy_depth(under, cube)
    cube.bind_as_target(face)


_FACE_NAMES = ("+X", "-X", "+Y", "-Y", "+Z", "-Z")


@cache
def _faces_text(face_mask: int) -> str:
    drawn = [name for face, name in enumerate(_FACE_NAMES) if face_mask & (1 << face)]
    skipped = [name for face, name in enumerate(_FACE_NAMES) if not face_mask & (1 << face)]
    text = "faces drawn: " + (" ".join(drawn) or "none")
    if skipped:
        text += "; skipped (no caster in frustum): " + " ".join(skipped)
    return text
