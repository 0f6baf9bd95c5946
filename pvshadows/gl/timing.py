"""GPU time of a pass, from a pair of ``GL_TIMESTAMP`` queries around it.

PyOpenGL's wrapper of ``glGetQueryObjectui64v`` has no array type for 64-bit
integers, so the raw entry point is called with a ctypes integer.
"""

from __future__ import annotations

import ctypes
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.report import PassReport


class PassTimer:
    """Measures passes on the GPU; results are read once, after the frame.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the passes.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._free: list[int] = []
        self._pending: list[tuple[int, int, PassReport]] = []

    @contextmanager
    def measure(self, report: PassReport) -> Iterator[None]:
        """Time the GL work issued inside the block into ``report.ms``.

        Parameters
        ----------
        report : PassReport
            Receives its ``ms`` when :meth:`collect` runs.

        Yields
        ------
        None
        """
        gl = self._gl
        if len(self._free) < 2:
            self._free.extend(int(q) for q in np.asarray(gl.glGenQueries(2)).ravel())
        start, end = self._free.pop(), self._free.pop()
        gl.glQueryCounter(start, gl.GL_TIMESTAMP)
        try:
            yield
        finally:
            gl.glQueryCounter(end, gl.GL_TIMESTAMP)
            self._pending.append((start, end, report))

    def collect(self) -> None:
        """Read the finished queries into their reports (waits for the GPU)."""
        from OpenGL.raw.GL.VERSION.GL_3_3 import glGetQueryObjectui64v

        begun, ended = ctypes.c_uint64(0), ctypes.c_uint64(0)
        for start, end, report in self._pending:
            glGetQueryObjectui64v(start, self._gl.GL_QUERY_RESULT, ctypes.byref(begun))
            glGetQueryObjectui64v(end, self._gl.GL_QUERY_RESULT, ctypes.byref(ended))
            report.ms = (ended.value - begun.value) * 1e-6
            self._free.extend((start, end))
        self._pending.clear()

    def release(self) -> None:
        """Delete the query objects."""
        queries = self._free + [q for start, end, _ in self._pending for q in (start, end)]
        if queries:
            self._gl.glDeleteQueries(len(queries), queries)
        self._free.clear()
        self._pending.clear()
