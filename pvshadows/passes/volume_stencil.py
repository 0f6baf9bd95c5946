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
from pvshadows.gl.buffers import EmptyArray, IndexedBuffers
from pvshadows.gl.caster_draws import CasterDraws, draw_casters
from pvshadows.gl.mask_target import MaskTexture, VolumeTarget
from pvshadows.gl.programs import ProgramCache, ShaderCompileError, bind_program, compile_files
from pvshadows.gl.raw_calls import raw_calls
from pvshadows.gl.timing import PassTimer
from pvshadows.gl.volume_batch import VolumeBatch, VolumeRun
from pvshadows.model.report import PassReport
from pvshadows.passes.gl_state import FaceCulling

#: Clip-space depth offset (times w) of light caps: they lie on the lit
#: surface they came from and must lose the depth test against it. About
#: eight steps of a 24-bit depth buffer.
CAP_DEPTH_OFFSET = 1.0e-6

#: The uniforms the extruding program reads per volume besides its matrix.
_GPU_UNIFORMS = ("lightModel", "extrudeTo")
#: The uniform arrays (and row base) the extruding program built ``BATCHED`` reads.
_BATCH_UNIFORMS = ("modelToClips", "lightModels", "extrudeTos", "rowBase")
#: ``GL_UNSIGNED_INT``, ``GL_TRIANGLES`` and ``GL_TRIANGLES_ADJACENCY``.
_UNSIGNED_INT, _TRIANGLES, _TRIANGLES_ADJACENCY = 0x1405, 0x0004, 0x000C

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

    What the camera and the light change, its matrix and the light in its
    frame, it reads from row :attr:`row` of the :class:`VolumeRows` the
    pass is given: a draw holds while only they change.

    Attributes
    ----------
    buffers : IndexedBuffers
        Positions and indices on the GPU.
    extrude : {"gpu", "cpu"}
        ``"gpu"``: ``GL_TRIANGLES_ADJACENCY`` through the extruding geometry
        shader; ``"cpu"``: ready-made homogeneous triangles.
    row : int
        Its caster's row of :class:`VolumeRows`.
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
    row: int
    mirrored: bool
    pieces: list[tuple[int, int, str]] = field(default_factory=list)
    extrude_to: float = 0.0


@dataclass(frozen=True)
class VolumeRows:
    """What the volumes of one count read per caster, stacked: one product each per frame.

    Attributes
    ----------
    to_clip : numpy.ndarray
        ``(n, 4, 4)`` float64, each caster's buffers' frame to clip space.
    lights : numpy.ndarray
        ``(n, 4)`` the light in each caster's buffers' frame (read by ``"gpu"``).
    """

    to_clip: np.ndarray
    lights: np.ndarray
    reaches: np.ndarray

    def float32(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return the matrices in OpenGL's column order, the lights and reaches, float32.

        Returns
        -------
        tuple of numpy.ndarray
            C-contiguous: flat, row ``n``'s matrix at ``[16 n, 16 n + 16)``;
            ``(n, 4)``; and ``(n,)``.
        """
        lights = np.ascontiguousarray(self.lights, dtype=np.float32).reshape(-1, 4)
        reaches = np.ascontiguousarray(self.reaches, dtype=np.float32).ravel()
        return column_major(self.to_clip.reshape(-1, 4, 4)), lights, reaches


@dataclass(frozen=True)
class StencilSide:
    """The volumes of one count batch drawn with one winding on screen.

    Attributes
    ----------
    mirrored : bool
        Their model matrices flip handedness: front and back swap.
    alone : list of VolumeDraw
        Those drawn one by one.
    runs : list of VolumeRun
        Those drawn through the light's :class:`~pvshadows.gl.volume_batch.VolumeBatch`.
    """

    mirrored: bool
    alone: list[VolumeDraw]
    runs: list[VolumeRun]


def stencil_sides(draws: list[VolumeDraw], batch: VolumeBatch | None) -> list[StencilSide]:
    """Sort a count batch's draws by winding, and into the volume batch's runs or alone.

    Parameters
    ----------
    draws : list of VolumeDraw
        Volumes counted together.
    batch : VolumeBatch or None
        The light's batch of small volumes extruded on the GPU, if any.

    Returns
    -------
    list of StencilSide
        The unmirrored volumes first; a winding without volumes is left out.
    """
    sides = []
    for mirrored in (False, True):
        mine = [d for d in draws if d.mirrored == mirrored]
        if not mine:
            continue
        batched = [
            batch is not None and d.extrude == "gpu" and bool(batch.in_batch[d.row]) for d in mine
        ]
        alone = [d for d, b in zip(mine, batched, strict=True) if not b]
        runs: list[VolumeRun] = []
        if batch is not None and any(batched):
            drawn = [(d.row, (first, count)) for d, b in zip(mine, batched, strict=True) if b
                     for first, count, _ in d.pieces]  # fmt: skip
            runs = batch.runs([row for row, _ in drawn], [span for _, span in drawn])
        sides.append(StencilSide(mirrored, alone, runs))
    return sides


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

    def _program(self, name: str, rows: int = 0) -> vtk.vtkShaderProgram:
        """Return a program of :data:`_STAGES`, built ``BATCHED`` so many rows when ``rows``."""
        vertex, fragment, *geometry = _STAGES[name]
        defines = {"BATCHED": rows} if rows else None
        return self._programs.get(
            (name, rows),
            lambda: compile_files(self._window, vertex, fragment, "".join(geometry), defines),
        )

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

    def _bind(self, name: str, rows: int = 0) -> vtk.vtkShaderProgram:
        program = self._program(name, rows)
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

    def depth(self, target: VolumeTarget, draws: CasterDraws, timer: PassTimer) -> PassReport:
        """Fill the target's depth with every visible actor (and clear its stencil).

        Parameters
        ----------
        target : VolumeTarget
            The framebuffer.
        draws : CasterDraws
            The visible actors, their matrices taking them to the camera's
            clip space; the casters of the snapshot's batch are drawn through it.
        timer : PassTimer
            Records the pass's GPU time.

        Returns
        -------
        PassReport
            The pass.
        """

        def program(batched: bool) -> vtk.vtkShaderProgram:
            rows = draws.batch.chunk if batched and draws.batch is not None else 0
            return self._bind("depth", rows)

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
            draw_casters(program, draws, FaceCulling(self._window))
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
        batches: list[list[StencilSide]],
        rows: VolumeRows,
        zmode: str,
        passing: list[float] | None = None,
        batch: VolumeBatch | None = None,
    ) -> None:
        """Count the volumes in the stencil, batch by batch, and leave the mask.

        Parameters
        ----------
        target : VolumeTarget
            The framebuffer, its depth filled by :meth:`depth`.
        mask : MaskTexture
            The light's mask, written: 1 lit, 0 in shadow.
        batches : list of list of StencilSide
            Volumes counted together (at most 255 bodies per batch), by
            winding (:func:`stencil_sides`).
        rows : VolumeRows
            The matrices and lights the draws read.
        zmode : {"zpass", "zfail"}
            Counting in front of the surface or behind it.
        passing : list of float, optional
            Per batch, the share of light its shadow lets through (the mask is
            multiplied by it where the batch's count is not zero); all 0
            (opaque) by default.
        batch : VolumeBatch, optional
            The light's batch of small volumes, which the sides' runs draw.
        """
        passing = [0.0] * len(batches) if passing is None else passing
        arrays = rows.float32()
        with self._state() as (gl, state):
            target.bind(mask)
            state.vtkglColorMask(True, True, True, True)
            state.vtkglClearColor(1.0, 1.0, 1.0, 1.0)
            state.vtkglClear(gl.GL_COLOR_BUFFER_BIT)
            state.vtkglEnable(gl.GL_STENCIL_TEST)
            for sides, through in zip(batches, passing, strict=True):
                state.vtkglStencilMask(0xFF)
                gl.glClearStencil(0)
                state.vtkglClear(gl.GL_STENCIL_BUFFER_BIT)
                self._count_batch(gl, state, sides, arrays, zmode, batch)
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

    def _count_batch(
        self,
        gl,
        state,
        sides: list[StencilSide],
        arrays: tuple[np.ndarray, np.ndarray, np.ndarray],
        zmode: str,
        batch: VolumeBatch | None,
    ) -> None:
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
        matrices, lights, _ = arrays
        for side in sides:
            first, second = (back, front) if side.mirrored else (front, back)
            state.vtkglStencilOpSeparate(gl.GL_FRONT, *first)
            state.vtkglStencilOpSeparate(gl.GL_BACK, *second)
            if side.alone:
                self._draw_volumes(side.alone, matrices, lights, zmode == "zfail")
            if side.runs:
                assert batch is not None  # the runs are the batch's
                self._draw_runs(batch, side.runs, arrays, zmode == "zfail")

    def _draw_runs(
        self,
        batch: VolumeBatch,
        runs: list[VolumeRun],
        arrays: tuple[np.ndarray, np.ndarray, np.ndarray],
        caps: bool,
    ) -> None:
        """Draw runs of the batch's volumes: per chunk of rows, its uniforms and one multi-draw."""
        matrices, lights, reaches = arrays
        raw = raw_calls()
        program = self._bind("gpu", batch.chunk)
        program.SetUniformi("caps", int(caps))
        program.SetUniformf("capDepthOffset", CAP_DEPTH_OFFSET)
        to_clip, light_at, reach_at, base_at = (program.FindUniform(n) for n in _BATCH_UNIFORMS)
        position, row = (program.FindAttributeArray(n) for n in ("position", "casterRow"))
        raw.bind(batch.buffers.vertex_array(position, row))
        for run in runs:
            base, size = run.base, run.size
            raw.matrix(to_clip, size, 0, matrices.ctypes.data + 64 * base)
            raw.vector(light_at, size, lights.ctypes.data + 16 * base)
            raw.floats(reach_at, size, reaches.ctypes.data + 4 * base)
            raw.uniform_int(base_at, base)
            raw.multi_draw(
                _TRIANGLES_ADJACENCY,
                run.counts.ctypes.data,
                _UNSIGNED_INT,
                run.offsets.ctypes.data,
                len(run.counts),
            )
            batch.calls += 1
        raw.bind(0)

    def _draw_volumes(
        self,
        draws: list[VolumeDraw],
        matrices: np.ndarray,
        lights: np.ndarray,
        caps: bool,
        colour: list[float] | None = None,
    ) -> None:
        """Draw volumes, each with its row of the float32 matrices and lights.

        Each program is bound, and what it reads the same for every volume
        (caps, ``colour``) set, once per run of volumes extruded alike. Each
        volume's matrix and light are then set by location from its rows
        (:meth:`VolumeRows.float32`, read in place by address) and its
        pieces drawn, with the plain GL calls of
        :func:`~pvshadows.gl.raw_calls.raw_calls`: a few calls of about a
        microsecond each per volume.
        """
        assert matrices.dtype == np.float32 and matrices.flags.c_contiguous  # read by address
        assert lights.dtype == np.float32 and lights.flags.c_contiguous
        raw = raw_calls()
        matrix_base, light_base = matrices.ctypes.data, lights.ctypes.data
        bound = ""
        program = None
        to_clip = position = light_at = reach_at = -1
        reach = None
        for draw in draws:
            n = draw.row
            if draw.extrude != bound or program is None:
                bound = draw.extrude
                program = self._bind(bound)
                if colour is not None:
                    program.SetUniform4f("colour", colour)
                if bound == "gpu":
                    program.SetUniformi("caps", int(caps))
                    program.SetUniformf("capDepthOffset", CAP_DEPTH_OFFSET)
                    light_at, reach_at = (program.FindUniform(name) for name in _GPU_UNIFORMS)
                    reach = None
                to_clip = program.FindUniform("modelToClip")
                position = program.FindAttributeArray("position")
            raw.matrix(to_clip, 1, 0, matrix_base + 64 * n)
            raw.bind(draw.buffers.vertex_array(position))
            if bound == "gpu":
                raw.vector(light_at, 1, light_base + 16 * n)
                if draw.extrude_to != reach:
                    reach = draw.extrude_to
                    raw.uniform_float(reach_at, reach)
                for first, count, _ in draw.pieces:
                    if count > 0:
                        raw.draw(_TRIANGLES_ADJACENCY, count, _UNSIGNED_INT, 4 * first)
                continue
            for first, count, part in draw.pieces:
                if count <= 0 or (part != "sides" and not caps):
                    continue
                program.SetUniformf("capDepthOffset", CAP_DEPTH_OFFSET if part == "light" else 0.0)
                raw.draw(_TRIANGLES, count, _UNSIGNED_INT, 4 * first)
        raw.bind(0)

    def overlay(
        self,
        draws: list[VolumeDraw],
        rows: VolumeRows,
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
        rows : VolumeRows
            The matrices and lights they read.
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
            matrices, lights, _ = rows.float32()
            self._draw_volumes(draws, matrices, lights, False, list(colour))

    def release(self) -> None:
        """Release the programs and the empty vertex array."""
        self._programs.release()
        if self._empty is not None:
            self._empty.release()
            self._empty = None
