"""What the current OpenGL context offers: its version and its extensions."""

from __future__ import annotations

from types import ModuleType


def gl_version(gl: ModuleType) -> tuple[int, int]:
    """Return the current context's OpenGL version.

    Parameters
    ----------
    gl : module
        ``OpenGL.GL`` for the current context.

    Returns
    -------
    tuple of int
        ``(major, minor)``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.capabilities import gl_version
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> gl_version(opengl_for(pl.ren_win)) >= (3, 2)
    True
    """
    return int(gl.glGetIntegerv(gl.GL_MAJOR_VERSION)), int(gl.glGetIntegerv(gl.GL_MINOR_VERSION))


def extension_names(gl: ModuleType) -> set[str]:
    """Return the names of the current context's extensions.

    Parameters
    ----------
    gl : module
        ``OpenGL.GL`` for the current context.

    Returns
    -------
    set of str
        For example ``{"GL_ARB_copy_image", ...}``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.capabilities import extension_names
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> "GL_ARB_shading_language_420pack" in extension_names(opengl_for(pl.ren_win))  # Mesa
    True
    """
    count = int(gl.glGetIntegerv(gl.GL_NUM_EXTENSIONS))
    return {gl.glGetStringi(gl.GL_EXTENSIONS, i).decode() for i in range(count)}


def image_copies_supported(gl: ModuleType) -> bool:
    """Tell whether the current context copies texels between textures (``glCopyImageSubData``).

    Parameters
    ----------
    gl : module
        ``OpenGL.GL`` for the current context.

    Returns
    -------
    bool
        ``True`` for OpenGL 4.3 or later, or with ``GL_ARB_copy_image``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.capabilities import image_copies_supported
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> image_copies_supported(opengl_for(pl.ren_win))  # Mesa's OpenGL 4.5
    True
    """
    return gl_version(gl) >= (4, 3) or "GL_ARB_copy_image" in extension_names(gl)
