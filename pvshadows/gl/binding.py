"""Import PyOpenGL so that it talks to the context VTK created.

PyOpenGL picks its platform (EGL, GLX, WGL, ...) once, at its first import.
With an EGL window (off screen, no display) it must be told
``PYOPENGL_PLATFORM=egl`` before that import, or calls that take arrays fail;
with an X window it must not be. This module chooses from the window VTK
gives us, and says clearly when PyOpenGL was already imported for another
platform.
"""

from __future__ import annotations

import os
import sys
from types import ModuleType

import vtk

#: PyOpenGL platform for each VTK render window class; classes not listed
#: use PyOpenGL's own default for the operating system.
PLATFORM_OF_WINDOW = {
    "vtkEGLRenderWindow": "egl",
    "vtkXOpenGLRenderWindow": "glx",
    "vtkOSOpenGLRenderWindow": "osmesa",
    "vtkWin32OpenGLRenderWindow": "nt",
}

_PLATFORM_CLASS_NAMES = {
    "egl": "EGLPlatform",
    "glx": "GLXPlatform",
    "osmesa": "OSMesaPlatform",
    "nt": "Win32Platform",
}


class OpenGLPlatformError(RuntimeError):
    """PyOpenGL was set up for a different kind of window than VTK's."""


def platform_for(window: vtk.vtkRenderWindow) -> str | None:
    """Return the PyOpenGL platform name that matches a VTK render window.

    Parameters
    ----------
    window : vtk.vtkRenderWindow
        The render window VTK created.

    Returns
    -------
    str or None
        ``"egl"``, ``"glx"``, ``"osmesa"`` or ``"nt"``; ``None`` where
        PyOpenGL's default for the operating system is right (macOS).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import platform_for
    >>> platform_for(pv.Plotter(off_screen=True).ren_win) in ("egl", "glx", "osmesa", "nt", None)
    True
    """
    return PLATFORM_OF_WINDOW.get(window.GetClassName())


def opengl_for(window: vtk.vtkRenderWindow) -> ModuleType:
    """Return ``OpenGL.GL``, imported for the platform of ``window``.

    Parameters
    ----------
    window : vtk.vtkRenderWindow
        The render window whose context the GL calls will use.

    Returns
    -------
    module
        The ``OpenGL.GL`` module.

    Raises
    ------
    OpenGLPlatformError
        If PyOpenGL was already imported for another platform in this
        process (for example an X window after an off-screen EGL one).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> GL = opengl_for(pv.Plotter(off_screen=True).ren_win)
    >>> GL.GL_DEPTH_COMPONENT32F > 0
    True
    """
    wanted = platform_for(window)
    if "OpenGL.platform" not in sys.modules:
        if wanted is not None:
            os.environ["PYOPENGL_PLATFORM"] = wanted
        import OpenGL

        OpenGL.ERROR_CHECKING = False
        OpenGL.ERROR_LOGGING = False
    from OpenGL import platform

    current = type(platform.PLATFORM).__name__
    if wanted is not None and current != _PLATFORM_CLASS_NAMES[wanted]:
        msg = (
            f"PyOpenGL was already imported for {current}, but this {window.GetClassName()} "
            f"needs the {wanted!r} platform. Use one kind of window per process, or set "
            f"PYOPENGL_PLATFORM={wanted} before anything imports OpenGL."
        )
        raise OpenGLPlatformError(msg)
    from OpenGL import GL

    return GL
