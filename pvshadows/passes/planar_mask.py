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
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.buffers import TriangleBuffers
from pvshadows.gl.colour_target import ColourTarget
from pvshadows.gl.mask_target import MaskTexture
from pvshadows.gl.programs import bind_program, compile_files


@dataclass
class FlatDraw:
    """One caster as the planar pass draws it.

    Attributes
    ----------
    buffers : TriangleBuffers
        Its triangles on the GPU, in its centred model coordinates.
    model_to_clip : numpy.ndarray
        ``(4, 4)`` float64: camera projection, view, flattening and model.
    plane_model : numpy.ndarray
        ``(4,)`` the plane in the caster's model coordinates, positive on
        the light's side.
    flat_w : numpy.ndarray
        ``(4,)`` the flattened point's ``w`` as a function of the model point.
    transmittance : float, default: 0.0
        Share of light each of its surfaces lets through (``1 - opacity``).
    """

    buffers: TriangleBuffers
    model_to_clip: np.ndarray
    plane_model: np.ndarray
    flat_w: np.ndarray
    transmittance: float = 0.0


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
        self._program: vtk.vtkShaderProgram | None = None
        self._target: ColourTarget | None = None

    def _bind(self) -> vtk.vtkShaderProgram:
        if self._program is None:
            self._program = compile_files(self._window, "planar_flatten.vert", "planar_mask.frag")
        bind_program(self._window, self._program)
        return self._program

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

    def draw(self, mask: MaskTexture, draws: list[FlatDraw]) -> None:
        """Clear a light's mask to lit and multiply in each flattened caster's transmittance.

        Parameters
        ----------
        mask : MaskTexture
            The light's mask, the size of the viewport.
        draws : list of FlatDraw
            The casters.
        """
        with self._state(mask) as gl:
            gl.glEnable(gl.GL_CLIP_DISTANCE0)
            gl.glEnable(gl.GL_CLIP_DISTANCE1)
            gl.glEnable(gl.GL_DEPTH_CLAMP)
            state = self._window.GetState()
            state.vtkglEnable(gl.GL_BLEND)
            state.vtkglBlendFunc(gl.GL_ZERO, gl.GL_SRC_COLOR)
            program = self._bind()
            # Every draw's values rounded to float32 at once, not draw by draw.
            matrices = column_major(np.array([d.model_to_clip for d in draws]).reshape(-1, 4, 4))
            planes = np.array([d.plane_model for d in draws], np.float32).tolist()
            ws = np.array([d.flat_w for d in draws], np.float32).tolist()
            for number, draw in enumerate(draws):
                matrix = matrices[16 * number : 16 * number + 16]
                program.SetUniformMatrix4x4v("modelToClip", 1, matrix)
                program.SetUniform4f("planeModel", planes[number])
                program.SetUniform4f("flatW", ws[number])
                program.SetUniformf("transmittance", float(draw.transmittance))
                draw.buffers.draw_triangles(program)

    def release(self) -> None:
        """Release the program and the framebuffer."""
        if self._program is not None:
            self._program.ReleaseGraphicsResources(self._window)
            self._program = None
        if self._target is not None:
            self._target.release()
            self._target = None
