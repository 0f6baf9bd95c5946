"""GPU time of a pass, from a pair of ``GL_TIMESTAMP`` queries around it.

Results are read when the GPU has them (``GL_QUERY_RESULT_AVAILABLE``),
usually a frame or two after the pass, so reading them never makes the CPU
wait for the GPU in a normal frame. A pass's :class:`PassReport` gets its
``ms`` then; a query still not ready :data:`MAX_FRAMES_IN_FLIGHT` frames
later is waited for, as engines bound the frames the GPU may lag behind.

PyOpenGL's wrapper of ``glGetQueryObjectui64v`` has no array type for 64-bit
integers, so the raw entry point is called with a ctypes integer.
"""

from __future__ import annotations

import ctypes
import time
from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.model.report import PassReport

#: Frames a pass's timing may wait for the GPU before it is read with a wait.
MAX_FRAMES_IN_FLIGHT = 3


class PassTimer:
    """Measures passes on the GPU; results are read when ready, without stalling.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the passes.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._free: list[int] = []
        self._pending: list[tuple[int, int, PassReport, int]] = []
        self._frame = 0
        #: Results read with a wait because the GPU had not finished them in time.
        self.waited = 0

    @contextmanager
    def measure(self, report: PassReport) -> Iterator[None]:
        """Time the GL work issued inside the block into ``report.ms``.

        The CPU time of issuing it goes to ``report.cpu_ms`` at once.

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
        began = time.thread_time()
        gl.glQueryCounter(start, gl.GL_TIMESTAMP)
        try:
            yield
        finally:
            gl.glQueryCounter(end, gl.GL_TIMESTAMP)
            self._pending.append((start, end, report, self._frame))
            report.cpu_ms += (time.thread_time() - began) * 1e3

    def collect(self, *, wait: bool = False) -> None:
        """Read the queries the GPU has finished into their reports; keep the others.

        Called after each frame. A query issued :data:`MAX_FRAMES_IN_FLIGHT`
        or more frames ago is read even if that means waiting.

        Parameters
        ----------
        wait : bool, default: False
            Wait for every pending query (tests and shutdown).
        """
        self._frame += 1
        if not self._pending:
            return
        from OpenGL.raw.GL.VERSION.GL_3_3 import glGetQueryObjectui64v

        gl = self._gl
        ready, begun, ended = ctypes.c_uint64(0), ctypes.c_uint64(0), ctypes.c_uint64(0)
        kept = []
        for start, end, report, frame in self._pending:
            late = wait or self._frame - frame >= MAX_FRAMES_IN_FLIGHT
            if not late:
                glGetQueryObjectui64v(end, gl.GL_QUERY_RESULT_AVAILABLE, ctypes.byref(ready))
                if not ready.value:
                    kept.append((start, end, report, frame))
                    continue
            elif not wait:
                self.waited += 1
            glGetQueryObjectui64v(start, gl.GL_QUERY_RESULT, ctypes.byref(begun))
            glGetQueryObjectui64v(end, gl.GL_QUERY_RESULT, ctypes.byref(ended))
            report.ms = (ended.value - begun.value) * 1e-6
            self._free.extend((start, end))
        self._pending = kept

    def release(self) -> None:
        """Delete the query objects."""
        queries = self._free + [q for start, end, _, _ in self._pending for q in (start, end)]
        if queries:
            self._gl.glDeleteQueries(len(queries), queries)
        self._free.clear()
        self._pending.clear()
