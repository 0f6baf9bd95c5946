"""GL entry points bound with plain ctypes, for the calls pvshadows makes every frame.

PyOpenGL's wrapped functions convert and check every argument in Python,
which costs more than the GL call itself: a few microseconds each, paid per
caster drawn and per pass timed. These bindings are looked up in the GL library PyOpenGL loaded
for the window's platform, as PyOpenGL itself does for core functions, but
declared with ctypes' own argument types.
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable
from functools import cache
from types import SimpleNamespace

_int, _uint, _uint64_p = ctypes.c_int, ctypes.c_uint, ctypes.POINTER(ctypes.c_uint64)


def _bound(name: str, *arguments: type) -> Callable:
    """Return ``name`` from the platform's GL library, declared to take ``arguments``."""
    from OpenGL import platform

    prototype = ctypes.CFUNCTYPE(None, *arguments)
    try:
        return prototype((name, platform.PLATFORM.GL))
    except AttributeError:  # not exported (some libOSMesa builds): only by address
        address = platform.PLATFORM.getExtensionProcedure(name.encode())
        if not address:
            msg = f"the OpenGL library of this window does not provide {name}"
            raise RuntimeError(msg) from None
        return prototype(address)


@cache
def raw_calls() -> SimpleNamespace:
    """Return the plain bindings of the GL calls of the caster loop, pass timing and the block.

    Call it with the window's context current, after PyOpenGL was bound to
    the window's platform (:func:`pvshadows.gl.binding.opengl_for`).

    Returns
    -------
    types.SimpleNamespace
        ``matrix`` (``glUniformMatrix4fv``), ``bind`` (``glBindVertexArray``),
        ``draw`` (``glDrawElements``), ``multi_draw``
        (``glMultiDrawElements``), ``uniform_int`` (``glUniform1i``),
        ``uniform_float`` (``glUniform1f``), ``vector`` (``glUniform4fv``),
        ``floats`` (``glUniform1fv``), ``query_counter``
        (``glQueryCounter``), ``query_result`` (``glGetQueryObjectui64v``), and
        ``bind_buffer_base`` (``glBindBufferBase``) and ``buffer_data``
        (``glBufferData``) for the frame's uniform block.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.raw_calls import raw_calls
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> _ = opengl_for(pl.ren_win)
    >>> callable(raw_calls().draw)
    True
    """
    return SimpleNamespace(
        matrix=_bound("glUniformMatrix4fv", _int, _int, ctypes.c_ubyte, ctypes.c_void_p),
        bind=_bound("glBindVertexArray", _uint),
        draw=_bound("glDrawElements", _uint, _int, _uint, ctypes.c_void_p),
        multi_draw=_bound(
            "glMultiDrawElements", _uint, ctypes.c_void_p, _uint, ctypes.c_void_p, _int
        ),
        uniform_int=_bound("glUniform1i", _int, _int),
        uniform_float=_bound("glUniform1f", _int, ctypes.c_float),
        vector=_bound("glUniform4fv", _int, _int, ctypes.c_void_p),
        floats=_bound("glUniform1fv", _int, _int, ctypes.c_void_p),
        query_counter=_bound("glQueryCounter", _uint, _uint),
        query_result=_bound("glGetQueryObjectui64v", _uint, _uint, _uint64_p),
        bind_buffer_base=_bound("glBindBufferBase", _uint, _uint, _uint),
        buffer_data=_bound("glBufferData", _uint, ctypes.c_ssize_t, ctypes.c_void_p, _uint),
    )


@cache
def image_copy() -> Callable:
    """Return ``glCopyImageSubData`` bound with plain ctypes.

    Call it only where the context copies images
    (:func:`~pvshadows.gl.capabilities.image_copies_supported`), with the
    context current and PyOpenGL bound to the window's platform.

    Returns
    -------
    callable
        ``glCopyImageSubData(source, target, level, x, y, z, destination,
        target, level, x, y, z, width, height, depth)``.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.binding import opengl_for
    >>> from pvshadows.gl.raw_calls import image_copy
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> _ = opengl_for(pl.ren_win)
    >>> callable(image_copy())
    True
    """
    place = (_int,) * 4  # level, x, y, z
    return _bound("glCopyImageSubData", _uint, _uint, *place, _uint, _uint, *place, *(_int,) * 3)
