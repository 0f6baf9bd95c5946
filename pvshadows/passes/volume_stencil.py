"""The shadow-volume passes: depth pre-pass, stencil counting, mask, and the debug overlay.

Each pass enters GL state through ``vtkOpenGLState`` (``Push``/``Pop``
restore the framebuffer bindings, viewport, program, stencil, depth, blend
and colour-mask state VTK tracks) and switches depth clamping, which VTK
does not track, back off before leaving.

Counting, per light: the mask is cleared to 1 (lit); then for every batch of
at most 255 bodies the stencil is cleared, the batch's volumes are drawn
with ``INCR_WRAP``/``DECR_WRAP`` (z-pass: on depth pass, front faces up and
back faces down; z-fail: on depth fail, back faces up and front faces down)
with depth clamping, so nothing is clipped at the far plane, and a
full-screen triangle writes 0 into the mask wherever the count is not zero.
The batches are thus AND-ed into the mask, and an 8-bit count only has to
hold one batch.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.buffers import EmptyArray, IndexedBuffers, TriangleBuffers
from pvshadows.gl.mask_target import MaskTexture, VolumeTarget
from pvshadows.gl.programs import ProgramCache, ShaderCompileError, bind_program, compile_files
from pvshadows.gl.timing import PassTimer
from pvshadows.model.report import PassReport

#: Clip-space depth offset (times w) of light caps: they lie on the lit
#: surface they came from and must lose the depth test against it. About
#: eight steps of a 24-bit depth buffer.
CAP_DEPTH_OFFSET = 1.0e-6

#: The stage files of each program: the depth pre-pass, volumes extruded on the
#: GPU (geometry shader) or built on the CPU, and the full-screen mask pass.
_STAGES: dict[str, tuple[str, str] | tuple[str, str, str]] = {
    "depth": ("volume_depth.vert", "volume_colour.frag"),
    "gpu": ("volume_extrude.vert", "volume_colour.frag", "volume_extrude.geom"),
    "cpu": ("volume_homogeneous.vert", "volume_colour.frag"),
    "fullscreen": ("volume_fullscreen.vert", "volume_colour.frag"),
}


@dataclass
class VolumeDraw:
    """One caster's volume (or part of it) as the stencil pass draws it.

    Attributes
    ----------
    buffers : IndexedBuffers
        Positions and indices on the GPU.
    extrude : {"gpu", "cpu"}
        ``"gpu"``: ``GL_TRIANGLES_ADJACENCY`` through the extruding geometry
        shader; ``"cpu"``: ready-made homogeneous triangles.
    model_to_clip : numpy.ndarray
        ``(4, 4)`` float64 from the buffers' frame to clip space.
    light_model : numpy.ndarray
        ``(4,)`` the light in the buffers' frame (used by ``"gpu"``).
    mirrored : bool
        The model matrix flips handedness: front and back swap on screen.
    pieces : list of tuple
        ``(first, count, part)`` index ranges to draw, ``part`` one of
        ``"all"`` (``"gpu"``: the shader emits what the counting needs),
        ``"sides"``, ``"light"`` (light cap) or ``"dark"`` (dark cap).
    extrude_to : float
        ``0``: extruded to infinity (``w = 0``); above 0, ``"gpu"`` only:
        extruded that far (model units) from the caster, for parallel
        projections (``"cpu"`` volumes are built finite instead).
    """

    buffers: IndexedBuffers
    extrude: str
    model_to_clip: np.ndarray
    light_model: np.ndarray
    mirrored: bool
    pieces: list[tuple[int, int, str]] = field(default_factory=list)
    extrude_to: float = 0.0


@dataclass
class DepthDraw:
    """One actor in the depth pre-pass: its triangles and its model-to-clip matrix."""

    buffers: TriangleBuffers
    model_to_clip: np.ndarray


class VolumePasses:
    """Runs the shadow-volume passes of one window.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs them.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._gl = opengl_for(window)
        self._programs = ProgramCache(window)
        self._empty: EmptyArray | None = None
        self._extrudes_on_gpu: bool | None = None

    # -- programs ---------------------------------------------------------------------------

    def _program(self, name: str) -> vtk.vtkShaderProgram:
        stages = _STAGES[name]
        return self._programs.get(name, lambda: compile_files(self._window, *stages))

    def can_extrude_on_gpu(self) -> bool:
        """Return whether the extruding geometry shader compiles in this context.

        Returns
        -------
        bool
            ``False`` when the driver refuses it (the technique then extrudes
            on the CPU). Tried once per window.
        """
        if self._extrudes_on_gpu is None:
            try:
                self._program("gpu")
            except ShaderCompileError:
                self._extrudes_on_gpu = False
            else:
                self._extrudes_on_gpu = True
        return self._extrudes_on_gpu

    def _bind(self, name: str) -> vtk.vtkShaderProgram:
        program = self._program(name)
        bind_program(self._window, program)
        return program

    def _empty_array(self) -> EmptyArray:
        if self._empty is None:
            self._empty = EmptyArray(self._window)
        return self._empty

    # -- state ------------------------------------------------------------------------------

    @contextmanager
    def _state(self) -> Iterator:
        gl = self._gl
        state = self._window.GetState()
        state.Push()
        try:
            state.vtkglDisable(gl.GL_BLEND)
            state.vtkglDisable(gl.GL_SCISSOR_TEST)
            state.vtkglDisable(gl.GL_CULL_FACE)
            state.vtkglDisable(gl.GL_STENCIL_TEST)
            yield gl, state
        finally:
            gl.glDisable(gl.GL_DEPTH_CLAMP)
            state.Pop()

    # -- passes -----------------------------------------------------------------------------

    def depth(self, target: VolumeTarget, draws: list[DepthDraw], timer: PassTimer) -> PassReport:
        """Fill the target's depth with every visible actor (and clear its stencil).

        Parameters
        ----------
        target : VolumeTarget
            The framebuffer.
        draws : list of DepthDraw
            The visible actors.
        timer : PassTimer
            Records the pass's GPU time.

        Returns
        -------
        PassReport
            The pass.
        """
        record = PassReport("volume depth pre-pass", "run", f"{len(draws)} actors")
        with timer.measure(record), self._state() as (gl, state):
            target.bind(None)
            state.vtkglEnable(gl.GL_DEPTH_TEST)
            state.vtkglDepthFunc(gl.GL_LESS)
            state.vtkglDepthMask(True)
            state.vtkglColorMask(False, False, False, False)
            state.vtkglClearDepth(1.0)
            state.vtkglStencilMask(0xFF)
            gl.glClearStencil(0)
            state.vtkglClear(gl.GL_DEPTH_BUFFER_BIT | gl.GL_STENCIL_BUFFER_BIT)
            program = self._bind("depth")
            matrices = _float32_matrices(draws)
            for number, draw in enumerate(draws):
                matrix = matrices[16 * number : 16 * number + 16]
                program.SetUniformMatrix4x4v("modelToClip", 1, matrix)
                draw.buffers.draw_triangles(program)
        return record

    def fill(self, target: VolumeTarget, mask: MaskTexture, value: float) -> None:
        """Set the whole mask to ``value`` (1 lit, 0 in shadow).

        Parameters
        ----------
        target : VolumeTarget
            The framebuffer.
        mask : MaskTexture
            The light's mask.
        value : float
            What to write.
        """
        with self._state() as (gl, state):
            target.bind(mask)
            state.vtkglColorMask(True, True, True, True)
            state.vtkglClearColor(value, value, value, 1.0)
            state.vtkglClear(gl.GL_COLOR_BUFFER_BIT)

    def count(
        self,
        target: VolumeTarget,
        mask: MaskTexture,
        batches: list[list[VolumeDraw]],
        zmode: str,
        passing: list[float] | None = None,
    ) -> None:
        """Count the volumes in the stencil, batch by batch, and leave the mask.

        Parameters
        ----------
        target : VolumeTarget
            The framebuffer, its depth filled by :meth:`depth`.
        mask : MaskTexture
            The light's mask, written: 1 lit, 0 in shadow.
        batches : list of list of VolumeDraw
            Volumes counted together (at most 255 bodies per batch).
        zmode : {"zpass", "zfail"}
            Counting in front of the surface or behind it.
        passing : list of float, optional
            Per batch, the share of light its shadow lets through (the mask is
            multiplied by it where the batch's count is not zero); all 0
            (opaque) by default.
        """
        passing = [0.0] * len(batches) if passing is None else passing
        with self._state() as (gl, state):
            target.bind(mask)
            state.vtkglColorMask(True, True, True, True)
            state.vtkglClearColor(1.0, 1.0, 1.0, 1.0)
            state.vtkglClear(gl.GL_COLOR_BUFFER_BIT)
            state.vtkglEnable(gl.GL_STENCIL_TEST)
            for batch, through in zip(batches, passing, strict=True):
                state.vtkglStencilMask(0xFF)
                gl.glClearStencil(0)
                state.vtkglClear(gl.GL_STENCIL_BUFFER_BIT)
                self._count_batch(gl, state, batch, zmode)
                # Mask: times what the batch lets through (0 when opaque) where it counted.
                gl.glDisable(gl.GL_DEPTH_CLAMP)
                state.vtkglDisable(gl.GL_DEPTH_TEST)
                state.vtkglColorMask(True, True, True, True)
                state.vtkglStencilFunc(gl.GL_NOTEQUAL, 0, 0xFF)
                state.vtkglStencilOp(gl.GL_KEEP, gl.GL_KEEP, gl.GL_KEEP)
                state.vtkglEnable(gl.GL_BLEND)
                state.vtkglBlendFunc(gl.GL_ZERO, gl.GL_SRC_COLOR)
                program = self._bind("fullscreen")
                program.SetUniform4f("colour", [float(through)] * 4)
                self._empty_array().draw_triangle()
                state.vtkglDisable(gl.GL_BLEND)

    def _count_batch(self, gl, state, batch: list[VolumeDraw], zmode: str) -> None:
        state.vtkglEnable(gl.GL_DEPTH_TEST)
        state.vtkglDepthFunc(gl.GL_LESS)
        state.vtkglDepthMask(False)
        state.vtkglColorMask(False, False, False, False)
        state.vtkglStencilFunc(gl.GL_ALWAYS, 0, 0xFF)
        gl.glEnable(gl.GL_DEPTH_CLAMP)
        if zmode == "zpass":
            up = (gl.GL_KEEP, gl.GL_KEEP, gl.GL_INCR_WRAP)
            down = (gl.GL_KEEP, gl.GL_KEEP, gl.GL_DECR_WRAP)
        else:
            up = (gl.GL_KEEP, gl.GL_INCR_WRAP, gl.GL_KEEP)
            down = (gl.GL_KEEP, gl.GL_DECR_WRAP, gl.GL_KEEP)
        front, back = (up, down) if zmode == "zpass" else (down, up)
        matrices = _float32_matrices(batch)
        lights = np.array([d.light_model for d in batch], np.float32).tolist()
        for mirrored in (False, True):
            numbers = [n for n, d in enumerate(batch) if d.mirrored == mirrored]
            if not numbers:
                continue
            first, second = (back, front) if mirrored else (front, back)
            state.vtkglStencilOpSeparate(gl.GL_FRONT, *first)
            state.vtkglStencilOpSeparate(gl.GL_BACK, *second)
            self._draw_volumes(
                [batch[n] for n in numbers], matrices, lights, numbers, zmode == "zfail"
            )

    def _draw_volumes(
        self,
        draws: list[VolumeDraw],
        matrices: np.ndarray,
        lights: list[list[float]],
        numbers: list[int],
        caps: bool,
        colour: list[float] | None = None,
    ) -> None:
        """Draw volumes, draw ``i`` with row ``numbers[i]`` of the float32 matrices and lights.

        Each program is bound, and what it reads the same for every volume
        (caps, ``colour``) set, once per run of volumes extruded alike.
        """
        gl = self._gl
        bound = ""
        program = None
        for draw, n in zip(draws, numbers, strict=True):
            if draw.extrude != bound or program is None:
                bound = draw.extrude
                program = self._bind(bound)
                if colour is not None:
                    program.SetUniform4f("colour", colour)
                if bound == "gpu":
                    program.SetUniformi("caps", int(caps))
                    program.SetUniformf("capDepthOffset", CAP_DEPTH_OFFSET)
            program.SetUniformMatrix4x4v("modelToClip", 1, matrices[16 * n : 16 * n + 16])
            if bound == "gpu":
                program.SetUniform4f("lightModel", lights[n])
                program.SetUniformf("extrudeTo", float(draw.extrude_to))
                for first, count, _ in draw.pieces:
                    draw.buffers.draw(program, gl.GL_TRIANGLES_ADJACENCY, first, count)
                continue
            for first, count, part in draw.pieces:
                if part != "sides" and not caps:
                    continue
                program.SetUniformf("capDepthOffset", CAP_DEPTH_OFFSET if part == "light" else 0.0)
                draw.buffers.draw(program, gl.GL_TRIANGLES, first, count)

    def overlay(
        self,
        draws: list[VolumeDraw],
        viewport: tuple[int, int, int, int],
        colour: tuple[float, float, float, float],
    ) -> None:
        """Draw the volumes' sides translucent into the bound framebuffer (VTK's frame).

        The caps are left out: the light cap lies on the caster's lit surface
        and the dark cap at infinity, so they show nothing of the volume.

        Parameters
        ----------
        draws : list of VolumeDraw
            The volumes.
        viewport : tuple of int
            The renderer's ``x, y, width, height`` in the window.
        colour : tuple of float
            RGBA; alpha sets the translucency.
        """
        with self._state() as (gl, state):
            state.vtkglViewport(*viewport)
            state.vtkglEnable(gl.GL_DEPTH_TEST)
            state.vtkglDepthFunc(gl.GL_LEQUAL)
            state.vtkglDepthMask(False)
            state.vtkglColorMask(True, True, True, True)
            state.vtkglEnable(gl.GL_BLEND)
            state.vtkglBlendFuncSeparate(
                gl.GL_SRC_ALPHA, gl.GL_ONE_MINUS_SRC_ALPHA, gl.GL_ZERO, gl.GL_ONE
            )
            gl.glEnable(gl.GL_DEPTH_CLAMP)
            matrices = _float32_matrices(draws)
            lights = np.array([d.light_model for d in draws], np.float32).tolist()
            numbers = list(range(len(draws)))
            self._draw_volumes(draws, matrices, lights, numbers, False, list(colour))

    def release(self) -> None:
        """Release the programs and the empty vertex array."""
        self._programs.release()
        if self._empty is not None:
            self._empty.release()
            self._empty = None


def _float32_matrices(draws: list) -> np.ndarray:
    """Return every draw's ``model_to_clip`` in OpenGL's column order, rounded to float32 at once.

    Draw ``n``'s matrix is ``[16 n, 16 n + 16)`` of the result.
    """
    return column_major(np.array([d.model_to_clip for d in draws]).reshape(-1, 4, 4))
