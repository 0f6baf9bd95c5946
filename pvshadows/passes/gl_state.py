"""Entering and leaving a map pass (depth or transmittance) without VTK losing track of GL state."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from types import ModuleType

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for


class DepthOnlyState:
    """Set up GL for writing depth only, and restore VTK's state afterwards (a ``with`` block).

    Everything goes through ``vtkOpenGLState`` (``Push``/``Pop`` restore the
    framebuffer bindings, viewport, program and the rest), except depth
    clamping, which VTK does not track and which is switched back off on
    leaving. A class, not a generator: entered once per pass, every frame a
    light moves.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the pass.
    """

    __slots__ = ("_gl", "_state")

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl, self._state = opengl_for(window), window.GetState()

    def __enter__(self) -> None:
        gl, state = self._gl, self._state
        state.Push()
        try:
            _enter_map_pass(gl, state)
            state.vtkglDisable(gl.GL_BLEND)
            state.vtkglEnable(gl.GL_DEPTH_TEST)
            state.vtkglDepthFunc(gl.GL_LESS)
            state.vtkglDepthMask(True)
            state.vtkglColorMask(False, False, False, False)
            state.vtkglClearDepth(1.0)
        except BaseException:
            _leave_map_pass(gl, state)
            raise

    def __exit__(self, *exc: object) -> None:
        _leave_map_pass(self._gl, self._state)


def _enter_map_pass(gl: ModuleType, state: vtk.vtkOpenGLState) -> None:
    """Set what every map pass shares, VTK's state pushed.

    Every map pass draws without scissor, stencil or culling (a caster asks
    for culling itself) and with depth clamping, so casters beyond the map's
    far plane stay drawn.
    """
    state.vtkglDisable(gl.GL_SCISSOR_TEST)
    state.vtkglDisable(gl.GL_STENCIL_TEST)
    state.vtkglDisable(gl.GL_CULL_FACE)
    gl.glEnable(gl.GL_DEPTH_CLAMP)


def _leave_map_pass(gl: ModuleType, state: vtk.vtkOpenGLState) -> None:
    """Switch depth clamping back off (VTK does not track it) and pop VTK's state."""
    gl.glDisable(gl.GL_DEPTH_CLAMP)
    state.Pop()


class FaceCulling:
    """Culls one side of the triangles drawn next, or none, calling GL only on a change.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context draws.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._state = window.GetState()
        self._side: str | bool | None = False  # neither a side nor None: not set yet

    def __call__(self, side: str | None) -> None:
        """Cull ``side`` (``"front"`` or ``"back"``) of the next triangles, or none (``None``)."""
        if side == self._side:
            return
        gl, state = self._gl, self._state
        if side is None:
            state.vtkglDisable(gl.GL_CULL_FACE)
        else:
            state.vtkglEnable(gl.GL_CULL_FACE)
            state.vtkglCullFace(gl.GL_FRONT if side == "front" else gl.GL_BACK)
        self._side = side


@contextmanager
def transmittance_state(window: vtk.vtkOpenGLRenderWindow) -> Iterator:
    """Set up GL for a transmittance companion, and restore VTK's state afterwards.

    No depth test and no culling (every translucent surface over a texel
    counts, both sides of a closed body); blending multiplies the colour by
    the fragment's and keeps the smaller alpha (``glsl/transmittance.frag``);
    the clear colour is 1 (nothing in the way). Depth clamping, as in
    :class:`DepthOnlyState`, keeps casters beyond the map's far plane drawn.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the pass.

    Yields
    ------
    module
        ``OpenGL.GL``, for the pass's own calls.
    """
    gl, state = opengl_for(window), window.GetState()
    state.Push()
    try:
        _enter_map_pass(gl, state)
        state.vtkglDisable(gl.GL_DEPTH_TEST)
        state.vtkglDepthMask(False)
        state.vtkglColorMask(True, True, True, True)
        state.vtkglEnable(gl.GL_BLEND)
        state.vtkglBlendEquationSeparate(gl.GL_FUNC_ADD, gl.GL_MIN)
        state.vtkglBlendFuncSeparate(gl.GL_ZERO, gl.GL_SRC_COLOR, gl.GL_ONE, gl.GL_ONE)
        state.vtkglClearColor(1.0, 1.0, 1.0, 1.0)
        yield gl
    finally:
        _leave_map_pass(gl, state)
