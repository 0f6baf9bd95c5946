"""What the current OpenGL context offers pvshadows, and which techniques it can run."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pyvista as pv
import vtk

from pvshadows.gl.binding import OpenGLPlatformError, opengl_for, platform_for


@dataclass(frozen=True)
class Capabilities:
    """The parts of an OpenGL context that pvshadows needs.

    Attributes
    ----------
    window : str
        VTK's render window class (EGL off screen, GLX in an X window, ...).
    platform : str
        How PyOpenGL reaches the context, or why it cannot.
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
    """

    window: str
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

    def techniques(self) -> dict[str, str]:
        """Return each technique with whether it can run here, and why not.

        Returns
        -------
        dict
            Technique name to ``"available"`` or the reason it is not.
        """
        if self.platform.startswith("unavailable"):
            return {"cubemap": self.platform}
        found = {
            "cubemap (passes='six')": "available",
            "cubemap (passes='single')": "available"
            if self.geometry_shaders
            else "unavailable: needs geometry shaders (OpenGL 3.2)",
            "map (spot, directional)": "available",
            "volume (extrude='gpu')": "available"
            if self.geometry_shaders
            else "unavailable: needs geometry shaders (OpenGL 3.2)",
            "volume (extrude='cpu')": "available",
            "planar (every light)": "available",
        }
        return found

    def __str__(self) -> str:
        lines = [
            f"window            {self.window}",
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
        lines += [f"  {name:26s}{state}" for name, state in self.techniques().items()]
        return "\n".join(lines)


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


def capabilities(window_size: tuple[int, int] = (64, 64)) -> Capabilities:
    """Open a small off-screen window and read what its OpenGL context offers.

    Parameters
    ----------
    window_size : tuple of int, default: (64, 64)
        Size of the window opened for the query.

    Returns
    -------
    Capabilities
        The context's vendor, version, limits and which techniques run.

    Examples
    --------
    >>> from pvshadows.info import capabilities
    >>> capabilities().max_texture_size >= 1024
    True
    """
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
    window = plotter.ren_win
    window.SetStencilCapable(1)
    plotter.add_mesh(pv.Sphere())
    plotter.screenshot(return_img=True)
    window.MakeCurrent()
    try:
        try:
            gl = opengl_for(window)
        except OpenGLPlatformError as error:
            return Capabilities(
                window.GetClassName(),
                f"unavailable: {error}",
                "",
                "",
                "",
                "",
                False,
                0,
                0,
                0,
                int(window.GetMultiSamples()),
            )
        text = lambda name: (gl.glGetString(name) or b"").decode(errors="replace")  # noqa: E731
        major = _integer(gl, gl.GL_MAJOR_VERSION)
        minor = _integer(gl, gl.GL_MINOR_VERSION)
        return Capabilities(
            window=window.GetClassName(),
            platform=platform_for(window) or "PyOpenGL default",
            vendor=text(gl.GL_VENDOR),
            renderer=text(gl.GL_RENDERER),
            version=text(gl.GL_VERSION),
            glsl=text(gl.GL_SHADING_LANGUAGE_VERSION),
            geometry_shaders=(major, minor) >= (3, 2),
            max_texture_size=_integer(gl, gl.GL_MAX_TEXTURE_SIZE),
            max_cube_map_size=_integer(gl, gl.GL_MAX_CUBE_MAP_TEXTURE_SIZE),
            stencil_bits=_stencil_bits(gl, window),
            multisamples=int(window.GetMultiSamples()),
        )
    finally:
        plotter.close()
