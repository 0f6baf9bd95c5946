"""Import PyOpenGL so that it talks to the context VTK created.

PyOpenGL picks its platform (EGL, GLX, WGL, ...) once per process, at its
first import, from ``PYOPENGL_PLATFORM`` or its own guess (which is EGL in a
Wayland session, GLX under X). The right one is the API of the window VTK
gives us: ``vtkEGLRenderWindow`` (off screen, no display) needs ``egl``,
``vtkXOpenGLRenderWindow`` (an X window, also on a Wayland desktop through
XWayland) needs ``glx``, ``vtkOSOpenGLRenderWindow`` needs ``osmesa``,
``vtkWin32OpenGLRenderWindow`` needs WGL (``nt``) and ``vtkCocoaRenderWindow``
needs ``darwin``. A window of another class (an embedding GUI's
``vtkGenericOpenGLRenderWindow``) is matched by the context that is current
once VTK made it current.

PyOpenGL finds most GL functions of libOSMesa only by address, so with
OSMesa the ones it cannot find by name are asked of ``OSMesaGetProcAddress``.

When PyOpenGL was already imported for the other of EGL and GLX (by the user,
or for an earlier window of the other kind), both reach the same GL through
libglvnd's shared dispatch on Linux: only PyOpenGL's idea of the *current
context* is wrong, so it is bridged to the window's API and checked against
the renderer VTK reports. Every other mismatch raises
:class:`OpenGLPlatformError` saying what to do.
"""

from __future__ import annotations

import ctypes
import os
import sys
from collections.abc import Callable
from types import ModuleType

from pvshadows import _vtk as vtk

#: PyOpenGL platform for each VTK render window class.
PLATFORM_OF_WINDOW = {
    "vtkEGLRenderWindow": "egl",
    "vtkXOpenGLRenderWindow": "glx",
    "vtkOSOpenGLRenderWindow": "osmesa",
    "vtkWin32OpenGLRenderWindow": "nt",
    "vtkCocoaRenderWindow": "darwin",
}

#: PyOpenGL's class for each platform name.
PLATFORM_CLASS_NAMES = {
    "egl": "EGLPlatform",
    "glx": "GLXPlatform",
    "osmesa": "OSMesaPlatform",
    "nt": "Win32Platform",
    "darwin": "DarwinPlatform",
}

#: How each API tells its current context on Linux: library names and function.
_CURRENT_CONTEXT = {
    "egl": (("libEGL.so.1", "libEGL.so"), "eglGetCurrentContext"),
    "glx": (("libGLX.so.0", "libGL.so.1", "libGL.so"), "glXGetCurrentContext"),
}

#: Platforms PyOpenGL was bridged to, and whether a window of each was checked.
_bridged: dict[str, bool] = {}


class OpenGLPlatformError(RuntimeError):
    """PyOpenGL was set up for a different kind of window than VTK's."""


def _current_context_function(api: str) -> Callable[[], int | None] | None:
    names, function = _CURRENT_CONTEXT[api]
    for name in names:
        try:
            found = getattr(ctypes.CDLL(name), function)
        except (OSError, AttributeError):
            continue
        found.restype = ctypes.c_void_p
        found.argtypes = []
        return found
    return None


def current_api() -> str | None:
    """Return the API (``"egl"`` or ``"glx"``) whose context is current in this thread.

    Returns
    -------
    str or None
        ``None`` when neither has a current context, or off Linux.

    Examples
    --------
    >>> from pvshadows.gl.binding import current_api
    >>> current_api() in ("egl", "glx", None)
    True
    """
    if not sys.platform.startswith("linux"):
        return None
    for api in ("egl", "glx"):
        function = _current_context_function(api)
        if function is not None and function():
            return api
    return None


def platform_for(window: vtk.vtkRenderWindow) -> str | None:
    """Return the PyOpenGL platform name that matches a VTK render window.

    Parameters
    ----------
    window : vtk.vtkRenderWindow
        The render window VTK created. A window of a class not in
        :data:`PLATFORM_OF_WINDOW` is made current and matched by the API of
        its context.

    Returns
    -------
    str or None
        ``"egl"``, ``"glx"``, ``"osmesa"``, ``"nt"`` or ``"darwin"``;
        ``None`` when it cannot be told (PyOpenGL's default is used).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import platform_for
    >>> platform_for(pv.Plotter(off_screen=True).ren_win) in ("egl", "glx", "osmesa", "nt")
    True
    """
    name = PLATFORM_OF_WINDOW.get(window.GetClassName())
    if name is not None:
        return name
    if sys.platform == "win32":
        return "nt"
    if sys.platform == "darwin":
        return "darwin"
    if window.GetInitialized():
        window.MakeCurrent()
        return current_api()
    return None


def loaded_platform() -> str | None:
    """Return the platform PyOpenGL was imported for, or ``None`` if it was not yet.

    Returns
    -------
    str or None
        A key of :data:`PLATFORM_CLASS_NAMES`, PyOpenGL's class name for a
        platform not listed there, or ``None`` before PyOpenGL's first import.

    Examples
    --------
    >>> from pvshadows.gl.binding import loaded_platform
    >>> loaded_platform() is None or isinstance(loaded_platform(), str)
    True
    """
    module = sys.modules.get("OpenGL.platform")
    if module is None:
        return None
    current = type(module.PLATFORM).__name__
    for name, class_name in PLATFORM_CLASS_NAMES.items():
        if class_name == current:
            return name
    return current


def _import_pyopengl(wanted: str | None) -> None:
    """Import PyOpenGL for ``wanted`` without leaving ``PYOPENGL_PLATFORM`` behind."""
    previous = os.environ.get("PYOPENGL_PLATFORM")
    if wanted is not None:
        os.environ["PYOPENGL_PLATFORM"] = wanted
    try:
        import OpenGL

        OpenGL.ERROR_CHECKING = False
        OpenGL.ERROR_LOGGING = False
        import OpenGL.platform  # importing it fixes the platform for this process
    finally:
        if previous is None:
            os.environ.pop("PYOPENGL_PLATFORM", None)
        else:
            os.environ["PYOPENGL_PLATFORM"] = previous


def _renderer_vtk_reports(window: vtk.vtkRenderWindow) -> str | None:
    for line in window.ReportCapabilities().splitlines():
        if line.startswith("OpenGL renderer string:"):
            return line.split(":", 1)[1].strip()
    return None


def reaches_window(gl: ModuleType, window: vtk.vtkRenderWindow) -> bool:
    """Tell whether PyOpenGL's calls reach the context of ``window``.

    Parameters
    ----------
    gl : module
        ``OpenGL.GL``.
    window : vtk.vtkRenderWindow
        An initialized window; it is made current.

    Returns
    -------
    bool
        Whether ``glGetString(GL_RENDERER)`` through PyOpenGL names the
        renderer VTK reports for the window.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for, reaches_window
    >>> pl = pv.Plotter(off_screen=True, window_size=[32, 32])
    >>> image = pl.screenshot(return_img=True)
    >>> reaches_window(opengl_for(pl.ren_win), pl.ren_win)
    True
    """
    window.MakeCurrent()
    try:
        ours = gl.glGetString(gl.GL_RENDERER)
    except Exception:
        return False
    return bool(ours) and ours.decode(errors="replace").strip() == _renderer_vtk_reports(window)


def _glvnd_loaded() -> bool:
    try:
        ctypes.CDLL("libGLdispatch.so.0", mode=os.RTLD_NOLOAD)
    except (OSError, AttributeError):
        return False
    return True


def _bridge(loaded: str | None, wanted: str) -> str | None:
    """Let PyOpenGL, imported for ``loaded``, see contexts of ``wanted``; return why not."""
    if {loaded, wanted} != {"egl", "glx"} or not sys.platform.startswith("linux"):
        return f"PyOpenGL cannot reach a {wanted!r} context from its {loaded!r} platform"
    if wanted in _bridged:
        return None
    if not _glvnd_loaded():
        return "EGL and GLX share GL functions only through libglvnd, which is not loaded"
    other = _current_context_function(wanted)
    if other is None:
        return f"no library tells the current {wanted.upper()} context"
    from OpenGL import platform

    native = platform.PLATFORM.GetCurrentContext

    def current_context() -> int | None:
        return native() or other()

    for target in (platform.PLATFORM, platform):
        target.GetCurrentContext = current_context
        target.CurrentContextIsValid = current_context
    _bridged[wanted] = False
    return None


def _complete_osmesa() -> None:
    """Resolve GL functions libOSMesa does not export through ``OSMesaGetProcAddress``.

    PyOpenGL looks core functions up by name in the library, and libOSMesa
    exports only the oldest ones; the rest exist only by address.
    """
    from OpenGL import platform

    if getattr(platform.PLATFORM, "_pvshadows_completed", False):
        return
    construct = platform.PLATFORM.constructFunction

    def construct_or_ask(name, dll, **options):
        try:
            return construct(name, dll, **options)
        except AttributeError:
            if options.get("force_extension"):
                raise
            return construct(name, dll, **{**options, "force_extension": True})

    platform.PLATFORM.constructFunction = construct_or_ask
    platform.PLATFORM._pvshadows_completed = True


def describe_binding(window: vtk.vtkRenderWindow) -> str:
    """Say how PyOpenGL reaches the context of ``window``, or why it cannot.

    Parameters
    ----------
    window : vtk.vtkRenderWindow
        The render window.

    Returns
    -------
    str
        The platform name (``"egl"``, ``"glx"``, ...), with how it was
        bridged where PyOpenGL had been imported for the other of EGL and
        GLX, or ``"unavailable: <why>"``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import describe_binding
    >>> pl = pv.Plotter(off_screen=True, window_size=[32, 32])
    >>> image = pl.screenshot(return_img=True)
    >>> describe_binding(pl.ren_win).startswith("unavailable")
    False
    """
    try:
        gl = opengl_for(window)
    except OpenGLPlatformError as error:
        return f"unavailable: {error}"
    loaded, wanted = loaded_platform(), platform_for(window)
    if wanted is None:
        text = f"{loaded} (PyOpenGL's default: the context's API could not be told)"
    elif loaded != wanted:
        assert loaded is not None
        text = (
            f"{loaded}, bridged to this {wanted.upper()} context through libglvnd "
            f"(PyOpenGL was imported for {loaded.upper()} first)"
        )
    else:
        text = loaded
    if window.GetInitialized() and not reaches_window(gl, window):
        return f"unavailable: PyOpenGL ({text}) does not reach the context VTK draws in"
    return text


def check_window(window: vtk.vtkRenderWindow) -> None:
    """Raise now, not at the first frame, if PyOpenGL cannot reach the context of ``window``.

    Only windows whose class names their API are checked before they exist;
    others are matched by their context at the first frame.

    Parameters
    ----------
    window : vtk.vtkRenderWindow
        The render window, drawn already or not.

    Raises
    ------
    OpenGLPlatformError
        As :func:`opengl_for`.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import check_window
    >>> check_window(pv.Plotter(off_screen=True).ren_win)
    """
    if window.GetClassName() in PLATFORM_OF_WINDOW:
        opengl_for(window)


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
        If PyOpenGL was already imported in this process for a platform that
        cannot reach this window's context (for example OSMesa before an EGL
        window), saying what to do instead.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> GL = opengl_for(pv.Plotter(off_screen=True).ren_win)
    >>> GL.GL_DEPTH_COMPONENT32F > 0
    True
    """
    matched = _matched.get(window.GetClassName())
    if matched is not None:
        return matched
    wanted = platform_for(window)
    if loaded_platform() is None:
        _import_pyopengl(wanted)
    loaded = loaded_platform()
    if loaded == "osmesa":
        _complete_osmesa()
    if wanted is not None and loaded != wanted:
        why = _bridge(loaded, wanted)
        if why is not None:
            msg = (
                f"PyOpenGL was already imported for {loaded!r}, but this "
                f"{window.GetClassName()} needs the {wanted!r} platform ({why}). Use one kind "
                f"of window per process, or set PYOPENGL_PLATFORM={wanted} before anything "
                "imports OpenGL."
            )
            raise OpenGLPlatformError(msg)
        if not _bridged[wanted] and window.GetInitialized():
            _bridged[wanted] = reaches_window(_gl(), window)
            if not _bridged[wanted]:
                msg = (
                    f"PyOpenGL, imported for {loaded!r} and bridged to this "
                    f"{window.GetClassName()}, does not reach its context. Set "
                    f"PYOPENGL_PLATFORM={wanted} before anything imports OpenGL."
                )
                raise OpenGLPlatformError(msg)
    if wanted is not None and loaded == wanted == PLATFORM_OF_WINDOW.get(window.GetClassName()):
        # This class of window always needs the platform PyOpenGL has: no check again.
        _matched[window.GetClassName()] = _gl()
    return _gl()


#: ``OpenGL.GL`` by the class names of windows whose platform PyOpenGL was loaded for.
_matched: dict[str, ModuleType] = {}


def _gl() -> ModuleType:
    from OpenGL import GL

    return GL
