"""The planar-shadow pass: casters flattened onto the plane, drawn into a light's mask.

Per light, in a framebuffer of pvshadows' own the size of the viewport
(:class:`pvshadows.gl.colour_target.ColourTarget`): the mask is cleared to 1
(lit), then every caster is drawn with the camera's projection times the
flattening matrix (:func:`pvshadows.scene.planes.flattening`), multiplying the mask
by its transmittance (``1 - opacity``, 0 for an opaque caster). Where opaque
casters cover a pixel it is 0 however many flattened triangles cover it,
which is what a stencil test ("draw where not yet drawn") would give; a
translucent caster's two surfaces each let ``1 - opacity`` through, as the
reference's shadow rays do. No depth test runs at all: only the plane reads the mask,
at its own pixels, so the shadow ends where the plane ends and cannot fight
with it in depth at any scale.

Two clip distances cut each flattened triangle where the caster's triangle
crosses the plane (only the part on the light's side casts) and where it
passes beyond a positional light's height (no anti-shadows in the mask; the
camera's own clipping already keeps them off the plane's pixels, since their
homogeneous image has a negative ``w`` and could only be seen, mirrored,
along lines of sight that point away from the plane). Depth clamping keeps
shadows that reach to infinity (a light barely above the plane) from being
cut at the far plane.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.caster_batch import chunk_rows
from pvshadows.gl.caster_draws import CasterDraws, draw_casters
from pvshadows.gl.colour_target import ColourTarget
from pvshadows.gl.mask_target import MaskTexture
from pvshadows.gl.programs import ProgramCache, bind_program, compile_files
from pvshadows.passes.gl_state import FaceCulling

#: The ``vec4`` uniforms of each flattened caster besides its matrix
#: (:attr:`~pvshadows.gl.caster_draws.CasterDraws.vectors`): the plane in its
#: model coordinates (positive on the light's side), the flattened point's
#: ``w`` as a function of the model point, and in ``x`` the share of light
#: each of its surfaces lets through (``1 - opacity``).
FLAT_VECTORS = ("planeModel", "flatW", "lightThrough")


class PlanarMaskPass:
    """Draws flattened casters into per-light masks, in one window.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs it.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._gl = opengl_for(window)
        self._programs = ProgramCache(window)
        self._target: ColourTarget | None = None
        self._chunk = 0

    def _bind(self, rows: int) -> vtk.vtkShaderProgram:
        """Bind the flattening program, built ``BATCHED`` so many rows when ``rows``."""
        defines = {"BATCHED": rows} if rows else None
        program = self._programs.get(
            rows,
            lambda: compile_files(
                self._window, "planar_flatten.vert", "planar_mask.frag", defines=defines
            ),
        )
        bind_program(self._window, program)
        return program

    def chunk(self, batch_chunk: int) -> int:
        """Return the rows per chunk the batched program holds: its uniforms, or the batch's.

        Parameters
        ----------
        batch_chunk : int
            The batch's rows per chunk of matrices.

        Returns
        -------
        int
            At most ``batch_chunk``.
        """
        if not self._chunk:
            self._chunk = chunk_rows(self._window, len(FLAT_VECTORS))
        return min(batch_chunk, self._chunk)

    @contextmanager
    def _state(self, mask: MaskTexture) -> Iterator:
        gl = self._gl
        state = self._window.GetState()
        state.Push()
        clips = (gl.GL_CLIP_DISTANCE0, gl.GL_CLIP_DISTANCE1, gl.GL_DEPTH_CLAMP)
        were = [bool(gl.glIsEnabled(cap)) for cap in clips]
        try:
            if self._target is None:
                self._target = ColourTarget(self._window)
            self._target.bind(mask)
            state.vtkglDisable(gl.GL_BLEND)
            state.vtkglDisable(gl.GL_SCISSOR_TEST)
            state.vtkglDisable(gl.GL_CULL_FACE)
            state.vtkglDisable(gl.GL_STENCIL_TEST)
            state.vtkglDisable(gl.GL_DEPTH_TEST)
            state.vtkglDepthMask(False)
            state.vtkglColorMask(True, True, True, True)
            state.vtkglClearColor(1.0, 1.0, 1.0, 1.0)
            state.vtkglClear(gl.GL_COLOR_BUFFER_BIT)
            yield gl
        finally:
            for cap, was in zip(clips, were, strict=True):
                (gl.glEnable if was else gl.glDisable)(cap)
            state.Pop()

    def fill_lit(self, mask: MaskTexture) -> None:
        """Clear a mask to 1 (lit everywhere).

        Parameters
        ----------
        mask : MaskTexture
            The light's mask.
        """
        with self._state(mask):
            pass

    def draw(self, mask: MaskTexture, draws: CasterDraws) -> None:
        """Clear a light's mask to lit and multiply in each flattened caster's transmittance.

        Parameters
        ----------
        mask : MaskTexture
            The light's mask, the size of the viewport.
        draws : CasterDraws
            The casters: matrices from their centred model coordinates through
            the flattening to the camera's clip space, and :data:`FLAT_VECTORS`;
            the casters of the snapshot's batch are drawn through it.
        """

        def program(batched: bool) -> vtk.vtkShaderProgram:
            return self._bind(draws.chunk if batched else 0)

        with self._state(mask) as gl:
            gl.glEnable(gl.GL_CLIP_DISTANCE0)
            gl.glEnable(gl.GL_CLIP_DISTANCE1)
            gl.glEnable(gl.GL_DEPTH_CLAMP)
            state = self._window.GetState()
            state.vtkglEnable(gl.GL_BLEND)
            state.vtkglBlendFunc(gl.GL_ZERO, gl.GL_SRC_COLOR)
            draw_casters(program, draws, FaceCulling(self._window))

    def release(self) -> None:
        """Release the program and the framebuffer."""
        self._programs.release()
        if self._target is not None:
            self._target.release()
            self._target = None
