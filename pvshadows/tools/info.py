"""What an OpenGL window offers pvshadows, and which techniques run in it.

:func:`capabilities` opens a small window — off screen, or on screen with
``onscreen=True`` —, says how PyOpenGL reaches its context, reads the
driver's limits and then *runs* every technique there on a small scene: a
technique is available when it drew a shadow that :meth:`visibility
<pvshadows.component.ShadowsComponent.visibility>` reads back, and otherwise
unavailable with the reason.
"""

from __future__ import annotations

import os
import sys
import warnings
from dataclasses import dataclass, field

import numpy as np
import pyvista as pv

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import describe_binding, opengl_for

#: Each row of the techniques table: label, light kinds tried, settings, needs a geometry shader.
TRIALS = (
    ("cubemap (passes='six')", ("point",), {"technique": "cubemap", "passes": "six"}, False),
    ("cubemap (passes='single')", ("point",), {"technique": "cubemap", "passes": "single"}, True),
    ("map (spot, directional)", ("spot", "directional"), {"technique": "map"}, False),
    ("volume (extrude='gpu')", ("point",), {"technique": "volume", "extrude": "gpu"}, True),
    ("volume (extrude='cpu')", ("point",), {"technique": "volume", "extrude": "cpu"}, False),
    ("planar (every light)", ("point", "spot", "directional"), {"technique": "planar"}, False),
)

_NEEDS_GEOMETRY_SHADERS = "unavailable: needs geometry shaders (OpenGL 3.2)"


@dataclass(frozen=True)
class Capabilities:
    """The parts of an OpenGL window that pvshadows needs.

    Attributes
    ----------
    window : str
        VTK's render window class (EGL off screen, GLX in an X window, ...).
    display : str
        The display the window was opened on, in words.
    platform : str
        How PyOpenGL reaches the context, or ``"unavailable: <why>"``.
    vendor, renderer, version, glsl : str
        What the driver says of itself.
    geometry_shaders : bool
        Whether geometry shaders exist (OpenGL 3.2 or later).
    max_texture_size, max_cube_map_size : int
        Largest 2D texture and cube-map face, in texels.
    stencil_bits : int
        Stencil bits of a window asked for a stencil buffer.
    multisamples : int
        Samples per pixel of a default PyVista window.
    techniques : dict
        Technique (with its setting) to ``"available"`` or
        ``"unavailable: <why>"``, as found by running it.
    """

    window: str
    display: str
    platform: str
    vendor: str
    renderer: str
    version: str
    glsl: str
    geometry_shaders: bool
    max_texture_size: int
    max_cube_map_size: int
    stencil_bits: int
    multisamples: int
    techniques: dict[str, str] = field(default_factory=dict)

    def __str__(self) -> str:
        lines = [
            f"window            {self.window}",
            f"display           {self.display}",
            f"PyOpenGL platform {self.platform}",
            f"vendor            {self.vendor}",
            f"renderer          {self.renderer}",
            f"OpenGL            {self.version}",
            f"GLSL              {self.glsl}",
            f"geometry shaders  {'yes' if self.geometry_shaders else 'no'}",
            f"max texture size  {self.max_texture_size}",
            f"max cube map face {self.max_cube_map_size}",
            f"stencil bits      {self.stencil_bits}",
            f"multisamples      {self.multisamples}",
            "techniques:",
        ]
        lines += [f"  {name:26s}{state}" for name, state in self.techniques.items()]
        return "\n".join(lines)


def display_in_words(onscreen: bool) -> str:
    """Describe where windows open: the X display, a Wayland session, or none.

    Parameters
    ----------
    onscreen : bool
        Whether the window is on screen.

    Returns
    -------
    str
        For example ``"X :0"``, ``"X :0 (XWayland in a Wayland session)"``
        or ``"none (off screen)"``.

    Examples
    --------
    >>> from pvshadows.tools.info import display_in_words
    >>> display_in_words(onscreen=False).startswith(("none", "X", "native"))
    True
    """
    if not sys.platform.startswith("linux"):
        return "native" if onscreen else "native (off screen)"
    x_display = os.environ.get("DISPLAY")
    wayland = bool(os.environ.get("WAYLAND_DISPLAY")) or (
        os.environ.get("XDG_SESSION_TYPE", "").lower() == "wayland"
    )
    if x_display:
        where = f"X {x_display}" + (" (XWayland in a Wayland session)" if wayland else "")
        return where if onscreen else f"{where} (off screen)"
    return "none (off screen)"


def onscreen_problem() -> str | None:
    """Say why no on-screen window can open here, or return ``None`` if one can.

    Returns
    -------
    str or None
        On Linux an on-screen VTK window is an X window (VTK has no Wayland
        window; a Wayland desktop runs it through XWayland), so it needs
        ``DISPLAY``.

    Examples
    --------
    >>> from pvshadows.tools.info import onscreen_problem
    >>> onscreen_problem() is None or "DISPLAY" in onscreen_problem()
    True
    """
    if not sys.platform.startswith("linux") or os.environ.get("DISPLAY"):
        return None
    if os.environ.get("WAYLAND_DISPLAY"):
        return (
            "DISPLAY is not set: VTK opens on-screen windows through X, which on a Wayland "
            "desktop needs XWayland (DISPLAY); without it only off-screen (EGL) windows work"
        )
    return "DISPLAY is not set: there is no X display for an on-screen window (try xvfb-run)"


def _integer(gl, name: int) -> int:
    return int(np.asarray(gl.glGetIntegerv(name)).ravel()[0])


def _stencil_bits(gl, window: vtk.vtkOpenGLRenderWindow) -> int:
    framebuffer = window.GetRenderFramebuffer()
    framebuffer.Bind()
    size = gl.glGetFramebufferAttachmentParameteriv(
        gl.GL_FRAMEBUFFER, gl.GL_DEPTH_ATTACHMENT, gl.GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE
    )
    framebuffer.UnBind()
    return int(np.asarray(size).ravel()[0])


def _reported(window: vtk.vtkRenderWindow, what: str) -> str:
    for line in window.ReportCapabilities().splitlines():
        if line.startswith(f"OpenGL {what} string:"):
            return line.split(":", 1)[1].strip()
    return ""


def _trial_light(kind: str) -> pv.Light:
    if kind == "point":
        return pv.Light(position=(0.3, 0.2, 3.0), positional=True, cone_angle=180)
    if kind == "spot":
        return pv.Light(position=(0.3, 0.2, 3.0), positional=True, cone_angle=50)
    return pv.Light(position=(1.0, 0.5, 6.0), focal_point=(0.0, 0.0, 0.0))


def _try(plotter: pv.Plotter, kind: str, settings: dict) -> str:
    """Run one technique for one kind of light; return ``"available"`` or why not."""
    plotter.remove_all_lights()
    light = _trial_light(kind)
    plotter.add_light(light)
    failure = None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            plotter.shadows.enable(**settings)
            shown = plotter.shadows.visibility(light)
            ran = plotter.shadows.last_frame.lights[0].technique
        except Exception as error:
            failure = error
    for warning in caught:
        if str(warning.message).startswith("pvshadows"):
            return f"unavailable: {warning.message}"
    if failure is not None:
        return f"unavailable: {failure}"
    if ran != settings["technique"]:
        return f"unavailable: {kind} light drew with {ran} instead"
    seen = shown[np.isfinite(shown)]
    if not (np.any(seen < 0.5) and np.any(seen >= 0.5)):
        return f"unavailable: drew no shadow from a {kind} light"
    return "available"


def _techniques(plotter: pv.Plotter, geometry_shaders: bool) -> dict[str, str]:
    found = {}
    for label, kinds, settings, needs_gs in TRIALS:
        if needs_gs and not geometry_shaders:
            found[label] = _NEEDS_GEOMETRY_SHADERS
            continue
        states = [_try(plotter, kind, settings) for kind in kinds]
        found[label] = next((s for s in states if s != "available"), "available")
    plotter.shadows.disable()
    return found


def capabilities(
    window_size: tuple[int, int] = (96, 96), *, onscreen: bool = False
) -> Capabilities:
    """Open a small window, read what its OpenGL context offers and run every technique in it.

    Parameters
    ----------
    window_size : tuple of int, default: (96, 96)
        Size of the window opened for the query.
    onscreen : bool, default: False
        Open an on-screen window (an X window through GLX on Linux)
        instead of an off-screen one.

    Returns
    -------
    Capabilities
        The window class, how PyOpenGL reaches it, the driver's limits and
        which techniques run (or why not).

    Raises
    ------
    RuntimeError
        If ``onscreen`` is asked for where no on-screen window can open.

    Examples
    --------
    >>> from pvshadows.tools.info import capabilities
    >>> found = capabilities()
    >>> found.max_texture_size >= 1024
    True
    >>> found.techniques["cubemap (passes='six')"]
    'available'
    """
    if onscreen and (problem := onscreen_problem()) is not None:
        msg = f"cannot open an on-screen window: {problem}"
        raise RuntimeError(msg)
    plotter = pv.Plotter(off_screen=not onscreen, window_size=list(window_size), lighting="none")
    try:
        window = plotter.ren_win
        assert window is not None
        window.SetStencilCapable(1)
        plotter.add_mesh(pv.Plane(i_size=8, j_size=8))
        plotter.add_mesh(pv.Sphere(radius=0.6, center=(0, 0, 1.2)))
        plotter.camera_position = [(0, -4, 8), (0, 0, 0), (0, 0, 1)]
        if onscreen:
            plotter.show(interactive_update=True, auto_close=False)
        else:
            plotter.screenshot(return_img=True)
        return _read(plotter, window, onscreen)
    finally:
        plotter.close()


def _read(plotter: pv.Plotter, window: vtk.vtkOpenGLRenderWindow, onscreen: bool) -> Capabilities:
    binding = describe_binding(window)
    display = display_in_words(onscreen)
    vendor, renderer, version = (_reported(window, w) for w in ("vendor", "renderer", "version"))
    if version.startswith("OpenGL ES"):
        binding = "unavailable: pvshadows needs desktop OpenGL (3.2 core), not OpenGL ES"
    if binding.startswith("unavailable"):
        techniques = {label: binding for label, *_ in TRIALS}
        return Capabilities(
            window.GetClassName(),
            display,
            binding,
            vendor,
            renderer,
            version,
            "",
            False,
            0,
            0,
            0,
            int(window.GetMultiSamples()),
            techniques,
        )
    window.MakeCurrent()
    gl = opengl_for(window)
    major = _integer(gl, gl.GL_MAJOR_VERSION)
    minor = _integer(gl, gl.GL_MINOR_VERSION)
    geometry_shaders = (major, minor) >= (3, 2)
    return Capabilities(
        window=window.GetClassName(),
        display=display,
        platform=binding,
        vendor=vendor,
        renderer=renderer,
        version=version,
        glsl=(gl.glGetString(gl.GL_SHADING_LANGUAGE_VERSION) or b"").decode(errors="replace"),
        geometry_shaders=geometry_shaders,
        max_texture_size=_integer(gl, gl.GL_MAX_TEXTURE_SIZE),
        max_cube_map_size=_integer(gl, gl.GL_MAX_CUBE_MAP_TEXTURE_SIZE),
        stencil_bits=_stencil_bits(gl, window),
        multisamples=int(window.GetMultiSamples()),
        techniques=_techniques(plotter, geometry_shaders),
    )
