"""The depth-cube pass for point lights: one layered draw, or one draw per face."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major, cube_face_projections, faces_touching_box
from pvshadows.gl.buffers import TriangleBuffers, draw_casters
from pvshadows.gl.cube_array import CubeSlot
from pvshadows.gl.programs import ProgramCache, bind_program, compile_files
from pvshadows.gl.textures import DepthCube
from pvshadows.gl.timing import PassTimer
from pvshadows.model.report import PassReport
from pvshadows.passes.gl_state import FaceCulling, depth_only_state


@dataclass
class CubeCaster:
    """One caster as the cube pass draws it.

    Attributes
    ----------
    buffers : TriangleBuffers
        Its triangles on the GPU, in shifted model coordinates.
    model_to_light : numpy.ndarray
        ``(4, 4)`` float64 from those coordinates to world axes centred on
        the light.
    face_mask : int
        Bit mask of the faces whose frustum may hold it.
    cull : {"front", "back"} or None
        The side of its triangles not to draw.
    """

    buffers: TriangleBuffers
    model_to_light: np.ndarray
    face_mask: int
    cull: str | None = None


def caster_face_mask(box_from_light: np.ndarray) -> int:
    """Return which cube faces a caster's light-relative bounds may touch.

    Parameters
    ----------
    box_from_light : numpy.ndarray
        ``(2, 3)`` bounds relative to the light.

    Returns
    -------
    int
        Face bit mask (all six when the light is inside the box).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.passes.cube_depth import caster_face_mask
    >>> caster_face_mask(np.array([[-1.0, -1, -1], [1, 1, 1]]))
    63
    """
    if np.all(box_from_light[0] <= 0.0) and np.all(box_from_light[1] >= 0.0):
        return 0b111111
    return faces_touching_box(box_from_light)


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

    def _program(self, passes: str) -> vtk.vtkShaderProgram:
        if passes == "single":
            stages = ("cube_depth.vert", "distance_depth.frag", "cube_depth.geom")
            return self._programs.get(passes, lambda: compile_files(self._window, *stages))
        return self._programs.get(
            passes,
            lambda: compile_files(
                self._window, "cube_depth.vert", "distance_depth.frag", defines={"SIX_PASSES": True}
            ),
        )

    def render(
        self,
        cube: DepthCube | CubeSlot,
        casters: list[CubeCaster],
        far: float,
        passes: str,
        timer: PassTimer,
    ) -> list[PassReport]:
        """Render the casters into the cube.

        Parameters
        ----------
        cube : DepthCube or CubeSlot
            The target: a cube of its own or one in a cube map array.
        casters : list of CubeCaster
            What to draw, with the faces each may touch.
        far : float
            Distance that maps to depth 1.
        passes : {"single", "six"}
            One layered draw through the geometry shader, or one draw per
            face with the casters culled against that face's frustum.
        timer : PassTimer
            Records each pass's GPU time.

        Returns
        -------
        list of PassReport
            One report per pass, run or skipped; GPU times arrive when the
            timer collects them after the frame.
        """
        if passes not in ("single", "six"):
            msg = f"the cube pass draws passes='single' or 'six', not {passes!r} (planned?)"
            raise ValueError(msg)
        face_mask = 0
        for caster in casters:
            face_mask |= caster.face_mask
        projections = cube_face_projections(far * 1e-4, far)
        program = self._program(passes)
        records: list[PassReport] = []
        with depth_only_state(self._window):
            bind_program(self._window, program)
            program.SetUniformf("invFar", 1.0 / far)
            cull = FaceCulling(self._window)
            if passes == "single":
                record = PassReport(
                    "cube depth (six faces, one draw)", "run", _faces_text(face_mask)
                )
                records.append(record)
                with timer.measure(record):
                    cube.bind_cleared()
                    program.SetUniformMatrix4x4v("faceProjection", 6, column_major(projections))
                    program.SetUniformi("faceMask", face_mask)
                    program.SetUniformi("layerBase", cube.layer_base)
                    draw_casters(program, casters, cull)
            else:
                for face in range(6):
                    drawn = [c for c in casters if c.face_mask & (1 << face)]
                    record = PassReport(f"cube face {_FACE_NAMES[face]}", "run")
                    records.append(record)
                    with timer.measure(record):
                        cube.bind_cleared(face)
                        if not drawn:
                            record.status, record.detail = (
                                "skipped",
                                "no caster in this face's frustum",
                            )
                            continue
                        record.detail = f"{len(drawn)} of {len(casters)} casters"
                        program.SetUniformMatrix4x4v(
                            "faceProjection", 1, column_major(projections[face])
                        )
                        draw_casters(program, drawn, cull)
        return records

    def release(self) -> None:
        """Release the compiled programs."""
        self._programs.release()


_FACE_NAMES = ("+X", "-X", "+Y", "-Y", "+Z", "-Z")


def _faces_text(face_mask: int) -> str:
    drawn = [name for face, name in enumerate(_FACE_NAMES) if face_mask & (1 << face)]
    skipped = [name for face, name in enumerate(_FACE_NAMES) if not face_mask & (1 << face)]
    text = "faces drawn: " + (" ".join(drawn) or "none")
    if skipped:
        text += "; skipped (no caster in frustum): " + " ".join(skipped)
    return text
